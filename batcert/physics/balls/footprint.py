"""Where and how hard the ball presses: its footprint on a barrel, from Hertz's theory.

A ball of radius ``R_b`` pressed onto a convex cylinder of radius ``R_c`` (a bat's barrel) by
``u`` (the ball's compression, its centre's approach) touches it over an ellipse, longer along
the bat than around it. Hertz's elliptical contact (Johnson, Contact Mechanics, 1985, Sec. 4.2;
the relative curvatures ``A = 1 / (2 R_b)`` along the bat and ``B = 1 / (2 R_b) + 1 / (2 R_c)``
around it) gives, with ``e^2 = 1 - (b/a)^2`` and the complete elliptic integrals ``K(e)``,
``E(e)``:

* the shape: ``B / A = ((1 / (1 - e^2)) E - K) / (K - E)``, independent of ``u``;
* the size: ``a^2 = u (K - E) / (A K e^2)``, ``b = a sqrt(1 - e^2)`` (``a^2 = R_b u`` on a
  flat, ``R_c`` infinite);
* the pressure: ellipsoidal, ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``; its marginals along and around
  the bat are parabolic, ``(1 - (x/a)^2)``;
* the force at a given ``u``: ``(2/3) pi a u E* / K(e)`` against ``(4/3) sqrt(R_b u) u E*`` on a
  flat: the cylinder's contact is softer by :func:`stiffness_ratio` (0.84 for a 2 5/8 in
  barrel), whatever the ball's modulus.

The engine (:mod:`batcert.engines.flexible`) spreads the contact force over this footprint as it
grows and shrinks with the compression: along the bat with the parabolic weight
(:func:`axial_weights`), around it through the factor :func:`circumferential_factor` of each
shell order. Hertz's theory holds for small deformations of a homogeneous sphere; a baseball
compressed by 15 mm (40 % of its radius) is far from that: a footprint rule
(:mod:`batcert.physics.balls.footprint_rules`, the ``rule`` argument below) multiplies Hertz's
semi-axes and stiffness factor by those of a 3-D finite-strain finite-element sphere
(``fe-finite-strain``, the engine's default) or keeps Hertz's (``hertz``, the default of these
functions); the checks against the FE are in docs/validation.md. Units: SI ([m]).
"""

from __future__ import annotations

import math

import numpy as np

from batcert import workspace
from batcert.physics.balls.footprint_rules import rule as _rule


def elliptic_integrals(m):
    """Complete elliptic integrals ``K(m)``, ``E(m)`` of the parameter ``m = e^2`` in [0, 1),
    by the arithmetic-geometric mean (Abramowitz & Stegun 17.6; to machine precision)."""
    m = np.asarray(m, dtype=float)
    a, b = np.ones_like(m), np.sqrt(1.0 - m)
    c2_sum, power = 0.5 * m, 0.5  # sum of 2^(n-1) c_n^2, c_0^2 = m
    for _ in range(40):
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), np.sqrt(a * b)
        power *= 2.0
        c2_sum = c2_sum + power * c**2
        if np.all(np.abs(c) < 1e-17):
            break
    k = 0.5 * np.pi / a
    return k, k * (1.0 - c2_sum)


def _elliptic(m: float) -> tuple[float, float]:
    """:func:`elliptic_integrals` of one ``m``, in plain floats (the bisection's inner loop)."""
    a, b = 1.0, math.sqrt(1.0 - m)
    c2_sum, power = 0.5 * m, 0.5
    for _ in range(40):
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        power *= 2.0
        c2_sum += power * c * c
        if abs(c) < 1e-17:
            break
    k = 0.5 * math.pi / a
    return k, k * (1.0 - c2_sum)


def _shape(curvature_ratio: float) -> tuple[float, float, float]:
    """:func:`_ellipse_shape`, kept by the active workspace (kind ``footprint``)."""
    return workspace.current().call("footprint", _ellipse_shape, float(curvature_ratio))


def _ellipse_shape(curvature_ratio: float) -> tuple[float, float, float]:
    """``e^2``, ``K``, ``E`` of the Hertz ellipse for ``B / A`` (bisection on ``e^2``)."""
    if curvature_ratio <= 1.0 + 1e-12:
        return 0.0, 0.5 * math.pi, 0.5 * math.pi
    lo, hi = 0.0, 1.0 - 1e-14
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        k, e = _elliptic(mid)
        ratio = (e / (1.0 - mid) - k) / (k - e) if mid > 1e-12 else 1.0
        lo, hi = (mid, hi) if ratio < curvature_ratio else (lo, mid)
    m = 0.5 * (lo + hi)
    k, e = _elliptic(m)
    return m, k, e


def _distinct(a: np.ndarray) -> list[float]:
    """The distinct values of ``a``, ascending (a plain set: ``np.unique`` of numpy 2.4
    imports ``numpy.ma``, 8-12 ms of a run's start, benchmarks/bench_cli.py)."""
    return sorted(set(np.asarray(a, dtype=float).ravel().tolist()))


def ellipse(ball_radius: float, surface_radius, compression, rule: str = "hertz"):
    """Semi-axes of the footprint [m]: ``a`` along the cylinder's axis, ``b`` around it
    (module notes): Hertz's, times the factors of the footprint ``rule``
    (:data:`~batcert.physics.balls.footprint_rules.RULES`; ``hertz``: none). ``surface_radius``
    [m]: the barrel's outer radius, a scalar or one per impact (``inf`` for a flat);
    ``compression`` [m], any shape broadcasting with it."""
    a, b = hertz_ellipse(ball_radius, surface_radius, compression)
    if rule == "hertz":
        return a, b
    u = np.maximum(np.asarray(compression, dtype=float), 0.0)
    fa, fb = _rule(rule).size(u / ball_radius, _radius_ratio(ball_radius, surface_radius))
    return a * fa, b * fb


def _radius_ratio(ball_radius: float, surface_radius) -> np.ndarray:
    """``R_b / R_c`` [-], 0 on a flat (``R_c`` infinite)."""
    return ball_radius / np.asarray(surface_radius, dtype=float)


def hertz_ellipse(ball_radius: float, surface_radius, compression):
    """Semi-axes of the Hertz footprint [m] (:func:`ellipse` with the rule ``hertz``)."""
    u = np.maximum(np.asarray(compression, dtype=float), 0.0)
    rc = np.broadcast_to(np.asarray(surface_radius, dtype=float), np.broadcast(u, np.asarray(
        surface_radius, dtype=float)).shape)
    a, b = np.empty(rc.shape), np.empty(rc.shape)
    u = np.broadcast_to(u, rc.shape)
    for value in _distinct(rc):
        mask = rc == value
        m, k, e = _shape(1.0 + ball_radius / value if np.isfinite(value) else 1.0)
        if m == 0.0:
            a[mask] = b[mask] = np.sqrt(ball_radius * u[mask])
        else:
            a[mask] = np.sqrt(2.0 * ball_radius * u[mask] * (k - e) / (k * m))
            b[mask] = a[mask] * np.sqrt(1.0 - m)
    return a, b


def stiffness_ratio(ball_radius: float, surface_radius, compression=None,
                    rule: str = "hertz") -> np.ndarray | float:
    """Force on a convex cylinder of radius ``surface_radius`` over the force on a flat at the
    same compression [-] (module notes): Hertz's ``pi a / (2 K(e) sqrt(R_b u))``, 1 for a flat,
    0.84 for a 36.9 mm ball on a 2 5/8 in barrel, times the factor of the footprint ``rule`` at
    ``compression`` [m] (broadcasting with ``surface_radius``; None: Hertz's, the
    small-compression limit of every rule). A ball law's stiffness refers to a flat rigid wall
    (the COR and compression tests); the engine scales it by this on a barrel."""
    gamma = _hertz_stiffness_ratio(ball_radius, surface_radius)
    if compression is None or rule == "hertz":
        return gamma
    u = np.maximum(np.asarray(compression, dtype=float), 0.0)
    out = gamma * _rule(rule).stiffness(u / ball_radius, _radius_ratio(ball_radius, surface_radius))
    return out if np.ndim(out) else float(out)


def _hertz_stiffness_ratio(ball_radius: float, surface_radius) -> np.ndarray | float:
    rc = np.asarray(surface_radius, dtype=float)
    out = np.ones(rc.shape)
    for value in _distinct(rc):
        if not np.isfinite(value):
            continue
        m, k, e = _shape(1.0 + ball_radius / value)
        if m > 0.0:
            out[rc == value] = 0.5 * np.pi / k * np.sqrt(2.0 * (k - e) / (k * m))
    return out if out.ndim else float(out)


def circumferential_factor(order, half_angle):
    """How a shell mode of circumferential order ``n`` feels a load spread around the barrel
    with Hertz's parabolic marginal over ``+-half_angle`` [rad]: the load's ``cos(n theta)``
    average, ``3 j1(x) / x`` with ``x = n beta`` and the spherical Bessel function
    ``j1(x) = (sin x - x cos x) / x^2`` [-]; 1 for a point (``beta = 0``) and for ``n = 0``."""
    x = np.asarray(order, dtype=float) * np.asarray(half_angle, dtype=float)
    small = np.abs(x) < 1e-2
    xs = np.where(small, 1.0, x)
    exact = 3.0 * (np.sin(xs) - xs * np.cos(xs)) / xs**3
    series = 1.0 - x**2 / 10.0 + x**4 / 280.0
    return np.where(small, series, exact)


def circumferential_factors(orders, half_angle) -> np.ndarray:
    """:func:`circumferential_factor` of every order in ``orders`` (non-negative integers,
    ascending) at each ``half_angle`` [rad] (any shape), shape ``(len(orders), *shape)``: the
    same function, with ``sin n beta`` and ``cos n beta`` from the angle-addition recurrence
    (two products per order instead of two transcendental functions; to about 1e-12, tests).
    The engine evaluates it for some 25 orders at 41 compressions of every impact."""
    beta = np.asarray(half_angle, dtype=float)
    orders = [int(n) for n in orders]
    if any(b < a for a, b in zip(orders, orders[1:], strict=False)) or (orders and orders[0] < 0):
        raise ValueError("orders must be non-negative and ascending")
    out = np.empty((len(orders), *beta.shape))
    s1, c1 = np.sin(beta), np.cos(beta)
    sn, cn = np.zeros_like(beta), np.ones_like(beta)  # sin, cos of n beta at n = 0
    n_now = 0
    for i, n in enumerate(orders):
        while n_now < n:
            sn, cn = sn * c1 + cn * s1, cn * c1 - sn * s1
            n_now += 1
        if n == 0:
            out[i] = 1.0
            continue
        x = n * beta
        with np.errstate(divide="ignore", invalid="ignore"):
            value = 3.0 * (sn - x * cn) / (x * x * x)
        small = np.abs(x) < 1e-2  # the series, as circumferential_factor
        if np.any(small):
            xs = x[small]
            value[small] = 1.0 - xs**2 / 10.0 + xs**4 / 280.0
        out[i] = value
    return out


def axial_weights(points: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`gauss_parabolic`, read-only, kept by the active workspace (kind ``footprint``)."""
    return workspace.current().call("footprint", _read_only_rule, int(points))


def _read_only_rule(points: int) -> tuple[np.ndarray, np.ndarray]:
    xi, w = gauss_parabolic(points)
    xi.setflags(write=False)
    w.setflags(write=False)
    return xi, w


def gauss_parabolic(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss rule of the parabolic weight ``(1 - xi^2)`` on [-1, 1] (Gauss-Jacobi, alpha =
    beta = 1): ``points`` abscissae and weights summing to 1, so that ``sum w f(xi)`` is the
    parabola-weighted mean of ``f`` (exact for polynomials of degree ``2 points - 1``). The
    abscissae are the roots of ``P'_(points+1)`` (Legendre)."""
    from numpy.polynomial import legendre

    xi = np.sort(legendre.Legendre.basis(points + 1).deriv().roots().real)
    # weights from the moments of (1 - xi^2): int xi^j (1 - xi^2) dxi, j < points
    j = np.arange(points)
    moments = np.where(j % 2 == 0, 2.0 / (j + 1) - 2.0 / (j + 3), 0.0)
    w = np.linalg.solve(np.vander(xi, points, increasing=True).T, moments)
    return xi, w / w.sum()
