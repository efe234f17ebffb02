"""Bending modes of a bat: the :class:`Modes` every engine reads, computed from the Timoshenko
beam of :mod:`batcert.physics.beam`, cached in-process, and their nodes."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from batcert import workspace
from batcert.physics.batmodel import BatModel, Material
from batcert.physics.beam import N_RIGID, assemble, check_support, free_dofs, mesh_nodes, rigid_modes


@dataclass(frozen=True)
class Modes:
    """Mass-normalised modes of the bat, rigid-body modes first.

    ``shapes[j] @ M @ shapes[j] = 1`` for the beam's mass matrix (including point masses), so that
    the modal equations read ``q_j'' + omega_j^2 q_j = phi_j(z_impact) * F``.
    """

    support: str  # "free" | "pinned"
    pivot: float  # pin position for "pinned" [m from knob]; recorded but unused for "free"
    z: np.ndarray  # node positions from the knob [m], shape (n_nodes,)
    omega: np.ndarray  # angular frequencies [rad/s], shape (n_modes,), ascending, rigid modes = 0
    shapes: np.ndarray  # transverse displacement at the nodes, shape (n_modes, n_nodes)
    rotations: np.ndarray  # section rotation at the nodes, shape (n_modes, n_nodes)
    n_rigid: int  # number of rigid-body modes at the front (2 free, 1 pinned)
    # the elastic flexibility between the nodes' transverse displacements [m/N], (n_nodes,
    # n_nodes), when it comes with the modes (batcert.physics.ritz); otherwise the residual
    # compliance solves for it from the beam
    flexibility: np.ndarray | None = None

    def at(self, z_points: np.ndarray) -> np.ndarray:
        """Mode shapes at arbitrary positions from the knob, shape (n_points, n_modes)."""
        z_points = np.atleast_1d(np.asarray(z_points, dtype=float))
        return np.stack([np.interp(z_points, self.z, s) for s in self.shapes], axis=-1)

    @property
    def frequencies_hz(self) -> np.ndarray:
        """Bending frequencies [Hz], rigid modes excluded, ascending."""
        return self.omega[self.n_rigid:] / (2 * np.pi)


def eigenpairs(k: np.ndarray, m: np.ndarray, n_skip: int,
                n_want: int) -> tuple[np.ndarray, np.ndarray]:
    """Eigenpairs ``n_skip .. n_skip + n_want - 1`` (ascending) of ``k x = lam m x``; ``k``
    and ``m`` may be stacks of matrices, (..., n, n), solved together (a Monte Carlo's drawn
    bats, :mod:`batcert.physics.ritz`).

    Dense, with numpy only (a bat has a few hundred DOFs; LAPACK through numpy avoids importing
    scipy on the run path): ``m = L L^T``, ``L^-1 k L^-T y = lam y``, ``x = L^-T y``. Vectors
    are returned mass-normalised.
    """
    low = np.linalg.cholesky(m)
    inv_low = np.linalg.inv(low)  # triangular and small; numpy has no triangular solve
    a = inv_low @ k @ np.swapaxes(inv_low, -1, -2)
    lam, y = np.linalg.eigh(0.5 * (a + np.swapaxes(a, -1, -2)))
    lam, y = lam[..., n_skip:n_skip + n_want], y[..., n_skip:n_skip + n_want]
    vec = np.swapaxes(inv_low, -1, -2) @ y
    vec = vec / np.sqrt(np.einsum("...di,...di->...i", vec, m @ vec))[..., None, :]
    return lam, vec


def compute_modes(bat: BatModel, support: str, pivot: float, n_modes: int = 24,
                  refine: int = 1) -> Modes:
    """Rigid-body and bending modes of ``bat``, mass-normalised.

    Solves ``K phi = omega^2 M phi`` for the Timoshenko mesh of :func:`assemble` (dense, see
    :func:`eigenpairs`). The rigid
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
    check_support(bat, support, pivot)
    if n_modes < 0:
        raise ValueError(f"n_modes must be >= 0, got {n_modes}")
    z_points = [pivot] + [zp for zp, _ in bat.point_masses]
    fe = assemble(bat, mesh_nodes(bat, refine, z_points))
    n_rigid = N_RIGID[support]
    keep = free_dofs(fe, support, pivot)
    n_bend = int(min(n_modes, keep.size - n_rigid))
    rigid = rigid_modes(fe, support, pivot)
    vectors = [rigid]
    omega = [np.zeros(n_rigid)]
    if n_bend > 0:
        lam, vec = eigenpairs(fe.stiffness[np.ix_(keep, keep)], fe.mass[np.ix_(keep, keep)],
                               n_rigid, n_bend)
        full = np.zeros((fe.z.size * 2, n_bend))
        full[keep] = vec
        full = tip_positive(full)
        vectors.append(full)
        omega.append(np.sqrt(np.clip(lam, 0.0, None)))
    phi = np.concatenate(vectors, axis=1).T
    return Modes(support=support, pivot=float(pivot), z=fe.z, omega=np.concatenate(omega),
                 shapes=np.ascontiguousarray(phi[:, 0::2]),
                 rotations=np.ascontiguousarray(phi[:, 1::2]), n_rigid=n_rigid)


def tip_positive(vectors: np.ndarray) -> np.ndarray:
    """Mode vectors on the full DOF vector, (..., 2 n_nodes, n), each signed so that its
    transverse displacement at the tip (the last node's ``w``) is positive: the modes' sign
    convention."""
    return vectors * np.where(vectors[..., -2:-1, :] < 0, -1.0, 1.0)


def full_vectors(modes: Modes) -> np.ndarray:
    """The modes on the beam's interleaved DOF vector ``[w_0, theta_0, ...]``, (2 n_nodes,
    n_modes)."""
    out = np.empty((2 * modes.z.size, modes.omega.size))
    out[0::2], out[1::2] = modes.shapes.T, modes.rotations.T
    return out


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


def beam_of(bat: BatModel) -> BatModel:
    """``bat`` with what its beam modes do not read set to neutral values: its name, its
    material (the sections already hold it) and its barrel shell's scales and end. Bats that
    differ only there share their modes; any other field, a new one included, is part of the
    key of :func:`cached_modes`."""
    return replace(bat, name="", material=_NO_MATERIAL, barrel_stiffness_scale=1.0,
                   barrel_mass_scale=1.0, barrel_end="closed")


_NO_MATERIAL = Material("", 0.0, 0.0, 0.0, 0.0, 0.0)


def cached_modes(bat: BatModel, support: str, pivot: float, n_modes: int = 24,
                 refine: int = 1) -> Modes:
    """:func:`compute_modes` of :func:`beam_of` ``(bat)``, kept by the active workspace
    (:mod:`batcert.workspace`, kind ``modes``: in the process and, where one is attached, in
    its disk store, which returns the computed arrays exactly).

    The returned arrays are read-only because they are shared between callers.
    """
    args = (beam_of(bat), str(support), float(pivot), int(n_modes), int(refine))
    return workspace.current().call(
        "modes", _read_only_modes, *args, save=_to_arrays,
        load=lambda a: _from_arrays(a, args[1], args[2]))


def _read_only_modes(bat: BatModel, support: str, pivot: float, n_modes: int,
                     refine: int) -> Modes:
    return _read_only(compute_modes(bat, support, pivot, n_modes, refine))


def _read_only(modes: Modes) -> Modes:
    for a in (modes.z, modes.omega, modes.shapes, modes.rotations):
        a.flags.writeable = False
    return modes


def _to_arrays(modes: Modes) -> dict[str, np.ndarray]:
    return {"z": modes.z, "omega": modes.omega, "shapes": modes.shapes,
            "rotations": modes.rotations, "n_rigid": np.array(modes.n_rigid)}


def _from_arrays(a: dict | None, support: str, pivot: float) -> Modes | None:
    """Stored modes, or None if ``a`` is missing or does not hold a consistent set."""
    if a is None:
        return None
    try:
        modes = Modes(support=support, pivot=pivot, z=a["z"], omega=a["omega"],
                      shapes=a["shapes"], rotations=a["rotations"], n_rigid=int(a["n_rigid"]))
        ok = (modes.z.ndim == 1 and modes.omega.ndim == 1 and modes.shapes.shape ==
              modes.rotations.shape == (modes.omega.size, modes.z.size)
              and 0 < modes.n_rigid <= modes.omega.size)
    except (KeyError, TypeError, ValueError):
        return None
    return _read_only(modes) if ok else None
