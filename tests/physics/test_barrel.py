"""Unit tests of the thin-ring barrel spring (batcert.physics.barrel)."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from batcert.physics import barrel
from batcert.physics.batmodel import Material

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/, for the shared helper
from r161 import r161_bat  # noqa: E402

# REFERENCE-DATA.md, "Materials" (H): aluminium 7050
AL7050 = Material("aluminium-7050", density=2830.0, youngs_modulus=71.7e9, shear_modulus=26.9e9,
                  poisson_ratio=0.33)
OUTER_RADIUS = 2.625 * 0.0254 / 2  # 2 5/8 in barrel [m]
WALLS = np.array([2.0e-3, 2.5e-3, 3.0e-3])  # [m]


def test_ring_frequencies_match_reference_data():
    # REFERENCE-DATA.md "Materials" (D): about 1.26 / 1.60 / 1.95 kHz for 2.0 / 2.5 / 3.0 mm.
    # The reference values are quoted to 3 significant figures: 2 % covers the rounding.
    f = barrel.hoop_frequency(OUTER_RADIUS, WALLS, AL7050)
    np.testing.assert_allclose(f, [1260.0, 1600.0, 1950.0], rtol=0.02)


def test_spring_and_mass_give_the_ring_frequency():
    k, m = barrel.barrel_spring(OUTER_RADIUS, WALLS, AL7050, effective_width=0.04)
    np.testing.assert_allclose(np.sqrt(k / m), barrel.hoop_angular_frequency(OUTER_RADIUS, WALLS,
                                                                              AL7050), rtol=1e-12)
    radius = OUTER_RADIUS - WALLS / 2
    np.testing.assert_allclose(m, 1.25 * np.pi * AL7050.density * 0.04 * WALLS * radius,
                               rtol=1e-12)


def test_stiffness_scales_with_wall_cubed_and_falls_as_the_wall_thins():
    walls = np.linspace(1.5e-3, 3.5e-3, 9)
    k, _ = barrel.barrel_spring(OUTER_RADIUS, walls, AL7050, 0.05)
    assert np.all(np.diff(k) > 0)
    # k = (9 pi / 12) E' b t^3 / R^3 with R = outer radius - t/2: exactly t^3 at fixed mean radius
    k_fixed_r, _ = barrel.barrel_spring(0.03 + walls / 2, walls, AL7050, 0.05)
    np.testing.assert_allclose(k_fixed_r / walls**3, k_fixed_r[0] / walls[0] ** 3, rtol=1e-12)
    slope = np.polyfit(np.log(walls), np.log(k), 1)[0]
    assert 3.0 < slope < 3.3  # the mean radius shrinks a little as the wall grows
    k_wide, _ = barrel.barrel_spring(OUTER_RADIUS, walls, AL7050, 0.10)
    np.testing.assert_allclose(k_wide, 2 * k, rtol=1e-12)


def hollow_r161(inner_from=0.55, wall=2.5e-3, width=0.05):
    """The R161 profile turned into an aluminium shell beyond ``inner_from`` [m] (test geometry)."""
    bat = r161_bat()
    hollow = bat.z_mid > inner_from
    inner = np.where(hollow, bat.outer_diameter - 2 * wall, 0.0)
    return dataclasses.replace(bat, construction="hollow", inner_diameter=inner,
                               material=AL7050, barrel_effective_width=width)


def test_spring_at_impact_locations():
    bat = hollow_r161()
    z0, z1 = barrel.barrel_region(bat)
    z = np.array([0.30, z0 + 0.3 * (z1 - z0), 0.5 * (z0 + z1), z0 + 0.8 * (z1 - z0)])
    k, m = barrel.barrel_spring_at(bat, z)
    assert k.shape == m.shape == (4,)
    assert k[0] == np.inf and m[0] == 0.0  # solid slice: no barrel spring
    s = np.searchsorted(bat.z_edges, z[1:], side="right") - 1
    k_ring, m_ring = barrel.barrel_spring(bat.outer_diameter[s] / 2, 2.5e-3, AL7050, 0.05)
    # the (2, 1) hoop mode: ring spring-mass divided by sin^2 of the axial position
    shape = np.sin(np.pi * (z[1:] - z0) / (z1 - z0))
    np.testing.assert_allclose(barrel.axial_shape(bat, z[1:]), shape, rtol=1e-12)
    np.testing.assert_allclose(k[1:], k_ring / shape**2, rtol=1e-12)
    np.testing.assert_allclose(m[1:], m_ring / shape**2, rtol=1e-12)
    k2, _ = barrel.barrel_spring_at(bat, z, effective_width=0.10)
    np.testing.assert_allclose(k2[1:], 2 * k[1:], rtol=1e-12)


def test_hoop_mode_is_most_compliant_mid_barrel_and_absent_off_it():
    bat = hollow_r161()
    z0, z1 = barrel.barrel_region(bat)
    z = np.linspace(z0 + 1e-3, z1 - 1e-3, 41)
    k, _ = barrel.barrel_spring_at(bat, z)
    finite = np.isfinite(k)
    assert abs(z[np.argmin(np.where(finite, k, np.inf))] - 0.5 * (z0 + z1)) < 0.01
    k_off, m_off = barrel.barrel_spring_at(bat, [z0 - 0.02])
    assert k_off[0] == np.inf and m_off[0] == 0.0


def test_default_width_is_half_the_full_diameter_barrel():
    bat = hollow_r161(width=None)
    z0, z1 = barrel.barrel_region(bat)
    assert 0 < z0 < z1 <= bat.length
    assert barrel.default_effective_width(bat) == pytest.approx(0.5 * (z1 - z0))
    k_default, _ = barrel.barrel_spring_at(bat, [0.5 * (z0 + z1)])
    k_explicit, _ = barrel.barrel_spring_at(bat, [0.5 * (z0 + z1)], 0.5 * (z1 - z0))
    np.testing.assert_allclose(k_default, k_explicit, rtol=1e-12)


def test_solid_bat_has_no_spring():
    assert barrel.barrel_spring_at(r161_bat(), [0.7]) is None
    assert barrel.default_effective_width(r161_bat()) is None
    assert np.isnan(barrel.barrel_region(r161_bat())[0])


def test_bad_geometry():
    with pytest.raises(ValueError):
        barrel.hoop_frequency(OUTER_RADIUS, 0.0, AL7050)
    with pytest.raises(ValueError):
        barrel.hoop_frequency(OUTER_RADIUS, OUTER_RADIUS * 1.1, AL7050)
