"""All terminal output goes through here: tables on stdout, messages on stderr.

On a terminal, rich draws them (styles, wrapping to the window); piped or redirected, they are
plain text, aligned when they fit ``COLUMNS`` (default 140) and otherwise stacked one
``header: value`` per line, never cut. With ``--json`` only JSON is written to stdout so that
scripts can parse it. Tables are the reports' own :class:`~batcert.reports.table.Table` objects
with the reports' formatting (:mod:`batcert.reports.format`); every piece of user text is shown
as plain text, never read as console markup or emoji codes.
"""

from __future__ import annotations

import math
import re
import shutil
import sys
from collections.abc import Sequence
from functools import lru_cache
from typing import Any

from batcert.console.wrap import wrap_parts, wrap_text
from batcert.reports.table import Badge, Table

STYLES = {"pass": "green", "fail": "red", "warn": "yellow", "na": "dim", "info": "bold"}


class _Settings:
    verbose = 0  # 1: log inputs, engine settings and timings to stderr
    quiet = False  # only verdicts and errors


def configure(verbose: int = 0, quiet: bool = False) -> None:
    """The command line's ``--verbose`` / ``--quiet``."""
    _Settings.verbose, _Settings.quiet = int(verbose), bool(quiet)


def log(message: str, level: int = 1) -> None:
    """A line on stderr when ``--verbose`` is at least ``level``."""
    if _Settings.verbose >= level:
        _emit([("batcert: ", "dim"), (message, "")], stderr=True)


class progress:
    """A progress display on a terminal for long work (rich, on stderr); nothing when stderr
    is not a terminal or with ``--quiet``. ``update(text)`` says what is being done."""

    def __init__(self, description: str):
        self.description = description
        self._live: Any = None
        self._task: Any = None
        self._bar: Any = None

    def __enter__(self) -> progress:
        if _terminal(sys.stderr) and not _Settings.quiet:
            from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

            self._live = Progress(SpinnerColumn(), TextColumn("{task.description}"),
                                  TimeElapsedColumn(), console=_console(True), transient=True)
            self._live.start()
            self._task = self._live.add_task(self.description)
        return self

    def update(self, text: str) -> None:
        if self._live is not None:
            self._live.update(self._task, description=f"{self.description}: {text}")

    def count(self, done: int, total: int, what: str = "variants") -> None:
        """A bar of ``done`` of ``total`` (with the rate and the time left)."""
        if self._live is None:
            return
        if self._bar is None:
            from rich.progress import BarColumn, MofNCompleteColumn, TimeRemainingColumn
            self._live.stop()
            from rich.progress import Progress, TextColumn, TimeElapsedColumn
            self._live = Progress(TextColumn("{task.description}"), BarColumn(),
                                  MofNCompleteColumn(), TextColumn(what), TimeElapsedColumn(),
                                  TimeRemainingColumn(), console=_console(True), transient=True)
            self._live.start()
            self._bar = self._task = self._live.add_task(self.description, total=total)
        self._live.update(self._task, completed=done, total=total)

    def __exit__(self, *exc) -> None:
        if self._live is not None:
            self._live.stop()


def _terminal(stream) -> bool:
    """Styled output (rich) only on a terminal; plain text when piped or redirected, which
    also spares a script the ~20 ms of importing rich."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


@lru_cache(maxsize=2)
def _console(stderr: bool):
    from rich.console import Console

    return Console(stderr=stderr, highlight=False, soft_wrap=True, emoji=False, markup=False)


def _width() -> int:
    """Columns for plain tables: ``COLUMNS`` when set (also when piped), else the terminal's,
    else 140 (a file or a pipe: wide enough for a run's table on one line per condition)."""
    return shutil.get_terminal_size((140, 24)).columns


def _columns(stderr: bool = False) -> int:
    """The width lines are laid out to: the terminal's (rich's), else :func:`_width`."""
    return _console(stderr).width if _terminal(sys.stderr if stderr else sys.stdout) \
        else _width()


# control characters other than tab and line feed (ESC starts a terminal escape sequence, CR
# overwrites a line): shown as \xNN, so text from a file or the command line cannot drive the
# terminal
_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def _visible(text: str) -> str:
    return _CONTROL.sub(lambda m: f"\\x{ord(m.group()):02x}", text)


def _emit(parts: Sequence[tuple[str, str]], stderr: bool = False, hang: int | None = None,
          wrap: bool = True) -> None:
    """One line made of (text, style) parts: styled on a terminal, plain otherwise; control
    characters shown escaped; wrapped to the width with continuation lines indented by ``hang``
    (default: the line's own indent + 4), so that a long headline or warning reads as one item
    at 80 columns; not with ``wrap=False`` (an error stays one line, for a script to read)."""
    parts = [(_visible(text), style) for text, style in parts]
    stream = sys.stderr if stderr else sys.stdout
    styled = _terminal(stream)
    lines = wrap_parts(parts, _columns(stderr), hang) if wrap else [parts]
    if styled:
        from rich.text import Text

        for line in lines:
            _console(stderr).print(Text.assemble(*line))
    else:
        stream.write("".join("".join(text for text, _ in line) + "\n" for line in lines))


def print_json(data: Any) -> None:
    """``data`` as strict JSON (a non-finite number, which no result should hold, is null)."""
    from batcert.results.serialise import dumps, map_floats

    finite = map_floats(data, lambda x: x if math.isfinite(x) else None)
    sys.stdout.write(dumps(finite) + "\n")
    sys.stdout.flush()


def print_results(command: str, results: list[Any]) -> None:
    """A command's ``--json`` output: the one envelope of every command (docs/results-json.md)
    around its ``results``."""
    from batcert.results.serialise import envelope
    from batcert.version import __version__
    print_json(envelope(command, results, __version__))


def error(message: str) -> None:
    _emit([("error: ", "bold red"), (message, "")], stderr=True, wrap=False)


def input_error(text: str) -> None:
    _emit([("invalid input", "bold red")], stderr=True)
    _emit([(text, "")], stderr=True, wrap=False)


def note(message: str) -> None:
    _emit([(message, "")], stderr=True)


def _cell_text(value: Any) -> str:
    return value.text if isinstance(value, Badge) else str(value)


def table(t: Table, title: str = "") -> None:
    """A report table on the terminal (summary rows after a blank line)."""
    if _Settings.quiet:
        return
    title = title or t.title
    if not _terminal(sys.stdout) or _natural_width(t) > _console(False).width:
        _plain_table(t, title)  # wider than the terminal: a row's cells one per line, never cut
        return
    from rich.table import Table as RichTable
    from rich.text import Text

    def cell(value: Any) -> Text:
        if isinstance(value, Badge):
            return Text(value.text, style=STYLES.get(value.css, ""))
        return Text(str(value))

    r = RichTable(title=Text(title) if title else None, box=None,
                  title_justify="left", header_style="bold", pad_edge=False)
    for i, h in enumerate(t.headers):
        r.add_column(Text(h), justify="right" if t.is_numeric(i) else "left")
    for row in t.rows:
        r.add_row(*(cell(c) for c in row))
    for row in t.foot:
        r.add_row(*(cell(c) for c in row), style="bold")
    _console(False).print(r)


def _widths(t: Table) -> list[int]:
    """Each column's natural width: its longest header line or cell."""
    rows = [[_cell_text(c) for c in row] for row in [*t.rows, *t.foot]]
    return [max([len(x) for x in h.split("\n")] + [len(r[i]) for r in rows])
            for i, h in enumerate(t.headers)]


def _natural_width(t: Table) -> int:
    """The width a table needs with nothing cut (two spaces between columns)."""
    widths = _widths(t)
    return sum(widths) + 2 * (len(widths) - 1)


def _plain_table(t: Table, title: str) -> None:
    """Aligned columns (headers over as many lines as they have) when they fit the width;
    otherwise each row as ``header: value`` lines (an empty cell left out), so that nothing is
    ever cut, long values wrapped under themselves."""
    head_lines = [h.split("\n") for h in t.headers]
    depth = max(len(h) for h in head_lines)
    rows = [[_cell_text(c) for c in row] for row in [*t.rows, *t.foot]]
    widths = _widths(t)
    width = _columns()
    lines = wrap_text(title, width) if title else []
    if _natural_width(t) <= width:
        def line(cells: Sequence[str]) -> str:
            return "  ".join(c.rjust(w) if t.is_numeric(i) else c.ljust(w)
                             for i, (c, w) in enumerate(zip(cells, widths, strict=True))).rstrip()
        lines += [line([h[k] if k < len(h) else "" for h in head_lines]) for k in range(depth)]
        lines += [line(r) for r in rows]
    else:
        heads = [" ".join(h) for h in head_lines]
        label = max(len(h) for h in heads[1:]) if len(heads) > 1 else 0
        for r in rows:
            lines += wrap_text(f"{heads[0]}: {r[0]}", width)
            for h, c in zip(heads[1:], r[1:], strict=True):
                lines += _labelled(h, label, c, width) if c.strip() else []  # empty: left out
    sys.stdout.write("\n".join(lines) + "\n")


def _labelled(key: str, label: int, value: str, width: int, indent: str = "  ") -> list[str]:
    """``key: value`` in a column of labels ``label`` wide; a long value wraps under itself
    (or 4 columns in when the labels take half the width)."""
    hang = len(indent) + label + 2
    return wrap_text(f"{indent}{key.ljust(label)}  {value}".rstrip(), width,
                     hang if hang <= width // 2 else len(indent) + 4)


def blocks(view: Sequence[tuple[str, Any]]) -> None:
    """Titled blocks of a view (:mod:`batcert.reports.inspect_view`): key-value rows or a
    table, each printed as such."""
    for title, content in view:
        if isinstance(content, Table):
            table(content, title)
        else:
            kv_table(title, content)


def kv_table(title: str, rows: Sequence[tuple[str, Any]]) -> None:
    t = Table(["", ""], [[k, v] for k, v in rows])
    if not _terminal(sys.stdout):
        label = max((len(k) for k, _ in rows), default=0)
        width = _columns()
        lines = wrap_text(title, width)
        for k, v in rows:
            lines += _labelled(k, label, _cell_text(v), width, indent="")
        sys.stdout.write("\n".join(lines) + "\n")
        return
    from rich.table import Table as RichTable
    from rich.text import Text

    r = RichTable(title=Text(title), show_header=False, box=None, title_justify="left",
                  pad_edge=False)
    r.add_column("", style="bold")
    r.add_column("")
    for k, v in t.rows:
        r.add_row(Text(k), Text(_cell_text(v), style=STYLES.get(getattr(v, "css", ""), "")))
    _console(False).print(r)


_VERDICT = {"pass": ("PASS", "bold green"), "fail": ("FAIL", "bold red")}


def _verdict(verdict: str | None) -> tuple[str, str]:
    return _VERDICT.get(verdict or "", ("no limit", "bold"))


def _wrote(paths: Sequence[Any]) -> None:
    for p in [] if _Settings.quiet else paths:
        _emit([(f"  wrote {p}", "")], wrap=False)  # the path whole, on its line


def warnings(warnings: Sequence[str]) -> None:
    """A result's warnings, on stderr in every mode (with ``--json`` too, where stdout holds
    only the JSON), so that a script reading stdout and a person reading the terminal both
    get them; not with ``--quiet``."""
    if _Settings.quiet:
        return
    for w in warnings:
        _emit([("  warning: ", "yellow"), (w, "")], stderr=True, hang=len("  warning: "))


_warnings = warnings


def note_out(message: str) -> None:
    """A plain line on stdout (e.g. ``ok  file.yaml (bat)``)."""
    _emit([(message, "")])
