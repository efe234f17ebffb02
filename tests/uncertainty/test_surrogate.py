"""The response surface that serves the Monte Carlo's draws (batcert.uncertainty.surrogate) and
its use in batcert.uncertainty.propagate.monte_carlo: its design and fit on known polynomials,
the draws it checks, and against full draws (every draw solved by the engine) on the same
draws (the same seed draws the same inputs, so the two agree draw by draw).

The engine tests use the rigid engine with the ball of Nathan's law (tests/fixtures/good/
ball-nathan-law.yaml, whose COR the rigid engine has in closed form: a few seconds for a few
hundred draws), as tests/uncertainty/test_propagate.py does; the shipped bats under the shipped
ball and the flexible engine, N = 1000, are the slow test at the end.
"""

from __future__ import annotations

import dataclasses
from itertools import combinations
from pathlib import Path

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import get_engine
from batcert.runner.runner import run_protocols
from batcert.uncertainty.propagate import DEFAULT_SEED, Job, draws, monte_carlo
from batcert.uncertainty.surrogate import (
    CORNERS,
    SURROGATE_CHECKED,
    ResponseSurface,
    axial,
    checked_draws,
    default_bound,
    most_runs,
    second_stage,
    strong_inputs,
    strong_pairs,
)

REPO = Path(__file__).resolve().parents[2]
BALL = REPO / "tests" / "fixtures" / "good" / "ball-nathan-law.yaml"


def uniform_draws(n: int, d: int, seed: int = 1) -> np.ndarray:
    return np.sqrt(3.0) * np.random.default_rng(seed).uniform(-1, 1, (n, d))


# --- the surface alone (numpy) ----------------------------------------------------------------
def design(z, f):
    """The two stages' points and results for the function ``f`` of the draws' ``k``."""
    first = axial(z)
    strong = strong_inputs(f(first))
    points = np.concatenate([first, second_stage(z, strong)])
    return points, f(points), strong


def test_the_surface_reproduces_a_polynomial_of_its_form():
    # one strong input (0), two weak ones: the second stage has input 0 at +/- a / 2 and the
    # corners of the pairs (0, 1) and (0, 2), and every term of the polynomial below is a term
    # of the surface, so the fit through the design's points is exact but for rounding (1e-12
    # of a result of order 1)
    z = uniform_draws(500, 3)

    def f(k):
        k0, k1, k2 = k.T
        return (0.5 + 0.03 * k0 + 1e-3 * k1 - 2e-4 * k2 + 2e-3 * k0**2 - 3e-4 * k0**3
                + 1e-5 * k1**2 + 4e-4 * k0 * k1 - 5e-5 * k0**2 * k2 + 6e-5 * k0 * k2**2)[:, None]

    points, values, strong = design(z, f)
    assert strong == [True, False, False] and strong_pairs(strong) == [(0, 1), (0, 2)]
    assert points.shape[0] == 1 + 2 * 3 + 2 + len(CORNERS) * 2
    np.testing.assert_allclose(ResponseSurface.fit(points, values, strong)(z), f(z), rtol=0,
                               atol=1e-12)


def test_what_the_surface_leaves_out_is_what_the_check_must_catch():
    # an interaction between two weak inputs (k1 k2) and a weak input's cubic (k2^3) are not
    # terms of the surface, which misses them by about their size at the corners and between
    # the axial points (the check on actual draws is what catches such a miss)
    z = uniform_draws(500, 3)
    f = lambda k: (0.5 + 0.03 * k[:, 0] + 1e-4 * k[:, 1] + 1e-4 * k[:, 2]  # noqa: E731
                   + 1e-4 * k[:, 1] * k[:, 2])[:, None]
    points, values, strong = design(z, f)
    assert (1, 2) not in strong_pairs(strong)
    miss = np.abs(ResponseSurface.fit(points, values, strong)(z) - f(z)).max()
    assert 1e-4 < miss <= 3.01e-4  # at most |k1 k2| = 3 (uniform: |k| <= sqrt 3) times 1e-4
    g = lambda k: (0.5 + 0.03 * k[:, 0] + 1e-4 * k[:, 2] ** 3)[:, None]  # noqa: E731
    points, values, strong = design(z, g)
    assert strong == [True, False, False]
    miss = np.abs(ResponseSurface.fit(points, values, strong)(z) - g(z)).max()
    # the quadratic through k2 = -a, 0, a misses 1e-4 k^3 by 1e-4 |k^3 - a^2 k|, at most
    # 1e-4 x 2 a^3 / (3 sqrt 3) = 2.0e-4 at k = a / sqrt 3 (a = sqrt 3, less in 500 draws)
    assert 1e-4 < miss <= 2.0001e-4


def test_every_pair_is_strong_when_the_inputs_are_alike():
    z = uniform_draws(200, 4)
    points, _, strong = design(z, lambda k: 1.0 + k.sum(axis=1, keepdims=True))
    assert strong == [True] * 4 and strong_pairs(strong) == list(combinations(range(4), 2))
    assert points.shape[0] + SURROGATE_CHECKED == most_runs(4)


def test_the_design_stays_within_the_draws_range_of_each_input():
    # no design point reaches a value of an input that the draws (checked as possible by
    # inputs.draw) do not
    rng = np.random.default_rng(3)
    z = np.column_stack([rng.standard_normal(1000), uniform_draws(1000, 2)])
    a = np.abs(z).max(axis=0)
    for points in (axial(z), second_stage(z, [True, False, True])):
        assert np.all(np.abs(points) <= a + 1e-15)
    assert np.abs(axial(z)).max(axis=0) == pytest.approx(a, rel=1e-15)


def test_the_checked_draws_include_the_extremes_and_follow_the_seed():
    z = uniform_draws(1000, 3)
    predicted = np.column_stack([z @ [1.0, 0.1, 0.01], -z[:, 0]])
    chosen = checked_draws(z, predicted, seed=7)
    assert len(chosen) == SURROGATE_CHECKED == len(set(chosen)) and chosen == sorted(chosen)
    assert int(np.argmax((z**2).sum(axis=1))) in chosen  # the farthest from the nominal
    assert int(np.argmax(predicted[:, 0])) in chosen and int(np.argmin(predicted[:, 0])) in chosen
    assert checked_draws(z, predicted, seed=7) == chosen  # the same seed, the same draws
    assert checked_draws(z, predicted, seed=8) != chosen  # the random ones move
    assert checked_draws(z[:5], predicted[:5], seed=7) == [0, 1, 2, 3, 4]  # fewer draws: all


# --- through the engine (rigid, Nathan's ball) ------------------------------------------------
@pytest.fixture(scope="module")
def rigid():
    return get_engine("rigid")


@pytest.fixture(scope="module")
def ash():
    return load_bat_any("ash-34").built


@pytest.fixture(scope="module")
def jobs(ash, rigid):
    """ncaa-bbcor (max-metric rule; the rigid bat's BBCOR peaks at the window's end) and
    astm-bpf (centre of percussion) with Nathan's ball, ash-34's nominal runs."""
    from batcert.specs.ball import load_ball

    ball = load_ball(BALL)
    out = []
    for pid in ("ncaa-bbcor", "astm-bpf"):
        p = dataclasses.replace(load_protocol_any(pid), ball=ball)
        (run,) = run_protocols([(ash, p.protocol, p.ball)], rigid)
        out.append(Job(p.protocol, p.ball, run))
    return out


N = 200


@pytest.fixture(scope="module")
def both(ash, jobs, rigid):
    return {m: monte_carlo(ash, jobs, rigid, N, method=m) for m in ("surrogate", "full")}


def test_the_surface_against_full_draws(both, jobs):
    for s, f, job in zip(both["surrogate"], both["full"], jobs, strict=True):
        p = s.propagation
        assert (p.method, p.requested, p.checked_draws, p.reason) == (
            "surrogate", "surrogate", SURROGATE_CHECKED, "")
        assert p.engine_draws == p.design_points + SURROGATE_CHECKED < N
        assert p.bound == default_bound(job.protocol.metric) == 1e-4  # BBCOR, BPF
        assert p.largest_difference <= p.bound
        assert "response surface" in s.method and "response surface" not in f.method
        assert f.propagation.method == "full" and f.propagation.largest_difference is None
        # Draw by draw: the surface's miss on all N draws against the engine's. Measured
        # 3.2e-10 (BBCOR: the rigid bat's impact stays at the window's end, and BBCOR follows
        # the ball's COR almost in a straight line) and 3.3e-8 (BPF); within the bound. The
        # checked draws include the extremes, so the check sees the largest miss or about it
        # (measured: the same, and 0.8 of it): 3 times it, plus 1e-6 for the flexible
        # engine's scatter from draw to draw should this ever run on it.
        gap = np.abs(np.array(s.values) - f.values)
        assert gap.max() <= p.bound
        assert gap.max() <= 3 * p.largest_difference + 1e-6
        # So the statistics agree to the same: the mean and each percentile move by at most
        # the largest miss; the standard deviation (ddof 1) by at most the RMS miss times
        # sqrt(N / (N - 1)) (triangle inequality on the centred draws)
        assert s.mean == pytest.approx(f.mean, abs=gap.max())
        assert s.standard_deviation == pytest.approx(
            f.standard_deviation, abs=np.sqrt((gap**2).sum() / (N - 1)) * (1 + 1e-12))
        for q in ("median", "interval_low", "interval_high", "minimum", "maximum"):
            assert getattr(s, q) == pytest.approx(getattr(f, q), abs=gap.max()), q
        # the pass probability moves only by the draws within the largest miss of the limit
        if f.pass_probability is not None:
            edge = job.nominal.limit + job.nominal.tolerance
            near = np.sum(np.abs(np.array(f.values) - edge) <= gap.max())
            assert abs(s.pass_probability - f.pass_probability) <= near / N
        # the sensitivities are slopes of the same draws' results: within the miss per u
        for a, b in zip(s.inputs, f.inputs, strict=True):
            assert a.sensitivity == pytest.approx(b.sensitivity, abs=gap.max())


def test_a_tiny_bound_falls_back_to_every_draw_and_says_so(ash, jobs, rigid, both):
    # 1e-15 is below what the surface misses by here (3e-10 and 3e-8, above), and
    # every draw is solved by the engine; the results are then the full draws' (the same
    # draws in the same chunks, so the same engine batches: to rounding, 1e-12 of order-1
    # results)
    back = monte_carlo(ash, jobs, rigid, N, method="surrogate", bound=1e-15)
    for u, f in zip(back, both["full"], strict=True):
        p = u.propagation
        assert (p.method, p.requested, p.bound) == ("full", "surrogate", 1e-15)
        assert p.largest_difference > 1e-15
        assert p.reason.startswith("the response surface missed the engine by ")
        assert " on 8 checked draws (protocol " in p.reason  # the worse of the two protocols
        assert p.reason.endswith(", more than the bound 1e-15")
        assert p.engine_draws == p.design_points + SURROGATE_CHECKED + N
        np.testing.assert_allclose(u.values, f.values, rtol=0, atol=1e-12)
        assert "response surface" not in u.method


def test_few_draws_are_all_solved(ash, jobs, rigid):
    # 20 draws cost fewer engine runs than the surface's design: full draws, with the reason
    (u, _) = monte_carlo(ash, jobs, rigid, 20)
    p = u.propagation
    assert (p.method, p.requested, p.engine_draws) == ("full", "surrogate", 20)
    assert f"20 draws are not more than the {most_runs(len(u.inputs))} engine runs" in p.reason


def test_the_seed_reproduces_the_surface_and_its_check(ash, jobs, rigid, both):
    again = monte_carlo(ash, jobs, rigid, N, method="surrogate")
    for a, b in zip(again, both["surrogate"], strict=True):
        assert a.values == b.values and a.propagation == b.propagation
    other = monte_carlo(ash, jobs, rigid, N, seed=DEFAULT_SEED + 1)
    assert other[0].values != both["surrogate"][0].values
    inputs, z = draws(ash.spec, [j.ball for j in jobs], N, DEFAULT_SEED)
    assert len(inputs) == 5 and z.shape == (N, 5)


# --- the shipped bats, flexible engine, N = 1000 ----------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("bat", ["aluminium-34", "ash-34"])
def test_the_shipped_bats_surface_against_full_draws(bat):
    # issue 42's case: `run BAT -p ncaa-bbcor --uncertainty 1000`. Full draws take 5-20 s.
    flexible = get_engine("flexible")
    built = load_bat_any(bat).built
    p = load_protocol_any("ncaa-bbcor")
    (run,) = run_protocols([(built, p.protocol, p.ball)], flexible)
    job = [Job(p.protocol, p.ball, run)]
    (s,) = monte_carlo(built, job, flexible, 1000)
    (f,) = monte_carlo(built, job, flexible, 1000, method="full")
    assert s.propagation.method == "surrogate"
    # Measured: the surface misses the engine by at most 1.7e-5 (aluminium-34) and 5.5e-6
    # (ash-34) over all 1000 draws, against spreads of 0.015; the bound (1e-4) is the test's
    gap = np.abs(np.array(s.values) - f.values)
    assert gap.max() <= s.propagation.bound == 1e-4
    assert s.mean == pytest.approx(f.mean, abs=gap.max())
    # the standard deviation by at most the RMS miss times sqrt(N / (N - 1)) (triangle
    # inequality; measured 1e-6)
    assert s.standard_deviation == pytest.approx(
        f.standard_deviation, abs=np.sqrt((gap**2).sum() / 999) * (1 + 1e-12))
    # the pass probability: a draw changes side only within the largest miss of the limit
    near = np.sum(np.abs(np.array(f.values) - (run.limit + run.tolerance)) <= gap.max())
    assert abs(s.pass_probability - f.pass_probability) <= near / 1000


def test_the_default_bound_is_the_last_digit_the_reports_show():
    # one unit of the metric registry's digits: 1e-4 for the dimensionless metrics (a tenth of
    # the last digit of a limit stated to three decimals), 0.01 m/s for the exit speed, where a
    # single 1e-4 m/s made an exit-speed protocol solve every draw (the surface's 1.5e-4 m/s on
    # ash-34 under usa-softball-2004, docs/uncertainty.md)
    from batcert.methods.metrics import METRICS
    assert {m: default_bound(m) for m in METRICS} == {
        "exit-speed": 0.01, "besr": 1e-4, "bpf": 1e-4, "bbcor": 1e-4,
        "collision-efficiency": 1e-4}
