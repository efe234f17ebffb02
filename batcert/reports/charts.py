"""Report charts as hand-written SVG: a line chart and a grouped bar chart.

Pure functions that return an SVG document as a string (:mod:`batcert.reports.svg` has the
drawing primitives). The SVG has a ``viewBox`` so it scales to its container, uses no element
ids, escapes every piece of text and draws with a colour-blind-safe palette plus a dash pattern
per series, so series stay distinguishable when printed in grey.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from batcert.reports.svg import (
    INK,
    BarSeries,
    Canvas,
    Point,
    SecondaryAxis,
    Series,
    VLine,
    axes,
    color,
    dash,
    finite,
    fmt_xy,
    legend_layout,
    marker_rows,
    nice_domain,
    runs,
    text_width,
)

MIN_PLOT_HEIGHT = 220.0  # [px] the plot area's least height


def line_chart(
    series: Sequence[Series],
    *,
    title: str = "",
    x_label: str = "",
    y_label: str = "",
    vlines: Sequence[VLine] = (),
    points: Sequence[Point] = (),
    point_legend: str = "",
    y2: SecondaryAxis | None = None,
    x_range: tuple[float, float] | None = None,
    y_range: tuple[float, float] | None = None,
    hlines: Sequence[tuple[float, str]] = (),
    width: int = 640,
    height: int = 360,
    x2: SecondaryAxis | None = None,
) -> str:
    """A line chart of several series with axes, ticks, legend and labelled vertical markers.

    ``x_range``/``y_range`` fix the axes (data outside is not drawn); otherwise the x axis fits the
    data and the y axis is padded out to round ticks. ``point_legend`` names the circles drawn
    for ``points`` in the legend (left out when empty).
    """
    (x_lo, x_hi), (y_lo, y_hi) = _line_domains(series, vlines, points, hlines, x_range, y_range)
    left, right = 66.0, (66.0 if y2 else 18.0)
    plot_w = width - left - right
    legend_names = [s.name for s in series] + ([point_legend] if point_legend and points else [])
    title_h = 26.0 if title else 8.0
    legend_h = legend_layout(legend_names, plot_w)[1]
    label_rows = marker_rows(vlines, x_lo, x_hi, left, plot_w)
    n_label_rows = 1 + max((r for r, _ in label_rows), default=-1)
    top = title_h + legend_h + 6 + 14 * n_label_rows
    bottom = 46.0 + (40.0 if x2 else 0.0)
    # the plot keeps a readable height whatever the legend and the second x scale take: the
    # figure grows instead (nine series of a two-parameter sweep squeezed it to 70 px)
    height = max(height + (40 if x2 else 0), int(top + MIN_PLOT_HEIGHT + bottom))
    plot_h = height - top - bottom

    def px(x: float) -> float:
        return left + (x - x_lo) / (x_hi - x_lo) * plot_w

    def py(y: float) -> float:
        return top + plot_h - (y - y_lo) / (y_hi - y_lo) * plot_h

    c = Canvas(width, height, title or y_label)
    if title:
        c.text(left, 18, title, size=14, weight="bold")
    c.legend([(s.name, color(i), dash(i), "line") for i, s in enumerate(series)]
             + ([(point_legend, INK, "", "point")] if point_legend and points else []),
             left, title_h, plot_w)
    axes(c, left, top, plot_w, plot_h, (x_lo, x_hi), (y_lo, y_hi), x_label, y_label, y2,
         x2=x2)
    _draw_markers(c, vlines, label_rows, hlines, (x_lo, x_hi), (y_lo, y_hi),
                  (left, top, plot_w, plot_h), px, py)
    _draw_lines(c, series, points, (x_lo, x_hi), (y_lo, y_hi), px, py)
    return c.done()


def _line_domains(series: Sequence[Series], vlines: Sequence[VLine], points: Sequence[Point],
                  hlines: Sequence[tuple[float, str]], x_range: tuple[float, float] | None,
                  y_range: tuple[float, float] | None
                  ) -> tuple[tuple[float, float], tuple[float, float]]:
    """The x and y ranges of a line chart: those given, else the x range of the data and
    markers (widened by 1 when it is a single value) and the y range padded to round ticks."""
    xs = finite([v for s in series for v in s.x]) + finite([m.x for m in vlines])
    ys = finite([v for s in series for v in s.y]) + finite([p.y for p in points]) \
        + finite([y for y, _ in hlines])
    x_lo, x_hi = x_range or ((min(xs), max(xs)) if xs else (0.0, 1.0))
    if x_lo == x_hi:
        x_lo, x_hi = x_lo - 0.5, x_hi + 0.5
    y_lo, y_hi = y_range or (nice_domain(min(ys), max(ys)) if ys else (0.0, 1.0))
    return (x_lo, x_hi), (y_lo, y_hi)


def _draw_markers(c: Canvas, vlines: Sequence[VLine], label_rows: list[tuple[int, str]],
                  hlines: Sequence[tuple[float, str]], xr: tuple[float, float],
                  yr: tuple[float, float], box: tuple[float, float, float, float],
                  px, py) -> None:
    """The labelled vertical markers (their labels in the rows of ``label_rows``, above the
    plot) and the labelled horizontal lines (e.g. a protocol's limit) within the ranges."""
    left, top, plot_w, plot_h = box
    n_label_rows = 1 + max((r for r, _ in label_rows), default=-1)
    for (row, anchor), m in zip(label_rows, vlines, strict=True):
        if xr[0] <= m.x <= xr[1]:
            x = px(m.x)
            c.line(x, top, x, top + plot_h, stroke=m.color, width=1.2, dasharray="4 3")
            c.text(x, top - 4 - 14 * (n_label_rows - 1 - row), m.label, size=11, anchor=anchor,
                   fill=m.color)
    for y, label in hlines:
        if math.isfinite(y) and yr[0] <= y <= yr[1]:
            c.line(left, py(y), left + plot_w, py(y), stroke=INK, width=1.5, dasharray="8 4")
            c.text(left + plot_w - 4, py(y) - 5, label, size=11, anchor="end")


def _draw_lines(c: Canvas, series: Sequence[Series], points: Sequence[Point],
                xr: tuple[float, float], yr: tuple[float, float], px, py) -> None:
    """The series as polylines (broken where values are missing) and the circled points."""
    for i, s in enumerate(series):
        for run in runs(s.x, s.y, xr, yr):
            pts = " ".join(f"{fmt_xy(px(x))},{fmt_xy(py(y))}" for x, y in run)
            d = f' stroke-dasharray="{dash(i)}"' if dash(i) else ""
            c.raw(f'<polyline points="{pts}" fill="none" stroke="{color(i)}" stroke-width="2.2" '
                  f'stroke-linejoin="round"{d}/>')
            if len(run) == 1:  # a lone point draws no line: mark it so it is not lost
                x, y = run[0]
                c.raw(f'<circle cx="{fmt_xy(px(x))}" cy="{fmt_xy(py(y))}" r="2.5" '
                      f'fill="{color(i)}"/>')
    for p in points:
        if xr[0] <= p.x <= xr[1] and yr[0] <= p.y <= yr[1]:
            c.raw(f'<circle cx="{fmt_xy(px(p.x))}" cy="{fmt_xy(py(p.y))}" r="4.5" '
                  f'fill="#ffffff" stroke="{color(p.series)}" stroke-width="2"/>')
            if p.label:
                c.text(px(p.x) + 7, py(p.y) - 7, p.label, size=10, fill=color(p.series))


def bar_chart(
    categories: Sequence[str],
    series: Sequence[BarSeries],
    *,
    title: str = "",
    y_label: str = "",
    limit: float | None = None,
    limit_label: str = "limit",
    value_format: str = "{:.3f}",
    baseline: float | None = 0.0,
    width: int = 640,
    height: int = 360,
) -> str:
    """Grouped bars: one group per category, one bar per series, each labelled with its value.

    ``limit`` draws a horizontal dashed line (e.g. a protocol's maximum). Bars grow from
    ``baseline`` (zero by default, so bar lengths compare honestly); with ``baseline=None`` the
    axis fits the values and bars grow from its bottom.
    """
    vals = finite([v for s in series for v in s.values]) + finite([limit]) \
        + finite([x for s in series for e in (s.errors or []) if e for x in e])
    lo, hi = (min(vals), max(vals)) if vals else (0.0, 1.0)
    if baseline is not None:
        lo, hi = min(lo, baseline), max(hi, baseline)
    y_lo, y_hi = nice_domain(lo, hi, pad=0.08)
    if baseline is not None and lo >= baseline:
        y_lo = baseline
    elif baseline is not None and hi <= baseline:  # elif: all values at the baseline keep y_hi
        y_hi = baseline
    base = baseline if baseline is not None else y_lo

    left, right = 66.0, 18.0
    plot_w = width - left - right
    title_h = 26.0 if title else 8.0
    legend_h = legend_layout([s.name for s in series], plot_w)[1]
    top, bottom = title_h + legend_h + 10, 40.0
    plot_h = height - top - bottom

    def py(y: float) -> float:
        return top + plot_h - (y - y_lo) / (y_hi - y_lo) * plot_h

    c = Canvas(width, height, title or y_label)
    if title:
        c.text(left, 18, title, size=14, weight="bold")
    c.legend([(s.name, _bar_fill(s, i), "", "bar") for i, s in enumerate(series)], left,
             title_h, plot_w)
    axes(c, left, top, plot_w, plot_h, (0.0, 1.0), (y_lo, y_hi), "", y_label, None,
          x_ticks=False)

    _draw_bars(c, categories, series, value_format, base, (left, top, plot_w, plot_h), py)
    if limit is not None and math.isfinite(limit):
        y = py(limit)
        c.line(left, y, left + plot_w, y, stroke=INK, width=1.5, dasharray="8 4")
        c.text(left + plot_w - 4, y - 5, f"{limit_label} {value_format.format(limit)}",
               size=11, anchor="end")
    return c.done()


def _bar_fill(s: BarSeries, i: int) -> str:
    """The series' colour (its ``style``, else its position), lighter when ``shade``."""
    col = color(i if s.style is None else s.style)
    return col + "80" if s.shade else col  # #RRGGBBAA: half opacity


def _draw_bars(c: Canvas, categories: Sequence[str], series: Sequence[BarSeries],
               value_format: str, base: float, box: tuple[float, float, float, float],
               py) -> None:
    """One group of labelled bars per category (values drawn from ``base``)."""
    left, top, plot_w, plot_h = box
    n_cat, n_ser = max(len(categories), 1), max(len(series), 1)
    group_w = plot_w / n_cat
    bar_w = min(group_w * 0.8 / n_ser, 60.0)
    for k, cat in enumerate(categories):
        gx = left + k * group_w + (group_w - bar_w * n_ser) / 2
        c.text(left + (k + 0.5) * group_w, top + plot_h + 17, cat, anchor="middle")
        for i, s in enumerate(series):
            v = s.values[k] if k < len(s.values) else None
            if v is None or not math.isfinite(v):
                continue
            x = gx + i * bar_w
            y0, y1 = sorted((py(base), py(v)))
            c.raw(f'<rect x="{fmt_xy(x + 1)}" y="{fmt_xy(y0)}" width="{fmt_xy(bar_w - 2)}" '
                  f'height="{fmt_xy(max(y1 - y0, 0.5))}" fill="{_bar_fill(s, i)}"/>')
            err = s.errors[k] if s.errors and k < len(s.errors) else None
            if err is not None and all(math.isfinite(e) for e in err):
                xm, (ya, yb) = x + bar_w / 2, (py(err[0]), py(err[1]))
                c.line(xm, ya, xm, yb, stroke=INK, width=1.3)
                for yy in (ya, yb):
                    c.line(xm - 4, yy, xm + 4, yy, stroke=INK, width=1.3)
            label = value_format.format(v)
            up = v >= base
            ty = py(v) - 4 if up else py(v) + 12
            if text_width(label, 10) > bar_w - 2:
                c.text(x + bar_w / 2 + 3, py(v) - 4 if up else py(v) + 4, label, size=10,
                       anchor="start" if up else "end", rotate=-90)
            else:
                c.text(x + bar_w / 2, ty, label, size=10, anchor="middle")
