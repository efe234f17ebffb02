"""The Timoshenko beam element (batcert.physics.beam): shape functions and stiffness."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from batcert.physics import beam
from batcert.physics.batmodel import Material

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
def test_shape_functions_reproduce_rigid_motion_and_constant_shear():
    xi = np.linspace(0.0, 1.0, 7)
    L, phi = np.array([0.01, 0.02]), np.array([0.3, 4.0])
    n_w, n_t, dn_t, shear = beam.shape_functions(xi, L, phi)
    x = xi[None, :] * L[:, None]
    # translation (1, 0, 1, 0) and rotation about node 1 (0, 1, L, 1)
    np.testing.assert_allclose(n_w @ np.array([1.0, 0, 1, 0]), 1.0, atol=1e-12)
    rot = np.stack([0 * L, 0 * L + 1, L, 0 * L + 1], axis=-1)[:, None, :]
    np.testing.assert_allclose((n_w * rot).sum(-1), x, atol=1e-12)
    np.testing.assert_allclose((n_t * rot).sum(-1), 1.0, atol=1e-12)
    # the shear strain of every shape function is constant along the element
    np.testing.assert_allclose(shear, shear[:, :1, :].repeat(xi.size, axis=1), atol=1e-9)


def test_closed_form_stiffness_equals_energy_integral():
    # independent check of the closed-form matrix: int EI dtheta^2 + kGA gamma^2 by quadrature
    L, ei, kga = np.array([0.01, 0.013]), np.array([40.0, 90.0]), np.array([6e5, 2e5])
    k, _ = beam.element_matrices(L, ei, kga, np.ones(2), np.ones(2))
    xg, wg = np.polynomial.legendre.leggauss(5)
    _, _, dn_t, shear = beam.shape_functions(0.5 * (xg + 1), L, 12 * ei / (kga * L**2))
    w = 0.5 * wg[None, :] * L[:, None]
    k_q = (np.einsum("eq,eqi,eqj->eij", w * ei[:, None], dn_t, dn_t)
           + np.einsum("eq,eqi,eqj->eij", w * kga[:, None], shear, shear))
    np.testing.assert_allclose(k, k_q, rtol=1e-10)


# --- frequencies against closed forms -----------------------------------------------------------
