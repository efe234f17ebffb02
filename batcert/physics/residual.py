"""Quasi-static (residual) compliance of the bending modes a truncated modal model leaves out.

Used by the flexible engine as a spring in series with the ball, so that its result does not
depend on how many modes it keeps (Craig & Kurdila, *Fundamentals of Structural Dynamics*, 2006,
Sec. 11.3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert import workspace
from batcert.physics.batmodel import BatModel
from batcert.physics.beam import assemble, check_support, free_dofs, rigid_modes
from batcert.physics.modes import Modes, beam_of


def patch_reader(z_nodes: np.ndarray, z_points: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """How each patch reads (and loads) the beam's transverse displacement: ``a[i, j]``, the
    weight of node ``j`` for patch ``i``, each sample point ``z_points[i, k]`` (weight
    ``weights[i, k]``) shared linearly between its two nearest nodes, as :meth:`Modes.at`
    interpolates. A patch's mode shapes are ``a @ shapes.T``; its unit load on the nodes is
    ``a``. Shape (p, n_nodes)."""
    zp = np.asarray(z_points, dtype=float)
    i = np.clip(np.searchsorted(z_nodes, zp, side="right") - 1, 0, z_nodes.size - 2)
    t = np.clip((zp - z_nodes[i]) / (z_nodes[i + 1] - z_nodes[i]), 0.0, 1.0)
    w = np.asarray(weights, dtype=float)
    n = z_nodes.size
    cell = np.arange(zp.shape[0]).reshape((-1,) + (1,) * (zp.ndim - 1)) * n + i
    # each point's two shares summed into their nodes, the lower nodes' first (one bincount,
    # in the order np.add.at would add them)
    a = np.bincount(np.concatenate([cell.ravel(), cell.ravel() + 1]),
                    np.concatenate([((1.0 - t) * w).ravel(), (t * w).ravel()]),
                    minlength=zp.shape[0] * n)
    return a.reshape(zp.shape[0], n)


def residual_compliance(bat: BatModel, modes: Modes, z_points, weights=None,
                        reader: np.ndarray | None = None) -> np.ndarray:
    """Static compliance at ``z_points`` of the bending modes that ``modes`` left out.

    The elastic (inertia-relief) flexibility of the FE beam, ``G = sum over all bending modes of
    phi_j(z)^2 / omega_j^2``, is computed without the eigenvectors: the load is made
    self-equilibrated against the rigid modes (``f - M Phi_r Phi_r^T f``), the beam is held by a
    statically determinate set of supports that then carry no reaction, and the rigid part is
    removed from the displacement (Craig & Kurdila, *Fundamentals of Structural Dynamics*, 2006,
    Sec. 11.3, residual flexibility). The kept modes' ``sum phi_j(z)^2 / omega_j^2`` is subtracted;
    what remains is the quasi-static flexibility of the truncated modes, to be put in series with
    the ball contact. The flexibility between the nodes' transverse displacements is formed once
    per modes, so each patch costs a quadratic form in its nodal weights.

    Parameters
    ----------
    bat : BatModel
        The bat the modes were computed for.
    modes : Modes
        Modes from :func:`compute_modes` (its node set defines the mesh).
    z_points : array_like
        Impact positions from the knob [m], shape (p,); or, with ``weights``, the sample points
        of a distributed load, shape (p, K).
    weights : array_like, optional
        Shape (p, K), each row summing to 1: the load of impact ``i`` is spread over
        ``z_points[i]`` with these weights (a contact patch); the compliance is then the
        work-conjugate one, ``f^T G f`` for the unit resultant ``f``.
    reader : numpy.ndarray, optional
        :func:`patch_reader` of these points and weights, if already at hand.

    Returns
    -------
    numpy.ndarray
        Residual compliance [m/N], shape (p,), >= 0.
    """
    check_support(bat, modes.support, modes.pivot)
    if reader is None:
        zp = np.asarray(z_points, dtype=float)
        if weights is None:
            zp, w = zp.reshape(-1, 1), np.ones((zp.size, 1))
        else:
            w = np.asarray(weights, dtype=float)
        reader = patch_reader(modes.z, zp, w)
    flex = _flexibility(bat, modes)
    full = np.einsum("pi,pi->p", reader @ flex.nodal, reader)
    elastic = slice(modes.n_rigid, None)
    phi = reader @ modes.shapes[elastic].T
    kept = (phi**2 / modes.omega[elastic] ** 2).sum(axis=1)
    return np.clip(full - kept, 0.0, None)


@dataclass(frozen=True)
class _Flexibility:
    z: np.ndarray  # mesh nodes [m]
    nodal: np.ndarray  # elastic flexibility between the nodes' transverse displacements, (N, N)


def _flexibility(bat: BatModel, modes: Modes) -> _Flexibility:
    """The factorised static problem behind :func:`residual_compliance`, kept by the active
    workspace (kind ``residual-flexibility``; or the flexibility that came with the modes,
    :mod:`batcert.physics.ritz`)."""
    if modes.flexibility is not None:
        return _Flexibility(modes.z, modes.flexibility)
    # keyed by the beam alone (beam_of): the plausible barrel's variants of one bat share it
    return workspace.current().call("residual-flexibility", _static_flexibility, beam_of(bat),
                                    modes)


def _static_flexibility(bat: BatModel, modes: Modes) -> _Flexibility:
    fe = assemble(bat, modes.z)
    keep = free_dofs(fe, modes.support, modes.pivot)
    rigid = rigid_modes(fe, modes.support, modes.pivot)[keep]
    k = fe.stiffness[np.ix_(keep, keep)]
    m = fe.mass[np.ix_(keep, keep)]
    # determinate supports: w at both ends (free) or w at the end farther from the pin (pinned)
    w_end = [0, keep.size - 2] if modes.support == "free" else (
        [keep.size - 2] if modes.pivot < 0.5 * (fe.z[0] + fe.z[-1]) else [0])
    solve = np.delete(np.arange(keep.size), w_end)  # (np.setdiff1d imports numpy.ma: 10 ms)
    # x = X f for a load f on the retained DOFs: balance f against the rigid modes' inertia,
    # solve on the determinate supports, remove the rigid part of the answer
    relief = np.eye(keep.size) - m @ rigid @ rigid.T
    inner = np.zeros((keep.size, keep.size))
    inner[np.ix_(solve, solve)] = np.linalg.inv(k[np.ix_(solve, solve)])
    x = relief.T @ inner @ relief
    # the transverse displacement DOFs (2 j) among the retained ones; a node whose w is held
    # (the pin) has no flexibility
    position = np.full(fe.z.size * 2, -1)
    position[keep] = np.arange(keep.size)
    w_rows = position[0::2]
    nodal = np.zeros((fe.z.size, fe.z.size))
    held = w_rows < 0
    nodal[np.ix_(~held, ~held)] = x[np.ix_(w_rows[~held], w_rows[~held])]
    return _Flexibility(fe.z, 0.5 * (nodal + nodal.T))


def nodal_flexibility(bat: BatModel, modes: Modes) -> np.ndarray:
    """The elastic flexibility between the nodes' transverse displacements of ``bat`` on the
    mesh of ``modes`` [m/N], (n_nodes, n_nodes) (the static problem of
    :func:`residual_compliance`)."""
    return _flexibility(bat, modes).nodal
