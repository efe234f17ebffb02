"""Render reports in memory, then write them atomically, as a set: a reader never sees half a
report, and a set is replaced whole or not at all.

All requested formats are rendered before anything touches the disk, so a rendering error writes
nothing. The files of one directory are then written as one transaction
(:mod:`batcert.reports.fileset`): staged, committed by a journal, moved into place; an error
rolls the set back, a crash is finished by the next writer into the directory, which also
removes what a crash left. A location that cannot hold the reports raises :class:`OutputError`
(the command line's exit code 4), and :func:`check_output_dir` finds it before any work is done.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from batcert.errors import OutputError
from batcert.reports.format import slugify

__all__ = ["OutputError", "check_output_dir", "render", "report_stem", "write_reports",
           "write_texts"]

SUFFIXES = {"md": ".md", "html": ".html", "json": ".json"}  # report formats and file suffixes


@dataclass(frozen=True)
class ReportKind:
    """How one kind of result is reported: its file stem and a renderer per format."""

    stem: Callable[[Any], str]
    markdown: Callable[..., str]
    html: Callable[..., str]
    # what the Markdown and HTML renderers share, made once for a set (None: nothing); the
    # renderers then take it as their second argument
    view: Callable[[Any], Any] | None = None

    def render(self, result: Any, fmt: str, view: Any = None) -> str:
        """``result`` as ``fmt`` (md, html or json); ``view``: :attr:`view` of it, if made."""
        extra = () if view is None else (view,)
        if fmt == "md":
            return self.markdown(result, *extra)
        if fmt == "html":
            return self.html(result, *extra)
        if fmt == "json":
            return result.to_json() + "\n"
        raise ValueError(f"unknown report format {fmt!r} (choose from {', '.join(SUFFIXES)})")


def _short(stem: str) -> str:
    """Keep file names short (well under any file system's 255 bytes); a hash of the whole
    keeps different inputs apart."""
    if len(stem) > 120:
        stem = stem[:100] + "-" + hashlib.sha256(stem.encode()).hexdigest()[:10]
    return stem


def run_stem(result: Any) -> str:
    """``<bat-slug>--<protocol-id>``, e.g. ``ash-34-in--proposed``."""
    return _short(f"{slugify(result.bat, 'bat')}--{slugify(result.protocol, 'protocol')}")


def run_stem_with_file(result: Any, file_stem: str) -> str:
    """``<bat-slug>--<bat file stem>--<protocol-id>``: a run's stem when bats of one batch
    share a name."""
    return _short(f"{slugify(result.bat, 'bat')}--{slugify(file_stem, 'bat')}--"
                  f"{slugify(result.protocol, 'protocol')}")


def _stem(kind: str, what: str, bats: str) -> str:
    return _short(f"{kind}--{slugify(what)}--{slugify(bats)}")


def comparison_stem(result: Any) -> str:
    """``compare--<study>`` or ``compare--<protocol ids>``, then the bats' file stems."""
    what = result.study or "+".join(p.protocol for p in result.protocols)
    return _stem("compare", what, "+".join(Path(b.path).stem for b in result.bats))


def league_stem(result: Any) -> str:
    return _stem("league", result.league, "+".join(Path(b.path).stem for b in result.bats))


def sweep_stem(result: Any) -> str:
    """``sweep--<protocol>--<parameters>--<bat file stem>`` (``design--`` for a design study)."""
    return variants_stem(result.protocol, [a.name for a in result.axes], result.bat_path,
                         result.design is not None)


def variants_stem(protocol: str, parameters: Sequence[str], bat_path: str,
                  design: bool = False) -> str:
    """The stem of :func:`sweep_stem` from its parts (a sweep's journal is named before its
    result exists)."""
    return _stem("design" if design else "sweep", protocol + "--" + "+".join(parameters),
                 Path(bat_path).stem)


def field_stem(result: Any) -> str:
    """``field--<batter ids>--<bats' file stems>``."""
    bats = result.batters[0].bats if result.batters else []
    return _stem("field", "+".join(b.batter for b in result.batters),
                 "+".join(Path(b.path).stem for b in bats))


def lab_stem(result: Any) -> str:
    """``lab--<protocol>--<session file stem>``."""
    return _stem("lab", result.protocol, Path(result.session_path).stem)


def _markdown():
    from batcert.reports import markdown  # imported on first use: a run's start-up stays light
    return markdown


def _sweep_view(result: Any) -> Any:
    from batcert.reports.sweep_view import sweep_view
    return sweep_view(result, charts=False)


def _html():
    from batcert.reports import html
    return html


# the report kind of each result type, by class name (the result modules are not imported to
# look a result up, which keeps a run's start-up from loading every other kind): its stem and
# its Markdown and HTML renderers, named outright
_KINDS: dict[str, ReportKind] = {
    "RunResult": ReportKind(run_stem, lambda r: _markdown().run_markdown(r),
                            lambda r: _html().run_html(r)),
    "ComparisonResult": ReportKind(comparison_stem, lambda r: _markdown().comparison_markdown(r),
                                   lambda r: _html().comparison_html(r)),
    "LeagueResult": ReportKind(league_stem, lambda r: _markdown().league_markdown(r),
                               lambda r: _html().league_html(r)),
    "SweepResult": ReportKind(sweep_stem, lambda r, v=None: _markdown().sweep_markdown(r, v),
                              lambda r, v=None: _html().sweep_html(r, v), _sweep_view),
    "FieldResult": ReportKind(field_stem, lambda r: _markdown().field_markdown(r),
                              lambda r: _html().field_html(r)),
    "LabResult": ReportKind(lab_stem, lambda r: _markdown().lab_markdown(r),
                            lambda r: _html().lab_html(r)),
}


def _kind(result: Any) -> ReportKind:
    """The report kind of a result."""
    cls = type(result)
    if not cls.__module__.startswith("batcert.results.") or cls.__name__ not in _KINDS:
        raise KeyError(cls)
    return _KINDS[cls.__name__]


def report_stem(result: Any) -> str:
    """The file stem of a result's reports (and of its figures and sweep journal)."""
    return _kind(result).stem(result)


def render(result: Any, fmt: str) -> str:
    """One report of a run, comparison or league result as text: ``fmt`` is md, html or json."""
    return _kind(result).render(result, fmt)


def write_reports(result: Any, out_dir: Path, formats: Sequence[str] = ("md", "html", "json"),
                  stem: str | None = None) -> list[Path]:
    """Render ``result`` in each format and write ``out_dir/<stem>.<ext>`` as one set.

    Every format is rendered before anything is written; then the files are staged and replaced
    together (:func:`write_texts`). Returns the paths in the order of ``formats`` (duplicates
    dropped). Raises ``ValueError`` for an unknown format or a stem that is not a plain file
    name; any rendering or writing error propagates after cleaning up, leaving no partial or
    temporary file and existing reports untouched.
    """
    wanted = list(dict.fromkeys(formats))
    unknown = [f for f in wanted if f not in SUFFIXES]
    if unknown:
        raise ValueError(f"unknown report format(s) {', '.join(map(repr, unknown))} "
                         f"(choose from {', '.join(SUFFIXES)})")
    kind = _kind(result)
    stem = kind.stem(result) if stem is None else stem
    if not stem or stem in (".", "..") or "/" in stem or "\\" in stem or "\0" in stem:
        raise ValueError(f"report stem {stem!r} must be a plain file name")
    out_dir = Path(out_dir)
    shared = kind.view(result) if kind.view is not None and {"md", "html"} & set(wanted) \
        else None
    return write_texts({out_dir / f"{stem}{SUFFIXES[f]}": kind.render(result, f, shared)
                        for f in wanted})


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc)


def check_output_dir(directory: Path) -> None:
    """Make sure reports can be written in ``directory`` before any work, leaving nothing
    behind (a missing directory is not created here): raise :class:`OutputError` if it, or the
    nearest existing folder above it, is not a directory or refuses a new file, or if a name on
    the way is too long."""
    directory = Path(directory)
    missing: list[str] = []
    existing = directory
    try:
        while not existing.exists() and existing != existing.parent:
            missing.append(existing.name)
            existing = existing.parent
        if existing.exists() and not existing.is_dir():
            raise OutputError(directory, f"{existing} is not a directory")
    except OSError as exc:
        if isinstance(exc, OutputError):
            raise
        raise OutputError(directory, _reason(exc)) from None
    try:
        limit = os.pathconf(existing, "PC_NAME_MAX")
    except (OSError, ValueError):
        limit = 255
    for name in missing:
        if len(name.encode()) > limit:
            raise OutputError(directory, f"the name {name[:40]}... is longer than {limit} bytes")
    try:
        fd, probe = tempfile.mkstemp(prefix=".batcert-probe.", suffix=".tmp", dir=existing)
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        raise OutputError(directory, _reason(exc)) from None


def check_output_file(path: Path, inputs: list[Path], what: str) -> None:
    """Make sure one file (``what``, for the message) can be written at ``path`` without
    harm, before any work: raise :class:`OutputError` if it exists and is not a regular file
    (a directory, a device, a FIFO), if it is one of the run's ``inputs`` (compared as files,
    through links: batcert never writes over an input), or if its folder refuses a new file
    (:func:`check_output_dir`)."""
    path = Path(path)
    try:
        if path.exists() or path.is_symlink():
            if not path.is_file():
                raise OutputError(path, "it exists and is not a regular file", what)
            for source in inputs:
                try:
                    same = Path(source).exists() and os.path.samefile(path, source)
                except OSError:
                    same = False
                if same:
                    raise OutputError(path, f"it is an input of this run ({source}); batcert "
                                      "never writes over an input: give a new file name", what)
    except OutputError:
        raise
    except OSError as exc:
        raise OutputError(path, _reason(exc), what) from None
    try:
        check_output_dir(path.parent if str(path.parent) else Path("."))
    except OutputError as exc:
        raise OutputError(path, exc.reason, what) from None


def write_texts(texts: dict[Path, str | bytes]) -> list[Path]:
    """Write already-rendered reports (text, or bytes such as a PNG) as one set (module
    notes). Parent directories are created. Raises :class:`OutputError`, leaving the previous set as it was."""
    try:
        for directory in {Path(p).parent for p in texts}:
            check_output_dir(directory)
            directory.mkdir(parents=True, exist_ok=True)
        _write_all({Path(p): t for p, t in texts.items()})
    except OutputError:
        raise
    except OSError as exc:
        where = Path(exc.filename) if getattr(exc, "filename", None) else next(iter(texts))
        raise OutputError(where, _reason(exc)) from None
    return [Path(p) for p in texts]


def atomic_write_text(path: Path, text: str, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` so that readers see either the old file or the whole new one."""
    path = Path(path)
    _write_all({path: text}, encoding)
    return path


def _write_all(texts: dict[Path, str | bytes], encoding: str = "utf-8") -> None:
    """Write each directory's files as one set (:func:`batcert.reports.fileset.write_set`:
    whole or not at all, even across a crash, and a crash's leftovers cleaned)."""
    from batcert.reports.fileset import write_set
    by_dir: dict[Path, dict[str, bytes]] = {}
    modes: dict[Path, dict[str, int]] = {}
    for target, text in texts.items():
        if target.is_dir():
            raise OutputError(target, "a directory is in the way of this report")
        data = text if isinstance(text, bytes) else text.encode(encoding)
        by_dir.setdefault(target.parent, {})[target.name] = data
        modes.setdefault(target.parent, {})[target.name] = _mode_for(target)
    for directory, files in by_dir.items():
        write_set(directory, files, modes[directory])


def _mode_for(target: Path) -> int:
    """Keep an existing report's permissions; a new one gets the usual 0o666 minus the umask
    (mkstemp alone would leave it readable by the owner only)."""
    try:
        return target.stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask
