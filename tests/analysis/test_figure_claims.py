"""batcert.analysis.claims: the claim checks that read a study figure, ``opposite-trends`` and
``figure-sweet-spot-less-than-rigid``.

The comparison is built from hand-made RunResults (no engine) and the figures by hand, with
numbers chosen so that each status is reached for a stated reason. Every expected number is one
subtraction of the chosen values, and the evidence prints it to 4 decimals (changes of a metric)
or 0.1 cm (movements): far coarser than the rounding of a float subtraction (about 1e-16), so
the expected text is exact.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from batcert.analysis.claims import _trend, evaluate_claim
from batcert.analysis.compare import compare
from batcert.results.compare import ComparisonResult, StudyFigure, StudyFigureBat
from batcert.results.run import ConditionResult, InputFile, MassProperties, RunResult, Sweep
from batcert.specs.common import spec_from
from batcert.specs.study import CLAIM_SCHEMA, ClaimSpec

WALL = 0.0027  # the aluminium bat's nominal wall [m]
WALLS = [0.6 * WALL, 0.8 * WALL, WALL, 1.2 * WALL]  # 60, 80, 100, 120 % of it
SPEEDS = [0.0, 20.0, 40.0, 60.0]  # swing speeds [rad/s]; Eq. 7 is undefined at 0


def _run(bat: str) -> RunResult:
    """One bat under protocol "p" with one condition; only the protocol id matters here."""
    sweep = Sweep([0.4, 0.55, 0.7], [30.0, 40.0, 30.0], [1.0, 1.0, 1.0])
    cond = ConditionResult(
        name="pitched-and-swung", setup="pitched-and-swung", pitch_speed=-31.0,
        bat_angular_speed=53.0, relative_speed=60.0, impact_location=0.55, exit_speed=40.0,
        bat_angular_speed_after=50.0, cor=0.5, ball_cor=0.5, bpf=1.0, besr=0.7, bbcor=0.5,
        collision_efficiency=0.2, metric_value=1.0, cop=0.54, sweet_spot=0.55,
        rigid_sweet_spot=0.75, at_window_edge=False, sweep=sweep)
    mp = MassProperties(0.86, 0.15, 0.9, 0.43, 0.2, 0.2 / (0.9 * 0.43), 0.9, 0.43, 0.2, None,
                        None, None, "none")
    return RunResult(
        protocol="p", protocol_title="p", protocol_version="1", protocol_reference="ref",
        protocol_notes="", bat=bat, ball="ball", metric="bpf", aggregate="mean", value=1.0,
        limit=None, tolerance=0.0, margin=None, verdict=None, impact_rule="sweet-spot",
        engine="flexible", engine_settings={}, support="pinned", mass_properties=mp,
        conditions=[cond], inputs=[InputFile("bat", bat, f"/bats/{bat}.yaml", "0" * 64)],
        batcert_version="test", created="2024-01-01T00:00:00+00:00")


BASE = compare([[_run("ash")], [_run("alu")]])


def _with(*figures: StudyFigure) -> ComparisonResult:
    return replace(BASE, figures=list(figures))


def _claim(check: str, **kw) -> ClaimSpec:
    defaults = {f.name: f.default for f in CLAIM_SCHEMA.fields}  # the study file's defaults
    return spec_from(ClaimSpec, {**defaults, "id": check, "statement": "s", "check": check,
                                 "protocols": ["p"], **kw})


def _wall_figure(*bats: tuple[str, list, list], nominal: float | None = WALL,
                 values: list[float] = WALLS) -> StudyFigure:
    """The wall figure: per bat (label, bpf values, besr values) against ``values``."""
    return StudyFigure("wall", "BPF and BESR against the wall", "p", "pitched-and-swung", "wall",
                       "length", [v / WALL * 100 for v in values], ["bpf", "besr"],
                       [StudyFigureBat(lab, nominal, list(values), {"bpf": bpf, "besr": besr})
                        for lab, bpf, besr in bats])


def _speed_figure(*bats: tuple[str, list, list]) -> StudyFigure:
    """The swing-speed figure: per bat (label, sweet spots, Eq. 7 sweet spots) [m]."""
    return StudyFigure("speed", "Sweet spot against swing speed", "p", "pitched-and-swung",
                       "bat_angular_speed", "angular_speed", None,
                       ["sweet_spot", "rigid_sweet_spot"],
                       [StudyFigureBat(lab, 53.0, list(SPEEDS),
                                       {"sweet_spot": s, "rigid_sweet_spot": r})
                        for lab, s, r in bats])


OPPOSITE = _claim("opposite-trends", figure="wall", metrics=["bpf", "besr"])
LESS = _claim("figure-sweet-spot-less-than-rigid", figure="speed")


# ---------------------------------------------------------------- _trend


def test_trend_is_the_smallest_value_minus_the_one_nearest_nominal():
    # value at x = 1 (the smallest) minus value at x = 2 (nearest 2.2): 3 - 2
    assert _trend([3.0, 2.0, 1.0], [1.0, 2.0, 3.0], 2.2) == 1.0
    # the order of the values does not matter, only x does
    assert _trend([1.0, 2.0, 3.0], [3.0, 2.0, 1.0], 2.2) == 1.0
    # an undefined value (a failed variant) is left out: the smallest defined x is 2
    assert _trend([None, 5.0, 1.5], [1.0, 2.0, 3.0], 3.0) == 3.5
    # nothing below the nominal, one point only, or no nominal: no trend
    assert _trend([1.0, 2.0], [2.0, 3.0], 2.0) is None
    assert _trend([None, 1.0], [1.0, 2.0], 2.0) is None
    assert _trend([1.0, 2.0], [1.0, 2.0], None) is None


# ---------------------------------------------------------------- opposite-trends


def test_opposite_trends_supported():
    # 100 % -> 60 %: BPF 1.05 -> 1.00 (-0.05), BESR 0.73 -> 0.75 (+0.02), both beyond 0.005
    fig = _wall_figure(("alu", [1.00, 1.02, 1.05, 1.06], [0.75, 0.74, 0.73, 0.72]))
    got = evaluate_claim(_with(fig), OPPOSITE)
    assert got.status == "supported"
    assert "bpf changes by -0.0500 and besr by +0.0200" in got.evidence


def test_opposite_trends_in_the_other_direction_are_opposite_too():
    fig = _wall_figure(("alu", [1.10, 1.08, 1.05, 1.06], [0.70, 0.71, 0.73, 0.72]))
    assert evaluate_claim(_with(fig), OPPOSITE).status == "supported"


def test_both_falling_is_not_opposite():
    # the model's own wall figure (docs/validation.md): both fall below nominal
    fig = _wall_figure(("alu", [0.877, 0.996, 1.053, 1.056], [0.580, 0.670, 0.731, 0.765]))
    got = evaluate_claim(_with(fig), OPPOSITE)
    assert got.status == "not-supported"
    assert "bpf changes by -0.1760 and besr by -0.1510" in got.evidence


def test_a_change_inside_the_dead_band_is_no_trend():
    # BPF moves by -0.003, inside the default tolerance 0.005; with tolerance 0.002 it counts
    fig = _wall_figure(("alu", [1.047, 1.05, 1.05, 1.06], [0.75, 0.74, 0.73, 0.72]))
    assert evaluate_claim(_with(fig), OPPOSITE).status == "not-supported"
    assert evaluate_claim(_with(fig), replace(OPPOSITE, tolerance=0.002)).status == "supported"


def test_opposite_trends_must_hold_for_every_bat():
    fig = _wall_figure(("ash", [1.00, 1.02, 1.05, 1.06], [0.75, 0.74, 0.73, 0.72]),
                       ("alu", [1.00, 1.02, 1.05, 1.06], [0.70, 0.72, 0.73, 0.72]))
    got = evaluate_claim(_with(fig), OPPOSITE)
    assert got.status == "not-supported"
    assert "ash:" in got.evidence and "alu:" in got.evidence


def test_opposite_trends_not_testable_without_values_below_nominal():
    above = [WALL, 1.2 * WALL, 1.4 * WALL]  # 100 % to 140 %: nothing thinner than nominal
    fig = _wall_figure(("alu", [1.0, 1.1, 1.2], [0.7, 0.6, 0.5]), values=above)
    got = evaluate_claim(_with(fig), OPPOSITE)
    assert got.status == "not-testable" and "no values below the nominal wall" in got.evidence
    no_nominal = _wall_figure(("alu", [1.00, 1.02, 1.05, 1.06], [0.75, 0.74, 0.73, 0.72]),
                              nominal=None)
    assert evaluate_claim(_with(no_nominal), OPPOSITE).status == "not-testable"


def test_a_figure_claim_without_its_figure_is_not_testable():
    got = evaluate_claim(BASE, OPPOSITE)  # the comparison has no figures
    assert got.status == "not-testable" and "'wall' was not computed" in got.evidence
    assert "--study-figures" in got.evidence  # and how to have it computed
    other = _speed_figure(("alu", [0.5, 0.5, 0.5, 0.5], [None, 0.4, 0.6, 0.8]))
    assert evaluate_claim(_with(other), OPPOSITE).status == "not-testable"


# ---------------------------------------------------------------- figure-sweet-spot-less-than-rigid


def test_sweet_spot_moving_less_than_half_of_eq7_is_supported():
    # over 20-60 rad/s (Eq. 7 defined): model 0.56 -> 0.57 (1 cm), Eq. 7 0.41 -> 0.79 (38 cm)
    fig = _speed_figure(("ash", [0.55, 0.56, 0.565, 0.57], [None, 0.41, 0.65, 0.79]),
                        ("alu", [0.54, 0.55, 0.56, 0.57], [None, 0.39, 0.63, 0.76]))
    got = evaluate_claim(_with(fig), LESS)
    assert got.status == "supported"
    assert "ash: over 3 speeds where Eq. 7 is defined and the sweet spot lies inside the " \
           "search window, the sweet spot moves 1.0 cm, Eq. 7 " \
           "38.0 cm" in got.evidence


def test_only_speeds_where_eq7_is_defined_count():
    # at w1 = 0 the sweet spot is 25 cm away; counted, the model would move 27 cm against
    # Eq. 7's 38 cm (more than half); left out, it moves 2 cm
    fig = _speed_figure(("ash", [0.30, 0.55, 0.56, 0.57], [None, 0.41, 0.65, 0.79]))
    assert evaluate_claim(_with(fig), LESS).status == "supported"


def test_a_sweet_spot_that_follows_eq7_is_not_supported():
    # a rigid bat's sweet spot is Eq. 7 (constant COR): it moves as far, ratio 1 > 0.5
    eq7 = [None, 0.41, 0.65, 0.79]
    fig = _speed_figure(("ash", [0.41, 0.41, 0.65, 0.79], eq7))
    got = evaluate_claim(_with(fig), LESS)
    assert got.status == "not-supported" and "moves 38.0 cm, Eq. 7 38.0 cm" in got.evidence
    # and every bat must pass: one bat moving as Eq. 7 fails the claim
    two = _speed_figure(("ash", [0.55, 0.56, 0.565, 0.57], eq7), ("alu", [0.41, 0.41, 0.65, 0.79], eq7))
    assert evaluate_claim(_with(two), LESS).status == "not-supported"


def test_factor_sets_the_accepted_ratio():
    # model 10 cm against Eq. 7 38 cm: ratio 0.26, below 0.5 but above 0.2
    fig = _speed_figure(("ash", [0.5, 0.5, 0.55, 0.6], [None, 0.41, 0.65, 0.79]))
    assert evaluate_claim(_with(fig), LESS).status == "supported"
    assert evaluate_claim(_with(fig), replace(LESS, factor=0.2)).status == "not-supported"


def test_fewer_than_two_speeds_with_eq7_is_not_testable():
    # a stationary bat (w1 = 0) everywhere but one point: one pair, no movement to compare
    fig = _speed_figure(("ash", [0.5, 0.5, 0.55, 0.6], [None, None, None, 0.79]))
    got = evaluate_claim(_with(fig), LESS)
    assert got.status == "not-testable" and "fewer than two speeds" in got.evidence
    # a figure that does not plot the sweet spot at all cannot be read either
    wall = _wall_figure(("alu", [1.00, 1.02, 1.05, 1.06], [0.75, 0.74, 0.73, 0.72]))
    assert evaluate_claim(_with(wall), replace(LESS, figure="wall")).status == "not-testable"


@pytest.mark.parametrize("claim", [OPPOSITE, LESS], ids=lambda c: c.check)
def test_figure_claim_on_a_protocol_not_compared_is_not_testable(claim):
    figs = [_wall_figure(("alu", [1.00, 1.02, 1.05, 1.06], [0.75, 0.74, 0.73, 0.72])),
            _speed_figure(("ash", [0.55, 0.56, 0.565, 0.57], [None, 0.41, 0.65, 0.79]))]
    got = evaluate_claim(_with(*figs), replace(claim, protocols=["missing"]))
    assert got.status == "not-testable" and "missing" in got.evidence
    assert evaluate_claim(_with(*figs), claim).status == "supported"  # the same, compared
