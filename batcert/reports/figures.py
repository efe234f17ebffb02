"""``--figures DIR``: every figure of a report as SVG, PDF and PNG files, drawn with matplotlib.

matplotlib is imported here only, when figures are asked for, so that no command pays its
start-up time otherwise (0.3-0.6 s here). The figures use the report charts' colour-blind-safe
palette and dash patterns, print-legible type (9 pt at 16 cm wide), and are written as one set
like the reports (:func:`batcert.reports.write.write_texts`). The files are reproducible: the
SVG and PDF carry no date and the SVG fixes matplotlib's random ids.
"""

from __future__ import annotations

import io
import math
import textwrap
from collections.abc import Callable, Sequence
from pathlib import Path

from batcert.reports.figure import BarFigure, Figure, LineFigure, named_series
from batcert.reports.svg import PALETTE, dash

FIGURE_FORMATS = ("svg", "pdf", "png")
WIDTH_IN, HEIGHT_IN, DPI = 6.3, 3.6, 200  # 16 cm x 9 cm; PNG at 200 dpi


def _dash(i: int):
    pattern = dash(i)
    return "solid" if not pattern else (0, tuple(float(x) * 0.8 for x in pattern.split()))


def _color(i: int) -> str:
    return PALETTE[i % len(PALETTE)]


def _draw_line(ax, fig: LineFigure) -> None:
    for i, s in enumerate(named_series(fig.series)):
        xs = [x for x, y in zip(s.x, s.y, strict=True)]
        ys = [math.nan if y is None else y for y in s.y]
        ax.plot(xs, ys, color=_color(i), linestyle=_dash(i), linewidth=1.6, label=s.name,
                marker="o" if len(xs) <= 12 else None, markersize=3)
    for v in fig.vlines:
        ax.axvline(v.x, color=v.color, linestyle=(0, (4, 3)), linewidth=1.0)
        ax.annotate(v.label, (v.x, 1.0), xycoords=("data", "axes fraction"), fontsize=8,
                    ha="center", va="bottom", color=v.color)
    for y, label in fig.hlines:
        ax.axhline(y, color="#222222", linestyle=(0, (6, 3)), linewidth=1.2)
        ax.annotate(label, (1.0, y), xycoords=("axes fraction", "data"), fontsize=8,
                    ha="right", va="bottom")
    for k, p in enumerate(fig.points):
        ax.plot([p.x], [p.y], "o", markerfacecolor="white", markeredgecolor=_color(p.series),
                markersize=6, label=fig.point_legend if k == 0 and fig.point_legend else None)
        if p.label:
            ax.annotate(p.label, (p.x, p.y), xytext=(6, 6), textcoords="offset points",
                        fontsize=8, color=_color(p.series))
    if fig.x_range:
        ax.set_xlim(*fig.x_range)
    ax.set_xlabel(fig.x_label)
    if fig.y2 is not None:
        y2 = fig.y2
        sec = ax.secondary_yaxis("right", functions=(y2.shown, y2.value))
        sec.set_ylabel(y2.label)
    if fig.x2 is not None:
        x2 = fig.x2
        sec = ax.secondary_xaxis("bottom", functions=(x2.shown, x2.value))
        sec.spines["bottom"].set_position(("outward", 40))
        sec.set_xlabel(x2.label)


def _draw_bars(ax, fig: BarFigure) -> None:
    n = max(len(fig.series), 1)
    width = 0.8 / n
    for i, s in enumerate(fig.series):
        xs = [k - 0.4 + width * (i + 0.5) for k in range(len(fig.categories))]
        vals = [math.nan if v is None else v for v in s.values]
        bottom = fig.baseline if fig.baseline is not None else 0.0
        col = _color(i if s.style is None else s.style)
        err = None
        if s.errors:
            lo = [v - e[0] if e else 0.0 for v, e in zip(vals, s.errors, strict=True)]
            hi = [e[1] - v if e else 0.0 for v, e in zip(vals, s.errors, strict=True)]
            err = [lo, hi]
        ax.bar(xs, [v - bottom for v in vals], width * 0.92, bottom=bottom, color=col,
               alpha=0.5 if s.shade else 1.0, label=s.name, yerr=err, capsize=3,
               error_kw={"elinewidth": 1.0, "ecolor": "#222222"})
    ax.set_xticks(range(len(fig.categories)), list(fig.categories))
    if sum(len(c) for c in fig.categories) > 60:  # long names (protocol ids) would overlap
        ax.tick_params(axis="x", labelrotation=20)
        for label in ax.get_xticklabels():
            label.set_horizontalalignment("right")
    if fig.baseline is None:
        vals = [v for s in fig.series for v in s.values if v is not None]
        if vals:
            least, most = min(vals), max(vals)
            pad = 0.1 * (most - least or abs(most) or 1.0)
            ax.set_ylim(least - pad, most + pad)
    if fig.limit is not None:
        ax.axhline(fig.limit, color="#222222", linestyle=(0, (6, 3)), linewidth=1.2)
        ax.annotate(f"limit {fig.value_format.format(fig.limit)}", (1.0, fig.limit),
                    xycoords=("axes fraction", "data"), fontsize=8, ha="right", va="bottom")


def render(fig: Figure, fmt: str) -> bytes:
    """One figure in one format (svg, pdf or png) as bytes."""
    return render_formats(fig, (fmt,))[fmt]


def render_formats(fig: Figure, formats: Sequence[str]) -> dict[str, bytes]:
    """One figure in each of ``formats`` (svg, pdf, png) as bytes: built and laid out once,
    then saved in each format (each save draws it once; built per format, with the layout run
    at every save, the 2001 study's 18 figures took 7.4 s in three formats)."""
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure as MplFigure

    with matplotlib.rc_context({"font.size": 9, "axes.titlesize": 10, "legend.fontsize": 8,
                                "svg.hashsalt": "batcert", "axes.grid": True,
                                "grid.color": "#d9d9d9", "grid.linewidth": 0.6,
                                # names come from the user's files: "$\frac{1}$" is text here
                                "text.parse_math": False}):
        n = len(fig.series)
        cols = 2 if max((len(x.name) for x in fig.series), default=0) <= 40 else 1
        least = 1 if isinstance(fig, BarFigure) else 2  # a bar's colour always needs its name
        rows = 0 if n < least else -(-n // cols)  # legend rows below the axes
        extra = 0.5 if getattr(fig, "x2", None) is not None else 0.0  # a second x scale
        f = MplFigure(figsize=(WIDTH_IN, HEIGHT_IN + 0.18 * rows + extra), layout="constrained")
        ax = f.add_subplot()
        (_draw_bars if isinstance(fig, BarFigure) else _draw_line)(ax, fig)  # type: ignore[arg-type]
        ax.set_title(textwrap.fill(fig.title, 64), loc="left", fontweight="bold")
        ax.set_ylabel(fig.y_label)
        if rows:
            f.legend(loc="outside lower center", frameon=False, ncols=cols)
        f.draw_without_rendering()  # the constrained layout, once; then the saves keep it
        f.set_layout_engine("none")
        out = {}
        for fmt in formats:
            buf = io.BytesIO()
            meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None},
                    "png": {}}[fmt]
            f.savefig(buf, format=fmt, dpi=DPI, metadata=meta)
            out[fmt] = buf.getvalue()
    return out


def write_figures(figs: Sequence[Figure], directory: Path, prefix: str,
                  formats: Sequence[str] = FIGURE_FORMATS,
                  on_progress: Callable[[int, int], None] | None = None) -> list[Path]:
    """Every figure in every format, written as one set: ``DIR/<prefix>--<figure>.<fmt>``;
    ``on_progress(figures_done, figures)`` follows the drawing."""
    from batcert.reports.write import write_texts
    files: dict[Path, str | bytes] = {}
    for k, fig in enumerate(figs):
        for fmt, data in render_formats(fig, formats).items():
            files[Path(directory) / f"{prefix}--{fig.name}.{fmt}"] = data
        if on_progress:
            on_progress(k + 1, len(figs))
    return write_texts(files) if files else []


def figures_of(result) -> list[Figure]:
    """Every figure of a result's report (what ``--figures`` writes)."""
    from batcert.results.compare import ComparisonResult
    from batcert.results.run import RunResult
    from batcert.results.sweep import SweepResult
    if isinstance(result, SweepResult):
        from batcert.reports.sweep_view import sweep_figures
        return sweep_figures(result)
    if isinstance(result, RunResult):
        from batcert.reports.html import run_figures
        return run_figures(result)
    from batcert.results.lab import LabResult
    if isinstance(result, LabResult):
        from batcert.reports.lab_view import lab_figures
        return list(lab_figures(result))
    if isinstance(result, ComparisonResult):
        from batcert.reports.compare_view import comparison_figures
        return comparison_figures(result)
    from batcert.results.field import FieldResult
    if isinstance(result, FieldResult):
        from batcert.reports.field_view import field_figures
        return field_figures(result)
    return []  # a league report has no figures
