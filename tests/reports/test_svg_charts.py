"""svg.py: line and bar charts are well-formed, labelled, escaped and robust to awkward data."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from itertools import pairwise

import pytest

from batcert.reports import charts, svg

NS = "{http://www.w3.org/2000/svg}"
NAN = float("nan")


def parse(doc: str) -> ET.Element:
    root = ET.fromstring(doc)
    assert root.tag == f"{NS}svg"
    assert re.fullmatch(r"0 0 \d+ \d+", root.get("viewBox"))
    return root


def texts(root: ET.Element) -> list[str]:
    return [t.text or "" for t in root.iter(f"{NS}text")]


def numbers(root: ET.Element) -> list[float]:
    """Every coordinate-like attribute and polyline point, to check nothing is NaN or inf."""
    out = []
    for el in root.iter():
        for key, value in el.attrib.items():
            if key in ("x", "y", "x1", "x2", "y1", "y2", "cx", "cy", "r", "width", "height"):
                out.append(float(value))
            elif key == "points":
                out += [float(v) for pair in value.split() for v in pair.split(",")]
    return out


def assert_finite_geometry(root: ET.Element) -> None:
    vals = numbers(root)
    assert vals and all(math.isfinite(v) for v in vals)


def tick_values(labels: list[str]) -> list[float]:
    return [float(t.replace("\u2212", "-").replace(",", "")) for t in labels]


def y_tick_labels(root: ET.Element) -> list[str]:
    """Left axis tick labels: the end-anchored, size-11 texts left of the plot area."""
    return [t.text for t in root.iter(f"{NS}text") if t.get("text-anchor") == "end"
            and t.get("font-size") == "11" and float(t.get("x")) < 66]


def x_tick_labels(root: ET.Element) -> list[str]:
    return [t.text for t in root.iter(f"{NS}text")
            if t.get("text-anchor") == "middle" and t.get("font-size") == "11"]


def is_nice(values: list[float]) -> bool:
    """Evenly spaced by 1, 2, 2.5 or 5 x 10^n and all multiples of that step."""
    if len(values) < 2:
        return True
    steps = {round(b - a, 12) for a, b in pairwise(values)}
    if len(steps) != 1:
        return False
    step = steps.pop()
    mantissa = step / 10 ** math.floor(math.log10(step))
    return (any(math.isclose(mantissa, m) for m in (1, 2, 2.5, 5))
            and all(math.isclose(v / step, round(v / step), abs_tol=1e-9) for v in values))


def line(**kw) -> str:
    defaults = dict(
        series=[svg.Series("stationary bat", [0.4, 0.5, 0.6], [20.0, 25.0, 22.0]),
                svg.Series("swung bat", [0.4, 0.5, 0.6], [60.0, 70.0, 66.0])],
        title="Exit speed against impact location", x_label="Impact location [m]",
        y_label="Exit speed [m/s]")
    defaults.update(kw)
    series = defaults.pop("series")
    return charts.line_chart(series, **defaults)


# ---- line chart ----


def test_line_chart_well_formed_and_labelled():
    root = parse(line(vlines=[svg.VLine(0.53, "COP")], points=[svg.Point(0.5, 25.0, 0)],
                      point_legend="impact point",
                      y2=svg.SecondaryAxis("Exit speed [mph]", 1 / 0.44704)))
    t = texts(root)
    for expected in ["Exit speed against impact location", "stationary bat", "swung bat",
                     "Impact location [m]", "Exit speed [m/s]", "Exit speed [mph]", "COP",
                     "impact point"]:
        assert expected in t
    assert root.find(f"{NS}title").text == "Exit speed against impact location"
    lines = root.findall(f"{NS}polyline")
    assert len(lines) == 2
    assert lines[0].get("stroke") != lines[1].get("stroke")
    assert lines[0].get("stroke-dasharray") != lines[1].get("stroke-dasharray")
    assert len(lines[0].get("points").split()) == 3
    assert_finite_geometry(root)
    assert "id=" not in line()  # several charts can share a page


def test_line_chart_ticks_are_nice_and_cover_data():
    root = parse(line())
    ys = tick_values(y_tick_labels(root))
    xs = tick_values(x_tick_labels(root))
    assert len(ys) >= 3 and is_nice(ys), ys
    assert len(xs) >= 3 and is_nice(xs), xs
    assert min(ys) <= 20.0 + 10 and max(ys) >= 70.0 - 10
    assert xs[0] >= 0.4 - 1e-9 and xs[-1] <= 0.6 + 1e-9
    labels = x_tick_labels(root)
    assert len(set(labels)) == len(labels)  # distinguishable
    assert all(len(lab.split(".")[-1]) <= 2 for lab in labels)  # no 0.30000000000000004


def test_line_chart_escapes_text():
    nasty = 'a <b> & "c"'
    doc = line(series=[svg.Series(nasty, [0, 1], [1, 2])], title=f"T {nasty}",
               x_label=f"x {nasty}", y_label=f"y {nasty}", vlines=[svg.VLine(0.5, f"v {nasty}")],
               points=[svg.Point(0.5, 1.5, 0, f"p {nasty}")], point_legend=f"pt {nasty}")
    assert "<b>" not in doc
    root = parse(doc)
    t = texts(root)
    for expected in [nasty, f"T {nasty}", f"x {nasty}", f"y {nasty}", f"v {nasty}",
                     f"p {nasty}", f"pt {nasty}"]:
        assert expected in t


def test_line_chart_single_point():
    root = parse(line(series=[svg.Series("only", [0.5], [30.0])]))
    assert_finite_geometry(root)
    assert "only" in texts(root)
    # a lone point draws no visible line, so it must be marked
    marks = [c for c in root.findall(f"{NS}circle") if c.get("fill") == svg.color(0)]
    assert len(marks) == 1
    ys = tick_values(y_tick_labels(root))
    assert min(ys) < 30.0 < max(ys)


def test_line_chart_nan_breaks_the_line():
    root = parse(line(series=[svg.Series("gappy", [0, 1, 2, 3, 4, 5],
                                         [1.0, 2.0, NAN, 3.0, math.inf, 4.0])]))
    assert_finite_geometry(root)
    runs = [len(p.get("points").split()) for p in root.findall(f"{NS}polyline")]
    assert runs == [2, 1, 1]
    assert len([c for c in root.findall(f"{NS}circle") if c.get("fill") == svg.color(0)]) == 2


def test_line_chart_all_nan_and_empty():
    for series in ([svg.Series("nothing", [0.0, 1.0], [NAN, NAN])], []):
        root = parse(line(series=series))
        assert_finite_geometry(root)
        assert root.findall(f"{NS}polyline") == []


def test_line_chart_negative_values():
    root = parse(line(series=[svg.Series("neg", [0, 1, 2], [-30.0, -10.0, -25.0])]))
    assert_finite_geometry(root)
    labels = y_tick_labels(root)
    assert all(lab.startswith("\u2212") for lab in labels if lab not in ("0", "0.0"))
    ys = tick_values(labels)
    assert min(ys) <= -25 and max(ys) >= -15 and is_nice(ys)


def test_line_chart_all_zero():
    root = parse(line(series=[svg.Series("flat", [0, 1, 2], [0.0, 0.0, 0.0])]))
    assert_finite_geometry(root)
    ys = tick_values(y_tick_labels(root))
    assert min(ys) < 0 < max(ys) and is_nice(ys)
    assert len(root.findall(f"{NS}polyline")) == 1


def test_line_chart_constant_with_rounding_noise():
    """A metric that is 1 by construction (rigid BPF) has noise at 1e-16: the axis must not
    zoom into the noise and show identical tick labels."""
    noisy = [1.0, 0.9999999999999996, 1.0000000000000004, 1.0]
    root = parse(line(series=[svg.Series("bpf", [0, 1, 2, 3], noisy)]))
    labels = y_tick_labels(root)
    assert len(labels) >= 2 and len(set(labels)) == len(labels), labels
    ys = tick_values(labels)
    assert is_nice(ys) and min(ys) < 1.0 < max(ys)
    pts = root.find(f"{NS}polyline").get("points").split()
    assert len({p.split(",")[1] for p in pts}) == 1  # drawn flat


def test_line_chart_vline_outside_range_not_drawn():
    root = parse(line(vlines=[svg.VLine(5.0, "far away")], x_range=(0.4, 0.6)))
    assert "far away" not in texts(root)


def test_line_chart_fixed_ranges_clip_data():
    root = parse(line(y_range=(0.0, 50.0)))
    assert_finite_geometry(root)
    assert tick_values(y_tick_labels(root)) == [0, 10, 20, 30, 40, 50]


# ---- bar chart ----


def bars(root: ET.Element) -> list[ET.Element]:
    return [r for r in root.findall(f"{NS}rect") if r.get("fill") in svg.PALETTE]


def bar(categories=("NCAA", "USSSA"), series=None, **kw) -> str:
    series = series or [svg.BarSeries("ash 34", [0.48, 0.50]),
                        svg.BarSeries("alloy 34", [0.50, 0.52])]
    kw.setdefault("title", "BBCOR by league")
    kw.setdefault("y_label", "BBCOR [-]")
    return charts.bar_chart(list(categories), series, **kw)


def test_bar_chart_well_formed_and_labelled():
    root = parse(bar(limit=0.5, limit_label="limit"))
    t = texts(root)
    for expected in ["BBCOR by league", "ash 34", "alloy 34", "NCAA", "USSSA", "BBCOR [-]",
                     "limit 0.500", "0.480", "0.520"]:
        assert expected in t
    assert len(bars(root)) == 2 * 2 + 2  # four bars and two legend swatches
    assert_finite_geometry(root)
    ys = tick_values(y_tick_labels(root))
    assert ys[0] == 0.0 and is_nice(ys) and max(ys) >= 0.52


def test_bar_chart_escapes_text():
    nasty = "<x> & y"
    doc = bar(categories=[nasty], series=[svg.BarSeries(f"s {nasty}", [1.0])],
              title=f"t {nasty}", y_label=f"y {nasty}", limit=2.0, limit_label=f"l {nasty}")
    t = texts(parse(doc))
    for expected in [nasty, f"s {nasty}", f"t {nasty}", f"y {nasty}", f"l {nasty} 2.000"]:
        assert expected in t


def test_bar_chart_all_zero():
    """Regression: every value 0 used to divide by zero (an empty y range)."""
    root = parse(bar(series=[svg.BarSeries("a", [0.0, 0.0]), svg.BarSeries("b", [0.0, 0.0])]))
    assert_finite_geometry(root)
    ys = tick_values(y_tick_labels(root))
    assert ys[0] == 0.0 and max(ys) > 0 and is_nice(ys)
    assert texts(root).count("0.000") == 4


def test_bar_chart_all_at_nonzero_baseline():
    root = parse(bar(series=[svg.BarSeries("a", [5.0, 5.0])], baseline=5.0))
    assert_finite_geometry(root)


def test_bar_chart_single_value():
    root = parse(bar(categories=["one"], series=[svg.BarSeries("only", [0.7])]))
    assert_finite_geometry(root)
    assert "0.700" in texts(root)
    assert len(bars(root)) == 2


def test_bar_chart_nan_and_missing_values():
    root = parse(bar(series=[svg.BarSeries("a", [NAN, 0.5]), svg.BarSeries("b", [None])]))
    assert_finite_geometry(root)
    assert len(bars(root)) == 1 + 2  # one drawn bar, two legend swatches
    root = parse(bar(series=[svg.BarSeries("a", [NAN, NAN])], limit=NAN))
    assert_finite_geometry(root)


def test_bar_chart_negative_values():
    root = parse(bar(series=[svg.BarSeries("down", [-1.0, -2.5])]))
    assert_finite_geometry(root)
    ys = tick_values(y_tick_labels(root))
    assert ys[-1] == 0.0 and min(ys) <= -2.5 and is_nice(ys)
    root = parse(bar(series=[svg.BarSeries("mixed", [-1.0, 2.0])]))
    ys = tick_values(y_tick_labels(root))
    assert min(ys) <= -1.0 and max(ys) >= 2.0 and 0.0 in ys


def test_bar_chart_empty():
    assert_finite_geometry(parse(charts.bar_chart([], [])))


def test_bar_chart_without_baseline_fits_values():
    root = parse(bar(series=[svg.BarSeries("a", [0.48, 0.52])], baseline=None))
    ys = tick_values(y_tick_labels(root))
    assert min(ys) > 0.3 and is_nice(ys)


# ---- ticks ----


@pytest.mark.parametrize("lo, hi", [(0, 1), (0.41, 0.76), (-3.2, 7.9), (0, 100), (1e-9, 3e-9),
                                    (-250, -10), (12345, 12400), (0.1, 0.3)])
def test_nice_ticks(lo, hi):
    ticks = svg.nice_ticks(lo, hi)
    assert 2 <= len(ticks) <= 6
    assert is_nice(ticks), ticks
    assert lo - 1e-12 <= ticks[0] and ticks[-1] <= hi + 1e-12
    labels = svg.tick_labels(ticks)
    assert len(set(labels)) == len(labels)
    assert tick_values(labels) == pytest.approx(ticks)


def test_nice_ticks_edge_cases():
    assert svg.nice_ticks(1.0, 0.0) == svg.nice_ticks(0.0, 1.0)
    assert svg.nice_ticks(2.0, 2.0) == [2.0]
    assert svg.nice_ticks(0.0, NAN) == []
    assert svg.nice_ticks(0.0, 1.0) == [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]


def test_tick_labels():
    assert svg.tick_labels([0.0, 0.25, 0.5]) == ["0.00", "0.25", "0.50"]
    assert svg.tick_labels([-1.0, 0.0, 1.0]) == ["\u22121", "0", "1"]
    assert svg.tick_labels([-0.0, 0.5]) == ["0.0", "0.5"]
    assert svg.tick_labels([0.0, 1000.0, 2000.0]) == ["0", "1,000", "2,000"]
    assert svg.tick_labels([3.0]) == ["3.000"]


@pytest.mark.parametrize("lo, hi", [(0.0, 0.0), (1.0, 1.0), (-2.0, -2.0),
                                    (0.9999999999999996, 1.0000000000000004), (20.0, 70.0)])
def test_nice_domain(lo, hi):
    d_lo, d_hi = svg.nice_domain(lo, hi)
    assert d_lo < lo <= hi < d_hi
    assert d_hi - d_lo > 1e-6 * max(1.0, abs(lo))
