"""Hand-written SVG for report charts: data types, palette, ticks, a canvas and axes.

The charts themselves (a line chart, a grouped bar chart) are in :mod:`batcert.reports.charts`.

Pure functions that return an SVG document as a string (no matplotlib: it would dominate start-up
time). The SVG has a ``viewBox`` so it scales to the width of its container, uses no element ids
(several charts can sit in one HTML page), escapes every piece of text and draws with the
Okabe-Ito colour-blind-safe palette plus a dash pattern per series, so series stay distinguishable
when printed in grey. Numbers are plotted as given; the charts know nothing about units beyond the
axis titles they are handed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from html import escape
from itertools import pairwise

# Okabe & Ito (2008) colour-blind-safe palette, yellow left out (too pale on white).
PALETTE = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000")
DASHES = ("", "7 3", "2 3", "9 3 2 3", "4 4", "1 2", "12 4")
INK, MUTED, GRID = "#222222", "#555555", "#d9d9d9"
FONT = "system-ui, -apple-system, 'Segoe UI', Roboto, Helvetica, Arial, sans-serif"
_CHAR_W = 0.58  # mean glyph width as a fraction of the font size, for layout estimates


@dataclass(frozen=True)
class Series:
    """One line of a line chart; non-finite y values break the line."""

    name: str
    x: Sequence[float]
    y: Sequence[float]


@dataclass(frozen=True)
class BarSeries:
    """One group member of a bar chart: a value per category (None = no bar).

    ``style`` picks the colour (default: the series' position), so that one bat keeps one
    colour across charts; ``shade`` draws the bar lighter (a second quantity of the same bat);
    ``errors`` draws a (low, high) interval on each bar (None = none)."""

    name: str
    values: Sequence[float | None]
    style: int | None = None
    shade: bool = False
    errors: Sequence[tuple[float, float] | None] | None = None


@dataclass(frozen=True)
class VLine:
    """A labelled vertical marker line, e.g. the centre of percussion."""

    x: float
    label: str
    color: str = MUTED


@dataclass(frozen=True)
class Point:
    """A highlighted point, drawn as an open circle; ``series`` picks its colour."""

    x: float
    y: float
    series: int = 0
    label: str = ""


@dataclass(frozen=True)
class SecondaryAxis:
    """A second scale of an axis, showing ``value * scale + offset``: a right-hand y axis (m/s
    on the left, mph on the right) or a second row under the x axis (metres from the pivot,
    inches from the tip: a negative scale)."""

    label: str
    scale: float
    offset: float = 0.0

    def shown(self, value: float) -> float:
        return value * self.scale + self.offset

    def value(self, shown: float) -> float:
        return (shown - self.offset) / self.scale


def color(i: int) -> str:
    return PALETTE[i % len(PALETTE)]


def dash(i: int) -> str:
    """The dash pattern of series ``i``: beyond the palette's length the patterns shift by one,
    so no two of the first 49 series share both colour and dash."""
    return DASHES[(i + i // len(PALETTE)) % len(DASHES)]


def nice_ticks(lo: float, hi: float, max_ticks: int = 6) -> list[float]:
    """Round tick values (1, 2, 5 x 10^n steps) covering ``[lo, hi]``, at most ``max_ticks``."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return []
    if hi < lo:
        lo, hi = hi, lo
    if hi == lo:
        return [lo]
    step = _nice_step((hi - lo) / max(max_ticks - 1, 1))
    while (math.floor(hi / step + 1e-9) - math.ceil(lo / step - 1e-9) + 1) > max_ticks:
        step = _nice_step(step * 1.01)
    first, last = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
    return [_clean(k * step) for k in range(first, last + 1)]


def _nice_step(raw: float) -> float:
    exponent = math.floor(math.log10(raw))
    base = 10.0**exponent
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        if raw <= m * base * (1 + 1e-9):
            return m * base
    return 10.0 * base


def _clean(v: float) -> float:
    v = float(f"{v:.12g}")
    return 0.0 if v == 0 else v


def nice_domain(lo: float, hi: float, pad: float = 0.05, max_ticks: int = 6) -> tuple[float, float]:
    """Widen ``[lo, hi]`` by ``pad`` of its span and out to the neighbouring round ticks."""
    if hi - lo <= 1e-9 * max(abs(lo), abs(hi)):  # equal, or apart only by rounding noise
        mid = (lo + hi) / 2
        half = abs(mid) * 0.1 or 1.0
        lo, hi = mid - half, mid + half
    span = hi - lo
    lo, hi = lo - pad * span, hi + pad * span
    step = _nice_step(span / max(max_ticks - 1, 1))
    return math.floor(lo / step) * step, math.ceil(hi / step) * step


def tick_labels(ticks: Sequence[float]) -> list[str]:
    """Format ticks with just enough decimals to tell them apart (minus sign, not hyphen)."""
    if len(ticks) < 2:
        return [_num(t, 3) for t in ticks]
    step = min(abs(b - a) for a, b in pairwise(ticks))
    decimals = max(0, -math.floor(math.log10(step) + 1e-9)) if step > 0 else 3
    if step > 0 and abs(round(step / 10.0**-decimals, 6) % 1) > 1e-6:
        decimals += 1  # steps such as 0.25
    return [_num(t, decimals) for t in ticks]


def _num(v: float, decimals: int) -> str:
    text = f"{v:,.{decimals}f}"
    return "\u2212" + text[1:] if text.startswith("-") and float(v) != 0 else text.lstrip("-")


def text_width(text: str, size: float) -> float:
    return len(text) * size * _CHAR_W


def fmt_xy(v: float) -> str:
    return f"{v:.1f}"


class Canvas:
    """Collects SVG elements; all text goes through :func:`html.escape`."""

    def __init__(self, width: int, height: int, title: str):
        self.width, self.height = width, height
        self.parts: list[str] = [
            f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" '
            f'width="{width}" height="{height}" role="img" font-family="{escape(FONT)}" '
            f'font-size="12" class="chart">',
            f"<title>{escape(title or 'chart')}</title>",
            f'<rect x="0" y="0" width="{width}" height="{height}" fill="#ffffff"/>',
        ]

    def text(self, x: float, y: float, text: str, *, size: float = 12, anchor: str = "start",
             fill: str = INK, weight: str = "normal", rotate: float | None = None) -> None:
        transform = f' transform="rotate({rotate:g} {fmt_xy(x)} {fmt_xy(y)})"' if rotate else ""
        bold = ' font-weight="bold"' if weight != "normal" else ""
        self.parts.append(
            f'<text x="{fmt_xy(x)}" y="{fmt_xy(y)}" font-size="{size:g}" text-anchor="{anchor}" '
            f'fill="{fill}"{bold}{transform}>{escape(text)}</text>'
        )

    def line(self, x1: float, y1: float, x2: float, y2: float, *, stroke: str = INK,
             width: float = 1.0, dasharray: str = "") -> None:
        d = f' stroke-dasharray="{dasharray}"' if dasharray else ""
        self.parts.append(
            f'<line x1="{fmt_xy(x1)}" y1="{fmt_xy(y1)}" x2="{fmt_xy(x2)}" y2="{fmt_xy(y2)}" stroke="{stroke}" '
            f'stroke-width="{width:g}"{d}/>'
        )

    def raw(self, element: str) -> None:
        self.parts.append(element)

    def legend(self, items: Sequence[tuple[str, str, str, str]], left: float, top: float,
               max_width: float) -> None:
        """Draw (name, colour, dash, kind) items in wrapping rows."""
        offsets, _ = legend_layout([item[0] for item in items], max_width)
        for (name, col, dsh, kind), (dx, dy) in zip(items, offsets, strict=True):
            x, cy = left + dx, top + dy + 9
            if kind == "bar":
                self.raw(f'<rect x="{fmt_xy(x)}" y="{fmt_xy(cy - 6)}" width="22" height="12" '
                         f'fill="{col}"/>')
            elif kind == "point":
                self.raw(f'<circle cx="{fmt_xy(x + 11)}" cy="{fmt_xy(cy)}" r="4.5" fill="#ffffff" '
                         f'stroke="{col}" stroke-width="2"/>')
            else:
                d = f' stroke-dasharray="{dsh}"' if dsh else ""
                self.raw(f'<line x1="{fmt_xy(x)}" y1="{fmt_xy(cy)}" x2="{fmt_xy(x + 22)}" y2="{fmt_xy(cy)}" '
                         f'stroke="{col}" stroke-width="2.5"{d}/>')
            self.text(x + 28, cy + 4, name)

    def done(self) -> str:
        return "\n".join(self.parts + ["</svg>"])


def legend_layout(names: Sequence[str], max_width: float) -> tuple[list[tuple[float, float]],
                                                                   float]:
    """Offsets of legend items flowing in rows of ``max_width``, and the legend's height."""
    x, y, row_h, out = 0.0, 0.0, 18.0, []
    for name in names:
        w = 30 + text_width(name, 12) + 16
        if x > 0 and x + w > max_width:
            x, y = 0.0, y + row_h
        out.append((x, y))
        x += w
    return out, (y + row_h if names else 0.0)


def finite(values: Sequence[float | None]) -> list[float]:
    return [float(v) for v in values if v is not None and math.isfinite(v)]


def marker_rows(vlines: Sequence[VLine], lo: float, hi: float, left: float,
                 plot_w: float) -> list[tuple[int, str]]:
    """Stack marker labels in rows so that neighbouring labels do not overlap."""
    ends: list[float] = []  # right edge of the last label in each row
    out: list[tuple[int, str]] = []
    for m in vlines:
        x = left + (m.x - lo) / (hi - lo) * plot_w if hi > lo else left
        w = text_width(m.label, 11)
        anchor = "end" if x + w / 2 > left + plot_w else "start" if x - w / 2 < left else "middle"
        start = x - w if anchor == "end" else x if anchor == "start" else x - w / 2
        row = next((r for r, e in enumerate(ends) if start > e + 6), len(ends))
        if row == len(ends):
            ends.append(0.0)
        ends[row] = start + w
        out.append((row, anchor))
    return out


def runs(xs: Sequence[float], ys: Sequence[float], xr: tuple[float, float],
          yr: tuple[float, float]) -> list[list[tuple[float, float]]]:
    runs: list[list[tuple[float, float]]] = [[]]
    for x, y in zip(xs, ys, strict=True):
        ok = (x is not None and y is not None and math.isfinite(x) and math.isfinite(y)
              and xr[0] <= x <= xr[1] and yr[0] <= y <= yr[1])
        if ok:
            runs[-1].append((float(x), float(y)))
        elif runs[-1]:
            runs.append([])
    return [r for r in runs if r]


def axes(c: Canvas, left: float, top: float, w: float, h: float, xr: tuple[float, float],
          yr: tuple[float, float], x_label: str, y_label: str,
          y2: SecondaryAxis | None, x_ticks: bool = True,
          x2: SecondaryAxis | None = None) -> None:
    """Grid, frame, ticks and axis titles of a plot area (``x2``: a second row of tick labels
    and its title under the x axis's)."""
    yt = nice_ticks(*yr)
    for t, lab in zip(yt, tick_labels(yt), strict=True):
        y = top + h - (t - yr[0]) / (yr[1] - yr[0]) * h
        c.line(left, y, left + w, y, stroke=GRID, width=0.8)
        c.text(left - 6, y + 4, lab, size=11, anchor="end", fill=MUTED)
    if x_ticks:
        xt = nice_ticks(*xr, max_ticks=max(3, min(8, int(w // 70))))
        for t, lab in zip(xt, tick_labels(xt), strict=True):
            x = left + (t - xr[0]) / (xr[1] - xr[0]) * w
            c.line(x, top, x, top + h, stroke=GRID, width=0.8)
            c.line(x, top + h, x, top + h + 4, stroke=INK)
            c.text(x, top + h + 17, lab, size=11, anchor="middle", fill=MUTED)
    c.raw(f'<rect x="{fmt_xy(left)}" y="{fmt_xy(top)}" width="{fmt_xy(w)}" height="{fmt_xy(h)}" fill="none" '
          f'stroke="{INK}" stroke-width="1"/>')
    if x_label:
        c.text(left + w / 2, top + h + 38, x_label, anchor="middle")
    if x2:
        lo, hi = sorted((x2.shown(xr[0]), x2.shown(xr[1])))
        t2 = nice_ticks(lo, hi, max_ticks=max(3, min(8, int(w // 70))))
        for t, lab in zip(t2, tick_labels(t2), strict=True):
            x = left + (x2.value(t) - xr[0]) / (xr[1] - xr[0]) * w
            c.text(x, top + h + 58, lab, size=11, anchor="middle", fill=MUTED)
        c.text(left + w / 2, top + h + 78, x2.label, anchor="middle")
    if y_label:
        c.text(16, top + h / 2, y_label, anchor="middle", rotate=-90)
    if y2:
        lo, hi = sorted((y2.shown(yr[0]), y2.shown(yr[1])))
        t2 = nice_ticks(lo, hi)
        for t, lab in zip(t2, tick_labels(t2), strict=True):
            y = top + h - (y2.value(t) - yr[0]) / (yr[1] - yr[0]) * h
            c.line(left + w, y, left + w + 4, y, stroke=INK)
            c.text(left + w + 7, y + 4, lab, size=11, fill=MUTED)
        c.text(c.width - 10, top + h / 2, y2.label, anchor="middle", rotate=90)
