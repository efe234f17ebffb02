"""Quasi-static (residual) compliance of the bending modes a truncated modal model leaves out.

Used by the flexible engine as a spring in series with the ball, so that its result does not
depend on how many modes it keeps (Craig & Kurdila, *Fundamentals of Structural Dynamics*, 2006,
Sec. 11.3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.batmodel import BatModel
from batcert.physics.beam import assemble, check_support, free_dofs, rigid_modes
from batcert.physics.modes import Modes


def _point_loads(z_nodes: np.ndarray, z_points) -> np.ndarray:
    """Unit transverse loads at ``z_points`` shared linearly between the two nearest nodes.

    The same interpolation as :meth:`Modes.at`, so ``phi @ f = modes.at(z)``. Shape (ndof, p).
    """
    zp = np.atleast_1d(np.asarray(z_points, dtype=float))
    i = np.clip(np.searchsorted(z_nodes, zp, side="right") - 1, 0, z_nodes.size - 2)
    t = np.clip((zp - z_nodes[i]) / (z_nodes[i + 1] - z_nodes[i]), 0.0, 1.0)
    f = np.zeros((2 * z_nodes.size, zp.size))
    cols = np.arange(zp.size)
    f[2 * i, cols] += 1.0 - t
    f[2 * i + 2, cols] += t
    return f


def _distributed_loads(z_nodes: np.ndarray, z_points: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """Unit resultant loads spread over ``z_points`` (p, K) with ``weights`` (p, K), each sample
    shared linearly between its two nearest nodes (as :func:`_point_loads`). Shape (ndof, p)."""
    zp = z_points.ravel()
    i = np.clip(np.searchsorted(z_nodes, zp, side="right") - 1, 0, z_nodes.size - 2)
    t = np.clip((zp - z_nodes[i]) / (z_nodes[i + 1] - z_nodes[i]), 0.0, 1.0)
    w = weights.ravel()
    cols = np.repeat(np.arange(z_points.shape[0]), z_points.shape[1])
    f = np.zeros((2 * z_nodes.size, z_points.shape[0]))
    np.add.at(f, (2 * i, cols), (1.0 - t) * w)
    np.add.at(f, (2 * i + 2, cols), t * w)
    return f


def residual_compliance(bat: BatModel, modes: Modes, z_points, weights=None) -> np.ndarray:
    """Static compliance at ``z_points`` of the bending modes that ``modes`` left out.

    The elastic (inertia-relief) flexibility of the FE beam, ``G = sum over all bending modes of
    phi_j(z)^2 / omega_j^2``, is computed without the eigenvectors: the load is made
    self-equilibrated against the rigid modes (``f - M Phi_r Phi_r^T f``), the beam is held by a
    statically determinate set of supports that then carry no reaction, and the rigid part is
    removed from the displacement (Craig & Kurdila, *Fundamentals of Structural Dynamics*, 2006,
    Sec. 11.3, residual flexibility). The kept modes' ``sum phi_j(z)^2 / omega_j^2`` is subtracted;
    what remains is the quasi-static flexibility of the truncated modes, to be put in series with
    the ball contact.

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

    Returns
    -------
    numpy.ndarray
        Residual compliance [m/N], shape (p,), >= 0.
    """
    check_support(bat, modes.support, modes.pivot)
    zp = np.asarray(z_points, dtype=float)
    if weights is None:
        zp, w = zp.reshape(-1, 1), np.ones((zp.size, 1))
    else:
        w = np.asarray(weights, dtype=float)
    flex = _flexibility(bat, modes)
    n_points, n_samples = zp.shape
    f = _distributed_loads(flex.z, zp, w)[flex.keep]
    f_eq = f - flex.m @ (flex.rigid @ (flex.rigid.T @ f))
    x = np.zeros_like(f_eq)
    x[flex.solve] = flex.flexibility @ f_eq[flex.solve]
    x -= flex.rigid @ (flex.rigid.T @ (flex.m @ x))
    full = np.einsum("dp,dp->p", f, x)
    elastic = slice(modes.n_rigid, None)
    phi = (modes.at(zp.ravel()).reshape(n_points, n_samples, -1) * w[..., None]).sum(axis=1)
    kept = (phi[:, elastic] ** 2 / modes.omega[elastic] ** 2).sum(axis=1)
    return np.clip(full - kept, 0.0, None)


@dataclass(frozen=True)
class _Flexibility:
    z: np.ndarray  # mesh nodes [m]
    keep: np.ndarray  # retained DOFs
    rigid: np.ndarray  # rigid modes on the retained DOFs
    m: np.ndarray  # mass matrix on the retained DOFs
    solve: np.ndarray  # DOFs solved for (determinate supports removed)
    flexibility: np.ndarray  # inverse of the stiffness on `solve` (dense: a few hundred DOFs)


_FLEX_CACHE: dict = {}


def _flexibility(bat: BatModel, modes: Modes) -> _Flexibility:
    """The factorised static problem behind :func:`residual_compliance`, cached per modes."""
    hit = _FLEX_CACHE.get(id(modes))
    if hit is not None and hit[0] is modes:
        return hit[1]
    fe = assemble(bat, modes.z)
    keep = free_dofs(fe, modes.support, modes.pivot)
    rigid = rigid_modes(fe, modes.support, modes.pivot)[keep]
    k = fe.stiffness[np.ix_(keep, keep)]
    m = fe.mass[np.ix_(keep, keep)]
    # determinate supports: w at both ends (free) or w at the end farther from the pin (pinned)
    w_end = [0, keep.size - 2] if modes.support == "free" else (
        [keep.size - 2] if modes.pivot < 0.5 * (fe.z[0] + fe.z[-1]) else [0])
    solve = np.delete(np.arange(keep.size), w_end)  # (np.setdiff1d imports numpy.ma: 10 ms)
    flexibility = np.linalg.inv(k[np.ix_(solve, solve)])
    flex = _Flexibility(fe.z, keep, rigid, m, solve, 0.5 * (flexibility + flexibility.T))
    _FLEX_CACHE[id(modes)] = (modes, flex)
    while len(_FLEX_CACHE) > 32:
        _FLEX_CACHE.pop(next(iter(_FLEX_CACHE)))
    return flex
