"""Bending modes of a bat as a non-uniform Timoshenko beam (finite elements).

The bat is meshed with two-node Timoshenko elements whose nodes sit at the slice edges of a
:class:`~batcert.physics.batmodel.BatModel` (each slice optionally cut into ``refine`` equal
elements), plus nodes inserted exactly at the pivot and at the point masses. Every element lies
inside one slice, so its section properties are uniform.

Element: the "interdependent interpolation" Timoshenko element (cubic transverse displacement,
quadratic section rotation, the two linked through the homogeneous static Timoshenko equations):
Przemieniecki, *Theory of Matrix Structural Analysis* (1968); Friedman & Kosmatka, "An improved
two-node Timoshenko beam finite element", Computers & Structures 47 (1993) 473. Its stiffness
matrix is the exact static stiffness of a uniform Timoshenko beam, so it cannot shear-lock, and it
reduces to the Hermite Euler-Bernoulli element when the shear stiffness is infinite. The mass
matrix is the consistent one from the same shape functions, with translational (``linear_density``)
and rotary (``rotary_inertia``) terms, integrated by 4-point Gauss quadrature (exact for these
polynomials).

Degrees of freedom are interleaved per node: ``[w_0, theta_0, w_1, theta_1, ...]`` with ``w`` the
transverse displacement [m] and ``theta`` the section rotation [rad] (``theta = dw/dz`` in the
Euler-Bernoulli limit). Positions ``z`` are measured from the knob [m].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.batmodel import BatModel
from batcert.physics.quadrature import GAUSS_POINTS, GAUSS_WEIGHTS

SUPPORTS = ("free", "pinned")
N_RIGID = {"free": 2, "pinned": 1}
_SNAP = 1e-3  # an inserted point closer than this fraction of its element's length reuses the node


@dataclass(frozen=True)
class _FiniteElements:
    z: np.ndarray  # node positions [m], (n_nodes,)
    stiffness: np.ndarray  # global stiffness [N/m, N, N m], dense (2 n_nodes, 2 n_nodes)
    mass: np.ndarray  # global consistent mass [kg, kg m, kg m^2], same shape


def shape_functions(xi: np.ndarray, length: np.ndarray, phi: np.ndarray):
    """Interdependent Timoshenko shape functions (Friedman & Kosmatka 1993).

    Derived here from the homogeneous Timoshenko statics: with ``w`` cubic and ``theta``
    quadratic, ``(kGA (w' - theta))' = 0`` makes the shear strain constant and
    ``EI theta'' + kGA (w' - theta) = 0`` fixes it, leaving four constants for the four nodal DOFs.

    Parameters
    ----------
    xi : array_like
        Local coordinate ``x / L`` in [0, 1] [-], shape (q,).
    length : array_like
        Element lengths ``L`` [m], shape (e,).
    phi : array_like
        Shear parameter ``12 EI / (kappa G A L^2)`` [-], shape (e,).

    Returns
    -------
    n_w, n_theta, dn_theta, shear : numpy.ndarray
        Shape functions of ``w`` [m per DOF], of ``theta`` [rad per DOF], of ``dtheta/dx``
        [1/m per DOF] and of the shear strain ``dw/dx - theta`` [rad per DOF], each of shape
        (e, q, 4) for the nodal DOFs ``(w_1, theta_1, w_2, theta_2)``.
    """
    x = np.asarray(xi, dtype=float)[None, :]
    L = np.asarray(length, dtype=float)[:, None]
    p = np.asarray(phi, dtype=float)[:, None]
    c = 1.0 / (1.0 + p)
    x2, x3 = x * x, x * x * x
    n_w = c[..., None] * np.stack(np.broadcast_arrays(
        2 * x3 - 3 * x2 - p * x + 1 + p,
        L * (x3 - (2 + p / 2) * x2 + (1 + p / 2) * x),
        -(2 * x3 - 3 * x2 - p * x),
        L * (x3 - (1 - p / 2) * x2 - (p / 2) * x)), axis=-1)
    n_t = c[..., None] * np.stack(np.broadcast_arrays(
        6 * (x2 - x) / L, 3 * x2 - (4 + p) * x + 1 + p,
        -6 * (x2 - x) / L, 3 * x2 - (2 - p) * x), axis=-1)
    dn_t = c[..., None] * np.stack(np.broadcast_arrays(
        6 * (2 * x - 1) / L**2, (6 * x - 4 - p) / L,
        -6 * (2 * x - 1) / L**2, (6 * x - 2 + p) / L), axis=-1)
    dn_w = c[..., None] * np.stack(np.broadcast_arrays(
        (6 * x2 - 6 * x - p) / L, 3 * x2 - (4 + p) * x + 1 + p / 2,
        -(6 * x2 - 6 * x - p) / L, 3 * x2 - (2 - p) * x - p / 2), axis=-1)
    return n_w, n_t, dn_t, dn_w - n_t


def element_matrices(length, bending_stiffness, shear_stiffness, linear_density, rotary_inertia):
    """Stiffness and consistent mass matrices of uniform Timoshenko elements.

    Parameters
    ----------
    length : array_like
        Element lengths [m], shape (e,).
    bending_stiffness : array_like
        ``E I`` [N m^2], shape (e,).
    shear_stiffness : array_like
        ``kappa G A`` [N], shape (e,); ``inf`` gives the Euler-Bernoulli element.
    linear_density : array_like
        Mass per length [kg/m], shape (e,).
    rotary_inertia : array_like
        Rotary inertia per length ``rho I`` [kg m], shape (e,).

    Returns
    -------
    stiffness, mass : numpy.ndarray
        Element matrices, shape (e, 4, 4), DOFs ``(w_1, theta_1, w_2, theta_2)``.
        The stiffness is the exact uniform-Timoshenko stiffness (Przemieniecki 1968; Friedman &
        Kosmatka 1993), ``EI / ((1 + phi) L^3)`` times the familiar 12/6L/(4+phi)L^2/(2-phi)L^2
        pattern with ``phi = 12 EI / (kGA L^2)``; the mass is the consistent matrix
        ``int (mu N_w^T N_w + rho I N_theta^T N_theta) dx``.
    """
    L = np.asarray(length, dtype=float)
    ei = np.asarray(bending_stiffness, dtype=float)
    phi = 12.0 * ei / (np.asarray(shear_stiffness, dtype=float) * L**2)
    a = ei / ((1.0 + phi) * L**3)
    k = np.empty((L.size, 4, 4))
    k[:, 0] = np.stack([12 + 0 * L, 6 * L, -12 + 0 * L, 6 * L], axis=-1)
    k[:, 1] = np.stack([6 * L, (4 + phi) * L**2, -6 * L, (2 - phi) * L**2], axis=-1)
    k[:, 2] = -k[:, 0]
    k[:, 3] = np.stack([6 * L, (2 - phi) * L**2, -6 * L, (4 + phi) * L**2], axis=-1)
    k *= a[:, None, None]
    n_w, n_t, _, _ = shape_functions(GAUSS_POINTS, L, phi)
    wq = GAUSS_WEIGHTS[None, :] * L[:, None]  # quadrature weights [m], (e, q)
    mu = np.asarray(linear_density, dtype=float)[:, None] * wq
    ri = np.asarray(rotary_inertia, dtype=float)[:, None] * wq
    m = np.einsum("eq,eqi,eqj->eij", mu, n_w, n_w) + np.einsum("eq,eqi,eqj->eij", ri, n_t, n_t)
    return k, m


def mesh_nodes(bat: BatModel, refine: int = 1, extra_points=()) -> np.ndarray:
    """Node positions: slice edges, each slice cut into ``refine`` elements, plus extra points.

    An extra point (the pivot, a point mass) becomes a node of its own; it reuses an existing node
    only when closer than 0.1 % of the local element length. Points outside the bat are ignored.

    Returns
    -------
    numpy.ndarray
        Sorted node positions from the knob [m].
    """
    if int(refine) != refine or refine < 1:
        raise ValueError(f"refine must be a positive integer, got {refine!r}")
    edges = np.asarray(bat.z_edges, dtype=float)
    frac = np.arange(int(refine)) / int(refine)
    nodes = np.append((edges[:-1, None] + np.diff(edges)[:, None] * frac).ravel(), edges[-1])
    for p in np.atleast_1d(np.asarray(extra_points, dtype=float)):
        if not edges[0] <= p <= edges[-1]:
            continue
        i = int(np.clip(np.searchsorted(nodes, p), 1, nodes.size - 1))
        h = nodes[i] - nodes[i - 1]
        if min(p - nodes[i - 1], nodes[i] - p) > _SNAP * h:
            nodes = np.insert(nodes, i, p)
    return nodes


def element_slices(bat: BatModel, nodes: np.ndarray) -> np.ndarray:
    """The slice each element of the mesh ``nodes`` takes its properties from: the slice
    holding its midpoint, (elements,)."""
    z = np.asarray(nodes, dtype=float)
    return bat.slice_at(0.5 * (z[1:] + z[:-1]))


def element_dofs(nodes: np.ndarray) -> np.ndarray:
    """Each element's DOFs ``(w_1, theta_1, w_2, theta_2)`` on the global vector, (e, 4)."""
    return 2 * np.arange(np.asarray(nodes).size - 1)[:, None] + np.arange(4)[None, :]


def point_mass_dofs(nodes: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """The transverse DOF each point mass at ``positions`` [m from knob] is lumped on: the
    nearest node's, (points,)."""
    z = np.asarray(nodes, dtype=float)
    return 2 * np.abs(z[None, :] - np.asarray(positions, dtype=float)[:, None]).argmin(axis=1)


def assemble(bat: BatModel, nodes: np.ndarray) -> _FiniteElements:
    """Global stiffness and mass matrices of ``bat`` on the mesh ``nodes`` (point masses included).

    Each element takes the properties of the slice holding its midpoint; a point mass is lumped on
    the transverse DOF of the nearest node (exact when a node sits at the mass, see
    :func:`mesh_nodes`; masses beyond the ends go to the end node). Point masses carry no rotary
    inertia of their own.
    """
    z = np.asarray(nodes, dtype=float)
    s = element_slices(bat, z)
    k_e, m_e = element_matrices(np.diff(z), bat.bending_stiffness[s], bat.shear_stiffness[s],
                                bat.linear_density[s], bat.rotary_inertia[s])
    n = 2 * z.size
    dofs = element_dofs(z)
    rows = np.broadcast_to(dofs[:, :, None], k_e.shape)
    cols = np.broadcast_to(dofs[:, None, :], k_e.shape)
    pm = np.asarray(bat.point_masses, dtype=float).reshape(-1, 2)
    j = point_mass_dofs(z, pm[:, 0])
    stiffness, mass = np.zeros((n, n)), np.zeros((n, n))  # dense: a bat has a few hundred DOFs
    np.add.at(stiffness, (rows, cols), k_e)
    np.add.at(mass, (rows, cols), m_e)
    np.add.at(mass, (j, j), pm[:, 1])
    return _FiniteElements(z=z, stiffness=stiffness, mass=mass)


def rigid_modes(fe: _FiniteElements, support: str, pivot: float) -> np.ndarray:
    """Exact mass-orthonormal rigid-body modes on the full DOF vector, shape (ndof, n_rigid).

    Free: translation, then rotation about the centre of gravity of the FE mass matrix. Pinned:
    rotation about the pivot. The element reproduces rigid motion exactly (w linear, theta
    constant), so these are exact null vectors of the stiffness matrix.
    """
    n = fe.z.size
    trans = np.zeros(2 * n)
    trans[0::2] = 1.0
    if support == "pinned":
        z_pin = fe.z[int(np.argmin(np.abs(fe.z - pivot)))]
        rot = np.zeros(2 * n)
        rot[0::2], rot[1::2] = fe.z - z_pin, 1.0
        return (rot / np.sqrt(rot @ fe.mass @ rot))[:, None]
    total = trans @ fe.mass @ trans
    rot0 = np.zeros(2 * n)
    rot0[0::2], rot0[1::2] = fe.z, 1.0
    z_cg = (trans @ fe.mass @ rot0) / total
    rot = rot0 - z_cg * trans
    return np.stack([trans / np.sqrt(total), rot / np.sqrt(rot @ fe.mass @ rot)], axis=1)


def free_dofs(fe: _FiniteElements, support: str, pivot: float) -> np.ndarray:
    """DOF indices left after the support constraint (``w = 0`` at the pivot node if pinned)."""
    all_dofs = np.arange(2 * fe.z.size)
    if support == "free":
        return all_dofs
    return np.delete(all_dofs, 2 * int(np.argmin(np.abs(fe.z - pivot))))


def check_support(bat: BatModel, support: str, pivot: float) -> None:
    if support not in SUPPORTS:
        raise ValueError(f"support must be one of {SUPPORTS}, got {support!r}")
    if support == "pinned" and not bat.z_edges[0] <= pivot <= bat.z_edges[-1]:
        raise ValueError(f"pivot {pivot} m lies outside the bat [0, {bat.z_edges[-1]}] m")
