r"""The shell of revolution (:class:`ShellOfRevolution`) and its element, a conical frustum, for
the semi-analytical finite element method of :mod:`batcert.physics.shell`: the strains of an
order ``n`` at points of every element, and the element matrices.

``U``, ``V``, ``W`` are the meridional, circumferential and normal (outward) amplitudes of order
``n`` (``u = U(s) cos(n theta)``, ``v = V(s) sin(n theta)``, ``w = W(s) cos(n theta)``, ``s`` the
arc length along the meridian).

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
tests). The wall's law is the 6 x 6 matrix ``L = [[A, B], [B, D]]`` of classical lamination
theory between the strains ``(eps_s, eps_th, gamma, kappa_s, kappa_th, tau)`` and the resultants
``(N_s, N_th, N_s th, M_s, M_th, M_s th)`` (:func:`wall_law`): the strain energy is
``1/2 int e^T L e r dtheta ds``. A uniform isotropic wall has ``B = 0``,
``A = C [[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu)/2]]`` and ``D`` the same with ``D`` for ``C``
(``C = E t / (1 - nu^2)``, ``D = E t^3 / (12 (1 - nu^2))``); a laminated one has the ``A``, ``B``,
``D`` of its plies (:mod:`batcert.physics.laminate`) about the mid-surface. The shear-coupling
terms (``A16``, ``A26``, ``B16`` ..) pair a ``cos(n theta)`` strain with a ``sin(n theta)`` one, so
that the harmonics' symmetric and antimetric parts would no longer separate; a law with them is
refused (:class:`ShellOfRevolution`). The kinetic energy is
``1/2 int rho t (u_t^2 + v_t^2 + w_t^2) r dtheta ds`` (rotary inertia of the wall neglected;
``rho t`` the wall's mass per unit area). The ``theta`` integrals give ``pi`` for ``n >= 1`` and
``2 pi`` (cosine terms only) for ``n = 0``.

Elements: ``U`` linear, ``V`` and ``W`` cubic Hermite (``V`` cubic too, so that the
inextensional ring modes, ``n V + W = 0``, are represented without membrane locking). The node
unknowns are global, ``(u_z, V, V', u_r, W')`` for ``n >= 1`` and ``(u_z, u_r, W')`` for ``n = 0``
(no torsion): the axial and radial displacements, which each element turns into its own ``U``
and ``W`` (:func:`_to_global`), so that elements of different cone angles meet consistently and
a rigid axial translation is strain-free across a kink in the meridian.
Four-point Gauss quadrature; the element matrices include the ``theta`` integral.

Units: SI throughout ([m], [Pa], [kg/m^3], [N]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.laminate import shear_coupled
from batcert.physics.quadrature import GAUSS_POINTS, GAUSS_WEIGHTS

ENDS = ("open", "closed")  # an open edge, or one held round by a rigid cap (V = W = 0)


@dataclass(frozen=True)
class ShellOfRevolution:
    """The mid-surface meridian, wall and material of a shell of revolution.

    ``z`` and ``r`` are node positions (axial [m], mid-surface radius [m]), shape (N + 1,);
    ``thickness``, ``density`` and ``youngs_modulus`` are per element, shape (N,). A laminated
    (or multi-wall) wall gives its law per element instead, ``law`` (N, 6, 6) (module notes;
    :func:`wall_law`); ``youngs_modulus`` and ``poisson_ratio`` are then not read, and
    ``density`` times ``thickness`` is the wall's mass per unit area.
    """

    z: np.ndarray  # [m]
    r: np.ndarray  # [m]
    thickness: np.ndarray  # [m]
    density: np.ndarray  # [kg/m^3]
    youngs_modulus: np.ndarray  # [Pa]
    poisson_ratio: float  # [-]
    ends: tuple[str, str] = ("closed", "closed")  # at z[0] and z[-1]
    law: np.ndarray | None = None  # [[A, B], [B, D]] per element, (N, 6, 6) [N/m, N, N m]

    def __post_init__(self) -> None:
        if self.z.ndim != 1 or self.z.size < 2 or np.any(np.diff(self.z) <= 0):
            raise ValueError("shell nodes must be at least two, with increasing z")
        if np.any(self.r <= 0) or np.any(self.thickness <= 0):
            raise ValueError("shell radii and wall thickness must be positive")
        if any(e not in ENDS for e in self.ends):
            raise ValueError(f"shell ends must be one of {ENDS}, got {self.ends}")
        if self.law is not None:
            _check_law(np.asarray(self.law), self.z.size - 1)

    @property
    def n_elements(self) -> int:
        return self.z.size - 1

    @property
    def lengths(self) -> np.ndarray:
        """Meridian length of each element [m]."""
        return np.hypot(np.diff(self.z), np.diff(self.r))

    def node_dofs(self, n: int) -> int:
        return 3 if n == 0 else 5


def _check_law(law: np.ndarray, elements: int) -> None:
    if law.shape != (elements, 6, 6) or not np.all(np.isfinite(law)):
        raise ValueError(f"a shell's law must be finite, shape ({elements}, 6, 6), got "
                         f"{law.shape}")
    if not np.allclose(law, law.transpose(0, 2, 1), rtol=1e-12, atol=0.0):
        raise ValueError("a shell's law must be symmetric")
    if np.any(shear_coupled(law)):
        raise ValueError(
            "the wall's law couples stretching or bending with shear or twist (A16, A26, "
            "B16, B26, D16 or D26 not zero): the shell of revolution separates each "
            "harmonic's cos and sin parts and cannot carry it")


def isotropic_law(youngs_modulus, thickness, poisson_ratio: float) -> np.ndarray:
    """``[[A, 0], [0, D]]`` of uniform isotropic walls (module notes), (N, 6, 6)."""
    nu = poisson_ratio
    base = np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, 0.5 * (1 - nu)]])
    t = np.asarray(thickness, dtype=float)
    c = np.asarray(youngs_modulus, dtype=float) * t / (1 - nu**2)
    law = np.zeros((t.size, 6, 6))
    law[:, :3, :3] = c[:, None, None] * base
    law[:, 3:, 3:] = (c * t**2 / 12.0)[:, None, None] * base
    return law


def wall_law(shell: ShellOfRevolution) -> np.ndarray:
    """The law ``[[A, B], [B, D]]`` of every element (N, 6, 6): the shell's own ``law``, or
    that of its isotropic wall (:func:`isotropic_law`)."""
    if shell.law is not None:
        return np.asarray(shell.law, dtype=float)
    return isotropic_law(shell.youngs_modulus, shell.thickness, shell.poisson_ratio)


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


def _quadrature(weight: np.ndarray, a: np.ndarray, law: np.ndarray | None,
                b: np.ndarray) -> np.ndarray:
    """``sum_q weight[e, q] a[e, q]^T law[e] b[e, q]`` for every element, (e, i, j): the
    quadrature of an element matrix from its strain (or displacement) matrices ``a``, ``b``
    (e, q, c, d) and each element's law (e, c, c; None for the identity), as one batched
    matrix product per element (a four-operand einsum is several times slower)."""
    e, q, c, d = a.shape
    right = b if law is None else np.matmul(law[:, None], b)
    left = (a * weight[:, :, None, None]).reshape(e, q * c, d)
    return np.matmul(left.transpose(0, 2, 1), right.reshape(e, q * c, b.shape[-1]))


def element_matrices(shell: ShellOfRevolution, n: int):
    """Stiffness and mass matrices of every element for order ``n``, shape (e, d, d), the
    ``theta`` integral included (``pi``, or ``2 pi`` for ``n = 0``)."""
    b_m, b_b, disp, r = _strain_matrices(shell, n, GAUSS_POINTS)
    law = wall_law(shell).copy()
    if n == 0:  # sin^2 terms (gamma, tau, v) integrate to zero
        law[:, [2, 5], :] = 0.0
        law[:, :, [2, 5]] = 0.0
    factor = 2 * np.pi if n == 0 else np.pi
    wq = factor * GAUSS_WEIGHTS[None, :] * shell.lengths[:, None] * r  # (e, q)
    strains = np.concatenate([b_m, b_b], axis=2)  # (e, q, 6, d)
    k = _quadrature(wq, strains, law, strains)
    rho_t = (shell.density * shell.thickness)[:, None] * wq
    m = _quadrature(rho_t, disp, None, disp)
    return k, m


def element_power_matrices(shell: ShellOfRevolution) -> tuple[np.ndarray, np.ndarray]:
    """The element matrices of every order ``n >= 1`` at once: for these orders the strains are
    polynomials in ``n`` (membrane of degree 1, bending of degree 2), so each element's
    stiffness is ``sum_p n^p K_p``, ``p = 0..4``, and its mass does not depend on ``n``. Returns
    the ``K_p`` (5, e, 10, 10) and the mass (e, 10, 10), on the layout of the orders ``>= 1``,
    the ``theta`` integral (``pi``) included."""
    wq = np.pi * GAUSS_WEIGHTS[None, :] * shell.lengths[:, None]
    bm = [_strain_matrices(shell, v, GAUSS_POINTS, layout=1)[0] for v in (0.0, 1.0)]
    bb = [_strain_matrices(shell, v, GAUSS_POINTS, layout=1)[1] for v in (0.0, 1.0, 2.0)]
    disp, r = _strain_matrices(shell, 1.0, GAUSS_POINTS, layout=1)[2:]
    c2 = 0.5 * (bb[2] - 2 * bb[1] + bb[0])
    # the strains (membrane over bending) as S_0 + n S_1 + n^2 S_2; the membrane's are linear
    terms = [np.concatenate(pair, axis=2) for pair in
             ((bm[0], bb[0]), (bm[1] - bm[0], bb[1] - bb[0] - c2), (np.zeros_like(c2), c2))]
    law = wall_law(shell)
    powers = np.zeros((5, shell.n_elements, 10, 10))
    for i, a in enumerate(terms):
        for j, b in enumerate(terms):
            powers[i + j] += _quadrature(wq * r, a, law, b)
    rho_t = (shell.density * shell.thickness)[:, None] * wq * r
    return powers, _quadrature(rho_t, disp, None, disp)
