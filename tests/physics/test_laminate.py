"""Classical lamination theory (batcert.physics.laminate) against an independent implementation,
the `composites` package (PyPI, used only here), and against what the theory must give.

The ply values are round carbon/epoxy-like numbers: the checks compare two implementations of
the same equations, or the equations with their own limits, so any orthotropic values serve.
Tolerances: 1e-12 relative against `composites` (the same sums in another order, double
rounding only: measured 4e-16); 1e-12 for the identities."""

from __future__ import annotations

import numpy as np
import pytest

from batcert.physics.laminate import Layer, OrthotropicPly, laminate, turned

CARBON = OrthotropicPly("carbon/epoxy-like", 138e9, 8.96e9, 7.1e9, 0.3, 1600.0)
GLASS = OrthotropicPly("glass/epoxy-like", 39e9, 8.6e9, 3.8e9, 0.28, 2100.0)
PLY = 0.125e-3  # [m]


def _layers(angles, plies=None, thickness=None):
    plies = plies or [CARBON] * len(angles)
    thickness = thickness or [PLY] * len(angles)
    return [Layer(p, np.radians(a), t) for a, p, t in zip(angles, plies, thickness, strict=True)]


@pytest.mark.parametrize("angles, plies, thickness", [
    ([0, 45, -45, 90, 90, -45, 45, 0], None, None),  # symmetric quasi-isotropic
    ([0, 45, -45, 90, 30], None, [0.125e-3, 0.2e-3, 0.125e-3, 0.15e-3, 0.1e-3]),  # neither
    ([20, -20], [CARBON, GLASS], None),  # two materials, unsymmetric angle pair
])
def test_a_b_d_agree_with_the_composites_package(angles, plies, thickness):
    composites = pytest.importorskip("composites")
    got = laminate(_layers(angles, plies, thickness))
    plies = plies or [CARBON] * len(angles)
    ref = composites.laminated_plate(
        angles, plyts=thickness or [PLY] * len(angles),
        laminaprops=[(p.e1, p.e2, p.nu12, p.g12, p.g12, p.g12) for p in plies])
    # each against its own scale (B's: A h, as B of a symmetric stack is rounding only)
    h = got.thickness
    scales = (np.abs(ref.A).max(), np.abs(ref.A).max() * h, np.abs(ref.D).max())
    for mine, theirs, scale in zip((got.a, got.b, got.d), (ref.A, ref.B, ref.D), scales,
                                   strict=True):
        np.testing.assert_allclose(mine, theirs, rtol=0, atol=1e-12 * scale)


def test_a_symmetric_layup_has_no_coupling_and_a_quasi_isotropic_one_is_isotropic_in_plane():
    lam = laminate(_layers([0, 45, -45, 90, 90, -45, 45, 0]))
    np.testing.assert_allclose(lam.b, 0.0, atol=1e-12 * np.abs(lam.a).max() * PLY)
    a = lam.a
    assert a[0, 0] == pytest.approx(a[1, 1], rel=1e-12)
    assert a[2, 2] == pytest.approx((a[0, 0] - a[0, 1]) / 2, rel=1e-12)
    assert abs(a[0, 2]) < 1e-12 * a[0, 0] and abs(a[1, 2]) < 1e-12 * a[0, 0]


def test_an_isotropic_ply_gives_the_plate_s_stiffnesses():
    e, nu, t = 70e9, 0.33, 2.5e-3
    iso = OrthotropicPly("aluminium", e, e, e / (2 * (1 + nu)), nu, 2700.0)
    lam = laminate([Layer(iso, 0.3, t)])  # any angle
    assert lam.a[0, 0] == pytest.approx(e * t / (1 - nu**2), rel=1e-12)
    assert lam.d[0, 0] == pytest.approx(e * t**3 / (12 * (1 - nu**2)), rel=1e-12)
    assert lam.a[2, 2] == pytest.approx(e * t / (2 * (1 + nu)), rel=1e-12)
    assert lam.areal_density == pytest.approx(2700.0 * t, rel=1e-15)
    assert not lam.couples_shear()


def test_balanced_angle_plies_couple_bending_with_twist_where_they_sit_at_different_depths():
    # symmetric [+30/-30/-30/+30]: A16 = 0 and B = 0, but D16 != 0 (the +30 plies are outside)
    sym = laminate(_layers([30, -30, -30, 30]))
    assert abs(sym.a[0, 2]) < 1e-12 * sym.a[0, 0]
    assert abs(sym.d[0, 2]) > 1e-2 * sym.d[0, 0]
    assert sym.couples_shear()
    # antisymmetric [+30/-30]: A16 = D16 = 0 (equal depths), stretching couples with twist, B16
    anti = laminate(_layers([30, -30]))
    assert abs(anti.a[0, 2]) < 1e-12 * anti.a[0, 0] and abs(anti.d[0, 2]) < 1e-12 * anti.d[0, 0]
    assert abs(anti.b[0, 2]) > 1e-2 * anti.a[0, 0] * anti.thickness
    assert anti.couples_shear()
    assert not laminate(_layers([0, 90, 90, 0])).couples_shear()  # a cross-ply does not


def test_turning_a_ply_by_90_degrees_swaps_its_axes():
    q = CARBON.stiffness()
    qt = turned(q, np.pi / 2)
    assert qt[0, 0] == pytest.approx(q[1, 1], rel=1e-12)
    assert qt[1, 1] == pytest.approx(q[0, 0], rel=1e-12)
    assert qt[2, 2] == pytest.approx(q[2, 2], rel=1e-12)


@pytest.mark.parametrize("bad", [dict(e1=-1.0), dict(nu12=4.0), dict(density=0.0)])
def test_an_impossible_ply_is_refused(bad):
    values = dict(name="x", e1=138e9, e2=8.96e9, g12=7.1e9, nu12=0.3, density=1600.0) | bad
    with pytest.raises(ValueError):
        OrthotropicPly(**values)
