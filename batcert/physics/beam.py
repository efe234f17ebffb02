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

import hashlib
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg

from batcert.physics.batmodel import BatModel
from batcert.physics.modes import Modes

SUPPORTS = ("free", "pinned")
_N_RIGID = {"free": 2, "pinned": 1}
_SNAP = 1e-3  # an inserted point closer than this fraction of its element's length reuses the node

_GX, _GW = np.polynomial.legendre.leggauss(4)
_XI = 0.5 * (_GX + 1.0)  # Gauss points on [0, 1]
_WXI = 0.5 * _GW  # weights on [0, 1]


@dataclass(frozen=True)
class _FiniteElements:
    z: np.ndarray  # node positions [m], (n_nodes,)
    stiffness: scipy.sparse.csc_matrix  # global stiffness [N/m, N, N m], (2 n_nodes, 2 n_nodes)
    mass: scipy.sparse.csc_matrix  # global consistent mass [kg, kg m, kg m^2], same shape


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
    n_w, n_t, _, _ = shape_functions(_XI, L, phi)
    wq = _WXI[None, :] * L[:, None]  # quadrature weights [m], (e, q)
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


def assemble(bat: BatModel, nodes: np.ndarray) -> _FiniteElements:
    """Global stiffness and mass matrices of ``bat`` on the mesh ``nodes`` (point masses included).

    Each element takes the properties of the slice holding its midpoint; a point mass is lumped on
    the transverse DOF of the nearest node (exact when a node sits at the mass, see
    :func:`mesh_nodes`; masses beyond the ends go to the end node). Point masses carry no rotary
    inertia of their own.
    """
    z = np.asarray(nodes, dtype=float)
    edges = np.asarray(bat.z_edges, dtype=float)
    mid = 0.5 * (z[1:] + z[:-1])
    s = np.clip(np.searchsorted(edges, mid, side="right") - 1, 0, edges.size - 2)
    k_e, m_e = element_matrices(np.diff(z), bat.bending_stiffness[s], bat.shear_stiffness[s],
                                bat.linear_density[s], bat.rotary_inertia[s])
    n = 2 * z.size
    dofs = 2 * np.arange(z.size - 1)[:, None] + np.arange(4)[None, :]  # (e, 4)
    rows = np.broadcast_to(dofs[:, :, None], k_e.shape).ravel()
    cols = np.broadcast_to(dofs[:, None, :], k_e.shape).ravel()
    pm = np.asarray(bat.point_masses, dtype=float).reshape(-1, 2)
    j = 2 * np.abs(z[None, :] - pm[:, :1]).argmin(axis=1)
    stiffness = scipy.sparse.csc_matrix((k_e.ravel(), (rows, cols)), shape=(n, n))
    mass = scipy.sparse.csc_matrix((np.concatenate([m_e.ravel(), pm[:, 1]]),
                                    (np.concatenate([rows, j]), np.concatenate([cols, j]))),
                                   shape=(n, n))
    return _FiniteElements(z=z, stiffness=stiffness, mass=mass)


def _rigid_modes(fe: _FiniteElements, support: str, pivot: float) -> np.ndarray:
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


def _free_dofs(fe: _FiniteElements, support: str, pivot: float) -> np.ndarray:
    """DOF indices left after the support constraint (``w = 0`` at the pivot node if pinned)."""
    all_dofs = np.arange(2 * fe.z.size)
    if support == "free":
        return all_dofs
    return np.delete(all_dofs, 2 * int(np.argmin(np.abs(fe.z - pivot))))


def _check(bat: BatModel, support: str, pivot: float) -> None:
    if support not in SUPPORTS:
        raise ValueError(f"support must be one of {SUPPORTS}, got {support!r}")
    if support == "pinned" and not bat.z_edges[0] <= pivot <= bat.z_edges[-1]:
        raise ValueError(f"pivot {pivot} m lies outside the bat [0, {bat.z_edges[-1]}] m")


_DENSE_MAX = 256  # up to this many DOFs dense LAPACK beats sparse shift-invert (measured)
_SHIFT = -(2 * np.pi * 10.0) ** 2  # shift-invert point below every bat mode [rad^2/s^2]


def _eigenpairs(k, m, n_skip: int, n_want: int) -> tuple[np.ndarray, np.ndarray]:
    """Eigenpairs ``n_skip .. n_skip + n_want - 1`` (ascending) of ``k x = lam m x``.

    Dense ``scipy.linalg.eigh`` (LAPACK ``sygvx``, wanted pairs only) for small meshes; ARPACK
    shift-invert (``scipy.sparse.linalg.eigsh``) about a point just below zero for large ones.
    Vectors are returned mass-normalised.
    """
    n = k.shape[0]
    if n <= _DENSE_MAX or n_skip + n_want >= n - 1:
        lam, vec = scipy.linalg.eigh(k.toarray(), m.toarray(), driver="gvx", check_finite=False,
                                     subset_by_index=[n_skip, n_skip + n_want - 1])
    else:
        lam, vec = scipy.sparse.linalg.eigsh(k, k=n_skip + n_want, M=m, sigma=_SHIFT,
                                             which="LM", v0=np.ones(n))
        order = np.argsort(lam)[n_skip:]
        lam, vec = lam[order], vec[:, order]
    vec = vec / np.sqrt(np.einsum("di,di->i", vec, m @ vec))
    return lam, vec


def compute_modes(bat: BatModel, support: str, pivot: float, n_modes: int = 24,
                  refine: int = 1) -> Modes:
    """Rigid-body and bending modes of ``bat``, mass-normalised.

    Solves ``K phi = omega^2 M phi`` for the Timoshenko mesh of :func:`assemble` (dense LAPACK
    for small meshes, sparse shift-invert for large ones, see :func:`_eigenpairs`). The rigid
    modes are built exactly and put first with ``omega = 0``; each shape satisfies
    ``phi^T M phi = 1`` for the full mass matrix (translation, rotary inertia and point masses), so that a
    transverse point force ``F`` at ``z`` drives ``q_j'' + omega_j^2 q_j = phi_j(z) F`` (modal
    superposition as in Nathan 2000; Meirovitch, *Fundamentals of Vibrations*, 2001, ch. 7). Shapes
    are signed to be positive at the tip.

    Parameters
    ----------
    bat : BatModel
        The sliced bat.
    support : {"free", "pinned"}
        "free": two rigid modes (translation, rotation about the CG). "pinned": ``w = 0`` at the
        pivot, one rigid mode (rotation about the pivot).
    pivot : float
        Pivot position from the knob [m]; always a mesh node.
    n_modes : int
        Number of bending modes kept (fewer if the mesh has fewer) [-].
    refine : int
        Elements per slice [-].

    Returns
    -------
    Modes
        Node positions [m], ``omega`` [rad/s], shapes [1/sqrt(kg)], rotations [1/(m sqrt(kg))].
    """
    _check(bat, support, pivot)
    if n_modes < 0:
        raise ValueError(f"n_modes must be >= 0, got {n_modes}")
    z_points = [pivot] + [zp for zp, _ in bat.point_masses]
    fe = assemble(bat, mesh_nodes(bat, refine, z_points))
    n_rigid = _N_RIGID[support]
    keep = _free_dofs(fe, support, pivot)
    n_bend = int(min(n_modes, keep.size - n_rigid))
    rigid = _rigid_modes(fe, support, pivot)
    vectors = [rigid]
    omega = [np.zeros(n_rigid)]
    if n_bend > 0:
        lam, vec = _eigenpairs(fe.stiffness[keep][:, keep], fe.mass[keep][:, keep],
                               n_rigid, n_bend)
        full = np.zeros((fe.z.size * 2, n_bend))
        full[keep] = vec
        full *= np.where(full[-2] < 0, -1.0, 1.0)
        vectors.append(full)
        omega.append(np.sqrt(np.clip(lam, 0.0, None)))
    phi = np.concatenate(vectors, axis=1).T
    return Modes(support=support, pivot=float(pivot), z=fe.z, omega=np.concatenate(omega),
                 shapes=np.ascontiguousarray(phi[:, 0::2]),
                 rotations=np.ascontiguousarray(phi[:, 1::2]), n_rigid=n_rigid)


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
    _check(bat, modes.support, modes.pivot)
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
    x[flex.solve] = flex.lu.solve(f_eq[flex.solve])
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
    m: object  # mass matrix on the retained DOFs (sparse)
    solve: np.ndarray  # DOFs solved for (determinate supports removed)
    lu: object  # sparse LU of the stiffness on `solve`


_FLEX_CACHE: dict = {}


def _flexibility(bat: BatModel, modes: Modes) -> _Flexibility:
    """The factorised static problem behind :func:`residual_compliance`, cached per modes."""
    hit = _FLEX_CACHE.get(id(modes))
    if hit is not None and hit[0] is modes:
        return hit[1]
    fe = assemble(bat, modes.z)
    keep = _free_dofs(fe, modes.support, modes.pivot)
    rigid = _rigid_modes(fe, modes.support, modes.pivot)[keep]
    k = fe.stiffness[keep][:, keep]
    m = fe.mass[keep][:, keep]
    # determinate supports: w at both ends (free) or w at the end farther from the pin (pinned)
    w_end = [0, keep.size - 2] if modes.support == "free" else (
        [keep.size - 2] if modes.pivot < 0.5 * (fe.z[0] + fe.z[-1]) else [0])
    solve = np.setdiff1d(np.arange(keep.size), w_end)
    lu = scipy.sparse.linalg.splu(k[solve][:, solve].tocsc())
    flex = _Flexibility(fe.z, keep, rigid, m, solve, lu)
    _FLEX_CACHE[id(modes)] = (modes, flex)
    while len(_FLEX_CACHE) > 32:
        _FLEX_CACHE.pop(next(iter(_FLEX_CACHE)))
    return flex


def mode_nodes(modes: Modes, j: int) -> np.ndarray:
    """Nodes (zero crossings of the transverse shape) of bending mode ``j``.

    Parameters
    ----------
    modes : Modes
        Computed modes.
    j : int
        Bending mode number, 1 = fundamental (rigid modes are not counted), as in Nathan 2000
        Table II.

    Returns
    -------
    numpy.ndarray
        Node positions from the knob [m], ascending, linearly interpolated between mesh nodes. A
        pin counts as a node.
    """
    n_bend = modes.omega.size - modes.n_rigid
    if not 1 <= j <= n_bend:
        raise ValueError(f"bending mode number must be in 1..{n_bend}, got {j}")
    s = modes.shapes[modes.n_rigid + j - 1]
    s = np.where(np.abs(s) <= 1e-9 * np.abs(s).max(), 0.0, s)
    exact = modes.z[s == 0.0]
    a, b = s[:-1], s[1:]
    cross = a * b < 0
    z0, z1 = modes.z[:-1][cross], modes.z[1:][cross]
    crossing = z0 + (z1 - z0) * a[cross] / (a[cross] - b[cross])
    return np.sort(np.concatenate([exact, crossing]))


_CACHE: OrderedDict[tuple, Modes] = OrderedDict()
_CACHE_SIZE = 64


def model_hash(bat: BatModel) -> str:
    """SHA-256 of the arrays that define the beam (edges, section properties, point masses)."""
    h = hashlib.sha256()
    for a in (bat.z_edges, bat.linear_density, bat.rotary_inertia, bat.bending_stiffness,
              bat.shear_stiffness, np.asarray(bat.point_masses, dtype=float).reshape(-1)):
        h.update(np.ascontiguousarray(a, dtype=float).tobytes())
        h.update(b"|")
    return h.hexdigest()


def cached_modes(bat: BatModel, support: str, pivot: float, n_modes: int = 24,
                 refine: int = 1) -> Modes:
    """:func:`compute_modes` memoised in-process (LRU, 64 entries) on the model's content hash.

    The returned arrays are read-only because they are shared between callers.
    """
    key = (model_hash(bat), support, float(pivot), int(n_modes), int(refine))
    if key in _CACHE:
        _CACHE.move_to_end(key)
        return _CACHE[key]
    modes = compute_modes(bat, support, pivot, n_modes, refine)
    for a in (modes.z, modes.omega, modes.shapes, modes.rotations):
        a.flags.writeable = False
    _CACHE[key] = modes
    if len(_CACHE) > _CACHE_SIZE:
        _CACHE.popitem(last=False)
    return modes


def clear_mode_cache() -> None:
    """Empty the in-process mode cache."""
    _CACHE.clear()
