"""batcert.sweeps.design (``batcert design``): the parameter value at which a protocol's metric
meets its limit, against a root known in closed form.

The closed form: with the rigid engine a pinned bat's BBCOR is the ball's rigid-wall COR at the
wall speed of equal compression, ``e(v / sqrt(1 + k))`` with ``k = m r^2 / I`` (the rigid
engine's docstring; Smith 2001 for k). BBCOR grows with r, so the max-metric rule takes the
window's edge nearest the tip, ``r = L - pivot - 2 in`` for every pitch speed. The ball's COR is
linear between its points (0.546 at 85 ft/s, 0.50 at 71 m/s), so BBCOR = 0.52 has the root
``v* = sqrt(1 + k) * s*`` with ``s*`` read off that segment. ncaa-bbcor's own 0.500 sits where
the ball's COR is held constant, so the tests use a copy with a 0.52 limit.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from batcert.commands.sweep import plan_sweep, run_design, run_sweep
from batcert.model.mass import mass_properties
from batcert.reports.sweep_view import design_statement
from batcert.specs.protocol import load_protocol
from batcert.sweeps.design import margin_at, solve
from batcert.sweeps.variants import ParameterError

IN = 0.0254  # [m]
LIMIT = 0.52


@pytest.fixture
def bbcor_052(fixtures_dir) -> str:
    """tests/fixtures/good/bbcor-052.yaml: ncaa-bbcor with the limit LIMIT."""
    path = fixtures_dir / "good" / "bbcor-052.yaml"
    assert load_protocol(path).limit.max == LIMIT  # the closed form below assumes it
    return str(path)


def closed_form_root(plan) -> float:
    """The pitch speed [m/s] at which the rigid ash bat's BBCOR is the 0.52 limit (docstring)."""
    p, ball = plan.base.protocol, plan.ball.model
    r = plan.built.model.length - p.pivot - 2 * IN
    k = ball.mass * r**2 / mass_properties(plan.built, p.pivot).moi_pivot
    (s1, s2), (e1, e2) = ball.law.cor_speeds[1:], ball.law.cor_values[1:]  # 85 ft/s, 71 m/s
    assert (s1, e1, s2, e2) == pytest.approx((85 * 0.3048, 0.546, 71.0, 0.50))
    s = s1 + (LIMIT - e1) * (s2 - s1) / (e2 - e1)
    return math.sqrt(1 + k) * s


def test_margin_changes_sign_at_the_closed_form_root(bbcor_052):
    """The closed form itself, against the engine (margin_at): one millimetre per second either
    side of it the verdict flips (the margin's slope is about 1e-3 per m/s, so 1 mm/s moves it
    by 1e-6, far above rounding)."""
    plan = plan_sweep("ash-34", bbcor_052, ["pitch_speed=40m/s:75m/s:2"], engine="rigid")
    root = closed_form_root(plan)
    assert 55 < root < 62  # about 58.66 m/s
    assert margin_at(plan, root - 1e-3) < 0 < margin_at(plan, root + 1e-3)
    assert abs(margin_at(plan, root)) < 1e-12  # a few roundings of numbers near 0.5


def test_root_is_the_closed_form(bbcor_052):
    result = run_design("ash-34", bbcor_052, "pitch_speed", "40m/s:75m/s", engine="rigid",
                        tolerance="1e-6 m/s")
    plan = plan_sweep("ash-34", bbcor_052, ["pitch_speed=40m/s:75m/s:9"], engine="rigid")
    assert result.points == [[x] for x in plan.axes[0].values]  # the margin curve, 9 points
    design = result.design
    assert design.parameter == "pitch_speed" and design.tolerance == 1e-6
    assert design.range == [40.0, 75.0]
    (root,) = design.roots
    # Brent's method stops within xtol (1e-6 m/s) of the root, plus rtol 1e-12 of its value
    assert root.value == pytest.approx(closed_form_root(plan), abs=1e-6 + 1e-12 * 60)
    assert root.bracket == [57.5, 61.875]  # the curve's neighbours either side
    assert root.passes_above  # a faster ball rebounds less off the bat
    assert root.evaluations >= 1
    # the engine's impact point is the closed form's r at every point of the curve
    (c,) = result.conditions
    r = plan.built.model.length - plan.base.protocol.pivot - 2 * IN
    assert c.series["impact_location"] == pytest.approx([r] * 9, rel=1e-12)
    text = design_statement(result)
    assert text.startswith("The protocol passes for pitch_speed from 58.66 m/s")
    assert "the end of the range searched" in text


def test_default_tolerance_brackets_the_root(bbcor_052):
    """With the parameter's own tolerance (0.01 m/s) the margin has opposite signs a
    tolerance either side of the reported root."""
    result = run_design("ash-34", bbcor_052, "pitch_speed", "40m/s:75m/s", engine="rigid")
    plan = plan_sweep("ash-34", bbcor_052, ["pitch_speed=40m/s:75m/s:9"], engine="rigid")
    (root,) = result.design.roots
    tol = result.design.tolerance
    assert tol == 0.01
    assert margin_at(plan, root.value - tol) < 0 < margin_at(plan, root.value + tol)


def test_no_root_in_range(bbcor_052):
    result = run_design("ash-34", bbcor_052, "pitch_speed", "40m/s:45m/s", engine="rigid",
                        points=3)
    assert result.design.roots == []
    assert result.verdicts == ["fail"] * 3
    text = design_statement(result)
    assert text.startswith("No pitch_speed from 40 m/s")
    assert "meets the limit: the protocol fails over the whole range" in text
    assert text.endswith("widen the range with --range")


def test_a_protocol_without_a_limit_is_refused():
    with pytest.raises(ParameterError, match="'proposed' sets no limit"):
        run_design("ash-34", "proposed", "relative_speed", "50m/s:70m/s", engine="rigid")


def test_solve_refuses_a_curve_without_a_limit(bbcor_052):
    plan = plan_sweep("ash-34", "proposed", ["relative_speed=50m/s:70m/s:3"], engine="rigid")
    with pytest.raises(ParameterError, match="sets no limit"):
        solve(plan, run_sweep(plan), 0.01)


@pytest.mark.parametrize("tolerance, message", [
    ("0 m/s", "must be above zero"),
    ("0.01", "a unit is required"),
])
def test_bad_tolerance(bbcor_052, tolerance, message):
    with pytest.raises(ParameterError, match=message):
        run_design("ash-34", bbcor_052, "pitch_speed", "40m/s:75m/s", engine="rigid",
                   tolerance=tolerance)


def test_range_needs_two_ends(bbcor_052):
    with pytest.raises(ParameterError, match="two ends"):
        run_design("ash-34", bbcor_052, "pitch_speed", "50m/s", engine="rigid")


def test_flexible_wall_root_is_bracketed(tmp_path):
    """aluminium-34's wall under a 0.55 BBCOR limit, the shipped ball, flexible engine (about
    4 s): BBCOR falls from 0.571 at the nominal 2.7 mm (measured; 0.527 at 125 %, 0.504 at
    175 %) toward the rigid bat's as the wall thickens, so one root lies in 100 %..175 %; the
    margin has opposite signs a tolerance (1 um) either side."""
    path = tmp_path / "bbcor-055.yaml"
    path.write_text((Path(__file__).resolve().parents[2] / "protocols" / "ncaa-bbcor.yaml")
                    .read_text(encoding="utf-8").replace("max: 0.500", "max: 0.55"))
    result = run_design("aluminium-34", str(path), "wall", "100%:175%", engine="flexible",
                        points=3)
    (root,) = result.design.roots
    tol = result.design.tolerance
    assert tol == 1e-6 and root.passes_above
    assert 2.7e-3 < root.value < 1.75 * 2.7e-3
    plan = plan_sweep("aluminium-34", str(path), ["wall=100%:175%:3"], engine="flexible")
    assert margin_at(plan, root.value - tol) < 0 < margin_at(plan, root.value + tol)


def test_the_answer_states_the_bats_mass_and_drop(bbcor_052):
    # Issue 24: design gave a wall at which the bat weighs 22 oz (drop -12) without showing
    # mass or drop. The root now carries the bat there (as every variant: the geometry's mass
    # for a geometric parameter, the measured one otherwise) and the answer states its mass and
    # drop, as a league's drop rule reads them.
    from batcert.units import INCH, OUNCE
    result = run_design("ash-34", bbcor_052, "pitch_speed", "40m/s:75m/s", engine="rigid")
    (root,) = result.design.roots
    plan = plan_sweep("ash-34", bbcor_052, ["pitch_speed=40m/s:75m/s:9"], engine="rigid")
    mp = mass_properties(plan.built, plan.base.protocol.pivot)
    assert root.mass == pytest.approx(mp.mass, rel=1e-12)
    assert root.length == pytest.approx(plan.built.model.length, rel=1e-12)
    drop = root.length / INCH - root.mass / OUNCE
    assert f"(mass 0.906 kg (31.96 oz), drop {drop:.2f})" in design_statement(result)
