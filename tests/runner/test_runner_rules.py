"""Protocol runner (batcert.runner): conditions, impact-location rules, sweet-spot search,
aggregation and verdicts, all with the rigid engine and a ball of Nathan's law (batcert 0.2's
collegiate ball, tests/fixtures/good/ball-nathan-law.yaml) so that every number has a closed
form."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import ImpactBatch, get_engine
from batcert.errors import InputError
from batcert.physics import rigid
from batcert.results.run import RunResult
from batcert.runner.conditions import conditions_from_spec
from batcert.runner.runner import run_protocol

REPO = Path(__file__).resolve().parents[2]
NATHAN_LAW_BALL = REPO / "tests" / "fixtures" / "good" / "ball-nathan-law.yaml"
IN = 0.0254  # [m]
MPH = 0.44704  # [m/s]


@pytest.fixture(scope="module")
def ash():
    """Smith 2001 ash bat: 906 g, CG 0.429 m and MOI 0.209 kg m^2 about a pivot 150 mm from the
    knob, length 0.860 m."""
    return load_bat_any(str(REPO / "bats" / "ash-34.yaml")).built


@pytest.fixture
def protocol(tmp_path):
    """Write a protocol YAML (header added) and load it with its ball."""
    def make(body: str, ball: str = str(NATHAN_LAW_BALL), name: str = "p"):
        path = tmp_path / f"{name}.yaml"
        path.write_text(f"id: {name}\ntitle: test\nreference: test\nversion: '1'\nball: {ball}\n"
                        + textwrap.dedent(body), encoding="utf-8")
        return load_protocol_any(str(path))
    return make


def closed_form(inputs):
    """A shipped protocol with the ball of Nathan's law (module notes)."""
    import dataclasses

    from batcert.specs.ball import load_ball
    return dataclasses.replace(inputs, ball=load_ball(NATHAN_LAW_BALL))


def run(bat, inputs) -> RunResult:
    return run_protocol(bat, inputs.protocol, inputs.ball, get_engine("rigid"),
                        created="2001-01-01T00:00:00+00:00")


def dense_exit_speed(bat, inputs, cond_index, r):
    """Exit speed over impact locations ``r`` [m from pivot] for one condition (rigid engine)."""
    p = inputs.protocol
    cond = conditions_from_spec(p.conditions, bat.model, p.pivot)[cond_index]
    vp, w1 = cond.speeds(r)
    out = get_engine("rigid").solve(bat.model, inputs.ball.model, p.pivot,
                                    ImpactBatch(r, vp, w1), p.support)
    return out.exit_speed


def test_matched_relative_speed(ash):
    """Smith 2001 proposal: the moving body makes the relative speed 60 m/s at the impact point,
    w1 = (V - pitch) / r at every location."""
    inputs = closed_form(load_protocol_any("proposed"))
    res = run(ash, inputs)
    pitch = {"stationary-bat": 60.0, "stationary-ball": 0.0, "pitched-and-swung": 31.0}
    for c in res.conditions:
        r = c.impact_location
        assert c.pitch_speed == pytest.approx(-pitch[c.name])  # stored negative: toward the bat
        assert c.bat_angular_speed == pytest.approx((60.0 - pitch[c.name]) / r, rel=1e-12)
        assert c.relative_speed == pytest.approx(60.0, rel=1e-12)
        assert c.rigid_sweet_spot is None  # Eq. 7 assumes speeds that do not vary with r
    conds = conditions_from_spec(inputs.protocol.conditions, ash.model, 0.15)
    r = np.linspace(0.4, 0.7, 7)
    for cond in conds:
        vp, w1 = cond.speeds(r)
        np.testing.assert_allclose(w1 * r - vp, 60.0, rtol=1e-12)
        assert cond.setup == cond.name


def test_bat_speed_from_tip_sets_w1(ash):
    """NCAA BESR: 66 mph measured 6 in from the tip, pivot 6 in from the knob:
    w1 = v / (L - 6 in - pivot)."""
    res = run(ash, closed_form(load_protocol_any("ncaa-besr")))
    (c,) = res.conditions
    assert c.bat_angular_speed == pytest.approx(66 * MPH / (0.860 - 6 * IN - 6 * IN), rel=1e-12)
    assert c.pitch_speed == pytest.approx(-70 * MPH, rel=1e-12)
    assert c.setup == "pitched-and-swung"



@pytest.mark.parametrize("exponent", [0.0, 0.25, 0.5])
def test_bat_speed_from_moi_scales_w1(ash, protocol, exponent):
    """bat_speed_from_moi: w1 = w1_ref (I / I_ref)^-n with I the bat's MOI about the pivot
    (batcert.physics.swing); the ash bat's I is 0.209 kg m^2 about 150 mm (Smith 2001), the
    reference 0.150 kg m^2 is arbitrary. Both sides are the same closed form: rel=1e-12."""
    inputs = protocol(f"""\
        pivot: 150 mm
        conditions:
          - name: swung
            pitch_speed: 25 mph
            bat_speed: 85 mph
            bat_speed_from_tip: 6 in
            bat_speed_from_moi:
              reference_moi: 0.150 kg*m^2
              exponent: {exponent}
        impact_location:
          rule: sweet-spot
          window: [2 in, 12 in]
        metric: exit-speed
        """)
    (c,) = run(ash, inputs).conditions
    moi = ash.model.moi_about(0.150)
    assert moi == pytest.approx(0.209, rel=2e-3)  # the bat file's measured MOI
    w1_ref = 85 * MPH / (0.860 - 6 * IN - 0.150)
    assert c.bat_angular_speed == pytest.approx(w1_ref * (moi / 0.150) ** -exponent, rel=1e-12)


SWUNG = textwrap.dedent("""\
    pivot: 150 mm
    conditions:
      - name: swung
        pitch_speed: 40 m/s
        bat_angular_speed: 40 rad/s
    impact_location:
      rule: sweet-spot
    metric: exit-speed
""")


def test_sweet_spot_matches_eq7_to_1mm(ash, protocol):
    """With a speed-independent ball COR (Nathan 2000 ball) the rigid exit speed peaks exactly at
    Eq. 7, which for these speeds lies inside the default window (3-30 cm from the tip)."""
    inputs = protocol(SWUNG, ball="nathan-2000")
    res = run(ash, inputs)
    (c,) = res.conditions
    eq7 = float(rigid.rigid_sweet_spot(0.209, 0.145, -40.0, 40.0))
    near, far = 0.860 - 0.150 - 0.30, 0.860 - 0.150 - 0.03
    assert near + 0.01 < eq7 < far - 0.01
    assert c.rigid_sweet_spot == pytest.approx(eq7, rel=1e-9)
    assert abs(c.sweet_spot - eq7) < 1e-3  # the protocol's resolution (default 1 mm)
    assert c.impact_location == c.sweet_spot and not c.at_window_edge
    r = np.arange(near, far, 1e-5)
    assert abs(r[np.argmax(dense_exit_speed(ash, inputs, 0, r))] - eq7) < 2e-5


def test_sweet_spot_with_speed_dependent_cor(ash, protocol):
    """With the collegiate ball's COR falling with relative speed the maximum moves off Eq. 7;
    the search must still find the dense sweep's maximum to the 1 mm resolution."""
    inputs = protocol(SWUNG)
    (c,) = run(ash, inputs).conditions
    r = np.linspace(0.41, 0.68, 27001)  # the window (pivot 150 mm), every 0.01 mm
    best = r[np.argmax(dense_exit_speed(ash, inputs, 0, r))]
    assert abs(c.sweet_spot - best) < 1e-3
    assert abs(c.rigid_sweet_spot - best) > 1e-3  # the two differ here: the test means something


def test_resolution_is_honoured(ash, protocol):
    body = SWUNG.replace("rule: sweet-spot", "rule: sweet-spot\n  resolution: 0.1 mm\n"
                         "  sweep_points: 11")
    (c,) = run(ash, protocol(body, ball="nathan-2000")).conditions
    assert abs(c.sweet_spot - rigid.rigid_sweet_spot(0.209, 0.145, -40.0, 40.0)) < 1e-4


def test_cop_rule_uses_eq4(ash):
    """ASTM-style: impact at the centre of percussion q = I / (M rbar) about the protocol pivot."""
    res = run(ash, closed_form(load_protocol_any("astm-bpf")))  # pivot 150 mm, as measured
    (c,) = res.conditions
    assert c.impact_location == pytest.approx(0.209 / (0.906 * 0.429), rel=1e-9)
    assert res.mass_properties.cop == pytest.approx(c.impact_location, rel=1e-12)


def test_cop_about_another_pivot(ash, protocol):
    """About a 6 in pivot the MOI and CG change (parallel axes) and so does the COP."""
    res = run(ash, protocol("""\
        pivot: 6 in
        conditions:
          - name: stationary-bat
            pitch_speed: 31 m/s
            bat_angular_speed: 0 rad/s
        impact_location:
          rule: cop
        metric: bbcor
    """))
    p = 6 * IN
    rbar = 0.579 - p  # balance point 0.150 + 0.429 m from the knob
    moi = 0.209 - 0.906 * 0.429**2 + 0.906 * rbar**2
    assert res.conditions[0].impact_location == pytest.approx(moi / (0.906 * rbar), rel=1e-9)
    assert res.mass_properties.measured_moi_pivot == pytest.approx(moi, rel=1e-9)
    assert res.mass_properties.measured_cg == pytest.approx(rbar, rel=1e-9)


def test_fixed_from_tip(ash, protocol):
    res = run(ash, protocol("""\
        conditions:
          - name: stationary-bat
            pitch_speed: 31 m/s
            bat_angular_speed: 0 rad/s
        impact_location:
          rule: fixed-from-tip
          from_tip: 6 in
        metric: exit-speed
    """))
    assert res.conditions[0].impact_location == pytest.approx(0.860 - 6 * IN - 6 * IN)


TWO = textwrap.dedent("""\
    conditions:
      - name: slow
        pitch_speed: 20 m/s
        bat_angular_speed: 30 rad/s
      - name: fast
        pitch_speed: 35 m/s
        bat_angular_speed: 55 rad/s
      - name: cannon
        pitch_speed: 50 m/s
        bat_angular_speed: 0 rad/s
    impact_location:
      rule: fixed-from-tip
      from_tip: 15 cm
    metric: exit-speed
""")


@pytest.mark.parametrize("aggregate, fn", [("mean", np.mean), ("min", np.min), ("max", np.max)])
def test_aggregate(ash, protocol, aggregate, fn):
    res = run(ash, protocol(TWO + f"aggregate: {aggregate}\n"))
    values = [c.metric_value for c in res.conditions]
    assert [c.metric_value for c in res.conditions] == [c.exit_speed for c in res.conditions]
    assert len(set(values)) == 3
    assert res.value == pytest.approx(float(fn(values)), rel=1e-15)
    assert res.aggregate == aggregate


def _with_limit(ash, protocol, offset, tolerance):
    value = run(ash, protocol(TWO)).value
    limit = f"limit:\n  max: {value + offset!r} m/s\n  tolerance: {tolerance!r} m/s\n"
    return value, run(ash, protocol(TWO + limit, name="limited"))


@pytest.mark.parametrize("offset, tolerance, verdict", [
    (+0.1, 0.0, "pass"),   # below the limit
    (0.0, 0.0, "pass"),    # at the limit passes
    (-0.1, 0.0, "fail"),   # above the limit
    (-0.1, 0.2, "pass"),   # above the limit but within the tolerance
    (-0.3, 0.2, "fail"),   # beyond limit + tolerance
])
def test_limit_tolerance_verdict_and_margin(ash, protocol, offset, tolerance, verdict):
    """margin = limit + tolerance - value: positive passes, negative fails."""
    value, res = _with_limit(ash, protocol, offset, tolerance)
    assert res.verdict == verdict
    assert res.margin == pytest.approx(offset + tolerance, abs=1e-9)
    assert (res.margin >= 0) == (verdict == "pass")
    assert res.limit == pytest.approx(value + offset) and res.tolerance == pytest.approx(tolerance)


def test_no_limit_no_verdict(ash, protocol):
    res = run(ash, protocol(TWO))
    assert (res.limit, res.margin, res.verdict) == (None, None, None)


def test_at_window_edge_warning(ash, protocol):
    """A stationary rigid bat's exit speed falls monotonically from the pivot: the maximum sits on
    the window's near edge, which the result flags and warns about."""
    res = run(ash, protocol("""\
        pivot: 150 mm
        conditions:
          - name: cannon
            pitch_speed: 31 m/s
            bat_angular_speed: 0 rad/s
          - name: swung
            pitch_speed: 40 m/s
            bat_angular_speed: 40 rad/s
        impact_location:
          rule: sweet-spot
          window: [3 cm, 30 cm]
        metric: exit-speed
    """, ball="nathan-2000"))
    cannon, swung = res.conditions
    assert cannon.at_window_edge and cannon.impact_location == pytest.approx(0.860 - 0.150 - 0.30)
    assert not swung.at_window_edge
    edge = [w for w in res.warnings if "window's edge" in w]
    assert len(edge) == 1 and edge[0].startswith("cannon:")


def test_max_metric(ash, protocol):
    """max-metric with exit speed is the sweet spot; with BESR it is BESR's own maximum, which for
    a rigid bat (recoil grows with r) lies on the window's near edge and is flagged."""
    base = SWUNG.replace("rule: sweet-spot", "rule: max-metric")
    (c,) = run(ash, protocol(base)).conditions
    assert abs(c.impact_location - c.sweet_spot) < 1e-6 and not c.at_window_edge
    inputs = protocol(base.replace("metric: exit-speed", "metric: besr"), name="besr")
    res = run(ash, inputs)
    (c,) = res.conditions
    r = np.linspace(0.860 - 0.150 - 0.30, 0.860 - 0.150 - 0.03, 27001)  # the window, 0.01 mm
    besr = rigid.besr(r, -40.0, 40.0, dense_exit_speed(ash, inputs, 0, r))
    assert abs(c.impact_location - r[np.argmax(besr)]) < 1e-3
    assert c.metric_value == pytest.approx(c.besr) == pytest.approx(besr.max(), rel=1e-6)
    assert c.at_window_edge and any("window's edge" in w for w in res.warnings)


def test_sweep_spans_the_window(ash):
    res = run(ash, closed_form(load_protocol_any("ncaa-besr")))
    (c,) = res.conditions
    grid = np.array(c.sweep.impact_location)
    pivot = 6 * IN
    assert grid[0] == pytest.approx(0.860 - pivot - 12 * IN)
    assert grid[-1] == pytest.approx(0.860 - pivot - 2 * IN)
    assert len(grid) == len(c.sweep.exit_speed) == len(c.sweep.metric) == 36
    assert np.all(np.diff(grid) > 0)


def test_besr_conditions_consistent(ash):
    """Every per-condition quantity agrees with the closed forms at the located point."""
    res = run(ash, closed_form(load_protocol_any("ncaa-besr")))
    (c,) = res.conditions
    moi, m = res.mass_properties.moi_pivot, 5.125 * 0.028349523125
    r, vp, w1, vb, w2 = (c.impact_location, c.pitch_speed, c.bat_angular_speed, c.exit_speed,
                         c.bat_angular_speed_after)
    assert moi * w1 + m * vp * r == pytest.approx(moi * w2 + m * vb * r, rel=1e-12)  # Eq. 1
    assert c.cor == pytest.approx((w2 * r - vb) / (vp - w1 * r), rel=1e-12)  # Eq. 3
    assert c.besr == pytest.approx((vb - (w1 * r + vp) / 2) / (w1 * r - vp), rel=1e-12)  # Eq. 2
    assert c.bpf == pytest.approx(c.cor / c.ball_cor, rel=1e-12)  # Eq. 5
    k = m * r**2 / moi
    assert c.collision_efficiency == pytest.approx((c.cor - k) / (1 + k), rel=1e-9)
    assert c.bbcor == pytest.approx(c.cor, rel=1e-9)  # pivoted rigid bat: BBCOR = e
    assert c.cop == pytest.approx(res.mass_properties.cop)


def test_rigid_bpf_warning(ash):
    # A rigid bat's BPF only reflects the ball's smaller loss when it is squeezed less against a
    # recoiling bat: e = e_b(v / sqrt(1 + k)) over e_b(v) for Nathan's law
    # (physics/balls/hysteresis.py; the viscoelastic ball likewise loses less when squeezed
    # less), slightly above 1 for a ball whose COR falls with speed; the engine says BPF needs the flexible engine.
    inputs = closed_form(load_protocol_any("astm-bpf"))
    res = run(ash, inputs)
    c = res.conditions[0]
    k = inputs.ball.model.mass * c.impact_location**2 / ash.model.moi_about(0.150)
    ball = inputs.ball.model
    expected = float(ball.cor(c.relative_speed / math.sqrt(1 + k)) / ball.cor(c.relative_speed))
    assert c.bpf == pytest.approx(expected, rel=1e-12) and 1.0 < c.bpf < 1.02
    assert any("use the flexible engine for a meaningful BPF" in w for w in res.warnings)


def test_window_beyond_the_pivot_is_refused(ash, protocol):
    inputs = protocol(TWO.replace("rule: fixed-from-tip\n  from_tip: 15 cm",
                                  "rule: sweet-spot\n  window: [3 cm, 80 cm]"))
    with pytest.raises(InputError, match=r":\d+: impact_location.window: the search window "
                       "reaches 80.0 cm from the tip: it must end at least 1 cm short of the pivot"):
        run(ash, inputs)


def test_results_round_trip(ash):
    res = run(ash, closed_form(load_protocol_any("proposed")))
    again = RunResult.from_dict(res.to_dict())
    assert again == res
    assert math.isfinite(again.value)
    assert [i.role for i in res.inputs] == ["bat", "protocol", "ball"]


def test_flat_metric_uses_the_sweet_spot_with_a_warning():
    # Rigid engine with the ball's COR taken at the relative speed (batcert 0.1's rule),
    # stationary bat: BBCOR equals that COR at every location (Smith 2001 Eq. 3 with Eq. 1), so
    # max-metric has no maximum; the runner says so and uses the sweet spot.
    from batcert.engines.rigid import RigidEngine
    inputs = closed_form(load_protocol_any("ncaa-bbcor"))
    result = run_protocol(load_bat_any("ash-34").built, inputs.protocol, inputs.ball,
                          RigidEngine(ball_loss="relative-speed"))
    c = result.conditions[0]
    assert c.impact_location == c.sweet_spot
    assert any("does not vary with impact location" in w for w in result.warnings)
