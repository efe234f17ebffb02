"""Band storage and the band of an inverse (batcert.physics.banded), against numpy's dense
inverse; and the barrel's stored flexibility band against the dense inverse of each order."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

from batcert.physics import barrel, shell
from batcert.physics.banded import inverse_band, lower_band
from batcert.physics.barrel import patch as patch_module
from batcert.physics.barrel import wall as wall_module

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "engines"))
from test_flexible import hollow_bat  # noqa: E402


def banded_spd(rng, n: int, b: int) -> np.ndarray:
    a = rng.normal(size=(n, n))
    a = np.triu(np.tril(a, b), -b)
    return a @ a.T + n * np.eye(n)  # bandwidth 2b, positive definite


def test_lower_band_is_lapacks_layout():
    rng = np.random.default_rng(3)
    a = banded_spd(rng, 12, 2)
    ab = lower_band(a, 4)
    for k in range(5):
        np.testing.assert_array_equal(ab[k, :12 - k], np.diagonal(a, -k))
        np.testing.assert_array_equal(ab[k, 12 - k:], 0.0)
    factor = scipy.linalg.cholesky_banded(ab, lower=True)
    x = scipy.linalg.cho_solve_banded((factor, True), np.eye(12))
    # exact arithmetic would give the inverse; the tolerance is rounding on a matrix whose
    # condition number is below 10
    np.testing.assert_allclose(x, np.linalg.inv(a), rtol=0, atol=1e-14)


@pytest.mark.parametrize("width", [4, 7, 30])
def test_inverse_band_equals_the_dense_inverse_within_the_band(width):
    rng = np.random.default_rng(width)
    n, b = 40, 4
    mats = [banded_spd(rng, n, 2) for _ in range(3)]
    factor = np.stack([scipy.linalg.cholesky_banded(lower_band(a, b), lower=True)
                       for a in mats])
    band = inverse_band(factor, width)
    assert band.shape == (3, n, b + width + 1)
    for o, a in enumerate(mats):
        inv = np.linalg.inv(a)
        for d in range(-b, width + 1):
            rows = np.arange(max(0, -d), min(n, n - d))
            # rounding only: the recursion is backward stable for a positive definite matrix
            np.testing.assert_allclose(band[o, rows, b + d], inv[rows, rows + d], rtol=0,
                                       atol=1e-14 * np.abs(inv).max())
        past = np.arange(n)[:, None] + np.arange(-b, width + 1)[None, :]
        assert np.all(band[o][(past < 0) | (past >= n)] == 0.0)


def test_inverse_band_refuses_a_band_narrower_than_the_matrix():
    factor = np.ones((1, 4, 10))
    with pytest.raises(ValueError, match="at least"):
        inverse_band(factor, 2)


@pytest.fixture(scope="module")
def wall():
    bat = hollow_bat(2.5e-3)
    return barrel.barrel_shell(bat), barrel.compute_barrel_modes(bat)


def _dense_flexibility(sh, n: int) -> np.ndarray:
    """The W-space flexibility of order n by numpy's dense inverse (order 0 with inertia
    relief, as shell.static_solve does it)."""
    system = shell.Assembler(sh).system(n, support=True)
    inv = np.linalg.inv(system.stiffness)
    if system.rigid is not None:
        r = system.rigid
        mr = system.mass @ r
        p = np.eye(r.size) - np.outer(r, mr)
        inv = p @ inv @ p.T
    full = np.zeros((system.node_dofs * sh.z.size,) * 2)
    full[np.ix_(system.free, system.free)] = inv
    w = wall_module._w_space(system, sh.z.size)
    return full[np.ix_(w, w)]


@pytest.mark.parametrize("n", [0, 2, 5, 24])
def test_barrel_flexibility_band_equals_the_dense_inverse(wall, n):
    sh, modes = wall
    dense = _dense_flexibility(sh, n)
    band = modes.green[modes.orders.index(n)]
    size, width = band.shape[0], band.shape[1] - 1
    for d in range(width + 1):
        # rounding only (condition number of the shell stiffness about 1e9, numpy's dense
        # inverse and the banded recursion round differently)
        np.testing.assert_allclose(band[:size - d, d], np.diagonal(dense, d), rtol=0,
                                   atol=1e-9 * np.abs(dense).max())


def test_the_band_covers_the_longest_patch_a_ball_spec_allows(wall):
    # the ball spec accepts radii up to 100 mm (batcert.specs.ball), so a patch is at most
    # 0.2 m long: its flexibility from the band equals the dense sum g^T G g
    sh, modes = wall
    z = np.array([0.45, 0.6, sh.z[0] + 0.002, sh.z[-1] - 0.002])
    half = np.full(z.size, 0.1)
    points = z[:, None] + half[:, None] * np.linspace(-1, 1, 15)[None, :]
    loads = patch_module._w_load(sh, points, np.full(points.shape, 1 / 15))
    band = patch_module._patch_flexibility_of(modes.green, loads)
    g = loads.dense()
    for o, n in enumerate(modes.orders[:3]):
        dense = np.einsum("pi,ij,pj->p", g, _dense_flexibility(sh, n), g)
        np.testing.assert_allclose(band[o], dense, rtol=1e-9)
    assert barrel.PATCH_SPAN >= 2 * 0.1
    wider = z[:1, None] + 0.15 * np.linspace(-1, 1, 15)[None, :]
    with pytest.raises(ValueError, match="longer than"):
        patch_module._patch_flexibility_of(
            modes.green, patch_module._w_load(sh, wider, np.full(wider.shape, 1 / 15)))


def test_patches_of_different_lengths_read_together(wall):
    # one call with short and long patches, patches at the wall's ends (their windows are
    # shifted to fit the wall) and one off the wall (it reads nothing): each equals the dense
    # sum g^T G g for that patch alone (rounding only, as above)
    sh, modes = wall
    z = np.array([0.45, 0.47, 0.6, sh.z[0] + 0.002, sh.z[-1] - 0.002, sh.z[0] - 0.15])
    half = np.array([0.1, 0.01, 0.03, 0.05, 0.1, 0.02])
    points = z[:, None] + half[:, None] * np.linspace(-1, 1, 15)[None, :]
    weights = np.full(points.shape, 1 / 15)
    loads = patch_module._w_load(sh, points, weights)
    g = loads.dense()
    assert not g[-1].any()
    together = patch_module._patch_flexibility_of(modes.green, loads)
    for o, n in enumerate(modes.orders[:3]):
        dense = np.einsum("pi,ij,pj->p", g, _dense_flexibility(sh, n), g)
        np.testing.assert_allclose(together[o, :-1], dense[:-1], rtol=1e-9)
    np.testing.assert_array_equal(together[:, -1], 0.0)
    for i in range(z.size - 1):  # alone, a patch has its own window
        alone = patch_module._w_load(sh, points[i:i + 1], weights[i:i + 1])
        np.testing.assert_allclose(alone.dense()[0], g[i], rtol=1e-15)
        np.testing.assert_allclose(together[:, i],
                                   patch_module._patch_flexibility_of(modes.green, alone)[:, 0],
                                   rtol=1e-13)
