"""L. V. Smith, "Evaluating baseball bat performance", Sports Engineering 4 (2001) 205-214: the
two bats of the study (its Table 1, as listed in DESIGN.md section 1) and the centre of
percussion, Eq. 4.

Study values, measured about a pivot 150 mm from the knob of a 34 in (860 mm) bat:
ash 906 g, CG 429 mm, MOI 0.209 kg m^2; aluminium 863 g, CG 418 mm, MOI 0.198 kg m^2.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from batcert.commands.inputs import load_bat_any
from batcert.model.mass import mass_properties
from batcert.physics.rigid import centre_of_percussion

REPO = Path(__file__).resolve().parents[2]
PIVOT = 0.150  # [m from knob], the study's pivot
TABLE_1 = {  # bat file: (mass [kg], CG from the pivot [m], MOI about the pivot [kg m^2])
    "ash-34": (0.906, 0.429, 0.209),
    "aluminium-34": (0.863, 0.418, 0.198),
}
# Eq. 4, q = I / (M rbar), worked by hand from Table 1:
#   ash       0.209 / (0.906 x 0.429) = 0.209 / 0.388674 = 0.537726 m
#   aluminium 0.198 / (0.863 x 0.418) = 0.198 / 0.360734 = 0.548881 m
COP = {"ash-34": 0.537726, "aluminium-34": 0.548881}


@pytest.mark.parametrize("bat", sorted(TABLE_1))
def test_shipped_study_bats_have_the_measured_mass_properties(bat):
    # Reconciliation matches the measured values exactly (three equations, three unknowns), so
    # the tolerance is rounding: 1e-9 relative.
    mp = mass_properties(load_bat_any(bat).built, PIVOT)
    mass, cg, moi = TABLE_1[bat]
    assert (mp.mass, mp.cg, mp.moi_pivot) == pytest.approx((mass, cg, moi), rel=1e-9)
    assert (mp.measured_mass, mp.measured_cg, mp.measured_moi_pivot) == pytest.approx(
        (mass, cg, moi), rel=1e-12)


@pytest.mark.parametrize("bat", sorted(TABLE_1))
def test_centre_of_percussion_eq4(bat):
    # The hand-worked values above are given to 6 digits: tolerance 1e-6 relative (half a unit
    # in the last place is 1e-6 m on 0.54 m).
    mass, cg, moi = TABLE_1[bat]
    assert centre_of_percussion(moi, mass, cg) == pytest.approx(COP[bat], rel=1e-6)
    assert mass_properties(load_bat_any(bat).built, PIVOT).cop == pytest.approx(COP[bat],
                                                                                rel=1e-6)


def test_the_aluminium_cop_lies_farther_out():
    # The study's point that the COP depends on the bat: 1.1 cm farther from the pivot for the
    # lighter aluminium bat (0.548881 - 0.537726 = 0.011155 m).
    assert COP["aluminium-34"] - COP["ash-34"] == pytest.approx(0.011155, abs=2e-6)
