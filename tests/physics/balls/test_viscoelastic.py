"""Unit tests of the viscoelastic ball law (batcert.physics.balls.viscoelastic) and its
integration against a rigid body (batcert.physics.balls.impact1d).

Two solvers for one law: batcert's fixed-step RK4 with ETDRK4 stages for the branch variable
(300 steps per estimated contact time) against :func:`reference_impact`, a tight-tolerance
``scipy.integrate.solve_ivp`` (LSODA) integration of the law's ODE written out here,
``mu u'' = -F``, ``F = max(k0 u^a - k1 s, 0)``, ``s' = (u^a - s) / tau``, with events for the
largest compression, the peak force and separation.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from dict_store import forget, installed
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from batcert.physics.balls import Viscoelastic, impact1d
from batcert.specs.ball import load_ball

REPO = Path(__file__).resolve().parents[3]
MASS = 0.145  # [kg] a baseball (5.125 oz)
# a ball of the shipped collegiate ball's order (its fit, rounded; as in tests/engines/test_flexible.py)
LAW = Viscoelastic(5.7e7, 1.68, 0.37, 155e-6)
# Nathan 2000's speeds: the collision-time points of the shipped ball file, and the 85 ft/s COR
SPEEDS = (1.0, 11.0, 25.9, 45.0, 67.0)


def reference_impact(law, mass, speed, recoil=0.0, scale=1.0, fraction=0.99):
    """The ball fired at ``speed`` at a rigid body (effective-mass ratio ``recoil``, stiffness
    factor ``scale``), integrated with solve_ivp (LSODA, rtol 1e-11, atol 1e-12 of each
    component's scale), independent of batcert's integrator. State: compression, its rate,
    the branch variable, the impulse."""
    k0 = law.stiffness * scale
    k1 = k0 * (1.0 - law.relaxed_fraction)
    a, tau = law.exponent, law.relaxation_time
    mu = mass / (1.0 + recoil)

    def measure(y):  # k0 x - k1 s: the force before clipping at zero
        return k0 * max(y[0], 0.0) ** a - k1 * y[2]

    def rhs(t, y):
        f = max(measure(y), 0.0)
        return [y[1], -f / mu, (max(y[0], 0.0) ** a - y[2]) / tau, f]

    def separation(t, y):  # the measure is 0 at first touch too: skip t = 0
        return measure(y) if t > 0 else 1.0

    def top(t, y):  # largest compression: u' falls through 0
        return y[1]

    def force_rate(t, y):  # peak force: dF/dt falls through 0 (while F > 0)
        u = max(y[0], 1e-300)
        return k0 * a * u ** (a - 1) * y[1] - k1 * (u**a - y[2]) / tau

    separation.terminal, separation.direction = True, -1
    top.direction = force_rate.direction = -1
    u_scale = ((1 + a) * mu * speed**2 / (2 * k0)) ** (1 / (1 + a))  # elastic max compression
    atol = 1e-12 * np.array([u_scale, speed, u_scale**a, mu * speed])
    res = solve_ivp(rhs, (0.0, 50 * u_scale / speed), [0.0, speed, 0.0, 0.0], method="LSODA",
                    rtol=1e-11, atol=atol, events=[separation, top, force_rate],
                    dense_output=True)
    assert res.status == 1, res.message  # ended at separation
    y_sep, y_top, y_peak = (res.y_events[i][0] for i in range(3))
    t_sep, impulse = res.t_events[0][0], y_sep[3]

    def when(j):  # the impulse is monotonic in time
        return brentq(lambda t: res.sol(t)[3] - j, 0.0, t_sep, xtol=1e-16, rtol=1e-14)

    tail = 0.5 * (1.0 - fraction) * impulse
    return {"cor": impulse / (mu * speed) - 1.0, "contact_time": t_sep,
            "max_compression": y_top[0], "peak_force": measure(y_peak),
            "force_at_max_compression": measure(y_top),
            "separation_compression": y_sep[0],
            "collision_time": when(impulse - tail) - when(tail),
            "time_of_max_compression": res.t_events[1][0], "time_of_peak_force": res.t_events[2][0],
            "rebound_speed": -y_sep[1]}


@pytest.fixture(scope="module")
def references():
    return {v: reference_impact(LAW, MASS, v) for v in SPEEDS}


# batcert (RK4, 300 steps per estimated contact time) against the reference, relative:
# - cor: 4th-order, measured <= 2.6e-7 (2.5e-6 at 150 steps, 6e-10 at 600);
# - contact time and separation compression: separation interpolated linearly in the contact
#   measure within its step, measured <= 1.4e-5 and <= 6.3e-5;
# - max compression: the largest of the sampled step-end and stage compressions, at most about
#   h^2 u'' / 8 below the top (1.4e-5 of it at 45 m/s), measured <= 1.1e-5;
# - peak force: the largest of the stage forces, whose RK4 predictor compressions overshoot by
#   O(h^2): measured 6.6e-5 to 9.6e-5 above (2.0e-5 at 600 steps, 3.4e-6 at 1200);
# - collision time: the impulse history interpolated linearly between step ends, measured
#   5.0e-5 to 1.1e-4.
TOLERANCES = {"cor": 2e-6, "contact_time": 5e-5, "separation_compression": 2e-4,
              "max_compression": 5e-5, "peak_force": 3e-4, "collision_time": 2e-4}


@pytest.mark.parametrize("speed", SPEEDS)
def test_wall_impact_matches_the_reference_integration(references, speed):
    ref = references[speed]
    got = LAW.wall_impact(MASS, speed)
    assert got.separated.all()
    for key, rtol in TOLERANCES.items():
        assert float(getattr(got, key)[0]) == pytest.approx(ref[key], rel=rtol), key
    # the COR from the impulse is the rebound speed over the approach speed (momentum)
    assert ref["cor"] == pytest.approx(ref["rebound_speed"] / speed, rel=1e-9)


@pytest.mark.parametrize("recoil, scale", [(0.3, 1.0), (0.0, 0.84), (0.5, 0.7)])
def test_body_impact_matches_the_reference_integration(recoil, scale):
    # a rigid bat (reduced mass m / (1 + recoil)) and a softer footprint (scale: a barrel's
    # stiffness ratio); same tolerances as the wall (measured cor <= 2.9e-7, peak force
    # <= 8.9e-5)
    ref = reference_impact(LAW, MASS, 30.0, recoil, scale)
    got = LAW.body_impact(MASS, 30.0, recoil, scale=scale)
    for key, rtol in TOLERANCES.items():
        assert float(getattr(got, key)[0]) == pytest.approx(ref[key], rel=rtol), key


def test_body_impact_rows_are_independent():
    # a batch of impacts (speeds, recoils, scales) gives each row its own impact
    speeds, recoil, scale = np.array([5.0, 30.0, 60.0]), np.array([0.0, 0.2, 0.4]), 0.9
    batch = LAW.body_impact(MASS, speeds, recoil, scale=scale)
    for i in range(3):
        one = LAW.body_impact(MASS, speeds[i], recoil[i], scale=scale)
        # the same steps in another batch: equal to rounding
        np.testing.assert_allclose(batch.cor[i], one.cor[0], rtol=1e-13)
        np.testing.assert_allclose(batch.peak_force[i], one.peak_force[0], rtol=1e-13)


def test_steps_refine_towards_the_reference(references):
    # the COR converges with the step: 150 -> 600 steps per contact time (measured 2.5e-6,
    # 6e-10 at 45 m/s)
    ref = references[45.0]["cor"]
    coarse, fine = (abs(LAW.body_impact(MASS, 45.0, steps=n).cor[0] - ref) for n in (150, 600))
    assert fine < coarse / 100
    assert fine < 1e-8


@pytest.mark.parametrize("speed", SPEEDS)
def test_peak_force_comes_before_the_largest_compression(references, speed):
    # the relaxing branch takes force away while the ball is still being squeezed (Cross 1999)
    ref = references[speed]
    assert 0 < ref["time_of_peak_force"] < ref["time_of_max_compression"] < ref["contact_time"]
    # so the force at the largest compression is below the peak (measured 5-8 % below)
    assert ref["force_at_max_compression"] < 0.99 * ref["peak_force"]


@pytest.mark.parametrize("speed", SPEEDS)
def test_ball_leaves_while_still_compressed(references, speed):
    got = LAW.wall_impact(MASS, speed)
    assert got.separation_compression[0] > 0
    assert references[speed]["separation_compression"] > 0
    # a sizeable part of the largest compression (measured 38-61 %): not a round-off effect
    assert got.separation_compression[0] > 0.1 * got.max_compression[0]
    assert 0 < got.cor[0] < 1


def test_force_is_never_negative():
    u = np.linspace(-5e-3, 3e-2, 71)[:, None]
    s = np.linspace(0.0, 2.0 * 3e-2**LAW.exponent, 41)[None, :]  # up to twice the largest x
    f = LAW.force(u, s)
    assert f.shape == (71, 41)
    assert np.all(f >= 0)
    assert np.any(f == 0) and np.any(f > 0)  # the clip is reached on this grid
    # where k0 x > k1 s the force is the law's, not clipped
    x = np.maximum(u, 0) ** LAW.exponent
    k1 = LAW.stiffness * (1 - LAW.relaxed_fraction)
    push = LAW.stiffness * x - k1 * s
    np.testing.assert_allclose(f[push > 0], push[push > 0], rtol=1e-14)
    # the march: a squeeze released faster than the branch relaxes (1 mm in 10 us, back in
    # 2 us; tau = 155 us) drives the contact measure negative, the stage forces stay >= 0
    state = LAW.march_rows(1, MASS).for_step(1e-6)
    path = np.concatenate([np.linspace(0, 1e-3, 11), np.linspace(1e-3, 0, 3)[1:], np.zeros(3)])
    forces, measures = [], []
    for u0, u1 in zip(path[:-1], path[1:], strict=True):
        um = np.array([0.5 * (u0 + u1)])
        forces += [state.start(np.array([u0])), state.half_a(um), state.half_b(um),
                   state.end(np.array([u1]))]
        measures.append(state.finish(np.array([u1])))
    assert min(measures) < 0
    assert min(float(f[0]) for f in forces) == 0.0


def test_quasi_static_force_is_the_relaxed_spring():
    u = np.array([-1e-3, 0.0, 1e-3, 3.175e-3, 1e-2])
    expected = 0.37 * 5.7e7 * np.maximum(u, 0) ** 1.68  # r k0 u^a, nothing for u <= 0
    np.testing.assert_allclose(LAW.quasi_static_force(u), expected, rtol=1e-14)
    assert LAW.relaxed_stiffness == pytest.approx(0.37 * 5.7e7, rel=1e-15)
    # a fully relaxed branch (s = x) leaves the relaxed spring's force
    x = 1e-2**1.68
    assert LAW.force(1e-2, x) == pytest.approx(LAW.quasi_static_force(1e-2), rel=1e-13)
    assert LAW.describe()["relaxed_stiffness"] == LAW.relaxed_stiffness


def test_lossless_limit_returns_all_the_energy():
    # relaxed_fraction = 1: no Maxwell branch, an elastic u^a spring, COR 1. Measured 1 + 8.0e-7
    # at every speed: the last step's impulse up to separation is a trapezoid of a force that
    # vanishes as (t_sep - t)^a, an O((1/300)^(1+a)) error
    law = dataclasses.replace(LAW, relaxed_fraction=1.0)
    res = law.body_impact(MASS, np.array([1.0, 11.0, 45.0, 150.0]))
    np.testing.assert_allclose(res.cor, 1.0, atol=2e-6)
    ref = reference_impact(law, MASS, 45.0)
    assert ref["cor"] == pytest.approx(1.0, abs=1e-9)  # the reference conserves energy
    # a nearly lossless ball loses nearly nothing
    assert 0.99 < dataclasses.replace(LAW, relaxed_fraction=0.999).body_impact(MASS, 45.0).cor[0] < 1


@pytest.mark.parametrize("field, value", [
    ("stiffness", 0.0), ("stiffness", -1.0), ("exponent", 0.99), ("exponent", 3.01),
    ("relaxed_fraction", 0.0), ("relaxed_fraction", 1.01), ("relaxation_time", 0.0),
    ("relaxation_time", -1e-4), ("stiffness", float("nan")),
])
def test_out_of_range_parameters_are_refused(field, value):
    with pytest.raises(ValueError, match="out of range"):
        dataclasses.replace(LAW, **{field: value})


def test_edge_parameters_are_accepted():
    for params in ((1e3, 1.0, 1.0, 1e-6), (1e13, 3.0, 1e-6, 1.0)):
        assert Viscoelastic(*params).exponent == params[1]


def test_branch_relaxation_is_exact_for_quadratic_forcing():
    # ETDRK4 (Cox & Matthews 2002) on s' = (x - s) / tau integrates the relaxation exactly: for
    # a forcing x(t) quadratic in time the stages give the exact convolution to rounding, at
    # steps of 0.3, 1 and 3 tau (exponent 1: x = u). Exact solutions, s(0) = 0, T = t / tau:
    # x = 1 -> 1 - e^-T; x = T -> T - 1 + e^-T; x = T^2 -> T^2 - 2T + 2 (1 - e^-T)
    law = dataclasses.replace(LAW, exponent=1.0)
    tau = law.relaxation_time
    exact = {0: lambda T: 1 - np.exp(-T), 1: lambda T: T - 1 + np.exp(-T),
             2: lambda T: T**2 - 2 * T + 2 * (1 - np.exp(-T))}
    h = np.array([0.3, 1.0, 3.0]) * tau
    for degree, solution in exact.items():
        state = law.march_rows(3, MASS).for_step(h)
        x = lambda t, d=degree: 1e-3 * (t / tau) ** d  # noqa: E731
        t = np.zeros(3)
        for _ in range(10):
            state.start(x(t))
            state.half_a(x(t + h / 2))
            state.half_b(x(t + h / 2))
            state.end(x(t + h))
            t = t + h
            measure = state.finish(x(t))
        s = 1e-3 * solution(t / tau)
        np.testing.assert_allclose(state.s[:, 0], s, rtol=1e-13)  # measured 4e-16 (one branch)
        # the contact measure is k0 x - k1 s, negative once the branch holds more than r x
        k1 = law.stiffness * (1 - law.relaxed_fraction)
        np.testing.assert_allclose(measure, law.stiffness * x(t) - k1 * s, rtol=1e-12)


def test_march_rows_take_keeps_rows():
    # rows taken mid-integration carry on as they would have in the whole batch
    scale, h = np.array([1.0, 0.9, 0.8, 0.7]), np.array([1e-6, 2e-6, 3e-6, 4e-6])
    state = LAW.march_rows(4, MASS, scale=scale).for_step(h)

    def step(st, u):
        st.start(u)
        st.half_a(u + 1e-4)
        st.half_b(u + 1e-4)
        st.end(u + 2e-4)
        return st.finish(u + 2e-4)

    u = np.array([1e-3, 2e-3, 3e-3, 4e-3])
    step(state, u)
    keep = np.array([1, 3])
    kept = state.take(keep)
    whole = step(state, u + 2e-4)
    part = step(kept, u[keep] + 2e-4)
    np.testing.assert_array_equal(part, whole[keep])
    np.testing.assert_array_equal(kept.s, state.s[keep])


def test_contact_time_estimate():
    # 3 u_m / v, u_m the elastic spring's largest compression; a linear spring's is
    # 3 sqrt(mu / k) at any speed (its half period: pi sqrt(mu / k))
    speeds = np.array([1.0, 10.0, 100.0])
    np.testing.assert_allclose(impact1d.contact_time_estimate(speeds, 0.145, 1e6, 1.0),
                               3 * np.sqrt(0.145 / 1e6), rtol=1e-14)
    # a stiffening spring: u_m ~ v^(2 / (1 + a)), so the time goes as v^(-(a - 1) / (a + 1))
    t = impact1d.contact_time_estimate(speeds, 0.145, 5.7e7, 1.68)
    np.testing.assert_allclose(t[1:] / t[:-1], 10.0 ** (-0.68 / 2.68), rtol=1e-13)


@pytest.fixture(scope="module")
def collegiate():
    ball = load_ball(REPO / "protocols" / "balls" / "collegiate-baseball.yaml").model
    return float(ball.mass), ball.law


def test_collegiate_ball_cor_falls_with_speed(collegiate):
    # the fitted shipped ball: a shortening pulse against its relaxation time loses more
    mass, law = collegiate
    assert isinstance(law, Viscoelastic)
    speeds = np.geomspace(1.0, 26.0, 12)
    cor = law.wall_cor(mass, speeds)
    assert np.all(np.diff(cor) < 0)
    # its file's points: 0.65 +/- 0.01 (uniform) at 1 m/s, 0.546 +/- 0.032 (uniform) at 85 ft/s
    assert 0.64 <= cor[0] <= 0.66
    assert 0.514 <= float(law.wall_cor(mass, 25.908)) <= 0.578


def test_wall_cor_table_matches_direct_integration(collegiate):
    # impact1d.wall_table: four-point Lagrange in log speed between 161 speeds, documented
    # within about 1e-5 of the integration (measured 1.2e-7)
    mass, law = collegiate
    speeds = np.geomspace(0.2, 250.0, 37)
    direct = law.body_impact(mass, speeds, history=False)
    np.testing.assert_allclose(law.wall_cor(mass, speeds), direct.cor, atol=1e-5)
    np.testing.assert_allclose(impact1d.from_wall_table(law, mass, speeds, "mean_compression"),
                               direct.mean_compression, rtol=1e-4)
    # outside 0.1-300 m/s the wall impact is integrated directly: the same numbers
    outside = np.array([0.05, 400.0])
    np.testing.assert_array_equal(law.wall_cor(mass, outside),
                                  law.body_impact(mass, outside, history=False).cor)
    # at a table speed the table's value itself
    v = impact1d.TABLE_SPEEDS[40]
    table = impact1d.wall_table(law, mass)
    assert law.wall_cor(mass, v) == pytest.approx(table["cor"][40], abs=1e-14)
    assert isinstance(law.wall_cor(mass, 10.0), float)
    assert impact1d.wall_table(law, mass) is table  # one integration per ball
    assert not table["cor"].flags.writeable


def test_a_stored_wall_table_is_the_computed_one_exactly(monkeypatch):
    # The command line keeps a ball's wall table in its cache directory (stores "ball-wall"):
    # a run that reads it must use the very numbers a run that computed it used. A second
    # process is mimicked by emptying the in-process memo; the integration must not run again.
    law = Viscoelastic(5.7e7, 1.68, 0.37, 155e-6)
    with installed("ball-wall") as store:
        computed = {k: v.copy() for k, v in impact1d.wall_table(law, 0.145).items()}
        assert store.saves == 1
        forget("ball-wall")
        monkeypatch.setattr(Viscoelastic, "body_impact",
                            lambda *a, **k: pytest.fail("the table was integrated again"))
        read = impact1d.wall_table(law, 0.145)
        assert store.loads == 2
        for name in ("cor", "mean_compression"):
            np.testing.assert_array_equal(read[name], computed[name])
            assert not read[name].flags.writeable
