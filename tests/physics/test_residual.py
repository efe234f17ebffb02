"""Residual compliance of the truncated modes (batcert.physics.residual)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from batcert.physics.batmodel import Material
from batcert.physics.modes import compute_modes
from batcert.physics.residual import residual_compliance

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/, for the shared helper
from r161 import r161_bat, solid_bat  # noqa: E402

PIVOT = 0.1524  # 6 in from the knob: inside a slice, so the pin node has to be inserted [m]


@pytest.fixture(scope="module")
def r161():
    return r161_bat()


def uniform_bat(n=84, length=0.84, diameter=0.06, kappa=1.0, point_masses=()):
    wood = Material("test-wood", 650.0, 1.5e10, 1.0e9, 0.3)
    return solid_bat("uniform", np.linspace(0.0, length, n + 1), np.full(n, diameter), wood,
                     kappa=kappa, point_masses=point_masses)


def full_vectors(modes):
    """Interleaved (w, theta) modal vectors, shape (n_dofs, n_modes)."""
    phi = np.empty((2 * modes.z.size, modes.omega.size))
    phi[0::2], phi[1::2] = modes.shapes.T, modes.rotations.T
    return phi


# --- the element ------------------------------------------------------------------------------
@pytest.mark.parametrize("support", ["free", "pinned"])
def test_residual_compliance_is_the_truncated_modal_sum(r161, support):
    z = np.array([0.30, 0.5, 0.6543, 0.70, 0.80, 0.835])
    kept = compute_modes(r161, support, PIVOT, 18)
    every = compute_modes(r161, support, PIVOT, 10_000)  # the whole FE spectrum
    n = every.n_rigid + 18
    expected = (every.at(z)[:, n:] ** 2 / every.omega[n:] ** 2).sum(axis=1)
    np.testing.assert_allclose(residual_compliance(r161, kept, z), expected, rtol=1e-5)
    # all modes kept: nothing left but round-off (about 1e-6 of the 18-mode residual)
    np.testing.assert_allclose(residual_compliance(r161, every, z), 0.0,
                               atol=1e-5 * expected.min())
    fewer = residual_compliance(r161, compute_modes(r161, support, PIVOT, 4), z)
    assert np.all(fewer > residual_compliance(r161, kept, z))


# --- cache and input checks ----------------------------------------------------------------------
