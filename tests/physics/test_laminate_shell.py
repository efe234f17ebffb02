"""The shell of revolution with a laminated or multi-wall wall (its law ``[[A, B], [B, D]]``,
batcert.physics.shell_element), and the beam sections a layup gives (batcert.model.geometry).

Checks against what the theory must give, with their tolerances:
- an isotropic wall given as a law, or as a one-ply laminate of the same metal, is the isotropic
  shell (the same sums: 1e-10 relative);
- a long open tube's lowest n = 2 mode is the inextensional ring's, whose frequency depends on
  the hoop bending stiffness ``D22`` and the mass per area only (Soedel, Vibrations of Shells and
  Plates, 3rd ed., 2004, Sec. 4.8). Hoop (90 deg) against axial (0 deg) fibres of the same ply
  move it by sqrt(E1 / E2) to within the tube's end effects and the ring's stretching: the
  shell is checked against the ring to 2 % (the isotropic tube of this length is within 0.5 %
  of its ring, test_shell.py's measure) and the ratio of the two layups to 2 %;
- two sliding walls have the sum of the walls' ``D``, so their ring frequency is that of
  ``D1 + D2``, not of the bonded stack: the same 2 %.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from batcert.model.geometry import section_properties, stack_section
from batcert.physics.laminate import Layer, OrthotropicPly, WallStack
from batcert.physics.shell import Assembler, ring_frequency_of
from batcert.physics.shell_element import ShellOfRevolution, isotropic_law

CARBON = OrthotropicPly("carbon", 140e9, 10e9, 5e9, 0.3, 1550.0)
AL = OrthotropicPly.isotropic("al", 71.7e9, 0.33, 2830.0)
RADIUS, LENGTH = 0.032, 1.2  # a long tube: its lowest n = 2 mode is the ring's


def _tube(law=None, wall=3e-3, density=1550.0, ends=("open", "open"), elements=60,
          length=LENGTH):
    z = np.linspace(0.0, length, elements + 1)
    ones = np.ones(elements)
    return ShellOfRevolution(z, np.full(z.size, RADIUS), wall * ones, density * ones,
                             71.7e9 * ones, 0.33, ends,
                             None if law is None else np.repeat(law[None], elements, axis=0))


def _lowest(shell, n=2):
    system = Assembler(shell).system(n)
    lam = scipy.linalg.eigh(system.stiffness, system.mass, eigvals_only=True,
                            subset_by_index=(0, 0))
    return float(np.sqrt(lam[0]) / (2 * np.pi))


def test_an_isotropic_law_or_a_metal_ply_is_the_isotropic_shell():
    base = _tube(None, density=2830.0, ends=("closed", "open"), length=0.3)
    law = isotropic_law([71.7e9], [3e-3], 0.33)[0]
    metal = WallStack(((Layer(AL, 0.4, 3e-3),),)).law()
    for given in (law, metal):
        other = _tube(given, density=2830.0, ends=("closed", "open"), length=0.3)
        for n in (0, 2, 3):
            a, b = Assembler(base).system(n), Assembler(other).system(n)
            np.testing.assert_allclose(b.stiffness, a.stiffness, rtol=0,
                                       atol=1e-10 * np.abs(a.stiffness).max())


@pytest.mark.parametrize("angle", [0.0, 90.0])
def test_a_long_laminated_tube_rings_at_its_hoop_bending_stiffness(angle):
    stack = WallStack(((Layer(CARBON, np.radians(angle), 3e-3),),))
    law = stack.law()
    shell = _tube(law)
    ring = float(ring_frequency_of(RADIUS, law[4, 4], 1550.0 * 3e-3))
    assert _lowest(shell) == pytest.approx(ring, rel=0.02)


def test_hoop_fibres_raise_the_ring_by_the_square_root_of_the_modulus_ratio():
    hoop, axial = (_lowest(_tube(WallStack(((Layer(CARBON, np.radians(a), 3e-3),),)).law()))
                   for a in (90.0, 0.0))
    assert hoop / axial == pytest.approx(np.sqrt(140e9 / 10e9), rel=0.02)


def test_two_sliding_walls_bend_as_the_sum_of_the_walls_not_as_one():
    one = (Layer(AL, 0.0, 1.5e-3),)
    double = WallStack((one, one)).law()
    bonded = WallStack(((Layer(AL, 0.0, 3e-3),),)).law()
    np.testing.assert_allclose(double[:3, :3], bonded[:3, :3], rtol=1e-12)  # same A
    assert double[4, 4] == pytest.approx(bonded[4, 4] / 4, rel=1e-12)  # 2 (t/2)^3 = t^3 / 4
    f_double = _lowest(_tube(double, density=2830.0))
    f_bonded = _lowest(_tube(bonded, density=2830.0))
    assert f_double / f_bonded == pytest.approx(0.5, rel=0.02)  # sqrt(1/4), same mass


def test_a_law_with_shear_coupling_is_refused():
    single = WallStack(((Layer(CARBON, np.radians(30), 3e-3),),)).law()
    with pytest.raises(ValueError, match="couples stretching or bending with shear"):
        _tube(single)
    balanced = WallStack(((Layer(CARBON, np.radians(30), 3e-3, balanced=True),),)).law()
    _tube(balanced)  # a balanced layer has none


def test_a_stack_s_beam_section_sums_its_walls():
    outer = np.array([0.0667])
    metal = stack_section(WallStack(((Layer(AL, 0.0, 1.2e-3),), (Layer(AL, 0.0, 1.5e-3),))),
                          outer)
    area, second = section_properties(outer, outer - 2 * 2.7e-3)
    # an isotropic wall's axial modulus is E, however it is split into walls
    assert metal["bending_stiffness"][0] == pytest.approx(71.7e9 * second[0], rel=1e-12)
    assert metal["linear_density"][0] == pytest.approx(2830.0 * area[0], rel=1e-12)
    assert metal["poisson_ratio"][0] == pytest.approx(0.33, rel=1e-12)
    hoop = stack_section(WallStack(((Layer(CARBON, np.pi / 2, 3e-3),),)), outer)
    axial = stack_section(WallStack(((Layer(CARBON, 0.0, 3e-3),),)), outer)
    # fibres along the bat stiffen its bending by E1 / E2, with the same mass
    assert axial["bending_stiffness"][0] / hoop["bending_stiffness"][0] == pytest.approx(
        14.0, rel=1e-9)
    assert axial["linear_density"][0] == pytest.approx(hoop["linear_density"][0], rel=1e-12)
