"""batcert.numerics against scipy (the implementations it replaces in the commands, to avoid
their imports): Brent's root and Student's t quantile."""

import math

import pytest
from scipy.optimize import brentq
from scipy.stats import t as student

from batcert.numerics import NoBracket, brent_root, student_t_cdf, student_t_quantile


@pytest.mark.parametrize("f, a, b", [
    (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),  # Wallis's cubic
    (lambda x: math.cos(x) - x, 0.0, 1.0),
    (lambda x: math.exp(x) - 10, -5.0, 5.0),
    (lambda x: 1e-9 * (x - 7.25), 0.0, 100.0),  # a tiny slope
    (lambda x: math.atan(50 * (x - 0.1)), -3.0, 3.0),
])
def test_brent_root_finds_scipy_brentqs_root(f, a, b):
    # the same tolerance (2e-12 absolute): both stop within it of the true root, so they agree
    # to twice it
    found = brent_root(f, a, b, xtol=2e-12)
    assert found.converged
    assert found.x == pytest.approx(brentq(f, a, b, xtol=2e-12), abs=4e-12)
    assert found.calls <= 60  # bisection alone would need about 40 here


def test_brent_root_finds_a_triple_root():
    # interpolation crawls on the flat cubic until bisection takes over: about 120 calls, more
    # than the default 100 (scipy's brentq also gives up at 100 here); the true root is 0.3
    found = brent_root(lambda x: (x - 0.3) ** 3, -1.0, 2.0, xtol=2e-12, maxiter=300)
    assert found.converged and found.calls < 300
    assert found.x == pytest.approx(0.3, abs=2e-12)


def test_brent_root_stops_at_the_tolerance_asked():
    found = brent_root(lambda x: x - 1 / 3, 0.0, 1.0, xtol=1e-3, rtol=0.0)
    assert abs(found.x - 1 / 3) <= 1e-3


def test_brent_root_refuses_an_interval_without_a_sign_change():
    with pytest.raises(NoBracket, match="same sign"):
        brent_root(lambda x: x * x + 1, -1.0, 1.0)


def test_brent_root_takes_an_end_that_is_a_root():
    assert brent_root(lambda x: x - 2, 2.0, 5.0).x == 2.0


@pytest.mark.parametrize("dof", [1, 1.5, 2, 3, 4.7, 9, 30, 120.5, 1e4, 9.9e5, 1.01e6, 1e7, 1e10,
                                 1e40, 1e300])
@pytest.mark.parametrize("p", [0.5, 0.6, 0.8413, 0.975, 0.995, 0.99999, 0.1, 0.025])
def test_student_t_quantile_matches_scipy(p, dof):
    # scipy's ppf is accurate to about 1e-14 relative; ours stops at 1e-13 and the CDF's
    # continued fraction at 1e-15: 1e-10 relative holds with a wide margin. Above 1e6 degrees
    # of freedom (a lab's exact hits: Welch-Satterthwaite with almost no scatter) the quantile
    # is Fisher's expansion; 1e10 was 3.6e-7 off and 1e40 overflowed before it
    assert student_t_quantile(p, dof) == pytest.approx(student.ppf(p, dof), rel=1e-10, abs=1e-12)


@pytest.mark.parametrize("t", [-40.0, -2.0, -0.3, 0.0, 0.7, 1.96, 12.0])
@pytest.mark.parametrize("dof", [1, 2.5, 8, 50, 1e5])
def test_student_t_cdf_matches_scipy(t, dof):
    assert student_t_cdf(t, dof) == pytest.approx(student.cdf(t, dof), rel=1e-11, abs=1e-15)


def test_student_t_quantile_with_infinite_dof_is_the_normals():
    assert student_t_quantile(0.975, math.inf) == pytest.approx(1.959963984540054, abs=1e-12)


@pytest.mark.parametrize("p, dof", [(0.0, 3), (1.0, 3), (0.9, 0), (0.9, -1)])
def test_student_t_quantile_refuses_impossible_arguments(p, dof):
    with pytest.raises(ValueError):
        student_t_quantile(p, dof)
