"""batcert.reports.sweep_view and the sweep templates: the Markdown and HTML of a sweep and of a
design study, their figures, the table's row limit and the design's answer in words.

The sweep is small and rigid (ash-34 under ncaa-bbcor, the pitch speed at 50, 55 and 60 m/s;
a few milliseconds a variant). The design answers are built by hand on it, with the parameter's
nominal set to 50 m/s so that every value reads as a round percent: 55 m/s is "110 % of
nominal".
"""

from __future__ import annotations

import re
from dataclasses import replace

import pytest

from batcert.commands.sweep import plan_sweep, run_sweep
from batcert.reports import sweep_view as view_module
from batcert.reports.figures import figures_of
from batcert.reports.sweep_view import axis_value, design_statement, sweep_figures, sweep_view
from batcert.reports.write import render
from batcert.results.sweep import DesignResult, DesignRoot, SweepResult


@pytest.fixture(scope="module")
def sweep() -> SweepResult:
    return run_sweep(plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:3"], "rigid"))


def _cells(md: str, head: str) -> list[str]:
    """The first cells of the Markdown table whose header row starts with ``head``."""
    lines = md.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(f"| {head}"))
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append(line.split("|")[1].strip())
    return rows


def test_markdown_lists_every_variant(sweep):
    md = render(sweep, "md")
    variants = ["50 m/s (82.24 % of nominal)", "55 m/s (90.46 % of nominal)",
                "60 m/s (98.69 % of nominal)"]  # of ncaa-bbcor's 136 mph = 60.797 m/s
    assert _cells(md, "pitch_speed") == variants  # the summary table, first of its kind
    assert md.count(variants[1]) == 2  # and the condition's table
    assert "variants shown (evenly spaced)" not in md
    for f in sweep_figures(sweep):  # the figures, listed by title
        assert f"- {f.title}" in md


def test_html_draws_every_figure_inline_without_scripts(sweep):
    html = render(sweep, "html")
    figs = sweep_figures(sweep)
    # metric, six per-condition metrics, sweet spot (a protocol parameter: no mass or MOI)
    assert [f.name for f in figs] == ["metric", "exit-speed", "cor", "bpf", "besr", "bbcor",
                                      "collision-efficiency", "sweet-spot"]
    assert html.count("<svg") == len(figs) == html.count("<figure>")
    assert "<script" not in html
    assert figures_of(sweep) == figs  # --figures writes what the report draws


def test_the_metric_figure_draws_the_limit(sweep):
    metric = sweep_figures(sweep)[0]
    # ncaa-bbcor: BBCOR at most 0.50 (tolerance 0); the line is at limit + tolerance
    assert (sweep.limit, sweep.tolerance) == (0.5, 0.0)
    assert list(metric.hlines) == [(0.5, "limit 0.5")]
    assert "the dashed line is its limit" in metric.caption
    assert [v.x for v in metric.vlines] == [sweep.axes[0].nominal]
    assert list(metric.series[0].y) == sweep.series["value"]
    html = render(sweep, "html")
    assert ">limit 0.5</text>" in html  # drawn in the inline SVG


def test_a_sweep_without_a_limit_draws_no_limit_line(sweep):
    metric = sweep_figures(replace(sweep, limit=None))[0]
    assert list(metric.hlines) == [] and "limit" not in metric.caption


def test_more_variants_than_rows_show_an_evenly_spaced_subset(monkeypatch):
    # 7 variants, 4 rows at most: every second one (50, 54, 58, 62 m/s), the last included
    monkeypatch.setattr(view_module, "MAX_ROWS", 4)
    result = run_sweep(plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:62m/s:7"],
                                  "rigid"))
    md = render(result, "md")
    assert [c.split()[0] for c in _cells(md, "pitch_speed")] == ["50", "54", "58", "62"]
    assert "4 of 7 variants shown (evenly spaced); the JSON report holds every variant." in md
    assert "4 of 7 variants shown (evenly spaced)" in render(result, "html")
    view = sweep_view(result, charts=False)
    assert (view["shown_rows"], view["variants"]) == (4, 7)
    assert len(sweep_figures(result)[0].series[0].x) == 7  # the figures keep every variant


def test_the_table_never_shows_more_than_max_rows(monkeypatch, sweep):
    monkeypatch.setattr(view_module, "MAX_ROWS", 4)
    eight = replace(sweep, points=[[50.0 + k] for k in range(8)], errors=[None] * 8)
    assert len(view_module._rows(eight)) <= 4  # shows rows 0, 2, 4, 6 and 7


# ---------------------------------------------------------------- the design's answer


def _design(sweep: SweepResult, roots: list[DesignRoot],
            margins: list[float] | None = None) -> SweepResult:
    axis = replace(sweep.axes[0], nominal=50.0)
    series = dict(sweep.series, margin=margins or sweep.series["margin"])
    return replace(sweep, axes=[axis], series=series,
                   design=DesignResult("pitch_speed", 0.01, roots, [50.0, 60.0]))


def test_axis_value_reads_in_display_units_with_percent_of_nominal(sweep):
    axis = replace(sweep.axes[0], nominal=50.0)
    assert str(axis_value(axis, 55.0)) == "55 m/s (110 % of nominal)"
    # no nominal: US units instead (55 m/s = 123.03 mph)
    us = axis_value(replace(axis, nominal=None), 55.0)
    assert us.si == "55 m/s" and "123" in us.us and "mph" in us.us


def test_design_passing_below_the_root(sweep):
    result = _design(sweep, [DesignRoot(55.0, [50.0, 60.0], 6, passes_above=False)])
    assert design_statement(result) == (
        "The protocol passes for pitch_speed from the start of the range searched, 50 m/s "
        "(100 % of nominal) to 55 m/s (110 % of nominal); the limit is met at 55 m/s (110 % of "
        "nominal)")


def test_design_passing_above_the_root(sweep):
    result = _design(sweep, [DesignRoot(55.0, [50.0, 60.0], 6, passes_above=True)])
    assert design_statement(result) == (
        "The protocol passes for pitch_speed from 55 m/s (110 % of nominal) to 60 m/s (120 % of "
        "nominal), the end of the range searched; the limit is met at 55 m/s (110 % of nominal)")


def test_design_with_two_roots_passes_between_them(sweep):
    roots = [DesignRoot(52.0, [50.0, 55.0], 5, passes_above=True),
             DesignRoot(58.0, [55.0, 60.0], 5, passes_above=False)]
    assert design_statement(_design(sweep, roots)) == (
        "The protocol passes for pitch_speed from 52 m/s (104 % of nominal) to 58 m/s (116 % of "
        "nominal); the limit is met at 52 m/s (104 % of nominal), 58 m/s (116 % of nominal)")


@pytest.mark.parametrize("margins, word, span", [
    ([0.01, 0.02, 0.03], "passes", "+0.01 to +0.03"),
    ([-0.03, -0.02, -0.01], "fails", "-0.03 to -0.01"),
])
def test_design_without_a_root(sweep, margins, word, span):
    assert design_statement(_design(sweep, [], margins)) == (
        f"No pitch_speed from 50 m/s (100 % of nominal) to 60 m/s (120 % of nominal) meets the "
        f"limit: the protocol {word} over the whole range (margin {span}); widen the range with "
        "--range")


def test_design_report_states_the_answer_and_draws_the_margin(sweep):
    result = _design(sweep, [DesignRoot(55.0, [50.0, 60.0], 6, passes_above=False)])
    md = render(result, "md")
    assert "## Design: where the margin is zero" in md
    assert design_statement(result) + ". Each root is located to within 0.01 m/s" in md
    margin = sweep_figures(result)[-1]
    assert margin.name == "margin" and list(margin.hlines) == [(0.0, "limit")]
    assert [(v.x, v.label) for v in margin.vlines] == [(55.0, "root 55 m/s")]
    html = render(result, "html")
    assert html.count("<svg") == len(sweep_figures(result)) and "<script" not in html
    assert re.search(r"<h2>Design: where the margin is zero</h2>", html)
