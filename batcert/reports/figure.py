"""A report's figures as data: what is plotted, with titles, axes and markers, drawn two ways.

Every chart of every report is first a :class:`LineFigure` or a :class:`BarFigure`. The HTML
report draws it as hand-written inline SVG (:func:`svg_of`, :mod:`batcert.reports.charts`: a few
kB, no start-up cost); ``--figures DIR`` draws the same figure with matplotlib as SVG, PDF and PNG
files for a paper (:mod:`batcert.reports.figures`). One description, so the two cannot disagree.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from batcert.reports.svg import BarSeries, Point, SecondaryAxis, Series, VLine


@dataclass(frozen=True)
class LineFigure:
    name: str  # file stem of the figure, e.g. "exit-speed"
    title: str
    x_label: str
    y_label: str
    series: Sequence[Series]
    caption: str = ""
    vlines: Sequence[VLine] = ()
    hlines: Sequence[tuple[float, str]] = ()  # (y, label), e.g. the protocol's limit
    points: Sequence[Point] = ()
    point_legend: str = ""
    y2: SecondaryAxis | None = None
    x_range: tuple[float, float] | None = None
    x2: SecondaryAxis | None = None  # a second x scale (inches from the tip)


@dataclass(frozen=True)
class BarFigure:
    name: str
    title: str
    y_label: str
    categories: Sequence[str]
    series: Sequence[BarSeries]
    caption: str = ""
    limit: float | None = None
    value_format: str = "{:.3f}"
    baseline: float | None = 0.0
    width: int = 640
    extra: dict = field(default_factory=dict)


Figure = LineFigure | BarFigure


def legend_names(series: Sequence[Series]) -> list[str]:
    """Each line's legend name, with "(same as X)" when its points coincide with an earlier
    line's, so that a line hidden under another is not taken for missing."""
    import math
    names = []
    for i, s in enumerate(series):
        name = s.name
        for t in series[:i]:
            if len(t.x) == len(s.x) and len(s.x) > 0 and all(
                    math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
                    for a, b in zip([*t.x, *t.y], [*s.x, *s.y], strict=True)
                    if not (math.isnan(a) and math.isnan(b))):
                name = f"{s.name} (same as {t.name})"
                break
        names.append(name)
    return names


def named_series(series: Sequence[Series]) -> list[Series]:
    return [Series(n, s.x, s.y) for n, s in zip(legend_names(series), series, strict=True)]


def svg_of(fig: Figure) -> str:
    """The figure as inline SVG for an HTML report."""
    from batcert.reports import charts
    if isinstance(fig, BarFigure):
        return charts.bar_chart(fig.categories, fig.series, title=fig.title, y_label=fig.y_label,
                                limit=fig.limit, value_format=fig.value_format,
                                baseline=fig.baseline, width=fig.width)
    return charts.line_chart(named_series(fig.series), title=fig.title, x_label=fig.x_label,
                             y_label=fig.y_label, vlines=fig.vlines, points=fig.points,
                             point_legend=fig.point_legend, y2=fig.y2, hlines=fig.hlines,
                             x_range=fig.x_range, x2=fig.x2)

