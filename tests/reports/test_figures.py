"""batcert.reports.figures (and figure.py): figures as data, drawn by matplotlib as SVG, PDF and
PNG; which figures each result has; and how ``--figures`` names and writes them.

The results are built by hand (tests/reports/sample.py), so no engine runs here; the CLI's
``--figures`` is tested in tests/cli/test_figures_cli.py.
"""

from __future__ import annotations

import copy
import io
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from sample import sample_result

from batcert.analysis.compare import compare
from batcert.reports import figures as figures_module
from batcert.reports.figure import BarFigure, LineFigure
from batcert.reports.figures import (
    DPI,
    HEIGHT_IN,
    WIDTH_IN,
    figures_of,
    render,
    render_formats,
    write_figures,
)
from batcert.reports.svg import BarSeries, Point, SecondaryAxis, Series, VLine
from batcert.results.compare import StudyFigure, StudyFigureBat

pytest.importorskip("matplotlib")

NAN = float("nan")
LINE = LineFigure(
    "line", "A line figure with every marker", "impact location [m]", "exit speed [m/s]",
    [Series("first", [0.4, 0.5, 0.6], [30.0, NAN, 34.0]),  # a gap: a failed variant
     Series("second", [0.4, 0.5, 0.6], [31.0, 33.0, 32.0])],
    vlines=[VLine(0.54, "COP")], hlines=[(33.5, "limit 33.5")],
    points=[Point(0.5, 33.0, 1, "impact point")], point_legend="impact points",
    y2=SecondaryAxis("exit speed [mph]", 2.2369), x_range=(0.35, 0.65))
BAR = BarFigure("bar", "A bar figure", "BBCOR [-]", ["stationary-bat", "stationary-ball"],
                [BarSeries("ash", [0.52, None]), BarSeries("aluminium", [0.53, 0.51])],
                limit=0.5, baseline=None)
SVG = "{http://www.w3.org/2000/svg}svg"


# ---------------------------------------------------------------- render


@pytest.mark.parametrize("fig", [LINE, BAR], ids=["line", "bar"])
def test_svg_is_valid_and_reproducible(fig):
    first, second = render(fig, "svg"), render(fig, "svg")
    assert first == second  # no date, fixed ids (svg.hashsalt): the same file every time
    assert ET.fromstring(first).tag == SVG
    assert b"<dc:date>" not in first


@pytest.mark.parametrize("fig", [LINE, BAR], ids=["line", "bar"])
def test_pdf_is_valid_and_reproducible(fig):
    first, second = render(fig, "pdf"), render(fig, "pdf")
    assert first == second  # no CreationDate: the same file every time
    assert first.startswith(b"%PDF-") and first.rstrip().endswith(b"%%EOF")
    assert b"startxref" in first and b"/CreationDate" not in first


def test_png_is_a_picture_of_the_documented_size():
    from matplotlib.image import imread
    pixels = imread(io.BytesIO(render(LINE, "png")), format="png")
    # 16 cm (6.3 in) wide at 200 dpi; 9 cm (3.6 in) high plus 0.18 in for the one legend row
    # of two series side by side
    assert (WIDTH_IN, HEIGHT_IN, DPI) == (6.3, 3.6, 200)
    assert pixels.shape[:2] == (round((3.6 + 0.18) * 200), round(6.3 * 200))
    assert pixels.min() < 0.5 < pixels.max()  # something is drawn on the white page


def test_svg_draws_the_markers_and_labels():
    # matplotlib draws text as paths and keeps each string in a comment before its glyphs
    text = render(LINE, "svg").decode()
    for label in ("A line figure with every marker", "limit 33.5", "COP", "impact point",
                  "exit speed [mph]", "first", "second", "impact points"):
        assert f"<!-- {label} -->" in text, label
    bar = render(BAR, "svg").decode()
    assert "<!-- limit 0.500 -->" in bar  # the limit in the figure's value format


# ---------------------------------------------------------------- write_figures


@pytest.fixture
def fake_render(monkeypatch):
    """Rendering replaced by a stub (render is tested above): the bytes name what was drawn."""
    drawn = []

    def fake(fig, formats):
        drawn.append(fig.name)  # each figure drawn once, saved in every format
        return {fmt: f"{fig.name} as {fmt}".encode() for fmt in formats}

    monkeypatch.setattr(figures_module, "render_formats", fake)
    return drawn


def test_write_figures_names_every_file_prefix_figure_format(tmp_path, fake_render):
    out = tmp_path / "new" / "figures"  # created
    paths = write_figures([LINE, BAR], out, "ash-34--proposed")
    names = [f"ash-34--proposed--{n}.{x}" for n in ("line", "bar") for x in ("svg", "pdf", "png")]
    assert [p.name for p in paths] == names
    assert sorted(p.name for p in out.iterdir()) == sorted(names)
    assert (out / "ash-34--proposed--bar.pdf").read_bytes() == b"bar as pdf"
    assert fake_render == ["line", "bar"]  # built once per figure, not once per format
    assert write_figures([LINE], out, "x", formats=("png",)) == [out / "x--line.png"]


def test_write_figures_reports_its_progress(tmp_path, fake_render):
    seen = []
    write_figures([LINE, BAR], tmp_path / "f", "p", on_progress=lambda d, n: seen.append((d, n)))
    assert seen == [(1, 2), (2, 2)]


def test_write_figures_writes_all_or_nothing(tmp_path, monkeypatch):
    def fail_on_bar(fig, formats):
        if fig.name == "bar":
            raise RuntimeError("cannot draw")
        return {fmt: b"drawn" for fmt in formats}

    monkeypatch.setattr(figures_module, "render_formats", fail_on_bar)
    with pytest.raises(RuntimeError):
        write_figures([LINE, BAR], tmp_path / "f", "p")
    assert not (tmp_path / "f").exists()  # the line figure, drawn first, was not written


def test_no_figures_write_nothing(tmp_path, fake_render):
    assert write_figures([], tmp_path / "f", "p") == []
    assert not (tmp_path / "f").exists() and fake_render == []


# ---------------------------------------------------------------- figures_of


def test_a_run_has_its_sweeps_as_figures():
    run = sample_result()  # metric BPF: the exit speed and the metric, each against location
    exit_speed, metric = figures_of(run)
    assert (exit_speed.name, metric.name) == ("exit-speed", "metric")
    for fig, key in ((exit_speed, "exit_speed"), (metric, "metric")):
        assert [(s.name, list(s.x), list(s.y)) for s in fig.series] == [
            (c.name, c.sweep.impact_location, getattr(c.sweep, key)) for c in run.conditions]
    assert [(p.x, p.y) for p in exit_speed.points] == [(c.impact_location, c.exit_speed)
                                                       for c in run.conditions]
    assert [(p.x, p.y) for p in metric.points] == [(c.impact_location, c.metric_value)
                                                   for c in run.conditions]


def test_a_run_by_exit_speed_has_one_figure():
    (fig,) = figures_of(sample_result(metric="exit-speed", limit=40.0))
    assert fig.name == "exit-speed"


def _comparison(figures=()):
    """The sample ash run and a copy 2 % better in every condition: P = +2 %."""
    ash = sample_result()
    alu = copy.deepcopy(ash)
    alu.bat = "Aluminium"
    alu.inputs[0].path = "bats/aluminium.yaml"
    for c in alu.conditions:
        c.metric_value *= 1.02
    return compare([[ash], [alu]], figures=figures)


def test_a_comparison_has_overview_protocol_and_study_figures():
    wall = StudyFigure(
        "Wall thickness", "BPF against the wall", "proposed", "pitched and swung", "wall",
        "length", [60.0, 100.0, 140.0], ["bpf"],
        [StudyFigureBat("Aluminium", 0.0027, [0.00162, 0.0027, 0.00378],
                        {"bpf": [1.01, None, 1.03]})])
    speed = StudyFigure(
        "speed", "Sweet spot against swing speed", "proposed", "pitched and swung",
        "bat_angular_speed", "angular_speed", None, ["sweet_spot", "rigid_sweet_spot"],
        [StudyFigureBat(lab, 53.0, [0.0, 30.0, 60.0],
                        {"sweet_spot": [0.52, 0.55, 0.57], "rigid_sweet_spot": [None, 0.55, 0.79]})
         for lab in ("Ash 34 in (Smith 2001)", "Aluminium")])
    figs = figures_of(_comparison([wall, speed]))
    assert [f.name for f in figs] == ["overview", "proposed--metric", "proposed--relative",
                                      "proposed--sweet-spot", "study--wall-thickness",
                                      "study--speed"]
    study = figs[-2]
    assert (study.title, study.x_label) == ("BPF against the wall", "wall [% of nominal]")
    (s,) = study.series
    assert s.name == "Aluminium: BPF" and list(s.x) == [60.0, 100.0, 140.0]
    assert s.y[0] == 1.01 and math.isnan(s.y[1]) and s.y[2] == 1.03  # a failed variant: a gap
    # given in rad/s: plotted against the values themselves; positions share one axis
    by_speed = figs[-1]
    assert (by_speed.x_label, by_speed.y_label) == ("bat_angular_speed [rad/s]",
                                                    "distance from the pivot [m]")
    assert [s.name for s in by_speed.series] == [
        f"{lab}: {q}" for lab in ("Ash 34 in (Smith 2001)", "Aluminium")
        for q in ("sweet spot", "rigid sweet spot (Eq. 7)")]
    assert all(list(s.x) == [0.0, 30.0, 60.0] for s in by_speed.series)


def test_a_comparison_without_differences_has_no_overview():
    ash = sample_result()
    same = copy.deepcopy(ash)
    same.bat = "Copy"
    figs = figures_of(compare([[ash], [same]]))
    # P = 0 everywhere: neither the overview nor the P chart has anything to show
    assert [f.name for f in figs] == ["proposed--metric", "proposed--sweet-spot"]


def test_a_league_has_no_figures():
    from batcert.commands.league import run_league
    repo = Path(__file__).resolve().parents[2]
    league = run_league("mlb", [str(repo / "bats" / "ash-34.yaml")], engine="rigid")
    assert figures_of(league) == []


def test_legend_says_when_curves_coincide():
    """A line drawn exactly under another is named "(same as ...)" in both renderers' legends;
    a line that differs anywhere keeps its name."""
    from batcert.reports.figure import legend_names
    a = Series("stationary-bat", [0.5, 0.6], [40.0, 41.0])
    b = Series("stationary-ball", [0.5, 0.6], [40.0, 41.0])  # the same curve
    c = Series("pitched-and-swung", [0.5, 0.6], [40.0, 41.000001])  # differs by 2.4e-8
    assert legend_names([a, b, c]) == ["stationary-bat", "stationary-ball (same as "
                                       "stationary-bat)", "pitched-and-swung"]


def test_comparison_charts_keep_one_colour_per_bat_and_show_p_ranges():
    """Every comparison chart colours a bat by its place among the bats (the P charts, which
    leave the reference out, too; the COP bar is the bat's colour, lighter), and the overview's
    whiskers span P's range over the conditions around its mean."""
    from batcert.commands.compare import run_comparison
    from batcert.reports.compare_view import comparison_figures
    three = Path(__file__).resolve().parents[2] / "protocols/studies/smith2001-bpf-sweet-spot.yaml"
    result = run_comparison(["ash-34", "aluminium-34", "r161"], [str(three)], engine="rigid")
    labels = [b.label for b in result.bats]
    figs = [f for f in comparison_figures(result) if isinstance(f, BarFigure)]
    for fig in figs:
        for s in fig.series:
            bat = next(lab for lab in labels if s.name == lab or s.name.startswith(f"{lab}: "))
            assert s.style == labels.index(bat), (fig.name, s.name)
            assert s.shade == s.name.endswith("COP (lighter)")
    overview = next(f for f in figs if f.name == "overview")
    p = result.protocols[0]
    for s in overview.series:
        spread = p.relative_spread[s.name]
        (mean,), ((lo, hi),) = s.values, s.errors
        # the chart rounds P to 1e-4 % (as its bars) so that rounding noise sets no axis
        assert lo == pytest.approx(spread.min * 100, abs=5e-5)
        assert hi == pytest.approx(spread.max * 100, abs=5e-5)
        assert lo <= mean <= hi


def test_one_build_saved_in_every_format_is_each_format_built_alone():
    # issue 29: a figure is built and laid out once and saved in each format; what each save
    # gives is what that format built on its own gives
    together = render_formats(LINE, ("svg", "pdf", "png"))
    assert together["svg"] == render(LINE, "svg")
    assert together["pdf"] == render(LINE, "pdf")
    assert together["png"] == render(LINE, "png")
