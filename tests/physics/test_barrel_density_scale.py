"""A hollow bat whose density is scaled uniformly (a draw reconciled to another measured mass)
has the same wall with another mass: batcert.physics.barrel.cached_barrel_modes folds the scale
into the barrel's mass scale instead of computing the wall again. Checked against
compute_barrel_modes of the scaled bat itself (the wall built from its own density, nothing
cached or scaled), and for what the cache then holds."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any
from batcert.physics import barrel

HOLLOW = ("aluminium-34", "bbcor-alloy-34")
# (density factor, barrel_mass_scale, barrel_stiffness_scale): a draw's mass, and the same on
# a calibrated barrel (a measured hoop frequency scales the wall's stiffness and mass)
CASES = [(1.003, 1.0, 1.0), (0.97, 1.0, 1.0), (1.003, 1.1, 0.9), (0.97, 0.95, 1.2)]
PATCH = 15  # sample points across a contact patch, as the engine's default


@pytest.fixture(scope="module")
def models():
    return {name: load_bat_any(name).built.model for name in HOLLOW}


def scaled(model, factor, mass_scale=1.0, stiffness_scale=1.0):
    return dataclasses.replace(model, linear_density=np.asarray(model.linear_density) * factor,
                               barrel_mass_scale=model.barrel_mass_scale * mass_scale,
                               barrel_stiffness_scale=model.barrel_stiffness_scale
                               * stiffness_scale)


def patches(model):
    """Three patches on the barrel (semicircular weight over +/- 25 mm, the size of a BBCOR
    impact's contact) as the engine lays them: points (3, K), weights (3, K), half-angles."""
    z = np.array([0.60, 0.70, 0.78])  # [m from knob]
    half = np.full(z.size, 0.025)
    k = np.arange(1, PATCH + 1)
    xi = np.cos(k * np.pi / (PATCH + 1))
    w = np.sin(k * np.pi / (PATCH + 1)) ** 2
    points = z[:, None] + half[:, None] * xi[None, :]
    weights = np.broadcast_to(w / w.sum(), points.shape)
    return points, weights, barrel.patch_half_angle(model, z, half)


def level(model):
    """The 1/16-octave step of the density scale the cache key rounds to (barrel.py)."""
    return round(math.log2(float(np.max(model.linear_density))) * 16)


@pytest.mark.parametrize("factor, mass_scale, stiffness_scale", CASES)
@pytest.mark.parametrize("name", HOLLOW)
def test_a_scaled_density_is_the_wall_computed_afresh(models, own_barrel_cache, name, factor,
                                                      mass_scale, stiffness_scale):
    # Folding the scale into the mass scale is exact (K and M scale, the shapes do not), so the
    # two agree to the rounding of two eigen-solutions. Measured over CASES and both bats:
    # omega 3.1e-12, shapes 4.7e-12 (of the largest), flexibility 1.7e-15 (of the largest; the
    # static flexibility does not depend on the mass), patch static compliance 1.0e-13, gains
    # 7.1e-12, residual compliance 1.2e-10 (static minus the modes' part: a difference). 1e-9
    # is a few times the largest.
    model = scaled(models[name], factor, mass_scale, stiffness_scale)
    barrel.cached_barrel_modes(models[name])  # the nominal wall, as a Monte Carlo's first run
    cached = barrel.cached_barrel_modes(model)
    direct = barrel.compute_barrel_modes(model, barrel.MAX_FREQUENCY)
    np.testing.assert_array_equal(cached.mode_orders, direct.mode_orders)
    np.testing.assert_allclose(cached.omega, direct.omega, rtol=1e-9)
    # each mode's sign is fixed by the eigen-solver: compare up to it
    sign = np.sign((cached.shapes * direct.shapes).sum(axis=0))
    assert np.abs(cached.shapes - direct.shapes * sign).max() < 1e-9 * np.abs(direct.shapes).max()
    flex_c = cached.green_scale * cached.green
    flex_d = direct.green_scale * direct.green
    assert np.abs(flex_c - flex_d).max() < 1e-9 * np.abs(flex_d).max()
    # the shell the engine sees is the scaled bat's own
    for field in ("z", "r", "thickness", "density", "youngs_modulus"):
        np.testing.assert_allclose(getattr(cached.shell, field), getattr(direct.shell, field),
                                   rtol=1e-12, err_msg=field)
    # what the engine takes from it at three patches
    points, weights, angle = patches(model)
    rc = barrel.barrel_response(cached, points, weights, angle)
    rd = barrel.barrel_response(direct, points, weights, angle)
    np.testing.assert_allclose(rc.static, rd.static, rtol=1e-9)
    np.testing.assert_allclose(rc.residual, rd.residual, rtol=1e-9)
    np.testing.assert_allclose(np.abs(rc.gain), np.abs(rd.gain), rtol=1e-9,
                               atol=1e-9 * np.abs(rd.gain).max())
    # and the scales did act: each order's lowest mode moved by sqrt(stiffness / mass), the
    # mass being the density factor times the mass scale (1e-9: rounding, as above)
    nominal = barrel.cached_barrel_modes(models[name])
    ratio = math.sqrt(stiffness_scale / (factor * mass_scale))
    for n in np.intersect1d(nominal.mode_orders, cached.mode_orders):  # those below 10 kHz
        lowest = cached.omega[cached.mode_orders == n][0]
        assert lowest == pytest.approx(nominal.omega[nominal.mode_orders == n][0] * ratio,
                                       rel=1e-9)


@pytest.mark.parametrize("name", HOLLOW)
def test_a_scaled_density_reuses_the_nominal_wall(models, empty_barrel_cache, name):
    # The cache key rounds the density's scale to 1/16 octave (2^(1/16) = 1.044): within a
    # step every scale reuses the wall computed once; a scale across a step boundary is
    # computed once more, and then reused in turn.
    model = models[name]
    barrel.cached_barrel_modes(model)
    assert empty_barrel_cache.count("barrel") == 1
    base = empty_barrel_cache.entries("barrel")[0]
    for factor, mass_scale in [(1.003, 1.0), (0.999, 1.0), (1.003, 1.1)]:
        drawn = scaled(model, factor, mass_scale)
        assert level(drawn) == level(model)  # the premise: the same step
        barrel.cached_barrel_modes(drawn)
        assert empty_barrel_cache.count("barrel") == 1, factor
        assert empty_barrel_cache.entries("barrel")[0] is base
    # 0.97: a step boundary lies between (aluminium-34's largest density, 1.525 kg/m, sits at
    # 9.74 sixteenths of an octave, x 0.97 at 9.04; the alloy's at 11.06 and 10.36), so one
    # new wall
    across = scaled(model, 0.97)
    assert level(across) != level(model)
    barrel.cached_barrel_modes(across)
    assert empty_barrel_cache.count("barrel") == 2
    barrel.cached_barrel_modes(scaled(model, 0.975))  # the same step as 0.97
    barrel.cached_barrel_modes(across)
    assert empty_barrel_cache.count("barrel") == 2


def test_a_solid_bat_has_no_barrel(empty_barrel_cache):
    ash = load_bat_any("ash-34").built.model
    assert barrel.cached_barrel_modes(scaled(ash, 1.003)) is None
    assert empty_barrel_cache.count("barrel") == 0
