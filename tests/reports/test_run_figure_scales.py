"""The run report's plots against impact location: the metric's plot draws the protocol's limit,
and both offer the location in inches from the tip (what a lab reads) under metres from the
pivot, in the HTML's SVG and in --figures."""

from __future__ import annotations

import re

from sample import sample_result

from batcert.reports import html
from batcert.reports.figure import svg_of
from batcert.units import INCH


def test_the_metric_plot_draws_the_limit_and_inches_from_the_tip():
    result = sample_result()
    figs = {f.name: f for f in html.run_figures(result)}
    metric = figs.get("metric")
    assert metric is not None, list(figs)
    assert result.limit is not None
    assert [y for y, _ in metric.hlines] == [result.limit + result.tolerance]
    for fig in (figs["exit-speed"], metric):
        mp = result.mass_properties
        # the pivot's own location is (length - pivot) from the tip; the tip is 0 in
        assert fig.x2.shown(0.0) * INCH == mp.length - mp.pivot
        assert abs(fig.x2.shown(mp.length - mp.pivot)) < 1e-12
        text = svg_of(fig)
        assert "Impact location from the tip [in]" in text
    assert re.search(f">limit {re.escape(format(result.limit, 'g'))}", svg_of(metric))


def test_the_figures_carry_the_second_scale(tmp_path):
    from batcert.reports.figures import render
    fig = next(f for f in html.run_figures(sample_result()) if f.name == "metric")
    svg = render(fig, "svg").decode()
    assert "Impact location from the tip [in]" in svg
