"""Unit tests of Nathan's ball law and its rigid-wall closed forms
(batcert.physics.balls.hysteresis)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from batcert.physics.balls import PowerLawHysteresis
from batcert.physics.balls import hysteresis as contact

# Nathan's ball (Nathan, Am. J. Phys. 68 (2000) 979; REFERENCE-DATA.md)
MASS, K1, ALPHA = 0.145, 6.53e7, 1.84


def wall_impact_numerically(speed, e0, fraction=0.99):
    """Integrate m u'' = -F(u) against a rigid wall with solve_ivp (independent of the closed
    forms): compression until u' = 0, then restitution until u = 0. Returns cor, contact time,
    max compression, peak force and the central-``fraction`` collision time."""
    beta = contact.restitution_exponent(ALPHA, e0)

    def rhs(t, y, u_max):
        f = contact.contact_force(y[0], u_max, K1, ALPHA, beta)
        return [y[1], -f / MASS, f]

    turn = lambda t, y, u_max: y[1]  # noqa: E731
    turn.terminal, turn.direction = True, -1
    leave = lambda t, y, u_max: y[0] if t > 0 else 1.0  # noqa: E731
    leave.terminal, leave.direction = True, -1
    opts = {"method": "DOP853", "rtol": 1e-12, "atol": 1e-15, "dense_output": True}
    a = solve_ivp(rhs, (0, 0.02), [0.0, speed, 0.0], events=turn, args=(0.0,), **opts)
    u_max = a.y[0, -1]
    b = solve_ivp(rhs, (a.t[-1], 0.02), a.y[:, -1], events=leave, args=(u_max,), **opts)
    t_end, impulse_total = b.t[-1], b.y[2, -1]
    # impulse(t) is monotonic: invert it by bisection on the dense outputs
    def when(j):
        lo, hi = 0.0, t_end
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            imp = (a.sol(mid) if mid <= a.t[-1] else b.sol(mid))[2]
            lo, hi = (mid, hi) if imp < j else (lo, mid)
        return 0.5 * (lo + hi)

    tails = 0.5 * (1 - fraction) * impulse_total
    return {"cor": -b.y[1, -1] / speed, "contact_time": t_end, "max_compression": u_max,
            "peak_force": K1 * u_max**ALPHA,
            "collision_time": when(impulse_total - tails) - when(tails)}


def test_restitution_exponent_at_58_m_s():
    # REFERENCE-DATA.md (D): beta = (1 + 1.84) / 0.53^2 - 1 = 9.11 at 58 m/s
    assert contact.restitution_exponent(ALPHA, 0.53) == pytest.approx(9.11, abs=0.005)


@pytest.mark.parametrize("e0", [0.0, -0.5, 1.2])
def test_restitution_exponent_rejects_impossible_cor(e0):
    with pytest.raises(ValueError, match="COR"):
        contact.restitution_exponent(ALPHA, e0)


def test_force_branches():
    beta = contact.restitution_exponent(ALPHA, 0.5)
    u = np.array([-1e-3, 0.0, 5e-3, 1e-2])
    # before any compression (u_max = 0) the compression branch applies
    np.testing.assert_allclose(contact.contact_force(u, 0.0, K1, ALPHA, beta),
                               [0.0, 0.0, K1 * 5e-3**ALPHA, K1 * 1e-2**ALPHA], rtol=1e-14)
    # restitution from u_m = 1 cm: F = k1 u_m^alpha (u/u_m)^beta, meeting the law at u_m
    f = contact.contact_force(u, 1e-2, K1, ALPHA, beta)
    np.testing.assert_allclose(f[2:], K1 * 1e-2**ALPHA * np.array([0.5**beta, 1.0]), rtol=1e-14)
    assert f[0] == f[1] == 0.0
    # above the previous maximum the compression branch takes over again
    assert contact.contact_force(2e-2, 1e-2, K1, ALPHA, beta) == pytest.approx(K1 * 2e-2**ALPHA)


def test_deformation_work():
    um = 1.5e-2
    stored = K1 * um ** (1 + ALPHA) / (1 + ALPHA)
    # lossless ball: the work is the elastic energy on both branches
    for u in (0.5e-2, um):
        assert contact.deformation_work(u, um, K1, ALPHA, ALPHA) == pytest.approx(
            K1 * u ** (1 + ALPHA) / (1 + ALPHA), rel=1e-12)
    # lossy ball: at separation the work left is the energy lost, (1 - e0^2) of the stored one
    beta = contact.restitution_exponent(ALPHA, 0.5)
    assert contact.deformation_work(0.0, um, K1, ALPHA, beta) == pytest.approx(
        (1 - 0.25) * stored, rel=1e-12)


@pytest.mark.parametrize("speed, e0", [(1.0, 0.66), (11.0, 0.53), (45.0, 0.53), (67.0, 0.53),
                                       (30.0, 1.0), (30.0, 0.3)])
def test_closed_form_matches_numerical_integration(speed, e0):
    # Two independent solutions of the same law: incomplete-beta closed forms vs a DOP853
    # integration at rtol 1e-12; 1e-6 covers the integrator and the bisection on its output.
    exact = contact.rigid_wall_impact(speed, MASS, K1, ALPHA, e0)
    num = wall_impact_numerically(speed, e0)
    for key in ("cor", "contact_time", "max_compression", "peak_force", "collision_time"):
        assert float(getattr(exact, key)) == pytest.approx(num[key], rel=1e-6), key


def test_rigid_wall_cor_is_e0_at_every_speed():
    # the law's energy ratio (1 + alpha) / (1 + beta) = e0^2 does not depend on the speed
    speeds = np.geomspace(0.5, 80.0, 12)
    res = contact.rigid_wall_impact(speeds, MASS, K1, ALPHA, 0.53)
    np.testing.assert_allclose(res.cor, 0.53, rtol=1e-12)
    assert wall_impact_numerically(80.0, 0.53)["cor"] == pytest.approx(0.53, rel=1e-8)
    assert np.all(np.diff(res.contact_time) < 0)  # stiffening law: shorter at higher speed


def test_ball_spec_cor_is_honoured_at_each_speed():
    law = PowerLawHysteresis(K1, ALPHA, (1.0, 25.9, 58.0), (0.64, 0.546, 0.53))
    speeds = np.array([1.0, 10.0, 25.9, 40.0, 58.0, 70.0])
    res = law.wall_impact(MASS, speeds)
    np.testing.assert_allclose(res.cor, law.wall_cor(MASS, speeds), rtol=1e-12)
    np.testing.assert_allclose(res.e0, law.cor_at(speeds))


def test_integrated_wall_impact_matches_the_closed_form():
    # physics/balls/impact1d.py integrates any law against a rigid body; for Nathan's law the
    # closed forms give the same impact: COR, contact time and 99 % collision time to 1e-4
    # (the integration's step: 300 per contact time, the force's sharp fall at separation;
    # measured 6e-6, 1e-5, 4e-5)
    law = PowerLawHysteresis(K1, ALPHA, (1.0, 25.9, 58.0), (0.64, 0.546, 0.53))
    speeds = np.array([1.0, 11.0, 45.0, 67.0])
    exact = law.wall_impact(MASS, speeds)
    integrated = law.body_impact(MASS, speeds)
    np.testing.assert_allclose(integrated.cor, exact.cor, rtol=1e-4)
    np.testing.assert_allclose(integrated.contact_time, exact.contact_time, rtol=1e-4)
    np.testing.assert_allclose(integrated.collision_time, exact.collision_time, rtol=1e-4)
    np.testing.assert_allclose(integrated.max_compression, exact.max_compression, rtol=1e-4)


def test_max_compression_of_a_ball_on_a_heavy_body():
    # the reduced mass m M / (m + M) replaces m for a free body of mass M
    m_red = MASS * 1.0 / (MASS + 1.0)
    assert contact.max_compression(40.0, m_red, K1, ALPHA) < contact.max_compression(
        40.0, MASS, K1, ALPHA)
    assert contact.peak_force(40.0, MASS, K1, ALPHA) == pytest.approx(
        K1 * contact.max_compression(40.0, MASS, K1, ALPHA) ** ALPHA)


def test_bad_arguments():
    with pytest.raises(ValueError, match="fraction"):
        contact.rigid_wall_impact(10.0, MASS, K1, ALPHA, 0.5, fraction=1.0)
    with pytest.raises(ValueError, match="positive"):
        contact.rigid_wall_impact(0.0, MASS, K1, ALPHA, 0.5)
