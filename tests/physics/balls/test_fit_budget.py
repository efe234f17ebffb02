"""The ball fit's budget (batcert.physics.balls.fit_budget, issue 40 item 6a): a fit to tests
that contradict one another ends within a count of test evaluations, whatever the machine, and
says what it did: no law found (not converged), or the test at fault not searched for to the
end (the one the full fit misses most is named, and the message says the search stopped).
Forty contradictory tests took five minutes before the budget."""

from __future__ import annotations

import numpy as np
import pytest

from batcert.physics.balls.fit import BallTest, FitError, _solve, fit_ball
from batcert.physics.balls.fit_budget import Budget, Exhausted

MASS, RADIUS = 0.145, 0.0369  # [kg, m] a baseball


def contradictory(n: int) -> list[BallTest]:
    """``n`` CORs and ``n`` collision times at the same speeds, each pair flipping between two
    balls that cannot be one (tiny uncertainties)."""
    speeds = 5.0 + 3.0 * np.arange(n)
    cors = [BallTest("cor", v, 0.7 if i % 2 else 0.4, 0.001) for i, v in enumerate(speeds)]
    times = [BallTest("collision_time", v, 2e-3 if i % 2 else 0.5e-3, 1e-5)
             for i, v in enumerate(speeds)]
    return cors + times


def test_budget_counts_and_stops():
    budget = Budget(10)
    budget.spend(4)
    budget.spend(6)
    assert budget.used == 10
    with pytest.raises(Exhausted):
        budget.spend(1)
    with pytest.raises(ValueError, match="at least one test evaluation"):
        Budget(0)


def test_fit_that_spends_its_budget_is_refused_as_not_converged():
    with pytest.raises(FitError) as caught:
        fit_ball(contradictory(10), MASS, RADIUS, evaluations=300)
    assert not caught.value.converged and caught.value.test is None
    assert str(caught.value) == (
        "the fit of the viscoelastic ball to its 20 tests did not converge within its budget "
        "of 300 test evaluations: the tests contradict one another (not of one ball), or an "
        "uncertainty is too small")


def test_search_for_the_test_at_fault_stops_at_the_budget():
    # a COR of 0.9 at 58 m/s among tests of a ball like the collegiate one (two parameters held
    # to keep the refits short)
    fixed = (("exponent", 1.68), ("relaxation_time", 155e-6))
    tests = (BallTest("cor", 1.0, 0.65, 0.01), BallTest("cor", 25.0, 0.55, 0.01),
             BallTest("cor", 58.0, 0.9, 0.01), BallTest("compression", 0.00635, 1500.0, 50.0),
             BallTest("collision_time", 11.0, 1e-3, 5e-5))
    # what the full fit spends (the calls fit_ball makes), and one more: the fit ends, the
    # leave-one-out refits that look for the test at fault do not
    spent = Budget()
    _, r, _ = _solve(tests, MASS, RADIUS, fixed, budget=spent)
    assert np.max(np.abs(r)) > 3  # refused
    with pytest.raises(FitError) as caught:
        fit_ball(tests, MASS, RADIUS, fixed, evaluations=spent.used + 1)
    error = caught.value
    assert error.converged and error.test == 2 == int(np.argmax(np.abs(r)))  # the worst miss
    assert str(error).startswith("the viscoelastic law fitted to all 5 tests misses 4 of them "
                                 "by more than 3 standard uncertainties, this one most, by")
    assert str(error).endswith(f"(the search for the test at fault stopped at the fit's budget "
                               f"of {spent.used + 1:,} test evaluations)")
