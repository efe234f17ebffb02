"""Uncertainties in spec files: the fields that take ``+/-`` (the bat's measured block and wall,
the ball's mass and COR points) load as Uncertain with the right standard uncertainty u; the
fields that do not are refused at their file, line and field.

Each file is a shipped one with a few lines edited (written to tmp_path). Unit factors are exact
(1 g = 1e-3 kg, 1 mm = 1e-3 m, 1 oz = 0.028349523125 kg), so values compare to rel 1e-12; a
uniform u is the stated half-width / sqrt 3 (JCGM 100 4.3.7).
"""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import pytest

from batcert.errors import InputError
from batcert.specs.ball import load_ball
from batcert.specs.bat import load_bat
from batcert.specs.protocol import load_protocol
from batcert.uncertainty.inputs import stated_inputs
from batcert.units import OUNCE, Uncertain

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/, for the shared helper
from edits import edited, line_of  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
ASH = REPO / "bats" / "ash-34.yaml"
ALUMINIUM = REPO / "bats" / "aluminium-34.yaml"
BALL = REPO / "protocols" / "balls" / "collegiate-baseball.yaml"
NATHAN_BALL = REPO / "tests" / "fixtures" / "good" / "ball-nathan-law.yaml"
BBCOR = REPO / "protocols" / "ncaa-bbcor.yaml"
SQRT3 = math.sqrt(3.0)
REL = 1e-12  # exact unit factors: only float rounding remains


def assert_uncertain(v, value: float, u: float, distribution: str) -> None:
    assert type(v) is Uncertain, repr(v)
    assert float(v) == pytest.approx(value, rel=REL)
    assert v.u == pytest.approx(u, rel=REL)
    assert v.distribution == distribution


ASH_MEASURED = ("  mass: 906 g +/- 0.5 g (uniform)\n"
                "  cg: 429 mm +/- 0.5 mm (uniform)          # from the pivot\n"
                "  moi: 0.209 kg*m^2 +/- 0.0005 kg*m^2 (uniform) # about the pivot\n")
ALUMINIUM_WALL = ("wall:               # [position from knob, wall thickness]\n"
                  "  - [0 in, 1.8 mm]\n"
                  "  - [11 in, 1.8 mm]\n"
                  "  - [20 in, 2.2 mm]\n"
                  "  - [22 in, 2.7 mm]\n"
                  "  - [860 mm, 2.7 mm]\n")
COR_85 = "  - [85 ft/s, 0.546 +/- 0.032 (uniform)]\n"


# ---------------------------------------------------------------- the bat's measured block


def test_measured_fields_load_with_their_uncertainty(tmp_path):
    """Normal, uniform, a bare-number u and the ± sign, each on one measured field."""
    path = edited(tmp_path, ASH, (ASH_MEASURED, "  mass: 906 g +/- 2 g\n"
                                                "  cg: 429 mm ± 1 (uniform)\n"
                                                "  moi: 0.209 kg*m^2 +/- 0.001 kg*m^2 (normal)\n"))
    m = load_bat(path).measured
    assert_uncertain(m.mass, 0.906, 0.002, "normal")
    assert_uncertain(m.cg, 0.429, 0.001 / SQRT3, "uniform")  # bare 1 -> 1 mm, half-width
    assert_uncertain(m.moi, 0.209, 0.001, "normal")
    assert type(m.pivot) is float and m.pivot == pytest.approx(0.150, rel=REL)  # none stated


@pytest.mark.parametrize("source, old, new, field, value, u, distribution", [
    (ASH, "  cg: 429 mm +/- 0.5 mm (uniform)          # from the pivot\n",
     "  balance_point: 579 mm +/- 1 mm\n", "balance_point", 0.579, 0.001, "normal"),
    (ASH, "  moi: 0.209 kg*m^2 +/- 0.0005 kg*m^2 (uniform) # about the pivot\n",
     "  radius_of_gyration: 120 mm +/- 3 mm (uniform)\n", "radius_of_gyration", 0.120,
     0.003 / SQRT3, "uniform"),
    (ASH, "  moi: 0.209 kg*m^2 +/- 0.0005 kg*m^2 (uniform) # about the pivot\n",
     "  pendulum_period: 1.5 s +/- 2 ms\n", "pendulum_period", 1.5, 0.002, "normal"),
    (ASH, "reconcile: density-profile\n",  # appended at the end of the measured block
     "  first_bending_frequency: 165 Hz +/- 4 Hz (uniform)\nreconcile: density-profile\n",
     "first_bending_frequency", 165.0, 4.0 / SQRT3, "uniform"),
    (ALUMINIUM, "reconcile: point-masses\n",
     "  hoop_frequency: 1500 Hz +/- 15 Hz\nreconcile: point-masses\n", "hoop_frequency",
     1500.0, 15.0, "normal"),
])
def test_every_measured_field_that_may_carry_an_uncertainty(tmp_path, source, old, new, field,
                                                            value, u, distribution):
    m = load_bat(edited(tmp_path, source, (old, new))).measured
    assert_uncertain(getattr(m, field), value, u, distribution)


@pytest.mark.parametrize("source, old, new, start, field, loader", [
    (ASH, "length: 860 mm\n", "length: 860 mm +/- 1 mm\n", "length:", "length", load_bat),
    (ASH, "  - [28.0 in, 2.61 in]\n", "  - [28.0 in, 2.61 in +/- 0.01 in]\n", "  - [28.0 in",
     "profile[13]", load_bat),
    (ASH, "  pivot: 150 mm\n", "  pivot: 150 mm +/- 1 mm\n", "  pivot:", "measured.pivot",
     load_bat),
    (BALL, "radius: 36.9 mm\n", "radius: 36.9 mm ± 0.1 mm\n", "radius:", "radius", load_ball),
    (BBCOR, "pivot: 6 in\n", "pivot: 6 in +/- 1 mm\n", "pivot:", "pivot", load_protocol),
])
def test_a_field_that_takes_no_uncertainty_is_refused_at_its_line(tmp_path, source, old, new,
                                                                   start, field, loader):
    path = edited(tmp_path, source, (old, new))
    with pytest.raises(InputError) as exc:
        loader(path)
    [problem] = exc.value.problems
    line = line_of(path, start)
    assert (problem.file, problem.line, problem.field) == (str(path), line, field)
    assert "cannot carry an uncertainty ('+/-')" in problem.message
    assert "docs/uncertainty.md" in problem.message
    assert f"{path}:{line}: {field}: cannot read" in exc.value.render()


# ---------------------------------------------------------------- the wall


def test_a_constant_wall_loads_with_its_uncertainty(tmp_path):
    path = edited(tmp_path, ALUMINIUM, (ALUMINIUM_WALL, "wall: 2.5 mm +/- 0.1 mm (uniform)\n"))
    assert_uncertain(load_bat(path).wall, 0.0025, 0.0001 / SQRT3, "uniform")


def test_wall_stations_load_each_with_its_own_uncertainty(tmp_path):
    path = edited(tmp_path, ALUMINIUM, ("  - [11 in, 1.8 mm]\n", "  - [11 in, 1.8 mm +/- 0.1 mm]\n"),
                  ("  - [22 in, 2.7 mm]\n", "  - [22 in, 2.7 mm +/- 0.05]\n"))
    positions, walls = load_bat(path).wall
    assert all(type(z) is float for z in positions)  # positions take no uncertainty
    assert_uncertain(walls[1], 0.0018, 0.0001, "normal")
    assert_uncertain(walls[3], 0.0027, 0.00005, "normal")  # bare 0.05 -> mm
    assert [type(t) for t in walls] == [float, Uncertain, float, Uncertain, float]


@pytest.mark.parametrize("old, new, start, field", [
    (ALUMINIUM_WALL, "wall: 2.5 mm +/- -0.1 mm\n", "wall:", "wall"),
    ("  - [22 in, 2.7 mm]\n", "  - [22 in, 2.7 mm +/- -0.05 mm]\n", "  - [22 in", "wall[3]"),
])
def test_a_negative_wall_uncertainty_is_refused(tmp_path, old, new, start, field):
    path = edited(tmp_path, ALUMINIUM, (old, new))
    with pytest.raises(InputError) as exc:
        load_bat(path)
    [problem] = exc.value.problems
    assert (problem.line, problem.field) == (line_of(path, start), field)
    assert "the uncertainty must not be negative" in problem.message


def test_wall_stations_of_mixed_distributions_are_refused_at_the_wall(tmp_path):
    """Stations move together (one draw for all), so they must share a distribution; loading
    accepts each station, stated_inputs refuses the mix at the ``wall:`` line."""
    path = edited(tmp_path, ALUMINIUM, ("  - [11 in, 1.8 mm]\n", "  - [11 in, 1.8 mm +/- 0.1 mm]\n"),
                  ("  - [22 in, 2.7 mm]\n", "  - [22 in, 2.7 mm +/- 0.05 mm (uniform)]\n"))
    bat = load_bat(path)
    with pytest.raises(InputError) as exc:
        stated_inputs(bat, [])
    [problem] = exc.value.problems
    assert (problem.file, problem.line, problem.field) == (str(path), line_of(path, "wall:"), "wall")
    assert "must share one distribution" in problem.message


# ---------------------------------------------------------------- the ball


def test_shipped_ball_states_its_mass_and_cor_band():
    """collegiate-baseball.yaml: mass uniform over 5-5 1/4 oz (5.125 +/- 0.125 oz), the COR
    points uniform: +/- 0.01 at 1 m/s (0.64-0.66), +/- 0.032 at 85 ft/s (MLB's 0.514-0.578
    band) and at 58 m/s (assumed as wide)."""
    spec = load_ball(BALL)
    assert_uncertain(spec.model.mass, 5.125 * OUNCE, 0.125 * OUNCE / SQRT3, "uniform")
    cors = [p for key, p in spec.tests if key == "cor"]
    for p, nominal, half in zip(cors, (0.65, 0.546, 0.53), (0.01, 0.032, 0.032), strict=True):
        assert_uncertain(p.value, nominal, half / SQRT3, "uniform")
        assert type(p.condition) is float


def test_ball_mass_and_cor_points_in_other_forms(tmp_path):
    path = edited(tmp_path, NATHAN_BALL,
                  ("mass: 5.125 oz +/- 0.125 oz (uniform)\n", "mass: 145 g +/- 1\n"),
                  ("  - [1 m/s, 0.64 +/- 0.032 (uniform)]\n", "  - [1 m/s, 0.64]\n"),
                  (COR_85, "  - [85 ft/s, 0.546 ± 0.008]\n"),
                  ("  - [71 m/s, 0.50 +/- 0.032 (uniform)]\n", "  - [71 m/s, 0.50 +/- 0.01 (normal)]\n"))
    model = load_ball(path).model
    assert_uncertain(model.mass, 0.145, 0.001, "normal")  # bare 1 -> 1 g
    cor = model.law.cor_values
    assert type(cor[0]) is float and cor[0] == 0.64
    assert_uncertain(cor[1], 0.546, 0.008, "normal")
    assert_uncertain(cor[2], 0.50, 0.01, "normal")


@pytest.mark.parametrize("cor, message", [
    ("0.546 +/- -0.01", "the COR's uncertainty must lie in [0, 1), got '0.546 +/- -0.01'"),
    ("0.546 +/- 1.5", "the COR's uncertainty must lie in [0, 1)"),
    ("0.546 +/- 0.01 (weird)", "unknown distribution 'weird' (choose normal or uniform)"),
    ("0.546 +/- 0.01 g", "COR must be a number in (0, 1], or one with its standard uncertainty"),
    ("+/- 0.01", "give a value and its standard uncertainty"),
    ("1.2 +/- 0.01", "COR must be a number in (0, 1]"),  # the nominal is still checked
])
def test_a_bad_cor_uncertainty_is_refused_at_its_point(tmp_path, cor, message):
    path = edited(tmp_path, NATHAN_BALL, (COR_85, f"  - [85 ft/s, {cor}]\n"))
    with pytest.raises(InputError) as exc:
        load_ball(path)
    [problem] = exc.value.problems
    assert (problem.line, problem.field) == (line_of(path, "  - [85 ft/s"), "cor[1]")
    assert message in problem.message


def test_cor_points_of_mixed_distributions_are_refused_at_the_cor(tmp_path):
    path = edited(tmp_path, NATHAN_BALL, (COR_85, "  - [85 ft/s, 0.546 +/- 0.01]\n"))
    ball = load_ball(path)  # each point reads
    with pytest.raises(InputError) as exc:
        stated_inputs(load_bat(ASH), [ball])
    [problem] = exc.value.problems
    assert (problem.file, problem.line, problem.field) == (str(path), line_of(path, "cor:"), "cor")
    assert "must share one distribution" in problem.message


def test_the_shipped_bats_state_uncertainties_only_in_their_measured_block():
    """Every shipped bat reads; its Uncertain values are exactly the measured fields written
    with +/- (docs/uncertainty.md, "What the shipped files state"), and its wall has none."""
    for path in sorted((REPO / "bats").glob("*.yaml")):
        bat = load_bat(path)
        text = path.read_text(encoding="utf-8")
        stated = {name for name in bat.measured.__dataclass_fields__
                  if isinstance(getattr(bat.measured, name), Uncertain)}
        written = set(re.findall(r"^  (\w+): [^#\n]*\+/-", text, re.M))
        assert stated == written and stated, path.name
        walls = () if bat.wall is None else bat.wall[1] if isinstance(bat.wall, tuple) \
            else (bat.wall,)
        assert not any(isinstance(t, Uncertain) for t in walls), path.name
