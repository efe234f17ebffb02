"""The one table model of every report and of the terminal.

A :class:`Table` holds display cells: plain text, a :class:`~batcert.units.Display` (SI, with US
customary alongside) or a :class:`Badge` (a coloured status label). Markdown, HTML and the
terminal each lay a table out in their own way; none of them formats numbers (that is
:mod:`batcert.reports.format`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class Badge:
    """A status label; ``css`` picks its colour: pass, fail, warn, na or info."""

    text: str
    css: str

    def __str__(self) -> str:
        return self.text


@dataclass
class Table:
    """Headers, rows of display cells, right-aligned (numeric) columns, optional row classes
    (HTML) and summary rows shown below the body (``foot``)."""

    headers: list[str]
    rows: list[list[Any]] = field(default_factory=list)
    numeric: list[bool] = field(default_factory=list)
    row_classes: list[str] = field(default_factory=list)
    foot: list[list[Any]] = field(default_factory=list)
    title: str = ""

    def is_numeric(self, i: int) -> bool:
        return bool(self.numeric) and i < len(self.numeric) and self.numeric[i]
