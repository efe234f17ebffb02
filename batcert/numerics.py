"""Two numbers that would otherwise cost a large import: a root of a function of one variable
(Brent's method) and a quantile of Student's t distribution.

Importing :mod:`scipy.optimize` takes about 0.4 s and :mod:`scipy.stats` about 0.7 s on the
reference machine (docs/performance.md), for one root bracketing at a time (``design
--solve``, a lab's barrel calibration) and one coverage factor per certificate (``reduce``).
Both are written here from their textbook definitions, in the standard library's ``math``, and
checked against scipy in the tests (tests/test_numerics.py).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from statistics import NormalDist


class NoBracket(ValueError):
    """The function has the same sign at both ends of the interval."""


@dataclass(frozen=True)
class Root:
    """A root and what finding it took."""

    x: float
    calls: int  # evaluations of the function
    converged: bool


def brent_root(f: Callable[[float], float], a: float, b: float, xtol: float = 1e-12,
               rtol: float = 4 * 2.220446049250313e-16, maxiter: int = 100) -> Root:
    """A root of ``f`` in ``[a, b]``, where ``f(a)`` and ``f(b)`` differ in sign, located to
    ``xtol + rtol |x|`` (Brent, "Algorithms for Minimization without Derivatives", 1973,
    chapter 4: inverse quadratic interpolation or the secant step where they make progress,
    bisection where they do not, so that it never takes more than about the bisection's number
    of steps squared and usually converges superlinearly).

    Raises :class:`NoBracket` when ``f(a)`` and ``f(b)`` have the same sign."""
    fa, fb = f(a), f(b)
    calls = 2
    if fa == 0:
        return Root(a, calls, True)
    if fb == 0:
        return Root(b, calls, True)
    if (fa > 0) == (fb > 0):
        raise NoBracket(f"f({a:g}) = {fa:g} and f({b:g}) = {fb:g} have the same sign")
    c, fc = a, fa  # b: the best estimate; c: the other end of the bracket
    d = e = b - a  # the last step and the one before it
    for _ in range(maxiter):
        if (fb > 0) == (fc > 0):
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):  # keep b the better end
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 0.5 * (xtol + rtol * abs(b))
        half = 0.5 * (c - b)
        if abs(half) <= tol or fb == 0:
            return Root(b, calls, True)
        if abs(e) >= tol and abs(fa) > abs(fb):
            d, e = _interpolated_step(a, b, c, fa, fb, fc, half, tol, d, e)
        else:
            d = e = half
        a, fa = b, fb
        b += d if abs(d) > tol else math.copysign(tol, half)
        fb = f(b)
        calls += 1
    return Root(b, calls, False)


def _interpolated_step(a, b, c, fa, fb, fc, half, tol, d, e) -> tuple[float, float]:
    """The secant (two distinct points) or inverse quadratic interpolation (three) step from
    ``b``, and the step before it; the bisection's when the interpolated step leaves the
    bracket's inner three quarters or shrinks too slowly (Brent 1973, section 4.3)."""
    s = fb / fa
    if a == c:
        p, q = 2 * half * s, 1 - s
    else:
        qa, r = fa / fc, fb / fc
        p = s * (2 * half * qa * (qa - r) - (b - a) * (r - 1))
        q = (qa - 1) * (r - 1) * (s - 1)
    if p > 0:
        q = -q
    p = abs(p)
    if 2 * p < min(3 * half * q - abs(tol * q), abs(e * q)):
        return p / q, d
    return half, half


def student_t_cdf(t: float, dof: float) -> float:
    """P(T <= t) for Student's t with ``dof`` > 0 degrees of freedom: ``1 - I_x(dof/2, 1/2) /
    2`` for t >= 0, ``x = dof / (dof + t^2)`` (Abramowitz & Stegun 26.7.1 with 26.5.27)."""
    if not dof > 0:
        raise ValueError(f"degrees of freedom must be > 0, got {dof}")
    if t == 0:
        return 0.5
    # x = dof / (dof + t^2) and y = 1 - x, with their logarithms, each without cancellation
    x, y = dof / (dof + t * t), t * t / (dof + t * t)
    log_x, log_y = -math.log1p(t * t / dof), 2 * math.log(abs(t)) - math.log(dof + t * t)
    tail = 0.5 * _incomplete_beta(0.5 * dof, 0.5, (x, log_x), (y, log_y))
    return 1.0 - tail if t >= 0 else tail


LARGE_DOF = 1e6  # degrees of freedom above which the t quantile is its expansion in 1/dof


def student_t_quantile(p: float, dof: float) -> float:
    """The ``p`` quantile of Student's t with ``dof`` > 0 degrees of freedom (``math.inf``:
    the normal's), to about 1e-12 relative: Newton's method on :func:`student_t_cdf` from the
    normal quantile, kept inside a shrinking bracket."""
    if not 0 < p < 1:
        raise ValueError(f"a quantile needs 0 < p < 1, got {p}")
    z = NormalDist().inv_cdf(p)
    if math.isinf(dof):
        return z
    if dof > LARGE_DOF:  # Fisher's expansion in 1/dof (Abramowitz & Stegun 26.7.5), its next
        # term about 1e-20 here; the CDF's own evaluation loses digits as dof grows
        g1 = (z**3 + z) / 4
        g2 = (5 * z**5 + 16 * z**3 + 3 * z) / 96
        g3 = (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384
        inv = 1.0 / dof  # its powers underflow to 0 where dof's would overflow
        return z + inv * (g1 + inv * (g2 + inv * g3))
    if p < 0.5:
        return -student_t_quantile(1 - p, dof)
    if p == 0.5:
        return 0.0
    low, high = 0.0, max(1.0, 2 * z)
    while student_t_cdf(high, dof) < p:
        low, high = high, 2 * high
    x = min(max(z, low), high)
    for _ in range(200):
        err = student_t_cdf(x, dof) - p
        if err > 0:
            high = x
        else:
            low = x
        step = err / _student_t_pdf(x, dof)
        new = x - step
        if not low < new < high:
            new = 0.5 * (low + high)
        if abs(new - x) <= 1e-13 * max(1.0, abs(x)):
            return new
        x = new
    return x


def _student_t_pdf(t: float, dof: float) -> float:
    log = (_log_gamma_half_ratio(0.5 * dof) - 0.5 * math.log(dof * math.pi)
           - 0.5 * (dof + 1) * math.log1p(t * t / dof))
    return math.exp(log)


def _log_gamma_half_ratio(a: float) -> float:
    """``ln Gamma(a + 1/2) - ln Gamma(a)``; for large ``a`` by its asymptotic series (the
    difference of two large logarithms would keep only about 1e-16 a of it)."""
    if a < 100:
        return math.lgamma(a + 0.5) - math.lgamma(a)
    # from Stirling's series of each (Abramowitz & Stegun 6.1.41); the next term is ~a^-9
    inv = 1.0 / a  # powers of 1/a, which underflow to 0 where a's powers would overflow
    return (0.5 * math.log(a) - inv / 8 + inv**3 / 192 - inv**5 / 640 + 17 * inv**7 / 14336)


def _incomplete_beta(a: float, b: float, x: tuple[float, float], y: tuple[float, float]
                     ) -> float:
    """The regularised incomplete beta function I_x(a, b), 0 < x < 1, for the t
    distribution's ``b = 1/2`` or ``a = 1/2``; ``x`` and ``y = 1 - x`` each given with its
    logarithm (computed apart, without cancellation: ``a ln x`` is large where the degrees of
    freedom are). Its continued fraction (Abramowitz & Stegun 26.5.8) evaluated by the
    modified Lentz method, on the side of the symmetry ``I_x(a, b) = 1 - I_y(b, a)`` where it
    converges fast."""
    if x[0] > (a + 1) / (a + b + 2):
        return 1.0 - _incomplete_beta(b, a, y, x)
    big, small = (a, b) if b == 0.5 else (b, a)
    assert small == 0.5, "only the t distribution's incomplete beta functions are written"
    log_front = _log_gamma_half_ratio(big) - math.lgamma(0.5) + a * x[1] + b * y[1]
    return math.exp(log_front) * _beta_fraction(a, b, x[0]) / a


def _beta_fraction(a: float, b: float, x: float) -> float:
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 500):
        for num in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                    -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + num * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + num / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) < 1e-15:
            break
    return h
