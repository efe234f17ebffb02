r"""Thin shells of revolution by the semi-analytical finite element method.

A shell of revolution about the z axis is described by its mid-surface meridian, nodes
``(z_i, r_i)`` (axial position, mid-surface radius), and a wall thickness per element. Each
element is a conical frustum. Under circumferential order ``n`` the displacements symmetric about
``theta = 0`` are

    u = U(s) cos(n theta)   (meridional),  v = V(s) sin(n theta)   (circumferential),
    w = W(s) cos(n theta)   (normal, positive outward),

with ``s`` the arc length along the meridian. Harmonics are uncoupled, so each ``n`` is a 1-D
finite-element problem along the meridian (Zienkiewicz & Taylor, *The Finite Element Method*,
vol. 2, ch. "Axisymmetric shells", Fourier analysis; Grafton & Strome, AIAA J. 1 (1963) 2342).

The shell's description, its element (a conical frustum), the strains and the element matrices
are in :mod:`batcert.physics.shell_element`. Here: the global matrices of each order with the end
conditions (:class:`Assembler`, :func:`assemble`), the static solution (:func:`static_solve`),
the modes (:func:`harmonic_modes`), how ``W`` is read at a point (:func:`normal_reader`) and the
thin ring's frequency, for comparison. The matrices include the ``theta`` integral, so that with
modes normalised to ``phi^T M phi = 1`` a normal point force ``F`` (outward) at
``(s, theta = 0)`` drives mode ``j`` with ``F W_j(s)``.

Units: SI throughout ([m], [Pa], [kg/m^3], [N]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.banded import lower_band
from batcert.physics.shell_element import (
    ShellOfRevolution,
    element_matrices,
    element_power_matrices,
)

__all__ = ["Assembler", "HarmonicModes", "HarmonicSystem", "ShellOfRevolution", "assemble",
           "element_matrices", "harmonic_modes", "normal_reader", "normal_weights",
           "ring_frequency", "ring_frequency_of", "static_solve"]


@dataclass(frozen=True)
class HarmonicSystem:
    """The assembled problem of one circumferential order: ``K x = f`` and ``K x = w^2 M x``
    on the free dofs ``free`` of the full dof vector (``node_dofs`` per node)."""

    n: int
    stiffness: np.ndarray  # (m, m) on the free dofs
    mass: np.ndarray  # (m, m)
    free: np.ndarray  # indices of the free dofs in the full vector
    node_dofs: int
    w_offset: int  # index of W within a node's dofs (W' follows)
    rigid: np.ndarray | None = None  # n = 0 with ``support``: the axial translation on the
    # free dofs, mass-normalised (the load is equilibrated against it, see static_solve)


def _global(shell: ShellOfRevolution, nd: int, blocks: np.ndarray) -> np.ndarray:
    """Assemble element blocks (e, 2 nd, 2 nd) into the global dense matrix."""
    size = nd * shell.z.size
    idx = (nd * np.arange(shell.n_elements))[:, None] + np.arange(2 * nd)[None, :]
    out = np.zeros((size, size))
    np.add.at(out, (idx[:, :, None], idx[:, None, :]), blocks)
    return out


class Assembler:
    """Global matrices of every order of one shell, built once.

    For the orders ``n >= 1`` the strains are polynomials in ``n`` (membrane of degree 1,
    bending of degree 2), so the stiffness is ``sum_p n^p K_p``, ``p = 0..4``, and the mass does
    not depend on ``n``: five matrices assembled once serve every order
    (:func:`~batcert.physics.shell_element.element_power_matrices`). Order 0 has its own layout
    (no torsion) and is assembled directly.
    """

    def __init__(self, shell: ShellOfRevolution):
        self.shell = shell
        k0, m0 = element_matrices(shell, 0)
        self._k0, self._m0 = _global(shell, 3, k0), _global(shell, 3, m0)
        powers, mass = element_power_matrices(shell)
        # the orders n >= 1 share their free dofs (support only concerns order 0): their
        # matrices are kept on them
        self._free, _ = _free_dofs(shell, 1, False)
        ix = np.ix_(self._free, self._free)
        self._k = [_global(shell, 5, kp)[ix] for kp in powers]
        self._m = _global(shell, 5, mass)[ix]
        self._k_bands = lower_band(np.stack(self._k), 9)  # (5, 10, m)

    def system(self, n: int, support: bool = False) -> HarmonicSystem:
        """The problem of order ``n`` with the end conditions applied (see :func:`assemble`)."""
        if n == 0:
            return _with_ends(self.shell, 0, self._k0, self._m0, support)
        k = self._k[0].copy()
        for p, kp in enumerate(self._k[1:], start=1):
            k += float(n) ** p * kp
        return _system(n, k, self._m, self._free, 5, None)

    def stiffness_bands(self, orders) -> tuple[np.ndarray, np.ndarray]:
        """Lower band storage (:func:`batcert.physics.banded.lower_band`) of the stiffness of
        each order in ``orders`` (all ``>= 1``) on their free dofs, shape (orders, 10, m), and
        those free dofs (m,); half-bandwidth 9 (two nodes of five unknowns)."""
        n = np.asarray(orders, dtype=float)
        if np.any(n < 1):
            raise ValueError("stiffness_bands serves the orders n >= 1")
        powers = n[:, None] ** np.arange(5)[None, :]  # (orders, 5)
        return np.einsum("op,pkm->okm", powers, self._k_bands), self._free


def assemble(shell: ShellOfRevolution, n: int, support: bool = False) -> HarmonicSystem:
    """Global matrices of order ``n`` with the end conditions applied.

    Order 0 has a rigid axial translation (the beam's business, not the wall's). Without
    ``support`` it is left free (eigenvalue 0, dropped by :func:`harmonic_modes`); with it, ``u_z``
    is held at the first node so that the stiffness is invertible, and :func:`static_solve`
    equilibrates the load against the translation's inertia first (inertia relief).
    """
    nd = shell.node_dofs(n)
    k_e, m_e = element_matrices(shell, n)
    return _with_ends(shell, n, _global(shell, nd, k_e), _global(shell, nd, m_e), support)


def _free_dofs(shell: ShellOfRevolution, n: int, support: bool
               ) -> tuple[np.ndarray, np.ndarray | None]:
    """The free dofs of order ``n`` (a closed end holds ``u_r`` and, for ``n >= 1``, ``V``; a
    supported order 0 holds ``u_z`` at the first node) and, for a supported order 0, its axial
    translation on the full dof vector (else None)."""
    nd = shell.node_dofs(n)
    n_nodes = shell.z.size
    size = nd * n_nodes
    fixed: list[int] = []
    w_off = 1 if n == 0 else 3
    for end, node in zip(shell.ends, (0, n_nodes - 1), strict=True):
        if end == "closed":  # held round by a rigid cap: no radial or circumferential motion
            fixed += [nd * node + w_off] + ([nd * node + 1] if n else [])
    translation = None
    if n == 0 and support:
        translation = np.zeros(size)
        translation[0::nd] = 1.0
        fixed.append(0)
    return np.delete(np.arange(size), np.asarray(fixed, dtype=int)), translation


def _system(n: int, k_free: np.ndarray, m_free: np.ndarray, free: np.ndarray, nd: int,
            translation: np.ndarray | None) -> HarmonicSystem:
    """A :class:`HarmonicSystem` from matrices already on the free dofs."""
    rigid = None
    if translation is not None:
        t = translation[free]
        rigid = t / np.sqrt(t @ m_free @ t)
    return HarmonicSystem(n, k_free, m_free, free, nd, 1 if n == 0 else 3, rigid)


def _with_ends(shell: ShellOfRevolution, n: int, k: np.ndarray, m: np.ndarray,
               support: bool) -> HarmonicSystem:
    free, translation = _free_dofs(shell, n, support)
    ix = np.ix_(free, free)
    return _system(n, k[ix], m[ix], free, shell.node_dofs(n), translation)


def static_solve(system: HarmonicSystem, factor, load: np.ndarray) -> np.ndarray:
    """Static displacements of the free dofs under ``load`` (free dofs, one column per case),
    with ``factor`` the Cholesky factor of the system's stiffness (``scipy.linalg.cho_factor``'s)
    or a function that solves with it; for a supported order 0 the load is first equilibrated
    against the axial translation and the translation removed from the answer (inertia relief;
    Craig & Kurdila 2006, Sec. 11.3)."""
    import scipy.linalg  # hollow bats only: ~0.15 s to import

    def solve(b: np.ndarray) -> np.ndarray:
        if callable(factor):
            return factor(b)
        return scipy.linalg.cho_solve(factor, b, check_finite=False)

    if system.rigid is None:
        return solve(load)
    mr = system.mass @ system.rigid
    balanced = load - np.outer(mr, system.rigid @ load)
    x = solve(balanced)
    return x - np.outer(system.rigid, mr @ x)


@dataclass(frozen=True)
class HarmonicModes:
    """Mass-normalised modes of one order, full dof vectors (fixed dofs zero)."""

    n: int
    omega: np.ndarray  # [rad/s], ascending, (k,)
    vectors: np.ndarray  # (ndof, k)


def harmonic_modes(shell: ShellOfRevolution, n: int, max_frequency: float,
                   system: HarmonicSystem | None = None) -> HarmonicModes:
    """Elastic modes of order ``n`` up to ``max_frequency`` [Hz]: counted and found on the
    banded matrices (:mod:`batcert.physics.band_modes`), or by the dense generalized
    eigenproblem where that does not settle; ``system`` may be passed if it is the unsupported
    one of :func:`assemble`."""
    sys_ = system if system is not None and system.rigid is None else assemble(shell, n)
    cut = (2 * np.pi * max_frequency) ** 2
    lam, vec = _modes_below(sys_, shell.z.size, cut)
    elastic = lam > (2 * np.pi * 1.0) ** 2  # drop order 0's rigid axial translation
    lam, vec = lam[elastic], vec[:, elastic]
    full = np.zeros((sys_.node_dofs * shell.z.size, lam.size))
    full[sys_.free] = vec
    return HarmonicModes(n, np.sqrt(np.clip(lam, 0.0, None)), full)


def _modes_below(system: HarmonicSystem, n_nodes: int, cut: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The eigenpairs of ``system`` below ``cut`` [rad^2/s^2]: banded count and Lanczos, else
    the dense solve (:func:`dense_modes_below`)."""
    from batcert.physics.band_modes import count_below, lowest_modes

    k, m = system.stiffness, system.mass
    count = count_below(k - cut * m, system.free, system.node_dofs, n_nodes)
    if count is not None:
        if count == 0:
            return np.zeros(0), np.zeros((k.shape[0], 0))
        found = lowest_modes(k, m, cut, 2 * system.node_dofs - 1, count)
        if found is not None:
            return found
    return dense_modes_below(system, cut)


def dense_modes_below(system: HarmonicSystem, cut: float) -> tuple[np.ndarray, np.ndarray]:
    """The eigenpairs of ``system`` below ``cut`` [rad^2/s^2] by the dense generalized
    eigenproblem (LAPACK ``dsygvx``), mass-normalised: the reference of the banded path."""
    import scipy.linalg  # hollow bats only: ~0.15 s to import

    return scipy.linalg.eigh(system.stiffness, system.mass, check_finite=False, driver="gvx",
                             subset_by_value=(-np.inf, cut))


def normal_reader(shell: ShellOfRevolution, n: int, z: np.ndarray):
    """How to read ``W`` (the normal displacement amplitude) of order ``n`` at axial positions
    ``z`` (any shape) from a full dof vector: the dof columns (..., 6) and weights (..., 6) of
    the containing element's ``u_z``, ``u_r`` and ``W'`` at its two nodes (:func:`normal_weights`);
    points off the shell get zero weights."""
    nd = shell.node_dofs(n)
    w_off = 1 if n == 0 else 3
    e, h = normal_weights(shell, z)
    cols = np.stack([nd * e, nd * e + w_off, nd * e + w_off + 1,
                     nd * (e + 1), nd * (e + 1) + w_off, nd * (e + 1) + w_off + 1], axis=-1)
    return cols, h


def normal_weights(shell: ShellOfRevolution, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The element that contains each axial position ``z`` (any shape), and the weights (..., 6)
    with which ``W`` there is read from that element's ``u_z``, ``u_r``, ``W'`` at its first and
    then its second node: ``W`` is cubic Hermite in the element's normal displacement
    ``-sin psi u_z + cos psi u_r`` and its slope. Points off the shell get zero weights."""
    inside = (z >= shell.z[0]) & (z <= shell.z[-1])
    e = np.clip(np.searchsorted(shell.z, z, side="right") - 1, 0, shell.n_elements - 1)
    xi = np.clip((z - shell.z[e]) / (shell.z[e + 1] - shell.z[e]), 0.0, 1.0)
    L = shell.lengths[e]
    sp = (shell.r[e + 1] - shell.r[e]) / L
    cp = (shell.z[e + 1] - shell.z[e]) / L
    h0, h1 = 1 - 3 * xi**2 + 2 * xi**3, L * (xi - 2 * xi**2 + xi**3)
    h2, h3 = 3 * xi**2 - 2 * xi**3, L * (-xi**2 + xi**3)
    h = np.empty(np.shape(z) + (6,))
    h[..., 0], h[..., 1], h[..., 2] = -sp * h0, cp * h0, h1
    h[..., 3], h[..., 4], h[..., 5] = -sp * h2, cp * h2, h3
    if not inside.all():
        h *= inside[..., None]
    return e, h


def ring_frequency(mean_radius, wall, youngs_modulus, density, poisson_ratio, n: int = 2):
    """Inextensional thin-ring frequency of order ``n`` [Hz] of an isotropic wall (Love 1927;
    Soedel 2004): :func:`ring_frequency_of` with ``D = E t^3 / (12 (1 - nu^2))`` and
    ``rho t``: the infinitely long barrel's lower bound, for comparison only.

    Examples
    --------
    A 7050 ring of 2.625 in outer diameter with a 2.5 mm wall (mean radius 32.09 mm):

    >>> round(float(ring_frequency(0.0320875, 0.0025, 71.7e9, 2830.0, 0.33)))
    1596
    """
    wall = np.asarray(wall)
    bending = youngs_modulus * wall**3 / (12.0 * (1.0 - poisson_ratio**2))
    return ring_frequency_of(mean_radius, bending, density * wall, n)


def ring_frequency_of(mean_radius, hoop_bending_stiffness, areal_density, n: int = 2):
    """Inextensional thin-ring frequency of order ``n`` [Hz] of a wall whose bending stiffness
    around the ring is ``hoop_bending_stiffness`` [N m] (``D22`` of a laminate) and whose mass
    per unit area is ``areal_density`` [kg/m^2]:
    ``omega = (n (n^2 - 1) / sqrt(n^2 + 1)) sqrt(D / (rho t)) / R^2``."""
    omega = (np.sqrt(np.asarray(hoop_bending_stiffness) / np.asarray(areal_density))
             / np.asarray(mean_radius) ** 2) * n * (n * n - 1) / np.sqrt(n * n + 1.0)
    return omega / (2 * np.pi)
