"""A two-parameter sweep's figures stay readable: nine lines keep a plot of at least
MIN_PLOT_HEIGHT (they squeezed it to 70 px), no two lines share colour and dash, and axes and
legends name parameters in words ("Pitch speed [m/s]", "bat angular speed 5 rad/s")."""

from __future__ import annotations

import re

from batcert.commands.sweep import plan_sweep, run_sweep
from batcert.reports import charts, svg
from batcert.reports.figure import svg_of
from batcert.reports.sweep_view import sweep_figures


def _grid():
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", ["pitch_speed=50m/s:70m/s:3",
                                                     "bat_angular_speed=0rad/s:40rad/s:9"],
                      engine="rigid")
    return run_sweep(plan)


def test_nine_lines_keep_a_readable_plot_and_words_for_names():
    figs = {f.name: f for f in sweep_figures(_grid())}
    exit_speed = figs["exit-speed"]
    assert exit_speed.x_label == "Pitch speed [m/s]"
    names = [s.name for s in exit_speed.series]
    assert names[:2] == ["bat angular speed 0 rad/s", "bat angular speed 5 rad/s"]
    text = svg_of(exit_speed)
    frame = re.search(r'<rect x="[\d.]+" y="([\d.]+)" width="[\d.]+" height="([\d.]+)" '
                      r'fill="none"', text)
    assert frame and float(frame.group(2)) >= charts.MIN_PLOT_HEIGHT


def test_no_two_of_many_lines_look_alike():
    looks = [(svg.color(i), svg.dash(i)) for i in range(len(svg.PALETTE) * len(svg.DASHES))]
    assert len(set(looks)) == len(looks)
