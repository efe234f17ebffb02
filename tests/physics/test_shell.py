"""The semi-analytical shell of revolution (batcert.physics.shell): rigid motions are
strain-free, the element converges, the long-tube limit is the thin ring, the order-polynomial
assembly equals the direct one."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from batcert.physics.shell import (
    Assembler,
    ShellOfRevolution,
    assemble,
    element_matrices,
    harmonic_modes,
    ring_frequency,
)

AL = dict(E=71.7e9, nu=0.33, rho=2830.0)


def tube(length=0.3, radius=0.0322, wall=0.0025, elements=60, ends=("open", "open")):
    z = np.linspace(0.0, length, elements + 1)
    ones = np.ones(elements)
    return ShellOfRevolution(z, np.full(z.size, radius), wall * ones, AL["rho"] * ones,
                             AL["E"] * ones, AL["nu"], ends)


def cone(elements=20):
    """A frustum (the bat's taper): radius 12 -> 33 mm over 0.25 m, 2 mm wall."""
    z = np.linspace(0.0, 0.25, elements + 1)
    r = np.linspace(0.012, 0.033, z.size)
    ones = np.ones(elements)
    return ShellOfRevolution(z, r, 0.002 * ones, AL["rho"] * ones, AL["E"] * ones, AL["nu"],
                             ("open", "open"))


def _global(shell, n):
    k_e, _ = element_matrices(shell, n)
    nd = shell.node_dofs(n)
    size = nd * shell.z.size
    k = np.zeros((size, size))
    idx = (nd * np.arange(shell.n_elements))[:, None] + np.arange(2 * nd)[None, :]
    np.add.at(k, (idx[:, :, None], idx[:, None, :]), k_e)
    return k


def kinked() -> ShellOfRevolution:
    """A meridian with kinks: a steep knob-like cone, a cylinder and a gentle taper."""
    z = np.array([0.0, 0.01, 0.02, 0.10, 0.20, 0.25, 0.30])
    r = np.array([0.028, 0.019, 0.012, 0.012, 0.015, 0.030, 0.030])
    ones = np.ones(z.size - 1)
    return ShellOfRevolution(z, r, 2e-3 * ones, AL["rho"] * ones, AL["E"] * ones, AL["nu"],
                             ("open", "open"))


@pytest.mark.parametrize("make", [cone, kinked])
def test_rigid_motions_are_strain_free(make):
    # Sanders-Koiter: translation across the axis and rotation about a transverse axis (order 1)
    # and translation along the axis (order 0) carry no strain energy. With U linear, V and W
    # cubic, and global node unknowns (u_z, u_r), the elements represent them exactly on a
    # frustum and across kinks in the meridian, so K x = 0 to rounding.
    sh = make()
    z, r = sh.z, sh.r
    k1 = _global(sh, 1)
    one, zero = np.ones(z.size), np.zeros(z.size)
    # (u_z, V, V', u_r, W') per node. Translation in x: u_r = cos, v = -sin, u_z = 0.
    translation = np.stack([zero, -one, zero, one, zero], axis=1).ravel()
    # Rotation about the y axis: u_x = z, u_z = -x: u_z = -r, v = -z, u_r = z (times cos/sin),
    # V' = -cos psi, W' = 1. Exact on one frustum only: V' jumps at a kink, and V is Hermite
    # (one V' per node). Order 1 is the beam's business; the barrel uses orders 0 and >= 2.
    scale = np.abs(k1).max()
    assert np.abs(k1 @ translation).max() < 1e-9 * scale
    if make is cone:
        length = np.hypot(np.diff(z), np.diff(r))[0]
        cp = np.diff(z)[0] / length
        rotation = np.stack([-r, -z, -np.full(z.size, cp), z, one], axis=1).ravel()
        assert np.abs(k1 @ rotation).max() < 1e-9 * scale * np.abs(rotation).max()
    k0 = _global(sh, 0)
    axial = np.stack([one, zero, zero], 1).ravel()  # (u_z, u_r, W') = (1, 0, 0)
    assert np.abs(k0 @ axial).max() < 1e-9 * np.abs(k0).max()


@pytest.mark.parametrize("n", [0, 2, 3, 7])
def test_polynomial_assembly_equals_direct(n):
    sh = cone()
    direct, poly = assemble(sh, n), Assembler(sh).system(n)
    np.testing.assert_allclose(poly.stiffness, direct.stiffness, rtol=0,
                               atol=1e-12 * np.abs(direct.stiffness).max())
    np.testing.assert_allclose(poly.mass, direct.mass, rtol=0, atol=1e-14)


def test_mesh_convergence():
    # Closed ends (shear diaphragm), 2.5 mm wall: the lowest n = 2 frequency changes by less than
    # 0.01 % from 60 to 240 elements (measured 0.0002 %), so 1 cm elements on a bat are plenty.
    f = [harmonic_modes(tube(elements=e, ends=("closed", "closed")), 2, 4000).omega[0]
         for e in (60, 240)]
    assert abs(f[0] / f[1] - 1) < 1e-4


def test_long_tube_tends_to_the_ring():
    # A long free-free tube's lowest n = 2 mode has no axial wave: its frequency is the
    # inextensional ring's (Love 1927), to within 1 % for a 1 m tube.
    sh = tube(length=1.0, elements=100)
    f = harmonic_modes(sh, 2, 3000).omega[0] / (2 * np.pi)
    ring = ring_frequency(0.0322, 0.0025, AL["E"], AL["rho"], AL["nu"])
    assert f == pytest.approx(ring, rel=0.01)


def test_ring_frequency_walls():
    # REFERENCE-DATA.md (derived): 7050, 2.625 in outer diameter, n = 2 ring frequencies of
    # about 1.26 / 1.60 / 1.95 kHz for 2.0 / 2.5 / 3.0 mm walls (quoted to 3 digits: 0.5 %).
    outer = 0.5 * 2.625 * 0.0254
    walls = np.array([2.0e-3, 2.5e-3, 3.0e-3])
    f = ring_frequency(outer - walls / 2, walls, AL["E"], AL["rho"], AL["nu"])
    np.testing.assert_allclose(f, [1260, 1600, 1950], rtol=5e-3)


def test_modes_are_mass_normalised_and_closed_ends_hold_the_edge():
    sh = tube(ends=("closed", "closed"))
    system = Assembler(sh).system(2)
    modes = harmonic_modes(sh, 2, 8000, system)
    v = modes.vectors[system.free]
    np.testing.assert_allclose(v.T @ system.mass @ v, np.eye(v.shape[1]), atol=1e-9)
    w_first, v_first = modes.vectors[3], modes.vectors[1]  # W and V at the first node
    assert np.all(w_first == 0) and np.all(v_first == 0)


def test_static_stiffness_is_symmetric_positive():
    for n in (0, 2, 5):
        k = Assembler(tube(ends=("closed", "closed"))).system(n, support=True).stiffness
        np.testing.assert_allclose(k, k.T, atol=1e-9 * np.abs(k).max())
        scipy.linalg.cholesky(k)  # raises if not positive definite
