"""Reports as self-contained HTML pages (inline CSS and SVG, no scripts, nothing loaded)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from batcert.reports import svg
from batcert.reports.figure import Figure, LineFigure, svg_of
from batcert.reports.format import metric_name
from batcert.reports.table import Badge, Table
from batcert.reports.templates import render_template
from batcert.units import INCH, Display, to_us

if TYPE_CHECKING:
    from markupsafe import Markup

    from batcert.results.compare import ComparisonResult
    from batcert.results.field import FieldResult
    from batcert.results.lab import LabResult
    from batcert.results.league import LeagueResult
    from batcert.results.run import RunResult
    from batcert.results.sweep import SweepResult

X_LABEL = "Impact location from the pivot [m]"


def cell(value: object) -> Markup:
    """A table cell's content: a badge, SI with US customary below it, or escaped text (each
    part escaped, then joined: ``Markup.format`` took 0.4 s for an 800-variant sweep's table)."""
    from markupsafe import Markup, escape

    if isinstance(value, Badge):
        return Markup(f'<span class="badge badge-{escape(value.css)}">{escape(value.text)}</span>')
    if isinstance(value, Display):
        us = f'<span class="us">{escape(value.us)}</span>' if value.us else ""
        return Markup(f'<span class="si">{escape(value.si)}</span>{us}')
    return escape(str(value))


def table_html(t: Table) -> Markup:
    """A report table as HTML (``table.html.j2`` includes it): its header, then a row per line
    of cells (:func:`cell`), numeric columns classed ``num``. Written here rather than as a
    template loop: an 800-variant sweep's seven tables of 400 rows took 0.6 s in Jinja."""
    from markupsafe import Markup, escape

    num = [' class="num"' if t.is_numeric(i) else "" for i in range(len(t.headers))]
    head = "".join(f'<th scope="col"{num[i]}>{escape(h)}</th>' for i, h in enumerate(t.headers))
    # a row's cells past the headers are plain (the template's columns likewise)
    rows = "".join("<tr>" + "".join(f"<td{num[i] if i < len(num) else ''}>{cell(c)}</td>"
                                    for i, c in enumerate(row)) + "</tr>\n" for row in t.rows)
    return Markup(f'<div class="scroll">\n<table class="sweep">\n<thead><tr>{head}</tr></thead>\n'
                  f"<tbody>\n{rows}</tbody>\n</table>\n</div>\n")


def _cop_lines(result: RunResult) -> list[svg.VLine]:
    """One "COP" marker, or one per condition when the conditions' COPs differ."""
    cops = {round(c.cop, 6) for c in result.conditions}
    if len(cops) <= 1:
        cop = result.conditions[0].cop if result.conditions else result.mass_properties.cop
        return [svg.VLine(cop, "COP")]
    return [svg.VLine(c.cop, f"COP {c.name}", svg.color(i))
            for i, c in enumerate(result.conditions)]


def run_figures(result: RunResult) -> list[Figure]:
    """Exit speed against impact location, one line per condition, impact points circled;
    and the protocol metric likewise when it is not the exit speed."""
    from batcert.reports.run_view import shows_metric_plot
    points = [svg.Point(c.impact_location, c.exit_speed, i)
              for i, c in enumerate(result.conditions)]
    mp = result.mass_properties  # a lab reads locations in inches from the tip
    from_tip = svg.SecondaryAxis("Impact location from the tip [in]", -1.0 / INCH,
                                 (mp.length - mp.pivot) / INCH)
    figs: list[Figure] = [LineFigure(
        "exit-speed", "Exit speed against impact location", X_LABEL, "Exit speed [m/s]",
        [svg.Series(c.name, c.sweep.impact_location, c.sweep.exit_speed)
         for c in result.conditions],
        vlines=_cop_lines(result), points=points, point_legend="impact point",
        y2=svg.SecondaryAxis("Exit speed [mph]", to_us(1.0, "speed")), x2=from_tip)]
    if shows_metric_plot(result):
        name = metric_name(result.metric)
        figs.append(LineFigure(
            "metric", f"{name} against impact location", X_LABEL, f"{name} [-]",
            [svg.Series(c.name, c.sweep.impact_location, c.sweep.metric)
             for c in result.conditions],
            vlines=_cop_lines(result), point_legend="impact point",
            points=[svg.Point(c.impact_location, c.metric_value, i)
                    for i, c in enumerate(result.conditions)],
            hlines=[] if result.limit is None else [
                (result.limit + result.tolerance, f"limit {result.limit:g}"
                 + (f" + {result.tolerance:g}" if result.tolerance else ""))],
            x2=from_tip))
    from batcert.reports.uncertainty_view import uncertainty_figure
    spread = uncertainty_figure(result)
    return figs + ([spread] if spread is not None else [])


def css_string(text: object):
    """``text`` as the body of a CSS string: every character but letters, digits and spaces as
    a CSS escape, so that user text (a bat's name) can neither end the string nor the style
    element (``</style>``); marked safe, as HTML escaping inside a style element would show."""
    from markupsafe import Markup

    return Markup("".join(c if c.isalnum() and c.isascii() or c == " " else f"\\{ord(c):x} "
                          for c in str(text)))


FILTERS = {"cell": cell, "css_string": css_string, "table_html": table_html}


def run_html(result: RunResult) -> str:
    """The certificate of one protocol run as an HTML5 document."""
    from markupsafe import Markup

    from batcert.reports.run_view import run_view
    view = run_view(result)
    figures = run_figures(result)
    view["charts"] = [Markup(svg_of(f)) for f in figures if f.name != "uncertainty"]
    view["uncertainty_chart"] = next((Markup(svg_of(f)) for f in figures
                                      if f.name == "uncertainty"), None)
    return render_template("report.html.j2", view, FILTERS)


def comparison_html(result: ComparisonResult) -> str:
    """A comparison of bats as one styled HTML5 page."""
    from batcert.reports.compare_view import comparison_view
    return render_template("compare.html.j2", comparison_view(result), FILTERS)


def field_html(result: FieldResult) -> str:
    """An in-play prediction as one styled HTML5 page."""
    from batcert.reports.field_view import field_view
    return render_template("field.html.j2", field_view(result), FILTERS)


def league_html(result: LeagueResult) -> str:
    """A league evaluation as one styled HTML5 page."""
    from batcert.reports.league_view import league_view
    return render_template("league.html.j2", league_view(result), FILTERS)


def sweep_html(result: SweepResult, view: dict | None = None) -> str:
    """A sweep or design study as one styled HTML5 page with its figures; ``view``: its
    :func:`~batcert.reports.sweep_view.sweep_view` without charts, when already made."""
    from batcert.reports.sweep_view import sweep_view, with_charts
    view = sweep_view(result) if view is None else with_charts(view)
    return render_template("sweep.html.j2", view, FILTERS)


def lab_html(result: LabResult) -> str:
    """A lab certificate (``batcert reduce``)."""
    from batcert.reports.lab_view import lab_view
    return render_template("lab.html.j2", lab_view(result), FILTERS)
