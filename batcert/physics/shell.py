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

Strains (Sanders-Koiter first-approximation theory for a shell of revolution with lines of
curvature ``s``, ``theta``; Lame parameters 1 and ``r``; meridian angle ``psi`` with
``dr/ds = sin psi``, ``dz/ds = cos psi``; principal curvatures ``0`` along the frustum and
``cos psi / r`` around; Sanders, NASA TR R-24, 1959; Kraus, *Thin Elastic Shells*, 1967):

    eps_s   = U'
    eps_th  = (n V + U sin psi + W cos psi) / r
    gamma   = -n U / r + V' - V sin psi / r
    kappa_s = -W''
    kappa_th = n cos psi V / r^2 + n^2 W / r^2 - sin psi W' / r
    tau     = 2 n (W' / r - sin psi W / r^2) + (3/2) cos psi (V' / r - sin psi V / r^2)
              + n cos psi U / (2 r^2)

(``tau`` is the engineering twist: Love's twist plus Sanders' term ``cos psi / r`` times the
rotation about the normal, which makes every rigid-body motion strain-free: checked in the
tests). With ``C = E t / (1 - nu^2)`` and ``D = E t^3 / (12 (1 - nu^2))`` the strain energy is
``1/2 int [C (eps_s^2 + eps_th^2 + 2 nu eps_s eps_th + (1 - nu)/2 gamma^2) + D (kappa_s^2 +
kappa_th^2 + 2 nu kappa_s kappa_th + (1 - nu)/2 tau^2)] r dtheta ds``; the kinetic energy is
``1/2 int rho t (u_t^2 + v_t^2 + w_t^2) r dtheta ds`` (rotary inertia of the wall neglected). The
``theta`` integrals give ``pi`` for ``n >= 1`` and ``2 pi`` (cosine terms only) for ``n = 0``.

Elements: ``U`` linear, ``V`` and ``W`` cubic Hermite (``V`` cubic too, so that the
inextensional ring modes, ``n V + W = 0``, are represented without membrane locking). The node
unknowns are global, ``(u_z, V, V', u_r, W')`` for ``n >= 1`` and ``(u_z, u_r, W')`` for ``n = 0``
(no torsion): the axial and radial displacements, which each element turns into its own ``U``
and ``W`` (:func:`_to_global`), so that elements of different cone angles meet consistently and
a rigid axial translation is strain-free across a kink in the meridian.
Four-point Gauss quadrature. Matrices include the ``theta`` integral, so that with modes
normalised to ``phi^T M phi = 1`` a normal point force ``F`` (outward) at ``(s, theta = 0)``
drives mode ``j`` with ``F W_j(s)``.

Units: SI throughout ([m], [Pa], [kg/m^3], [N]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.banded import lower_band
from batcert.physics.quadrature import GAUSS_POINTS, GAUSS_WEIGHTS

ENDS = ("open", "closed")  # an open edge, or one held round by a rigid cap (V = W = 0)


@dataclass(frozen=True)
class ShellOfRevolution:
    """The mid-surface meridian, wall and material of a shell of revolution.

    ``z`` and ``r`` are node positions (axial [m], mid-surface radius [m]), shape (N + 1,);
    ``thickness``, ``density`` and ``youngs_modulus`` are per element, shape (N,).
    """

    z: np.ndarray  # [m]
    r: np.ndarray  # [m]
    thickness: np.ndarray  # [m]
    density: np.ndarray  # [kg/m^3]
    youngs_modulus: np.ndarray  # [Pa]
    poisson_ratio: float  # [-]
    ends: tuple[str, str] = ("closed", "closed")  # at z[0] and z[-1]

    def __post_init__(self) -> None:
        if self.z.ndim != 1 or self.z.size < 2 or np.any(np.diff(self.z) <= 0):
            raise ValueError("shell nodes must be at least two, with increasing z")
        if np.any(self.r <= 0) or np.any(self.thickness <= 0):
            raise ValueError("shell radii and wall thickness must be positive")
        if any(e not in ENDS for e in self.ends):
            raise ValueError(f"shell ends must be one of {ENDS}, got {self.ends}")

    @property
    def n_elements(self) -> int:
        return self.z.size - 1

    @property
    def lengths(self) -> np.ndarray:
        """Meridian length of each element [m]."""
        return np.hypot(np.diff(self.z), np.diff(self.r))

    def node_dofs(self, n: int) -> int:
        return 3 if n == 0 else 5


def _hermite(xi: np.ndarray, length: np.ndarray):
    """Cubic Hermite functions on [0, 1] and their first and second ``s`` derivatives for
    element lengths ``length``: arrays (e, q, 4) for the dofs (X_i, X'_i, X_j, X'_j)."""
    x = xi[None, :]
    L = length[:, None]
    h = np.stack(np.broadcast_arrays(1 - 3 * x**2 + 2 * x**3, L * (x - 2 * x**2 + x**3),
                                     3 * x**2 - 2 * x**3, L * (-x**2 + x**3)), axis=-1)
    dh = np.stack(np.broadcast_arrays((-6 * x + 6 * x**2) / L, 1 - 4 * x + 3 * x**2,
                                      (6 * x - 6 * x**2) / L, -2 * x + 3 * x**2), axis=-1)
    d2h = np.stack(np.broadcast_arrays((-6 + 12 * x) / L**2, (-4 + 6 * x) / L,
                                       (6 - 12 * x) / L**2, (-2 + 6 * x) / L), axis=-1)
    return h, dh, d2h


def _layout(n: int) -> dict[str, list[int]]:
    """Element dof indices of U (linear), V and W (Hermite) for order ``n``."""
    if n == 0:  # (U, W, W') per node
        return {"U": [0, 3], "V": [], "W": [1, 2, 4, 5]}
    return {"U": [0, 5], "V": [1, 2, 6, 7], "W": [3, 4, 8, 9]}


def _strain_matrices(shell: ShellOfRevolution, n: float, xi: np.ndarray, layout: int | None = None):
    """Membrane and bending strain matrices, displacement matrix and radius at points ``xi``
    of every element: B_m, B_b (e, q, 3, d), N (e, q, 3, d), r (e, q), with ``d`` the element
    dofs of the layout of order ``layout`` (default ``n``; any ``n`` may be evaluated on the
    layout of the orders >= 1, the strains being polynomials in ``n``)."""
    L = shell.lengths
    sp = (np.diff(shell.r) / L)[:, None]  # sin psi
    cp = (np.diff(shell.z) / L)[:, None]  # cos psi
    r = shell.r[:-1, None] + np.diff(shell.r)[:, None] * xi[None, :]
    lay_n = int(n) if layout is None else layout
    lay = _layout(lay_n)
    d = 2 * shell.node_dofs(lay_n)
    e, q = L.size, xi.size
    nu_lin = np.stack([np.broadcast_to(1 - xi, (e, q)), np.broadcast_to(xi, (e, q))], -1)
    dnu_lin = np.stack([np.broadcast_to(-1 / L[:, None], (e, q)),
                        np.broadcast_to(1 / L[:, None], (e, q))], -1)
    h, dh, d2h = _hermite(xi, L)

    def place(values, which):
        out = np.zeros((e, q, d))
        if lay[which]:
            out[..., lay[which]] = values
        return out

    U, dU = place(nu_lin, "U"), place(dnu_lin, "U")
    W, dW, d2W = place(h, "W"), place(dh, "W"), place(d2h, "W")
    V, dV = (place(h, "V"), place(dh, "V")) if lay_n else (np.zeros((e, q, d)),) * 2
    rr = r[..., None]
    eps_s = dU
    eps_t = (n * V + sp[..., None] * U + cp[..., None] * W) / rr
    gamma = -n * U / rr + dV - sp[..., None] * V / rr
    kap_s = -d2W
    kap_t = n * cp[..., None] * V / rr**2 + n * n * W / rr**2 - sp[..., None] * dW / rr
    tau = (2 * n * (dW / rr - sp[..., None] * W / rr**2)
           + 1.5 * cp[..., None] * (dV / rr - sp[..., None] * V / rr**2)
           + n * cp[..., None] * U / (2 * rr**2))
    b_m = np.stack([eps_s, eps_t, gamma], axis=2)
    b_b = np.stack([kap_s, kap_t, tau], axis=2)
    disp = np.stack([U, V, W], axis=2)
    t = _to_global(sp[:, 0], cp[:, 0], lay_n)[:, None]  # (e, 1, d, d)
    return b_m @ t, b_b @ t, disp @ t, r


def _to_global(sin_psi: np.ndarray, cos_psi: np.ndarray, n: int) -> np.ndarray:
    """Per element, the matrix ``T`` (e, d, d) with ``local = T global`` for the element dofs of
    order ``n``'s layout: the node unknowns are the axial and radial displacements
    ``(u_z, u_r)`` in the slots of ``U`` and ``W``, ``U = cos psi u_z + sin psi u_r``,
    ``W = -sin psi u_z + cos psi u_r``; ``V``, ``V'`` and ``W'`` (the rotation of the normal)
    are the same in every element."""
    nd = 3 if n == 0 else 5
    iu, iw = 0, (1 if n == 0 else 3)
    t = np.broadcast_to(np.eye(2 * nd), (sin_psi.size, 2 * nd, 2 * nd)).copy()
    for node in (0, nd):
        t[:, node + iu, node + iu] = cos_psi
        t[:, node + iu, node + iw] = sin_psi
        t[:, node + iw, node + iu] = -sin_psi
        t[:, node + iw, node + iw] = cos_psi
    return t


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
    not depend on ``n``: five matrices assembled once serve every order. Order 0 has its own
    layout (no torsion) and is assembled directly.
    """

    def __init__(self, shell: ShellOfRevolution):
        self.shell = shell
        k0, m0 = element_matrices(shell, 0)
        self._k0, self._m0 = _global(shell, 3, k0), _global(shell, 3, m0)
        nu = shell.poisson_ratio
        law = np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1 - nu)]])
        e_plane = shell.youngs_modulus / (1 - nu**2)
        wq = np.pi * GAUSS_WEIGHTS[None, :] * shell.lengths[:, None]
        bm = [_strain_matrices(shell, v, GAUSS_POINTS, layout=1)[0] for v in (0.0, 1.0)]
        bb = [_strain_matrices(shell, v, GAUSS_POINTS, layout=1)[1] for v in (0.0, 1.0, 2.0)]
        disp, r = _strain_matrices(shell, 1.0, GAUSS_POINTS, layout=1)[2:]
        mem = [bm[0], bm[1] - bm[0]]  # B_m = mem[0] + n mem[1]
        c2 = 0.5 * (bb[2] - 2 * bb[1] + bb[0])
        ben = [bb[0], bb[1] - bb[0] - c2, c2]  # B_b = ben[0] + n ben[1] + n^2 ben[2]
        cm = (wq * r) * (e_plane * shell.thickness)[:, None]
        cb = (wq * r) * (e_plane * shell.thickness**3 / 12.0)[:, None]
        powers = np.zeros((5, shell.n_elements, 10, 10))
        for i, a in enumerate(mem):
            for j, b in enumerate(mem):
                powers[i + j] += _quadrature(cm, a, law, b)
        for i, a in enumerate(ben):
            for j, b in enumerate(ben):
                powers[i + j] += _quadrature(cb, a, law, b)
        # the orders n >= 1 share their free dofs (support only concerns order 0): their
        # matrices are kept on them
        self._free, _ = _free_dofs(shell, 1, False)
        ix = np.ix_(self._free, self._free)
        self._k = [_global(shell, 5, kp)[ix] for kp in powers]
        rho_t = (shell.density * shell.thickness)[:, None] * wq * r
        self._m = _global(shell, 5, _quadrature(rho_t, disp, None, disp))[ix]
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


def _quadrature(weight: np.ndarray, a: np.ndarray, law: np.ndarray | None,
                b: np.ndarray) -> np.ndarray:
    """``sum_q weight[e, q] a[e, q]^T law b[e, q]`` for every element, (e, i, j): the
    quadrature of an element matrix from its strain (or displacement) matrices ``a``, ``b``
    (e, q, 3, d) and the material law (3, 3; None for the identity), as one batched matrix
    product per element (a four-operand einsum is several times slower)."""
    e, q, c, d = a.shape
    right = b if law is None else np.matmul(law, b)
    left = (a * weight[:, :, None, None]).reshape(e, q * c, d)
    return np.matmul(left.transpose(0, 2, 1), right.reshape(e, q * c, b.shape[-1]))


def element_matrices(shell: ShellOfRevolution, n: int):
    """Stiffness and mass matrices of every element for order ``n``, shape (e, d, d), the
    ``theta`` integral included (``pi``, or ``2 pi`` for ``n = 0``)."""
    b_m, b_b, disp, r = _strain_matrices(shell, n, GAUSS_POINTS)
    nu = shell.poisson_ratio
    law = np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1 - nu)]])
    if n == 0:  # sin^2 terms (gamma, tau, v) integrate to zero
        law[2, 2] = 0.0
    e_plane = shell.youngs_modulus / (1 - nu**2)
    c_m = e_plane * shell.thickness
    c_b = e_plane * shell.thickness**3 / 12.0
    factor = 2 * np.pi if n == 0 else np.pi
    wq = factor * GAUSS_WEIGHTS[None, :] * shell.lengths[:, None] * r  # (e, q)
    k = (_quadrature(wq * c_m[:, None], b_m, law, b_m)
         + _quadrature(wq * c_b[:, None], b_b, law, b_b))
    rho_t = (shell.density * shell.thickness)[:, None] * wq
    m = _quadrature(rho_t, disp, None, disp)
    return k, m


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
    with ``factor`` the Cholesky factor of the system's stiffness; for a supported order 0 the
    load is first equilibrated against the axial translation and the translation removed from
    the answer (inertia relief; Craig & Kurdila 2006, Sec. 11.3)."""
    import scipy.linalg  # hollow bats only: ~0.15 s to import

    if system.rigid is None:
        return scipy.linalg.cho_solve(factor, load, check_finite=False)
    mr = system.mass @ system.rigid
    balanced = load - np.outer(mr, system.rigid @ load)
    x = scipy.linalg.cho_solve(factor, balanced, check_finite=False)
    return x - np.outer(system.rigid, mr @ x)


@dataclass(frozen=True)
class HarmonicModes:
    """Mass-normalised modes of one order, full dof vectors (fixed dofs zero)."""

    n: int
    omega: np.ndarray  # [rad/s], ascending, (k,)
    vectors: np.ndarray  # (ndof, k)


def harmonic_modes(shell: ShellOfRevolution, n: int, max_frequency: float,
                   system: HarmonicSystem | None = None) -> HarmonicModes:
    """Elastic modes of order ``n`` up to ``max_frequency`` [Hz] (dense generalized
    eigenproblem); ``system`` may be passed if it is the unsupported one of :func:`assemble`."""
    import scipy.linalg  # hollow bats only: ~0.15 s to import

    sys_ = system if system is not None and system.rigid is None else assemble(shell, n)
    lam, vec = scipy.linalg.eigh(sys_.stiffness, sys_.mass, check_finite=False, driver="gvx",
                                 subset_by_value=(-np.inf, (2 * np.pi * max_frequency) ** 2))
    elastic = lam > (2 * np.pi * 1.0) ** 2  # drop order 0's rigid axial translation
    lam, vec = lam[elastic], vec[:, elastic]
    full = np.zeros((sys_.node_dofs * shell.z.size, lam.size))
    full[sys_.free] = vec
    return HarmonicModes(n, np.sqrt(np.clip(lam, 0.0, None)), full)


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
    """Inextensional thin-ring frequency of order ``n`` [Hz] (Love 1927; Soedel 2004):
    ``omega = (t / R^2) sqrt(E' / (12 rho)) n (n^2 - 1) / sqrt(n^2 + 1)``, ``E' = E/(1-nu^2)``:
    the infinitely long barrel's lower bound, for comparison only.

    Examples
    --------
    A 7050 ring of 2.625 in outer diameter with a 2.5 mm wall (mean radius 32.09 mm):

    >>> round(float(ring_frequency(0.0320875, 0.0025, 71.7e9, 2830.0, 0.33)))
    1596
    """
    e_plane = youngs_modulus / (1.0 - poisson_ratio**2)
    omega = (np.asarray(wall) / np.asarray(mean_radius) ** 2) * np.sqrt(
        e_plane / (12.0 * density)) * n * (n * n - 1) / np.sqrt(n * n + 1.0)
    return omega / (2 * np.pi)
