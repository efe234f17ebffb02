"""Rigid-body impact relations (batcert.physics.rigid) as properties over random inputs.

Equation numbers are those of L. V. Smith, "Evaluating baseball bat performance", Sports
Engineering 4 (2001) 205-214, as listed in DESIGN.md section 1. The inputs are numpy random
draws with a fixed seed: speeds and MOIs spanning bats from light to very heavy, ball-bat COR in
[0, 1], impact points along the barrel.
"""

from __future__ import annotations

import numpy as np
import pytest

from batcert.engines import ImpactBatch, get_engine
from batcert.model.geometry import build_geometry
from batcert.physics import rigid
from batcert.physics.ball import BallModel
from batcert.physics.balls import PowerLawHysteresis, Viscoelastic
from batcert.specs.materials import LIBRARY

N = 2000


@pytest.fixture
def draws():
    """Random impacts: m [kg], I [kg m^2], r [m from pivot], v_p [m/s] (<= 0), w1 [rad/s], e."""
    rng = np.random.default_rng(20010205)  # fixed seed: Sports Eng. 4 (2001) p. 205
    return dict(
        m=rng.uniform(0.1, 0.2, N), moi=rng.uniform(0.05, 0.5, N), r=rng.uniform(0.05, 0.75, N),
        vp=-rng.uniform(0.0, 60.0, N), w1=rng.uniform(0.0, 100.0, N), e=rng.uniform(0.0, 1.0, N))


def _solve(d, e=None):
    """Exit speed and w2 from the closed form (pivoted k) for the draws."""
    e = d["e"] if e is None else e
    k = rigid.recoil_factor_pivoted(d["m"], d["moi"], d["r"])
    vb = rigid.exit_speed(e, k, d["vp"], d["w1"] * d["r"])
    w2 = rigid.bat_angular_speed_after(d["moi"], d["m"], d["r"], d["vp"], d["w1"], vb)
    return vb, w2


def test_exit_speed_solves_momentum_and_restitution(draws):
    """The closed form against an independent solution: Eq. 1 (angular momentum about the pivot)
    and Eq. 3 (the COR) as a 2 x 2 linear system in (v_b, w2), solved numerically per impact:
        m r v_b + I w2 = I w1 + m r v_p
        -v_b + r w2 = e (v_p - w1 r)."""
    d = draws
    a = np.zeros((N, 2, 2))
    a[:, 0, 0], a[:, 0, 1] = d["m"] * d["r"], d["moi"]
    a[:, 1, 0], a[:, 1, 1] = -1.0, d["r"]
    b = np.stack([d["moi"] * d["w1"] + d["m"] * d["r"] * d["vp"],
                  d["e"] * (d["vp"] - d["w1"] * d["r"])], axis=1)
    vb_ref, w2_ref = np.linalg.solve(a, b[..., None])[..., 0].T
    vb, w2 = _solve(d)
    scale = np.abs(d["vp"]) + d["w1"] * d["r"] + 1.0  # speeds up to ~100 m/s
    np.testing.assert_allclose(vb, vb_ref, rtol=0, atol=1e-9 * scale.max())
    np.testing.assert_allclose(w2 * d["r"], w2_ref * d["r"], rtol=0, atol=1e-9 * scale.max())


def test_hand_computed_impact_of_the_study_ash_bat():
    """Smith 2001's ash bat (I = 0.209 kg m^2 about the pivot), a 0.145291 kg ball at r = 0.55 m,
    e = 0.5, v_p = -31 m/s, w1 = 53 rad/s, worked by hand:
    k = m r^2 / I = 0.145291 x 0.3025 / 0.209 = 0.210290; e_A = (0.5 - k) / (1 + k) = 0.239373;
    v_bat = 53 x 0.55 = 29.15 m/s; v_b = e_A x 31 + (1 + e_A) x 29.15 = 7.42056 + 36.12773
    = 43.5483 m/s; w2 = w1 + m r (v_p - v_b) / I = 53 - 0.0799101 x 74.5483 / 0.209 = 24.4969 rad/s.
    Tolerance: the hand values carry 6 significant digits."""
    m, moi, r, e, vp, w1 = 0.145291, 0.209, 0.55, 0.5, -31.0, 53.0
    k = rigid.recoil_factor_pivoted(m, moi, r)
    assert k == pytest.approx(0.210290, rel=2e-6)
    assert rigid.collision_efficiency(e, k) == pytest.approx(0.239373, rel=2e-6)
    vb = rigid.exit_speed(e, k, vp, w1 * r)
    assert vb == pytest.approx(43.5483, rel=2e-6)
    assert rigid.bat_angular_speed_after(moi, m, r, vp, w1, vb) == pytest.approx(24.4969,
                                                                                 rel=2e-6)
    assert rigid.besr(r, vp, w1, vb) == pytest.approx((43.5483 - (29.15 - 31) / 2) / 60.15,
                                                      rel=2e-6)


def test_cor_recovered(draws):
    """Eq. 3 applied to the solved speeds returns the COR that went in."""
    d = draws
    vb, w2 = _solve(d)
    e = rigid.cor_from_speeds(d["r"], d["vp"], d["w1"], vb, w2)
    ok = np.abs(d["vp"] - d["w1"] * d["r"]) > 1e-3  # Eq. 3 is 0/0 without an approach speed
    np.testing.assert_allclose(e[ok], d["e"][ok], rtol=1e-9, atol=1e-12)


def test_closed_form_equals_design_formula(draws):
    """v_b = [(1+e) I w1 r + v_p (m r^2 - e I)] / (I + m r^2) (DESIGN.md, Eqs. 1 and 3)."""
    d = draws
    m, i, r, vp, w1, e = (d[k] for k in ("m", "moi", "r", "vp", "w1", "e"))
    expected = ((1 + e) * i * w1 * r + vp * (m * r**2 - e * i)) / (i + m * r**2)
    vb, _ = _solve(d)
    np.testing.assert_allclose(vb, expected, rtol=1e-12, atol=1e-12)


def test_no_energy_gained(draws):
    """With 0 <= e <= 1 the kinetic energy after impact never exceeds that before; e = 1 keeps
    it exactly."""
    d = draws
    for e in (d["e"], np.ones(N)):
        vb, w2 = _solve(d, e)
        before = 0.5 * d["moi"] * d["w1"] ** 2 + 0.5 * d["m"] * d["vp"] ** 2
        after = 0.5 * d["moi"] * w2**2 + 0.5 * d["m"] * vb**2
        assert np.all(after <= before * (1 + 1e-12) + 1e-12)
    np.testing.assert_allclose(after, before, rtol=1e-10)


def test_sweet_spot_is_the_maximum(draws):
    """Eq. 7 is the location of maximum exit speed: compare with a dense sweep of the closed
    form. The sweep step is 0.1 mm; the maximum is flat, so the sampled argmax lies within one
    step of Eq. 7 (plus the few-step plateau of a flat maximum: allow 0.5 mm)."""
    d = {k: v[:200] for k, v in draws.items()}
    d["w1"] = d["w1"] + 5.0  # Eq. 7 needs a swinging bat
    rs = rigid.rigid_sweet_spot(d["moi"], d["m"], d["vp"], d["w1"])
    r = np.arange(0.0, 6.0, 1e-4)
    for j in range(200):
        if rs[j] > 5.9:  # very heavy, slow bats: the maximum is far off any bat
            continue
        k = rigid.recoil_factor_pivoted(d["m"][j], d["moi"][j], r)
        vb = rigid.exit_speed(d["e"][j], k, d["vp"][j], d["w1"][j] * r)
        assert abs(r[np.argmax(vb)] - rs[j]) < 5e-4
        vb_at = rigid.exit_speed(d["e"][j], rigid.recoil_factor_pivoted(d["m"][j], d["moi"][j],
                                 rs[j]), d["vp"][j], d["w1"][j] * rs[j])
        assert vb_at >= vb.max() - 1e-9


def test_sweet_spot_undefined_for_stationary_bat():
    assert np.isnan(rigid.rigid_sweet_spot(0.2, 0.145, -30.0, 0.0))


def test_besr_is_e_plus_half_when_w2_equals_w1(draws):
    """NCAA BESR assumes w2 = w1, i.e. an infinitely heavy bat: BESR = e + 1/2."""
    d = dict(draws)
    d["moi"] = np.full(N, 1e12)  # infinite-MOI limit: the bat does not recoil
    vb, w2 = _solve(d)
    np.testing.assert_allclose(w2, d["w1"], rtol=1e-9)
    besr = rigid.besr(d["r"], d["vp"], d["w1"], vb)
    ok = d["w1"] * d["r"] - d["vp"] > 1e-3
    np.testing.assert_allclose(besr[ok], d["e"][ok] + 0.5, rtol=1e-8, atol=1e-9)


def test_besr_penalises_light_bats(draws):
    """With recoil (finite MOI) BESR < e + 1/2 (Smith 2001: BESR ignores the bat's MOI)."""
    d = draws
    vb, _ = _solve(d)
    besr = rigid.besr(d["r"], d["vp"], d["w1"], vb)
    ok = d["w1"] * d["r"] - d["vp"] > 1e-3
    assert np.all(besr[ok] < d["e"][ok] + 0.5)


def test_bbcor_from_stationary_bat(draws):
    """A stationary-bat test measures e_A; BBCOR = e_A (1 + k) + k recovers the COR."""
    d = dict(draws)
    d["w1"] = np.zeros(N)
    d["vp"] = np.minimum(d["vp"], -1.0)
    vb, _ = _solve(d)
    e_a = rigid.collision_efficiency_from_speeds(d["r"], d["vp"], d["w1"], vb)
    np.testing.assert_allclose(e_a, vb / -d["vp"], rtol=1e-12)  # e_A = v_b / v_pitch at rest
    k = rigid.recoil_factor_pivoted(d["m"], d["moi"], d["r"])
    np.testing.assert_allclose(rigid.bbcor_from_collision_efficiency(e_a, k), d["e"],
                               rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(rigid.collision_efficiency(d["e"], k), e_a, rtol=1e-9, atol=1e-12)


def test_centre_of_percussion():
    """Eq. 4 for the study's ash bat: q = 0.209 / (0.906 x 0.429) = 0.5377 m from the pivot."""
    assert rigid.centre_of_percussion(0.209, 0.906, 0.429) == pytest.approx(0.537726, rel=1e-5)


def test_free_bat_recoil_factor():
    """Free bat: k = (m/M)(1 + d^2/k_cg^2); at the CG only the bat's mass counts."""
    assert rigid.recoil_factor_free(0.145, 0.9, 0.045, 0.0) == pytest.approx(0.145 / 0.9)
    k = rigid.recoil_factor_free(0.145, 0.9, 0.045, 0.2)
    assert k == pytest.approx(0.145 / 0.9 * (1 + 0.04 / 0.05))


@pytest.mark.parametrize("ball_loss", ["compression", "relative-speed"])
def test_engine_matches_closed_form_and_ball_cor(ball_loss):
    """RigidEngine with Nathan's law: pinned exit speed is the closed form with the ball's COR at
    the wall speed that compresses the ball as much, v_rel / sqrt(1 + k) (the 0.5 mu v^2 of the
    impact stored in the ball; physics/balls/hysteresis.py), or at the relative speed itself;
    the COR it reports (Eq. 3) equals that ball COR; Eq. 1 holds."""
    bat = build_geometry("rod", "solid", 0.84, [0.0, 0.84], [0.05, 0.065], LIBRARY["ash"][0])
    ball = BallModel("b", 0.145, 0.0366, PowerLawHysteresis(6.53e7, 1.84, (10.0, 60.0), (0.6, 0.5)))
    pivot = 0.15
    r = np.linspace(0.3, 0.65, 36)
    batch = ImpactBatch(r, np.full(r.size, -31.0), np.linspace(0.0, 60.0, r.size))
    out = get_engine("rigid", ball_loss=ball_loss).solve(bat, ball, pivot, batch)
    # (Nathan's law: the round surface does not change a rigid body's COR, the ball stores the
    # same energy whatever its stiffness)
    moi = bat.moi_about(pivot)
    reduced = 1 / (1 + ball.mass * r**2 / moi) if ball_loss == "compression" else 1.0
    e = ball.cor(batch.relative_speed * np.sqrt(reduced))
    expected = ((1 + e) * moi * batch.bat_angular_speed * r
                + batch.pitch_speed * (ball.mass * r**2 - e * moi)) / (moi + ball.mass * r**2)
    np.testing.assert_allclose(out.exit_speed, expected, rtol=1e-12)
    np.testing.assert_allclose(out.cor, e, rtol=1e-12)
    lhs = moi * batch.bat_angular_speed + ball.mass * batch.pitch_speed * r
    rhs = moi * out.bat_angular_speed_after + ball.mass * out.exit_speed * r
    np.testing.assert_allclose(rhs, lhs, rtol=1e-12)


def test_free_bat_reports_the_cor_it_used_and_conserves_momentum():
    """RigidEngine, support "free": the reported COR is the ball's COR used in the collision
    (at the free bat's compression-equivalent wall speed); linear momentum and
    angular momentum about the CG are conserved with the free bat's w2 (its angular velocity)."""
    bat = build_geometry("rod", "solid", 0.84, [0.0, 0.84], [0.05, 0.065], LIBRARY["ash"][0])
    ball = BallModel("b", 0.145, 0.0366, PowerLawHysteresis(6.53e7, 1.84, (10.0, 60.0), (0.6, 0.5)))
    pivot = 0.093  # instantaneous centre of Nathan's game-speed swing (24 m/s at 51 rad/s)
    r = np.linspace(0.3, 0.72, 22)
    batch = ImpactBatch(r, np.full(r.size, -40.0), np.full(r.size, 51.0))
    out = get_engine("rigid").solve(bat, ball, pivot, batch, support="free")
    m, big_m, zcg = ball.mass, bat.mass, bat.balance_point
    icg = bat.moi_about(zcg)
    d = r + pivot - zcg
    k = (m / big_m) * (1 + d**2 * big_m / icg)  # free bat's effective-mass ratio
    np.testing.assert_allclose(out.cor, ball.cor(batch.relative_speed / np.sqrt(1 + k)),
                               rtol=1e-12)
    v_cg = 51.0 * (zcg - pivot)
    dv_cg = m * (batch.pitch_speed - out.exit_speed) / big_m  # impulse / M
    # angular momentum about the CG: I_cg w1 + m v_p d = I_cg w2 + m v_b d
    np.testing.assert_allclose(icg * out.bat_angular_speed_after + m * out.exit_speed * d,
                               icg * 51.0 + m * batch.pitch_speed * d, rtol=1e-12)
    # the impact point's speed after impact gives back the COR (Eq. 3 generalised)
    point_after = v_cg + dv_cg + out.bat_angular_speed_after * d
    np.testing.assert_allclose((point_after - out.exit_speed)
                               / (batch.pitch_speed - batch.bat_angular_speed * r), out.cor,
                               rtol=1e-12)


def test_viscoelastic_ball_on_a_rigid_bat_is_its_integrated_impact():
    """RigidEngine with the viscoelastic law: the COR it reports is the ball's integrated
    impact on a rigid body of the bat's effective mass (Eq. 3), on the bat's round surface
    (the footprint rule's factor at the impact's u_rep, Hertz's with the rule "hertz"); a
    heavier effective mass (impacts near the pivot) gives a COR nearer the rigid wall's; Eq. 1
    holds."""
    from batcert.engines.flexible_system import patch_compression
    from batcert.physics.balls import footprint

    bat = build_geometry("rod", "solid", 0.84, [0.0, 0.84], [0.066, 0.066], LIBRARY["ash"][0])
    law = Viscoelastic(5.7e7, 1.68, 0.37, 155e-6)
    ball = BallModel("v", 0.145, 0.0369, law)
    pivot, r = 0.15, np.linspace(0.2, 0.65, 10)
    batch = ImpactBatch(r, np.full(r.size, -60.0), 0.0)
    out = get_engine("rigid").solve(bat, ball, pivot, batch)
    k = ball.mass * r**2 / bat.moi_about(pivot)
    hertz = footprint.stiffness_ratio(ball.radius, 0.033)
    on, speed = np.full(r.size, 0.033), np.full(r.size, 60.0)
    gamma = patch_compression("fe-finite-strain", ball, on, np.full(r.size, hertz), speed, k)[1]
    assert np.all(gamma < hertz)
    expected = law.body_impact(ball.mass, speed, k, history=False, scale=gamma).cor
    np.testing.assert_allclose(out.cor, expected, rtol=1e-12)
    old = get_engine("rigid", footprint="hertz").solve(bat, ball, pivot, batch).cor
    expected = law.body_impact(ball.mass, 60.0, k, history=False, scale=hertz).cor
    np.testing.assert_allclose(old, expected, rtol=1e-12)
    flat = get_engine("rigid", contact_surface="flat").solve(bat, ball, pivot, batch).cor
    assert np.all(flat != out.cor)  # the round surface matters for this law
    lhs = bat.moi_about(pivot) * 0.0 + ball.mass * -60.0 * r
    rhs = bat.moi_about(pivot) * out.bat_angular_speed_after + ball.mass * out.exit_speed * r
    np.testing.assert_allclose(rhs, lhs, rtol=1e-12)
