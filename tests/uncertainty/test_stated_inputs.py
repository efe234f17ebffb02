"""The stated inputs of a bat and its balls (batcert.uncertainty.inputs): which are found, their
draws (reproducible, standard normal or uniform with unit variance, impossible values refused)
and the bats and balls built from one row of draws.

Unit factors are exact (1 g = 1e-3 kg, 1 mm = 1e-3 m, 1 oz = 0.028349523125 kg), so values
compare to rel 1e-12; a uniform u is the stated half-width / sqrt 3 (JCGM 100 4.3.7).
"""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.special import ndtr

from batcert.errors import InputError
from batcert.specs.ball import load_ball
from batcert.specs.bat import MEASURED_SCHEMA, load_bat
from batcert.uncertainty.inputs import BAT_FIELDS, StatedInput, draw, sampled, stated_inputs
from batcert.units import OUNCE, Uncertain

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/, for the shared helper
from edits import edited, line_of  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
ASH = REPO / "bats" / "ash-34.yaml"
ALUMINIUM = REPO / "bats" / "aluminium-34.yaml"
BALL = REPO / "protocols" / "balls" / "collegiate-baseball.yaml"
NATHAN_BALL = REPO / "tests" / "fixtures" / "good" / "ball-nathan-law.yaml"  # batcert 0.2's
SQRT3 = math.sqrt(3.0)
REL = 1e-12  # exact unit factors: only float rounding remains


# ---------------------------------------------------------------- what is stated


def test_shipped_ash_and_collegiate_ball():
    """ash-34.yaml: mass 906 g, cg 429 mm, moi 0.209 kg m^2, each +/- half the last digit
    (uniform); the ball: mass 5.125 +/- 0.125 oz, COR 0.65 +/- 0.01, 0.546 and 0.53 each
    +/- 0.032 (all uniform). Bat fields first, in BAT_FIELDS order, then the ball's."""
    inputs = stated_inputs(load_bat(ASH), [load_ball(BALL)])
    expected = [
        ("bat", str(ASH), "measured.mass", line_of(ASH, "  mass:"), "mass", (0.906,), (0.0005,)),
        ("bat", str(ASH), "measured.cg", line_of(ASH, "  cg:"), "length", (0.429,), (0.0005,)),
        ("bat", str(ASH), "measured.moi", line_of(ASH, "  moi:"), "moi", (0.209,), (0.0005,)),
        ("ball", str(BALL), "mass", line_of(BALL, "mass:"), "mass", (5.125 * OUNCE,),
         (0.125 * OUNCE,)),
        ("ball", str(BALL), "cor", line_of(BALL, "cor:"), None, (0.65, 0.546, 0.53),
         (0.01, 0.032, 0.032)),
    ]
    assert [(s.file, s.path, s.field, s.line, s.dimension) for s in inputs] == \
        [e[:5] for e in expected]
    for s, (*_, nominal, half_width) in zip(inputs, expected, strict=True):
        assert s.distribution == "uniform", s.field
        assert s.nominal == pytest.approx(nominal, rel=REL)
        assert s.u == pytest.approx([a / SQRT3 for a in half_width], rel=REL)
        assert all(type(v) is float for v in s.nominal + s.u)  # plain numbers, not Uncertain
    assert inputs[0].label == "bat measured.mass"


def test_every_field_the_schema_lets_carry_an_uncertainty_is_looked_for():
    """A measured field read with uncertain=True but missing from BAT_FIELDS would load its
    +/- and then be silently left out of the Monte Carlo."""
    uncertain = {f.name for f in MEASURED_SCHEMA.fields if "may carry `+/- u`" in f.kind.describe}
    assert uncertain == set(BAT_FIELDS)
    dimensions = {f.name: re.match(r"quantity \((\w[\w ]*?)[ )]", f.kind.describe).group(1)
                  for f in MEASURED_SCHEMA.fields if f.name in BAT_FIELDS}
    assert {k: v.replace(" ", "_") for k, v in dimensions.items()} == BAT_FIELDS


def test_order_wall_and_a_ball_shared_by_two_protocols(tmp_path):
    """All measured fields that may carry one, then the wall, then each ball file once."""
    bat_path = edited(tmp_path, ALUMINIUM,
                      ("reconcile: point-masses\n", "  first_bending_frequency: 180 Hz +/- 2 Hz\n"
                       "  hoop_frequency: 1500 Hz +/- 15 Hz\nreconcile: point-masses\n"),
                      ("  - [22 in, 2.7 mm]\n", "  - [22 in, 2.7 mm +/- 0.1 mm]\n"))
    ball = load_ball(BALL)
    inputs = stated_inputs(load_bat(bat_path), [ball, ball])
    assert [s.label for s in inputs] == [
        "bat measured.mass", "bat measured.cg", "bat measured.moi",
        "bat measured.first_bending_frequency", "bat measured.hoop_frequency", "bat wall",
        "ball mass", "ball cor"]
    wall = inputs[5]
    assert wall.line == line_of(bat_path, "wall:") and wall.dimension == "length"
    assert wall.nominal == pytest.approx((0.0018, 0.0018, 0.0022, 0.0027, 0.0027), rel=REL)
    assert wall.u == pytest.approx((0, 0, 0, 0.0001, 0), rel=REL)  # 0 where none stated
    assert wall.distribution == "normal"


def test_a_ball_reached_by_two_spellings_of_its_path_is_one_source():
    by_name = load_ball(BALL)
    by_detour = load_ball(BALL.parent / ".." / "balls" / BALL.name)
    assert Path(by_detour.path).resolve() == Path(by_name.path).resolve()  # the same file
    inputs = stated_inputs(load_bat(ASH), [by_name, by_detour])
    labels = [s.label for s in inputs]
    assert labels.count("ball mass") == 1 and labels.count("ball cor") == 1


def test_nothing_stated_nothing_listed(tmp_path):
    # (a ball of Nathan's law: a fitted viscoelastic ball needs its tests' uncertainties)
    bat = tmp_path / "bat.yaml"
    bat.write_text(re.sub(r" \+/- [^#\n]*\(uniform\)", "", ASH.read_text(encoding="utf-8")))
    ball = tmp_path / "ball.yaml"
    ball.write_text(re.sub(r" \+/- [^\]\n]*\(uniform\)", "",
                           NATHAN_BALL.read_text(encoding="utf-8")))
    for path in (bat, ball):  # only comments still say +/-
        assert not any("+/-" in line.split("#")[0] for line in path.read_text().splitlines())
    assert stated_inputs(load_bat(bat), [load_ball(ball)]) == []
    # a stated zero is no uncertainty either
    zero = edited(tmp_path, bat, ("  mass: 906 g\n", "  mass: 906 g +/- 0 g\n"))
    assert isinstance(load_bat(zero).measured.mass, Uncertain)  # read, with u = 0
    assert stated_inputs(load_bat(zero), []) == []


# ---------------------------------------------------------------- draws


def stated(distribution: str, nominal: float = 1.0, u: float = 0.01) -> StatedInput:
    return StatedInput("bat", "bat.yaml", "measured.mass", 1, "mass", (nominal,), (u,),
                       distribution)


def test_draws_are_reproducible_for_a_seed_and_differ_for_another():
    inputs = stated_inputs(load_bat(ASH), [load_ball(BALL)])
    a = draw(inputs, 200, seed=11)
    assert a.shape == (200, len(inputs))
    assert np.array_equal(a, draw(inputs, 200, seed=11))
    b = draw(inputs, 200, seed=12)
    assert not np.any(a == b)  # continuous draws from another stream: no value in common


N = 20_000
SE = 1.0 / math.sqrt(N)  # standard error of the mean of N unit-variance draws (0.0071)
K = 5  # tolerances are K standard errors: a correct draw fails one with p < 1e-6


def test_normal_and_uniform_columns_have_mean_zero_and_unit_variance():
    """Normal: standard normal. Uniform: sqrt 3 (2 Phi(z) - 1), on [-sqrt 3, sqrt 3] with
    variance 1. Standard errors for N = 20000: mean 1/sqrt N; a normal sample's std
    1/sqrt(2N); a uniform one's sqrt((mu4/sigma^4 - 1)/N)/2 = sqrt(0.8/N)/2 (mu4 = 9/5
    sigma^4); a bin's share p, sqrt(p(1-p)/N)."""
    z = draw([stated("normal"), stated("uniform")], N, seed=20011)
    normal, uniform = z[:, 0], z[:, 1]
    assert abs(normal.mean()) < K * SE
    assert abs(normal.std() - 1) < K * SE / math.sqrt(2)
    # normal, not uniform: 2 (1 - Phi(sqrt 3)) = 8.3 % of the draws lie beyond +/- sqrt 3
    beyond = 2 * (1 - ndtr(SQRT3))
    assert abs(np.mean(np.abs(normal) > SQRT3) - beyond) < K * math.sqrt(beyond * (1 - beyond) / N)

    assert np.all(np.abs(uniform) <= SQRT3)  # hard bound
    assert abs(uniform.mean()) < K * SE
    assert abs(uniform.std() - 1) < K * math.sqrt(0.8 / N) / 2
    counts, _ = np.histogram(uniform, bins=6, range=(-SQRT3, SQRT3))
    p = 1 / 6  # flat: each sixth of the range holds a sixth of the draws
    assert np.all(np.abs(counts / N - p) < K * math.sqrt(p * (1 - p) / N)), counts / N
    # independent sources: correlation of two independent columns ~ N(0, 1/N)
    assert abs(np.corrcoef(normal, uniform)[0, 1]) < K * SE


def test_a_uniform_column_is_the_documented_transform_of_the_normal_one():
    """draw(): a uniform input's column is sqrt 3 (2 Phi(z) - 1) of the same seed's normal z."""
    z = draw([stated("normal")], 1000, seed=5)[:, 0]
    w = draw([stated("uniform")], 1000, seed=5)[:, 0]
    assert w == pytest.approx(SQRT3 * (2 * ndtr(z) - 1), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("source, old, new, start, field", [
    (ASH, "  mass: 906 g +/- 0.5 g (uniform)", "  mass: 906 g +/- 900 g", "  mass:",
     "measured.mass"),  # u = 0.99 of the value: P(draw <= 0) = Phi(-1.007) = 16 % a draw
    (BALL, "mass: 5.125 oz +/- 0.125 oz (uniform)", "mass: 145 g +/- 145 g", "mass:", "mass"),
])
def test_a_draw_at_or_below_zero_is_refused_at_the_input(tmp_path, source, old, new, start,
                                                         field):
    path = edited(tmp_path, source, (old, new))
    bat, balls = (load_bat(path), []) if source == ASH else (load_bat(ASH), [load_ball(path)])
    inputs = stated_inputs(bat, balls)
    with pytest.raises(InputError) as exc:
        draw(inputs, 1000, seed=3)  # 1000 draws at 16 %: one reaches <= 0 (P(none) ~ 1e-75)
    [problem] = exc.value.problems
    assert (problem.file, problem.line, problem.field) == (str(path), line_of(path, start), field)
    assert "not a possible value" in problem.message and "(seed 3)" in problem.message
    # the drawn value, in the input's SI unit: at or below zero
    drawn = re.search(r"uncertainty draws (\S+) kg in 1000 draws", problem.message)
    assert drawn is not None and float(drawn.group(1)) <= 0


def test_a_cor_draw_above_one_is_refused_at_the_cor(tmp_path):
    """Each point +/- 0.4 (uniform): the 0.64 point reaches above 1 when its move exceeds 0.36
    (5 % of draws), the lowest point 0.50 - 0.4 = 0.1 never reaches 0."""
    cor = ("  - [1 m/s, 0.64 +/- 0.4 (uniform)]\n  - [85 ft/s, 0.546 +/- 0.4 (uniform)]\n"
           "  - [71 m/s, 0.50 +/- 0.4 (uniform)]\n")
    old = ("  - [1 m/s, 0.64 +/- 0.032 (uniform)]\n  - [85 ft/s, 0.546 +/- 0.032 (uniform)]\n"
           "  - [71 m/s, 0.50 +/- 0.032 (uniform)]\n")
    path = edited(tmp_path, NATHAN_BALL, (old, cor))
    inputs = stated_inputs(load_bat(ASH), [load_ball(path)])
    with pytest.raises(InputError) as exc:
        draw(inputs, 1000, seed=3)  # P(no draw above 1) = 0.95^1000 ~ 5e-23
    [problem] = exc.value.problems
    assert (problem.file, problem.line, problem.field) == (str(path), line_of(path, "cor:"), "cor")
    drawn = re.search(r"uncertainty draws (\S+) in 1000 draws", problem.message)
    assert drawn is not None and 1 < float(drawn.group(1)) <= 1.04  # 0.64 + at most 0.4


def test_the_shipped_bands_never_reach_an_impossible_value():
    """Uniform bands are bounded: 0.546 + 0.032 < 1 and every mass stays far above 0, so no
    number of draws is refused."""
    inputs = stated_inputs(load_bat(ASH), [load_ball(BALL)])
    assert draw(inputs, 20_000, seed=1).shape == (20_000, 5)


# ---------------------------------------------------------------- sampled bats and balls


def test_sampled_moves_each_input_by_its_draw_times_u():
    bat, ball = load_bat(ASH), load_ball(NATHAN_BALL)
    inputs = stated_inputs(bat, [ball, ball])  # two protocols sharing the ball: listed once
    z = np.array([1.0, -2.0, 0.5, 1.5, -1.0])  # mass, cg, moi, ball mass, cor
    new_bat, new_balls = sampled(bat, [ball, ball], inputs, z)
    u = [s.u[0] for s in inputs]
    m = new_bat.measured
    assert m.mass == pytest.approx(0.906 + 1.0 * u[0], rel=REL)
    assert m.cg == pytest.approx(0.429 - 2.0 * u[1], rel=REL)
    assert m.moi == pytest.approx(0.209 + 0.5 * u[2], rel=REL)
    assert m.pivot == bat.measured.pivot and m.balance_point is None  # not stated: unchanged
    for b in new_balls:  # the same ball file moves the same way under both protocols
        assert b.model.mass == pytest.approx(5.125 * OUNCE + 1.5 * u[3], rel=REL)
        # every COR point moves by -1 of its own u (one source: the lot's liveliness)
        assert b.model.law.cor_values == pytest.approx(
            [e - 0.032 / SQRT3 for e in (0.64, 0.546, 0.50)], rel=REL)
        assert b.model.law.cor_speeds == ball.model.law.cor_speeds
        assert b.model.radius == ball.model.radius and b.model.law.k1 == ball.model.law.k1
    assert new_bat.profile == bat.profile and new_bat.length == bat.length
    # the loaded specs are not changed
    assert isinstance(bat.measured.mass, Uncertain) and bat.measured.mass == 0.906
    assert ball.model.law.cor_values == (0.64, 0.546, 0.50)


def test_sampled_moves_a_fitted_ball_along_its_fit():
    # the shipped viscoelastic ball: a draw of its COR moves the law along the fit's
    # linearisation (BallFit.moved), the test values themselves are the fit's data and stay
    ball = load_ball(BALL)
    inputs = stated_inputs(load_bat(ASH), [ball])
    z = np.array([0.0, 0.0, 0.0, 0.0, 1.5])  # the COR one and a half u up
    _, (moved,) = sampled(load_bat(ASH), [ball], inputs, z)
    assert moved.model.law == ball.fit.moved(1.5)
    assert moved.model.law != ball.model.law and moved.fit is ball.fit
    # a livelier lot: a higher rigid-wall COR at the tested speeds
    speeds = np.array([1.0, 25.908, 58.0])
    assert np.all(moved.model.cor(speeds) > ball.model.cor(speeds))


def test_sampled_moves_wall_stations_together_and_leaves_unstated_ones(tmp_path):
    path = edited(tmp_path, ALUMINIUM, ("  - [11 in, 1.8 mm]\n", "  - [11 in, 1.8 mm +/- 0.1 mm]\n"),
                  ("  - [22 in, 2.7 mm]\n", "  - [22 in, 2.7 mm +/- 0.2 mm]\n"))
    bat = load_bat(path)
    wall = [s for s in stated_inputs(bat, []) if s.field == "wall"]
    new_bat, _ = sampled(bat, [], wall, np.array([2.0]))
    positions, walls = new_bat.wall
    assert positions == bat.wall[0]
    # +2 u at each stated station (1.8 + 0.2, 2.7 + 0.4 mm); the others keep their thickness
    assert walls == pytest.approx((0.0018, 0.0020, 0.0022, 0.0031, 0.0027), rel=REL)
    # an input not passed to sampled keeps its value (here the measured mass, uncertain)
    assert new_bat.measured.mass is bat.measured.mass


def test_sampled_moves_a_constant_wall(tmp_path):
    old = ALUMINIUM.read_text(encoding="utf-8")
    block = old[old.index("wall:"):old.index("material:")]
    bat = load_bat(edited(tmp_path, ALUMINIUM, (block, "wall: 2.5 mm +/- 0.1 mm\n")))
    wall = [s for s in stated_inputs(bat, []) if s.field == "wall"]
    assert sampled(bat, [], wall, np.array([-1.5]))[0].wall == pytest.approx(0.0025 - 0.00015,
                                                                              rel=REL)


def test_a_zero_row_gives_the_nominal_values():
    bat, ball = load_bat(ASH), load_ball(BALL)
    inputs = stated_inputs(bat, [ball])
    new_bat, [new_ball] = sampled(bat, [ball], inputs, np.zeros(len(inputs)))
    assert new_bat.measured == bat.measured  # floats compare by value
    assert new_ball.model == ball.model
