"""Modes of a small variation of a bat from its nominal modes (Rayleigh-Ritz), for the many
drawn bats of a Monte Carlo (:mod:`batcert.uncertainty`): the nominal bat's bending modes span
the drawn bat's, so a small eigenproblem replaces a new one (Meirovitch, *Fundamentals of
Vibrations*, 2001, Sec. 8.6), and the elastic flexibility for the residual compliance is carried
along instead of solved again."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.batmodel import BatModel
from batcert.physics.beam import (
    assemble,
    element_dofs,
    element_matrices,
    element_slices,
    free_dofs,
    point_mass_dofs,
    rigid_modes,
)
from batcert.physics.modes import Modes, compute_modes, eigenpairs, full_vectors, tip_positive
from batcert.physics.residual import nodal_flexibility


def ritz_modes(bat: BatModel, basis: Modes, flexibility: np.ndarray | None,
               n_modes: int) -> Modes:
    """The modes of ``bat``, a small variation of the bat whose modes are ``basis``, by
    Rayleigh-Ritz: ``K`` and ``M`` of ``bat`` (same mesh) projected on the span of ``bat``'s
    own exact rigid modes and ``basis``'s bending modes, and the small eigenproblem solved
    (Meirovitch, *Fundamentals of Vibrations*, 2001, Sec. 8.6). The first ``n_modes`` bending
    modes are kept. The Ritz frequencies bound the exact ones from above and their error is of
    second order in the change of ``K`` and ``M``; ``basis`` should hold several times
    ``n_modes`` modes (tests/physics/test_ritz.py measures the error on sampled bats).

    ``flexibility`` is ``basis``'s bat's elastic nodal flexibility (:mod:`residual`); the
    returned modes carry ``bat``'s, estimated as that flexibility with the basis modes'
    ``sum phi phi^T / omega^2`` replaced by the Ritz modes' (the modes beyond the basis are
    taken as unchanged), so the residual compliance needs no new static solve; with None (a
    draw that changes the stiffness) the residual compliance solves for it.
    """
    fe = assemble(bat, basis.z)  # the basis's mesh (its refinement, pivot and point masses)
    keep = free_dofs(fe, basis.support, basis.pivot)
    rigid = rigid_modes(fe, basis.support, basis.pivot)
    nr = basis.n_rigid
    v = np.concatenate([rigid, full_vectors(basis)[:, nr:]], axis=1)[keep]
    k = v.T @ fe.stiffness[np.ix_(keep, keep)] @ v
    m = v.T @ fe.mass[np.ix_(keep, keep)] @ v
    lam, y = eigenpairs(0.5 * (k + k.T), 0.5 * (m + m.T), nr, v.shape[1] - nr)
    bend = np.zeros((2 * fe.z.size, lam.size))
    bend[keep] = v @ y
    bend = tip_positive(bend)
    return _with_flexibility(basis, flexibility, rigid[None], bend[None],
                             np.sqrt(np.clip(lam, 0.0, None))[None], n_modes)[0]


@dataclass(frozen=True)
class RitzBasis:
    """What :func:`reduced_modes` needs of a nominal bat, computed once: its modes and
    flexibility (the basis), and the projections that make a draw whose stiffness is the
    nominal one cost a few small matrix products.

    The basis vectors are the nominal bat's bending modes and its rigid modes (rotation about
    the pin; free: translation and rotation about the CG), whose span holds every draw's rigid
    motions. A draw that only
    redistributes mass changes ``M`` alone, and ``M`` is linear in each element's
    ``linear_density`` and ``rotary_inertia`` and in the point masses: the projected
    ``W^T M W`` is a weighted sum of per-element projections (``unit_translation``,
    ``unit_rotation``).
    """

    basis: Modes
    flexibility: np.ndarray  # nominal elastic nodal flexibility [m/N], (n_nodes, n_nodes)
    bending_stiffness: np.ndarray  # the nominal's, (slices,): the fast path's condition
    shear_stiffness: np.ndarray
    point_mass_positions: tuple[float, ...]  # [m from knob]
    vectors: np.ndarray  # W on the full DOF vector, rigid shapes first, (2 n_nodes, n_w)
    stiffness: np.ndarray  # W^T K W, (n_w, n_w)
    slice_of_element: np.ndarray  # (elements,)
    unit_translation: np.ndarray  # W_e^T m_e W_e for a unit linear density, (elements, n_w, n_w)
    unit_rotation: np.ndarray  # the same for a unit rotary inertia
    point_rows: np.ndarray  # the DOF each point mass is lumped on, (points,)


def ritz_basis(bat: BatModel, support: str, pivot: float, n_basis: int,
               refine: int = 1) -> tuple[RitzBasis, Modes]:
    """The :class:`RitzBasis` of ``bat`` with ``n_basis`` bending modes (and those modes)."""
    basis = compute_modes(bat, support, pivot, n_basis, refine)
    flexibility = nodal_flexibility(bat, basis)
    z = basis.z
    fe = assemble(bat, z)
    # the nominal rigid modes: fixed shapes (a draw only rescales them, or moves the free
    # bat's centre of rotation within their span)
    w = np.concatenate([rigid_modes(fe, support, pivot), full_vectors(basis)[:, basis.n_rigid:]],
                       axis=1)
    s = element_slices(bat, z)
    length = np.diff(z)
    ones, zeros = np.ones(length.size), np.zeros(length.size)
    _, m_t = element_matrices(length, bat.bending_stiffness[s], bat.shear_stiffness[s], ones,
                              zeros)
    _, m_r = element_matrices(length, bat.bending_stiffness[s], bat.shear_stiffness[s], zeros,
                              ones)
    we = w[element_dofs(z)]  # (e, 4, n_w)
    pm = np.asarray(bat.point_masses, dtype=float).reshape(-1, 2)
    rows = point_mass_dofs(z, pm[:, 0])
    project = "eai,eab,ebj->eij"
    return RitzBasis(basis, flexibility, np.array(bat.bending_stiffness, dtype=float),
                     np.array(bat.shear_stiffness, dtype=float), tuple(pm[:, 0]), w,
                     w.T @ fe.stiffness @ w, s, np.einsum(project, we, m_t, we),
                     np.einsum(project, we, m_r, we), rows), basis


def reduced_modes(rb: RitzBasis, bat: BatModel, n_modes: int) -> Modes:
    """:func:`reduced_modes_many` of one bat."""
    return reduced_modes_many(rb, [bat], n_modes)[0]


def reduced_modes_many(rb: RitzBasis, bats: list[BatModel], n_modes: int) -> list[Modes]:
    """:func:`ritz_modes` of each of ``bats`` on ``rb``. The bats that have the nominal's
    stiffness and point-mass positions (draws of mass properties) are solved together from the
    stored projections, without assembling anything: one stack of small eigenproblems (the same
    result to rounding as :func:`ritz_modes`, tests/physics/test_ritz.py); the others one by
    one."""
    out: list[Modes | None] = [None] * len(bats)
    fast = []
    for i, bat in enumerate(bats):
        pm = np.asarray(bat.point_masses, dtype=float).reshape(-1, 2)
        if (np.array_equal(bat.bending_stiffness, rb.bending_stiffness)
                and np.array_equal(bat.shear_stiffness, rb.shear_stiffness)
                and tuple(pm[:, 0]) == rb.point_mass_positions):
            fast.append(i)
        else:
            out[i] = ritz_modes(bat, rb.basis, None, n_modes)
    if fast:
        for i, modes in zip(fast, _mass_draws(rb, [bats[i] for i in fast], n_modes),
                            strict=True):
            out[i] = modes
    return out  # type: ignore[return-value]


def _mass_draws(rb: RitzBasis, bats: list[BatModel], n_modes: int) -> list[Modes]:
    """:func:`reduced_modes_many` of bats that differ from the nominal in their masses only:
    ``M`` projected from the per-element projections, stacked (bats, n_w, n_w)."""
    s = rb.slice_of_element
    m = (np.tensordot(np.stack([np.asarray(b.linear_density)[s] for b in bats]),
                      rb.unit_translation, 1)
         + np.tensordot(np.stack([np.asarray(b.rotary_inertia)[s] for b in bats]),
                        rb.unit_rotation, 1))
    wp = rb.vectors[rb.point_rows]  # (points, n_w)
    masses = np.stack([np.asarray(b.point_masses, dtype=float).reshape(-1, 2)[:, 1]
                       for b in bats])  # (bats, points)
    m += np.einsum("pi,bp,pj->bij", wp, masses, wp)
    m = 0.5 * (m + np.swapaxes(m, 1, 2))
    nr = rb.basis.n_rigid
    lam, y = eigenpairs(rb.stiffness, m, nr, m.shape[1] - nr)
    e = np.eye(m.shape[1])
    if nr == 1:
        rigid_y = e[None, :, :1] / np.sqrt(m[:, :1, :1])
    else:  # translation, then rotation about the CG (beam.rigid_modes)
        z_cg = m[:, 0, 1] / m[:, 0, 0]
        rot = e[1][None, :] - z_cg[:, None] * e[0][None, :]  # (bats, n_w)
        norm = np.sqrt(np.einsum("bi,bij,bj->b", rot, m, rot))
        rigid_y = np.stack([e[0][None, :] / np.sqrt(m[:, :1, 0]), rot / norm[:, None]],
                           axis=2)
    bend = tip_positive(rb.vectors @ y)
    omega_all = np.sqrt(np.clip(lam, 0.0, None))
    return _with_flexibility(rb.basis, rb.flexibility, rb.vectors @ rigid_y, bend, omega_all,
                             n_modes)


def _with_flexibility(basis: Modes, flexibility: np.ndarray | None, rigid: np.ndarray,
                      bend: np.ndarray, omega_all: np.ndarray, n_modes: int) -> list[Modes]:
    """Modes from full-vector rigid and bending modes, stacked (bats, 2 n_nodes, .) with their
    frequencies (bats, .), with the flexibility estimated as in :func:`ritz_modes` (None: the
    residual compliance solves for it)."""
    nr = basis.n_rigid
    flex: list[np.ndarray | None] = [None] * bend.shape[0]
    if flexibility is not None:
        old = basis.shapes[nr:]
        shapes_all = bend[:, 0::2]
        est = (flexibility - (old.T * _compliance(basis.omega[nr:])) @ old
               + (shapes_all * _compliance(omega_all)[:, None, :])
               @ np.swapaxes(shapes_all, 1, 2))
        flex = list(0.5 * (est + np.swapaxes(est, 1, 2)))
    phi = np.swapaxes(np.concatenate([rigid, bend[:, :, :n_modes]], axis=2), 1, 2)
    omega = np.concatenate([np.zeros((bend.shape[0], nr)), omega_all[:, :n_modes]], axis=1)
    return [Modes(support=basis.support, pivot=basis.pivot, z=basis.z, omega=omega[i],
                  shapes=np.ascontiguousarray(phi[i, :, 0::2]),
                  rotations=np.ascontiguousarray(phi[i, :, 1::2]), n_rigid=nr,
                  flexibility=flex[i])
            for i in range(bend.shape[0])]


def _compliance(omega: np.ndarray) -> np.ndarray:
    """``1 / omega^2`` of mass-normalised modes, 0 for a zero frequency (a rigid mode)."""
    return np.where(omega > 0, 1.0 / np.where(omega > 0, omega, 1.0) ** 2, 0.0)
