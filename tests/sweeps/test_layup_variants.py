"""The layup's sweep parameters (batcert.sweeps.layup_variants) on the shipped composite and
double-wall bats: their nominal values follow from the bat files by arithmetic, each variant
changes only what it names, and a bat without the layup it needs is refused before any work.
Tolerances: values made by one scale factor carry a rounding or two (1e-14 relative)."""

from __future__ import annotations

import math

import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.sweeps.variants import PARAMETERS, Case, ParameterError

MM = 1e-3


def case_of(bat: str):
    built = load_bat_any(bat).built
    return Case(built.spec, load_protocol_any("ncaa-bbcor").protocol), built


def barrel(case: Case):
    return case.bat.layup[-1][2]  # both bats' barrel is their last span


def test_the_nominal_values_are_the_bat_file_s():
    comp, dbl = case_of("composite-bbcor-34"), case_of("double-wall-alloy-34")
    assert PARAMETERS["ply_angle"].nominal(*comp) == pytest.approx(30.0, rel=1e-14)
    # 0.3 + 1.4 + 0.8 + 1.4 + 0.3 mm of 0.3 mm plies
    assert PARAMETERS["ply_count"].nominal(*comp) == pytest.approx(14.0, rel=1e-14)
    assert PARAMETERS["wall_split"].nominal(*dbl) == pytest.approx(1.45 / 2.85, rel=1e-14)


def test_ply_angle_turns_only_the_balanced_layers():
    case, built = case_of("composite-bbcor-34")
    varied = barrel(PARAMETERS["ply_angle"].apply(case, built, 45.0))
    for old, new in zip(barrel(case).walls[0], varied.walls[0], strict=True):
        assert new.thickness == old.thickness
        assert new.angle == (math.radians(45.0) if old.balanced else old.angle)
    assert case.bat.layup[0] == PARAMETERS["ply_angle"].apply(case, built, 45.0).bat.layup[0]


def test_ply_count_scales_every_layer_and_split_moves_thickness_between_walls():
    case, built = case_of("composite-bbcor-34")
    thicker = barrel(PARAMETERS["ply_count"].apply(case, built, 21.0))
    assert thicker.thickness == pytest.approx(1.5 * 4.2 * MM, rel=1e-14)
    case, built = case_of("double-wall-alloy-34")
    split = barrel(PARAMETERS["wall_split"].apply(case, built, 0.3))
    inner, outer = (sum(layer.thickness for layer in w) for w in split.walls)
    assert outer == pytest.approx(0.3 * 2.85 * MM, rel=1e-14)
    assert inner + outer == pytest.approx(2.85 * MM, rel=1e-14)
    assert PARAMETERS["wall_split"].apply(case, built, 0.3).bat.measured is None


@pytest.mark.parametrize("bat, name, message", [
    ("bbcor-alloy-34", "ply_angle", "has no layup"),
    ("composite-bbcor-34", "wall_split", "has one wall"),
    ("double-wall-alloy-34", "ply_angle", "no balanced"),
    ("hybrid-34", "ply_count", "does not cover its barrel"),
    ("composite-bbcor-34", "wall", "gives its walls as a layup"),
    ("composite-bbcor-34", "density", "has no material of its own"),
])
def test_a_bat_without_what_the_parameter_varies_is_refused(bat, name, message):
    with pytest.raises(ParameterError, match=message):
        PARAMETERS[name].nominal(*case_of(bat))
