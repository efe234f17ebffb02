"""Reports as GitHub-flavoured Markdown (tables and text; the plots are in the HTML)."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from batcert.reports.table import Table
from batcert.reports.templates import render_template
from batcert.units import Display

if TYPE_CHECKING:
    from batcert.results.compare import ComparisonResult
    from batcert.results.field import FieldResult
    from batcert.results.lab import LabResult
    from batcert.results.league import LeagueResult
    from batcert.results.run import RunResult
    from batcert.results.sweep import SweepResult

_CELL_SPECIALS = re.compile(r"([\\`*\[\]|<>]|(?<!\w)_|_(?!\w))")
_TEXT_SPECIALS = re.compile(r"([\\`*\[\]<>])")


def md_text(text: object) -> str:
    """Escape running text so that names and notes show literally (no HTML, no emphasis)."""
    out = _TEXT_SPECIALS.sub(r"\\\1", " ".join(str(text).split()))
    return "\\" + out if out[:1] in "#+-=>" and out else out


def md_code(text: object) -> str:
    """Text for inside a code span: on one line, with no backtick to close the span early."""
    return " ".join(str(text).replace("`", "'").split()) or " "


def md_cell(value: object) -> str:
    """One table cell: ``Display`` as "SI (US)", pipes and line breaks neutralised."""
    text = str(value) if isinstance(value, Display) else " ".join(str(value).split())
    return _CELL_SPECIALS.sub(r"\\\1", text) or " "


def md_table(table: Table) -> str:
    """A GFM pipe table (summary rows after the body); numeric columns are right-aligned."""
    numeric = [table.is_numeric(i) for i in range(len(table.headers))]
    lines = [
        "| " + " | ".join(md_cell(h) for h in table.headers) + " |",
        "|" + "|".join("---:" if n else ":---" for n in numeric) + "|",
    ]
    lines += ["| " + " | ".join(md_cell(c) for c in row) + " |"
              for row in [*table.rows, *table.foot]]
    return "\n".join(lines)


FILTERS = {"md_text": md_text, "md_code": md_code, "md_cell": md_cell, "md_table": md_table}


def run_markdown(result: RunResult) -> str:
    """The certificate of one protocol run."""
    from batcert.reports.run_view import run_view
    return render_template("report.md.j2", run_view(result), FILTERS)


def comparison_markdown(result: ComparisonResult) -> str:
    from batcert.reports.compare_view import comparison_view
    return render_template("compare.md.j2", comparison_view(result, charts=False), FILTERS)


def field_markdown(result: FieldResult) -> str:
    from batcert.reports.field_view import field_view
    return render_template("field.md.j2", field_view(result, charts=False), FILTERS)


def league_markdown(result: LeagueResult) -> str:
    from batcert.reports.league_view import league_view
    return render_template("league.md.j2", league_view(result), FILTERS)


def sweep_markdown(result: SweepResult, view: dict | None = None) -> str:
    """A sweep or design study; ``view``: its ``sweep_view`` without charts, when made."""
    from batcert.reports.sweep_view import sweep_view
    return render_template("sweep.md.j2", sweep_view(result, charts=False) if view is None
                           else view, FILTERS)


def lab_markdown(result: LabResult) -> str:
    """A lab certificate (``batcert reduce``)."""
    from batcert.reports.lab_view import lab_view
    return render_template("lab.md.j2", lab_view(result, charts=False), FILTERS)
