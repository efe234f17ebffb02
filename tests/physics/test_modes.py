"""Bending modes of the Timoshenko beam (batcert.physics.modes): frequencies, normalisation,
supports, convergence, nodes and the mode cache."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

from batcert import workspace
from batcert.physics import beam
from batcert.physics import modes as modes_module
from batcert.physics.batmodel import Material
from batcert.physics.modes import cached_modes, compute_modes, mode_nodes

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
def test_uniform_free_free_euler_bernoulli_limit():
    # Very stiff in shear and no rotary inertia: the Euler-Bernoulli free-free beam,
    # f_n = (beta_n L)^2 sqrt(EI / (mu L^4)) / (2 pi), beta L = 4.7300, 7.8532, 10.9956
    # (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1). 0.5 % as asked;
    # with 84 cubic elements the discretisation error is far smaller.
    bat = uniform_bat()
    bat = dataclasses.replace(bat, shear_stiffness=bat.shear_stiffness * 1e9,
                              rotary_inertia=bat.rotary_inertia * 1e-9)
    f = compute_modes(bat, "free", PIVOT, n_modes=3).frequencies_hz
    ei, mu, L = bat.bending_stiffness[0], bat.linear_density[0], bat.length
    exact = np.array([4.7300408, 7.8532046, 10.9956078]) ** 2 * np.sqrt(ei / (mu * L**4)) / (2 * np.pi)
    np.testing.assert_allclose(f, exact, rtol=5e-3)


def test_shear_and_rotary_inertia_lower_the_frequencies():
    bat = uniform_bat()
    eb = dataclasses.replace(bat, shear_stiffness=np.full(84, np.inf),
                             rotary_inertia=np.zeros(84))
    f_t = compute_modes(bat, "free", PIVOT, 5).frequencies_hz
    f_eb = compute_modes(eb, "free", PIVOT, 5).frequencies_hz
    assert np.all(f_t < f_eb)
    assert np.all(np.diff(f_t / f_eb) < 0)  # the effect grows with mode number


def test_stiff_limit_scales_with_sqrt_of_stiffness(r161):
    # Scaling every stiffness (E and G) by 1000 scales each omega by sqrt(1000), exactly.
    stiff = dataclasses.replace(r161, bending_stiffness=r161.bending_stiffness * 1e3,
                                shear_stiffness=r161.shear_stiffness * 1e3)
    f0 = compute_modes(r161, "free", PIVOT, 8).frequencies_hz
    f1 = compute_modes(stiff, "free", PIVOT, 8).frequencies_hz
    np.testing.assert_allclose(f1 / f0, np.sqrt(1e3), rtol=1e-7)
    # E alone: shear deformation then limits the rise, more so for higher modes
    e_only = dataclasses.replace(r161, bending_stiffness=r161.bending_stiffness * 1e3)
    ratio = compute_modes(e_only, "free", PIVOT, 8).frequencies_hz / f0
    assert np.all(ratio < np.sqrt(1e3)) and np.all(np.diff(ratio) < 0)


# --- normalisation, supports, convergence --------------------------------------------------------

def test_mass_normalisation_and_rigid_modes():
    masses = ((0.0, 0.03), (0.4037, 0.02), (0.84, 0.05))  # knob, an off-slice-edge mass, cap
    bat = uniform_bat(point_masses=masses)
    modes = compute_modes(bat, "free", PIVOT, 10)
    fe = beam.assemble(bat, modes.z)
    phi = full_vectors(modes)
    np.testing.assert_allclose(phi.T @ (fe.mass @ phi), np.eye(modes.omega.size), atol=1e-9)
    np.testing.assert_allclose(modes.shapes[0], 1.0 / np.sqrt(bat.mass), rtol=1e-12)
    assert np.all(modes.omega[:2] == 0) and modes.n_rigid == 2
    # the rotation mode turns about the centre of gravity (BatModel.balance_point)
    z_zero = np.interp(0.0, modes.shapes[1], modes.z)
    assert z_zero == pytest.approx(bat.balance_point, abs=1e-12)
    # and its moment of inertia is the bat's: phi_rot' = 1 / sqrt(I_cg)
    i_cg = bat.moi_about(bat.balance_point)
    np.testing.assert_allclose(modes.rotations[1], 1.0 / np.sqrt(i_cg), rtol=1e-12)
    np.testing.assert_allclose(phi[:, 2:].T @ (fe.stiffness @ phi[:, 2:]),
                               np.diag(modes.omega[2:] ** 2), rtol=1e-8, atol=1e-3)


def test_pinned_support_holds_the_pivot(r161):
    modes = compute_modes(r161, "pinned", PIVOT, 12)
    assert PIVOT in modes.z  # an exact node, not snapped to the 15 cm slice edge
    assert modes.n_rigid == 1 and modes.omega[0] == 0
    np.testing.assert_array_equal(modes.at(PIVOT), 0.0)
    np.testing.assert_allclose(modes.rotations[0], 1.0 / np.sqrt(r161.moi_about(PIVOT)),
                               rtol=1e-12)
    for j in range(1, 13):
        assert np.any(np.isclose(mode_nodes(modes, j), PIVOT, atol=1e-12))


def test_free_and_pinned_fundamental_nearly_agree_when_pinned_near_a_node(r161):
    # R161 mode-1 node is near 17 cm; pinning at 15.24 cm hardly changes mode 1 (Nathan 2000).
    f_free = compute_modes(r161, "free", PIVOT, 3).frequencies_hz[0]
    f_pin = compute_modes(r161, "pinned", PIVOT, 3).frequencies_hz[0]
    assert f_pin == pytest.approx(f_free, rel=0.02)


@pytest.mark.parametrize("support", ["free", "pinned"])
def test_convergence_under_refinement(r161, support):
    # What we measure: the first five bending frequencies and the mode-1..3 nodes of the R161 with
    # 1, 2 and 4 elements per 1 cm slice. The element is conforming and the meshes are nested, so
    # the frequencies fall monotonically; refine=2 changes them by < 0.1 % (measured 0.05 % for
    # mode 5) and the nodes by < 0.5 mm. refine=4 uses the sparse eigensolver, refine 1-2 dense.
    runs = [compute_modes(r161, support, PIVOT, 5, refine=r) for r in (1, 2, 4)]
    f = np.array([m.frequencies_hz for m in runs])
    assert np.all(np.diff(f, axis=0) <= 1e-9 * f[0])
    np.testing.assert_allclose(f[1], f[0], rtol=1e-3)
    np.testing.assert_allclose(f[2], f[1], rtol=3e-4)
    for j in (1, 2, 3):
        np.testing.assert_allclose(mode_nodes(runs[1], j), mode_nodes(runs[0], j),
                                   atol=5e-4)


def test_numpy_eigensolver_agrees_with_lapack_generalised(r161):
    # The run path solves K x = lam M x with numpy only (Cholesky of M, then eigh); scipy's
    # generalised LAPACK solver (sygvd) on the same matrices is the check: 1e-8 on frequencies
    # (rounding of a 500-DOF dense problem: the lowest mode's differs by 1.6e-9 on an AMD EPYC's
    # OpenBLAS kernels, under 1e-9 on others), shapes to 1e-7 after the same sign convention.
    import scipy.linalg

    from batcert.physics.beam import assemble, free_dofs, mesh_nodes

    fe = assemble(r161, mesh_nodes(r161, 3, [PIVOT]))
    keep = free_dofs(fe, "free", PIVOT)
    k, m = fe.stiffness[np.ix_(keep, keep)], fe.mass[np.ix_(keep, keep)]
    lam, vec = modes_module.eigenpairs(k, m, 2, 10)
    ref_lam, ref_vec = scipy.linalg.eigh(k, m, subset_by_index=[2, 11])
    np.testing.assert_allclose(np.sqrt(lam), np.sqrt(ref_lam), rtol=1e-8)
    sign = np.sign(vec[-2] * ref_vec[-2])
    np.testing.assert_allclose(vec * sign, ref_vec, atol=1e-7 * np.abs(ref_vec).max())


def test_mode_nodes_count(r161):
    modes = compute_modes(r161, "free", PIVOT, 6)
    for j in range(1, 7):
        nodes = mode_nodes(modes, j)
        assert nodes.size == j + 1 and np.all(np.diff(nodes) > 0)
    with pytest.raises(ValueError):
        mode_nodes(modes, 0)


# --- residual compliance -------------------------------------------------------------------------

def test_cache_keys_on_content(r161):
    workspace.current().clear("modes")
    a = cached_modes(r161, "free", PIVOT, 12)
    copy = dataclasses.replace(r161, bending_stiffness=r161.bending_stiffness.copy(), name="x")
    assert cached_modes(copy, "free", PIVOT, 12) is a
    assert not a.shapes.flags.writeable
    stiffer = dataclasses.replace(r161, bending_stiffness=r161.bending_stiffness * 1.01)
    assert cached_modes(stiffer, "free", PIVOT, 12) is not a
    assert cached_modes(r161, "pinned", PIVOT, 12) is not a
    assert cached_modes(r161, "free", PIVOT, 12, refine=2) is not a
    np.testing.assert_array_equal(a.omega, compute_modes(r161, "free", PIVOT, 12).omega)


def test_bad_arguments(r161):
    with pytest.raises(ValueError, match="support"):
        compute_modes(r161, "clamped", PIVOT)
    with pytest.raises(ValueError, match="pivot"):
        compute_modes(r161, "pinned", 1.2)
    with pytest.raises(ValueError, match="refine"):
        compute_modes(r161, "free", PIVOT, refine=0)
