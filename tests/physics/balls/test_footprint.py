"""Unit tests of the Hertz footprint of a ball on a barrel (batcert.physics.balls.footprint),
against Hertz's elliptical contact (Johnson, Contact Mechanics, 1985, Sec. 4.2) solved here with
scipy's elliptic integrals and root finder, and against scipy's quadrature and Gauss-Jacobi
rules."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk, roots_jacobi, spherical_jn

from batcert.physics.balls import footprint

BALL_RADIUS = 0.0369  # [m] the shipped collegiate ball (9 1/8 in circumference)
BARREL_RADIUS = 2.625 * 0.0254 / 2  # [m] a 2 5/8 in barrel: 33.34 mm


def hertz_ellipse(ball_radius, surface_radius, u):
    """Semi-axes ``a`` (along the cylinder), ``b`` and ``K(e)`` of Hertz's footprint, from
    Johnson (1985) Eqs. 4.39-4.41 with scipy: the relative curvatures ``A = 1 / (2 R_b)``,
    ``B = 1 / (2 R_b) + 1 / (2 R_c)``; ``e^2`` from ``B / A = ((1 / (1 - e^2)) E - K) / (K - E)``
    (brentq); the approach ``u = p0 b K / E*`` and ``A = p0 b (K - E) / (E* a^2 e^2)``."""
    A = 1 / (2 * ball_radius)
    B = A + 1 / (2 * surface_radius)

    def shape(m):
        K, E = ellipk(m), ellipe(m)
        return (E / (1 - m) - K) / (K - E) - B / A

    m = brentq(shape, 1e-12, 1 - 1e-14, xtol=1e-16, rtol=1e-15)
    K, E = ellipk(m), ellipe(m)
    # p0 b / E* = u / K from the approach, then a from A
    a = np.sqrt(u / K * (K - E) / (A * m))
    b = a * np.sqrt(1 - m)
    # the other curvature holds too (the reference solved the shape it states)
    assert B == pytest.approx(u / K * ((a / b) ** 2 * E - K) / (a**2 * m), rel=1e-10)
    return a, b, K


def test_elliptic_integrals_match_scipy():
    # the AGM to machine precision: measured 4.4e-16 (K) and 6.7e-16 (E) relative on [0, 0.999]
    m = np.concatenate([np.linspace(0.0, 0.999, 1000), [1e-12, 1 - 1e-6, 1 - 1e-10]])
    k, e = footprint.elliptic_integrals(m)
    np.testing.assert_allclose(k, ellipk(m), rtol=1e-13)
    np.testing.assert_allclose(e, ellipe(m), rtol=1e-13)
    # K(0) = E(0) = pi / 2
    assert footprint.elliptic_integrals(0.0) == (pytest.approx(np.pi / 2, rel=1e-15),
                                                 pytest.approx(np.pi / 2, rel=1e-15))


def test_flat_footprint_is_the_hertz_circle():
    u = np.array([0.0, 1e-4, 5e-3, 1.5e-2])
    a, b = footprint.ellipse(BALL_RADIUS, np.inf, u)
    np.testing.assert_allclose(a, np.sqrt(BALL_RADIUS * u), rtol=1e-15)  # a^2 = R u
    np.testing.assert_array_equal(a, b)
    # no footprint before touching
    a, b = footprint.ellipse(BALL_RADIUS, np.inf, -1e-3)
    assert a == b == 0.0


@pytest.mark.parametrize("surface_radius", [BARREL_RADIUS, 0.0286, 0.05, 0.2])
def test_cylinder_footprint_matches_hertz_theory(surface_radius):
    # bisection on e^2 (60 halvings) against brentq (xtol 1e-16): measured agreement <= 4.4e-16;
    # 1e-10 leaves room for the two root finders' stopping rules
    u = np.array([1e-4, 5e-3, 1.5e-2])
    a, b = footprint.ellipse(BALL_RADIUS, surface_radius, u)
    for i, ui in enumerate(u):
        a_ref, b_ref, _ = hertz_ellipse(BALL_RADIUS, surface_radius, ui)
        assert a[i] == pytest.approx(a_ref, rel=1e-10)
        assert b[i] == pytest.approx(b_ref, rel=1e-10)
    assert np.all(a > b)  # longer along the bat than around it
    # the footprint is narrower around the barrel than a flat's circle, longer along it
    circle = np.sqrt(BALL_RADIUS * u)
    assert np.all(b < circle) and np.all(a > circle)


def test_footprint_shape_does_not_depend_on_compression_and_size_goes_as_sqrt_u():
    u = np.geomspace(1e-5, 2e-2, 9)
    a, b = footprint.ellipse(BALL_RADIUS, BARREL_RADIUS, u)
    np.testing.assert_allclose(a / b, a[0] / b[0], rtol=1e-14)
    np.testing.assert_allclose(a / np.sqrt(u), a[0] / np.sqrt(u[0]), rtol=1e-14)
    # the barrel's shape: Hertz's a / b (1.64 for a 36.9 mm ball on a 2 5/8 in barrel)
    a_ref, b_ref, _ = hertz_ellipse(BALL_RADIUS, BARREL_RADIUS, 1e-3)
    assert a[0] / b[0] == pytest.approx(a_ref / b_ref, rel=1e-10)
    assert a[0] / b[0] == pytest.approx(1.64, abs=0.005)


def test_ellipse_broadcasts_surfaces_against_compressions():
    surfaces = np.array([[np.inf], [BARREL_RADIUS], [0.05]])
    u = np.array([1e-3, 4e-3])
    a, b = footprint.ellipse(BALL_RADIUS, surfaces, u)
    assert a.shape == b.shape == (3, 2)
    for i in range(3):
        ai, bi = footprint.ellipse(BALL_RADIUS, surfaces[i, 0], u)
        np.testing.assert_array_equal(a[i], ai)
        np.testing.assert_array_equal(b[i], bi)


def test_stiffness_ratio_of_a_flat_is_one():
    assert footprint.stiffness_ratio(BALL_RADIUS, np.inf) == 1.0
    np.testing.assert_array_equal(footprint.stiffness_ratio(BALL_RADIUS, [np.inf, np.inf]), 1.0)


def test_stiffness_ratio_on_a_barrel():
    # Hertz (module notes): 0.8396 for the 36.9 mm ball on a 2 5/8 in (33.34 mm) barrel;
    # engines/flexible.py quotes 0.84
    assert footprint.stiffness_ratio(BALL_RADIUS, BARREL_RADIUS) == pytest.approx(0.84, abs=0.005)
    # softer on a narrower cylinder, towards 1 on a wide one
    radii = np.array([0.01, 0.02, 0.0286, BARREL_RADIUS, 0.05, 0.2, 10.0])
    ratio = footprint.stiffness_ratio(BALL_RADIUS, radii)
    assert np.all(np.diff(ratio) > 0)
    assert np.all(ratio < 1) and ratio[-1] > 0.999


@pytest.mark.parametrize("surface_radius", [0.02, 0.0286, BARREL_RADIUS, 0.05, 0.2])
def test_stiffness_ratio_is_hertz_force_over_the_flats(surface_radius):
    # F = (2/3) pi a u E* / K(e) on the cylinder, (4/3) sqrt(R u) u E* on a flat (Johnson 4.41,
    # 4.23): the ratio at any u and E* (here u = 5 mm, E* = 1); measured agreement <= 4.4e-16,
    # 1e-10 as for the axes
    u = 5e-3
    a, _, K = hertz_ellipse(BALL_RADIUS, surface_radius, u)
    cylinder = 2 / 3 * np.pi * a * u / K
    flat = 4 / 3 * np.sqrt(BALL_RADIUS * u) * u
    assert footprint.stiffness_ratio(BALL_RADIUS, surface_radius) == pytest.approx(
        cylinder / flat, rel=1e-10)


def test_stiffness_ratio_keeps_the_shape_of_its_argument():
    radii = np.array([[BARREL_RADIUS, np.inf], [0.05, BARREL_RADIUS]])
    ratio = footprint.stiffness_ratio(BALL_RADIUS, radii)
    assert ratio.shape == (2, 2)
    assert ratio[0, 0] == ratio[1, 1] and ratio[0, 1] == 1.0
    assert isinstance(footprint.stiffness_ratio(BALL_RADIUS, 0.05), float)


def parabolic_average(n, beta):
    """``cos(n theta)`` averaged with the weight ``1 - (theta / beta)^2`` over +-beta (quad's
    cosine-weighted rule, QAWO)."""
    num, _ = quad(lambda t: 1 - (t / beta) ** 2, -beta, beta, weight="cos", wvar=n,
                  epsabs=1e-15, epsrel=1e-13)
    return num / (4 * beta / 3)  # the weight's integral


def test_circumferential_factor_limits():
    beta = np.array([0.0, 0.1, 0.5, 1.0])
    np.testing.assert_array_equal(footprint.circumferential_factor(0, beta), 1.0)  # n = 0
    np.testing.assert_array_equal(footprint.circumferential_factor(np.arange(8), 0.0), 1.0)


@pytest.mark.parametrize("n, beta", [(1, 0.3), (2, 0.25), (3, 0.6), (4, 1.0), (8, 0.4),
                                     (12, 0.9), (1, 0.005)])
def test_circumferential_factor_is_the_parabolic_average(n, beta):
    # quad to 1e-13; measured agreement <= 5.6e-16
    assert footprint.circumferential_factor(n, beta) == pytest.approx(parabolic_average(n, beta),
                                                                       abs=1e-14)


def test_circumferential_factor_series_joins_the_closed_form():
    # the series below n beta = 1e-2, the closed form above: both within rounding of
    # 3 j1(x) / x (scipy's spherical Bessel function); the closed form's cancellation in
    # sin x - x cos x at x = 1e-2 costs about eps / x^2 ~ 2e-12 (measured 1.4e-12)
    edge = 1e-2
    below, above = edge * (1 - 1e-12), edge * (1 + 1e-12)
    f_below, f_above = (float(footprint.circumferential_factor(1, x)) for x in (below, above))
    assert f_below == pytest.approx(3 * spherical_jn(1, below) / below, rel=1e-15)
    assert f_above == pytest.approx(3 * spherical_jn(1, above) / above, rel=1e-11)
    assert abs(f_above - f_below) < 1e-11
    x = np.concatenate([np.geomspace(1e-6, 0.5, 40), [edge]])
    np.testing.assert_allclose(footprint.circumferential_factor(1, x), 3 * spherical_jn(1, x) / x,
                               rtol=1e-11)


@pytest.mark.parametrize("points", [1, 2, 3, 4, 6, 8, 12, 15])  # 15: the flexible engine's
def test_axial_weights_are_gauss_jacobi(points):
    xi, w = footprint.axial_weights(points)
    assert xi.shape == w.shape == (points,)
    assert w.sum() == pytest.approx(1.0, abs=1e-14)
    assert np.all(w > 0) and np.all(np.abs(xi) < 1)
    np.testing.assert_allclose(xi, -xi[::-1], atol=1e-14)  # symmetric
    # the weights come from a Vandermonde solve, whose rounding grows with the points:
    # symmetric to 1.6e-12 (relative) at 15 points, 1.2e-12 at 12; 1.7e-11 at 15 on an AMD
    # EPYC's OpenBLAS kernels (the solve's rounding depends on the BLAS kernel)
    np.testing.assert_allclose(w, w[::-1], rtol=1e-10)
    # exact for xi^j, j < 2 points, against the normalised weight (1 - xi^2) / (4/3): the
    # moments 2/(j+1) - 2/(j+3) over 4/3 for even j, 0 for odd (measured <= 3e-15)
    for j in range(2 * points):
        moment = (2 / (j + 1) - 2 / (j + 3)) * 0.75 if j % 2 == 0 else 0.0
        assert np.sum(w * xi**j) == pytest.approx(moment, abs=1e-13), j
    # and the same rule as scipy's Gauss-Jacobi (alpha = beta = 1), normalised
    x_ref, w_ref = roots_jacobi(points, 1, 1)
    np.testing.assert_allclose(xi, x_ref, atol=1e-14)
    np.testing.assert_allclose(w, w_ref / w_ref.sum(), atol=1e-11)  # measured 8e-13 at 15


def test_axial_weights_are_shared_and_read_only():
    xi, w = footprint.axial_weights(5)
    assert footprint.axial_weights(5)[0] is xi
    assert not xi.flags.writeable and not w.flags.writeable
    # a degree-2P polynomial is not integrated exactly (the rule has P points)
    assert np.sum(w * xi**10) != pytest.approx((2 / 11 - 2 / 13) * 0.75, abs=1e-6)


def test_circumferential_factors_equal_the_factor_order_by_order():
    # The engine's path (the angle-addition recurrence for sin n beta, cos n beta) against
    # circumferential_factor itself, for the orders a barrel keeps (0, 2..30) and half-angles
    # from 0 (the series) to beyond a barrel's widest footprint. The recurrence's rounding
    # grows as n eps and is divided by x^3 near the series' switch at x = 1e-2, where
    # (sin x - x cos x) keeps x^3/3 of it: at most about n eps / x^2 = 7e-11 for n = 30;
    # measured 7.1e-12. 1e-10.
    orders = [0, *range(2, 31)]
    beta = np.concatenate([[0.0, 1e-9, 4e-4, 1e-3], np.linspace(1e-3, 1.6, 400)])
    got = footprint.circumferential_factors(orders, beta.reshape(4, 101))
    want = footprint.circumferential_factor(np.asarray(orders)[:, None, None],
                                            beta.reshape(4, 101)[None])
    assert got.shape == (len(orders), 4, 101)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-10)
    with pytest.raises(ValueError, match="ascending"):
        footprint.circumferential_factors([2, 0], beta)


# -- footprint rules (physics/balls/footprint_rules.py) -------------------------------------
def test_the_rules_registry():
    from batcert.physics.balls.footprint_rules import DEFAULT_RULE, RULES, rule

    assert set(RULES) == {"hertz", "fe-finite-strain"} and DEFAULT_RULE in RULES
    assert all(rule(name).name == name for name in RULES)
    with pytest.raises(ValueError, match="footprint must be one of"):
        rule("Hertz")
    with pytest.raises(ValueError, match="footprint must be one of"):
        footprint.ellipse(BALL_RADIUS, BARREL_RADIUS, 1e-3, rule="fem")


def test_the_hertz_rule_is_hertzs_footprint():
    u = np.array([1e-4, 5e-3, 1.5e-2])
    for surface in (np.inf, BARREL_RADIUS, 0.0286):
        a, b = footprint.ellipse(BALL_RADIUS, surface, u, rule="hertz")
        np.testing.assert_array_equal(np.stack([a, b]),
                                      np.stack(footprint.hertz_ellipse(BALL_RADIUS, surface, u)))
        assert np.all(footprint.stiffness_ratio(BALL_RADIUS, surface, u, rule="hertz")
                      == footprint.stiffness_ratio(BALL_RADIUS, surface))


def test_the_finite_strain_rule_tends_to_hertz_and_is_held_beyond_its_data():
    # each factor is 1 + c1 sqrt(x) + c2 x (x = u / R_b): Hertz's at x -> 0, to 1e-3 at
    # x = 1e-6 (|c1| < 1); held at x = 0.4 beyond the FE's compressions
    from batcert.physics.balls.footprint_rules import FE_X_MAX

    x = np.array([1e-6, FE_X_MAX, 0.6])
    for surface in (np.inf, BARREL_RADIUS, 0.0286, 0.02):
        h = np.stack(footprint.hertz_ellipse(BALL_RADIUS, surface, x * BALL_RADIUS))
        f = np.stack(footprint.ellipse(BALL_RADIUS, surface, x * BALL_RADIUS, rule="fe-finite-strain"))
        ratio = f / h
        np.testing.assert_allclose(ratio[:, 0], 1.0, atol=1e-3)
        np.testing.assert_allclose(ratio[:, 2], ratio[:, 1], rtol=1e-12)
        s = np.asarray(footprint.stiffness_ratio(BALL_RADIUS, surface, x * BALL_RADIUS,
                                                 rule="fe-finite-strain"))
        s = s / footprint.stiffness_ratio(BALL_RADIUS, surface)
        assert s[0] == pytest.approx(1.0, abs=1e-3) and s[2] == pytest.approx(s[1], rel=1e-12)
    # a flat's stiffness factor is 1 by definition, whatever the compression
    assert np.all(footprint.stiffness_ratio(BALL_RADIUS, np.inf, x * BALL_RADIUS,
                                            rule="fe-finite-strain") == 1.0)
