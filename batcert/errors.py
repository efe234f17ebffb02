"""Input errors that point into the user's file: file, line, field and message.

Every spec loader collects all problems of a file into one :class:`InputError` so that the user
sees them at once (exit code 3). Nothing downstream of a failed load is run or written.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path


class BatcertError(Exception):
    """Every error batcert raises for something its caller can fix: bad input
    (:class:`InputError`), an unknown name (:class:`batcert.specs.resolve.NotFound`), an
    impossible request or argument (:class:`UsageProblem`), a bat that cannot be modelled
    (:class:`ModelError`), reports that cannot be written (:class:`OutputError`), a scheduler
    that cannot be used (:class:`SchedulerUnavailable`). Anything else is a bug."""


@dataclass(frozen=True)
class Problem:
    """One thing wrong with an input file."""

    file: str
    line: int | None  # 1-based; None when the problem is not tied to a line
    field: str  # dotted path of the offending key, e.g. "measured.mass"; "" for the whole file
    message: str
    column: int | None = None  # 1-based column of the offending value, for the caret

    def render(self, source_lines: list[str] | None = None) -> str:
        where = f"{self.file}:{self.line}" if self.line else self.file
        head = f"{where}: {self.field}: {self.message}" if self.field else f"{where}: {self.message}"
        if source_lines and self.line and 0 < self.line <= len(source_lines):
            text, column = _excerpt(source_lines[self.line - 1].rstrip("\n"), self.column)
            gutter = f"{self.line:>5} | "
            head += f"\n{gutter}{text}"
            if column:
                head += "\n" + " " * (len(gutter) - 2) + "| " + " " * (column - 1) + "^"
        return head


QUOTE_WIDTH = 100  # characters of a source line quoted under a problem


def _excerpt(text: str, column: int | None) -> tuple[str, int | None]:
    """A long source line cut to :data:`QUOTE_WIDTH` characters around ``column`` (with "..."
    where cut), control characters shown as "?"; the caret's column in the excerpt."""
    text = "".join(c if c.isprintable() or c == "\t" else "?" for c in text)
    if len(text) <= QUOTE_WIDTH:
        return text, column
    start = max(0, min((column or 1) - 1 - QUOTE_WIDTH // 2, len(text) - QUOTE_WIDTH))
    piece = text[start:start + QUOTE_WIDTH]
    lead = "..." if start > 0 else ""
    tail = "..." if start + QUOTE_WIDTH < len(text) else ""
    return lead + piece + tail, (column - start + len(lead)) if column else None


@dataclass
class InputError(BatcertError):
    """All problems found in one or more input files."""

    problems: list[Problem] = field(default_factory=list)

    def __str__(self) -> str:
        return self.render()

    def render(self) -> str:
        sources: dict[str, list[str] | None] = {}
        out = []
        for p in self.problems:
            if p.file not in sources and p.line:
                try:
                    sources[p.file] = Path(p.file).read_text(encoding="utf-8-sig",
                                                         errors="replace").splitlines()
                except (OSError, UnicodeDecodeError):
                    sources[p.file] = None
            out.append(p.render(sources.get(p.file)))
        n = len(self.problems)
        files = sorted({p.file for p in self.problems})
        summary = f"{n} problem{'s' if n != 1 else ''} in {', '.join(files)}"
        return "\n".join(out) + f"\n{summary}"


class Collector:
    """Gathers problems for one file; raise them all at once with :meth:`raise_if_any`."""

    def __init__(self, file: str | Path):
        self.file = str(file)
        self.problems: list[Problem] = []

    def add(self, line: int | None, field_: str, message: str, column: int | None = None) -> None:
        self.problems.append(Problem(self.file, line, field_, message, column))

    def raise_if_any(self) -> None:
        """Raise every problem at once, in the order of the file's lines (problems without a
        line, about the file as a whole, first)."""
        if self.problems:
            raise InputError(sorted(self.problems, key=lambda p: p.line or 0))


class ModelError(BatcertError, ValueError):
    """A bat that cannot be modelled (an infeasible reconciliation, a wall that fills the
    section, an absurd calibration); ``field`` names the offending spec field, dotted."""

    def __init__(self, field_: str, message: str):
        super().__init__(message)
        self.field = field_


class UsageProblem(BatcertError, ValueError):
    """The command line asks for something impossible (e.g. fewer than two bats to compare)."""


class SchedulerUnavailable(BatcertError):
    """``--scheduler`` cannot be used: dask.distributed is not installed, or the scheduler cannot
    be reached, does not speak dask, has no workers: an environment problem, not bad input
    (one line, exit 5)."""


class OutputError(BatcertError, OSError):
    """Reports (or a sweep's journal) cannot be written where asked (permissions, a full disk,
    a path that is a file or too long): an environment problem, not bad input (exit 4)."""

    def __init__(self, where: Path, reason: str, what: str = "reports"):
        super().__init__(f"cannot write {what} to {where}: {reason}")
        self.where, self.reason = where, reason
