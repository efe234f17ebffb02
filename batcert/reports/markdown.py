"""The certification report as GitHub-flavoured Markdown (tables only; plots are in the HTML)."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from batcert.reports import Table, build_view, environment
from batcert.units import Display

if TYPE_CHECKING:
    from batcert.results import RunResult

_CELL_SPECIALS = re.compile(r"([\\`*\[\]|<>]|(?<!\w)_|_(?!\w))")
_TEXT_SPECIALS = re.compile(r"([\\`*\[\]<>])")


def md_text(text: object) -> str:
    """Escape running text so that names and notes show literally (no HTML, no emphasis)."""
    out = _TEXT_SPECIALS.sub(r"\\\1", " ".join(str(text).split()))
    return "\\" + out if out[:1] in "#+-=>" and out else out


def md_cell(value: object) -> str:
    """One table cell: ``Display`` as "SI (US)", pipes and line breaks neutralised."""
    text = str(value) if isinstance(value, Display) else " ".join(str(value).split())
    return _CELL_SPECIALS.sub(r"\\\1", text) or " "


def md_table(table: Table) -> str:
    """A GFM pipe table; numeric columns are right-aligned."""
    numeric = table.numeric or [False] * len(table.headers)
    lines = [
        "| " + " | ".join(md_cell(h) for h in table.headers) + " |",
        "|" + "|".join("---:" if n else ":---" for n in numeric) + "|",
    ]
    lines += ["| " + " | ".join(md_cell(c) for c in row) + " |" for row in table.rows]
    return "\n".join(lines)


def render_markdown(result: RunResult) -> str:
    """The full report as Markdown text."""
    env = environment().overlay()
    env.filters.update(md_text=md_text, md_cell=md_cell, md_table=md_table)
    return env.get_template("report.md.j2").render(**build_view(result))
