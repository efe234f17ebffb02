"""A laminated wall by classical lamination theory: the membrane, coupling and bending stiffness
(A, B, D) of a stack of orthotropic plies (the first step of issue 26: composite barrels).

Axes: ``x`` along the bat, ``y`` around the barrel (hoop), ``z`` outward through the wall from
its mid-surface; a ply's fibre direction ``1`` lies at ``angle`` from ``x`` toward ``y``. Plies
are listed from the inner surface outward. Each ply is in plane stress with the reduced stiffness

    Q11 = E1 / (1 - nu12 nu21),  Q22 = E2 / (1 - nu12 nu21),  Q12 = nu12 E2 / (1 - nu12 nu21),
    Q66 = G12,  nu21 = nu12 E2 / E1,

turned to the wall's axes (``Qbar``, e.g. R. M. Jones, Mechanics of Composite Materials, 2nd
ed., 1999, Eq. 2.85), and the wall's resultants are ``N = A eps + B kappa``,
``M = B eps + D kappa`` with ``(A, B, D) = sum_k Qbar_k (z_k - z_(k-1), (z_k^2 - z_(k-1)^2) / 2,
(z_k^3 - z_(k-1)^3) / 3)`` (engineering shear strain; Jones Eq. 4.24).

A *balanced* layer holds fibres at ``+angle`` and ``-angle`` interlaced at the same depth, as
filament winding and biaxial braiding lay them: its ``Qbar`` is the mean of the two, which has
no shear coupling (``Qbar16 = Qbar26 = 0``). A single off-axis ply has it, and so does a stack
of them unless balanced at every depth; the shell of revolution refuses such a wall
(:mod:`batcert.physics.shell_element`).

Several concentric walls (:class:`WallStack`, a multi-wall barrel) slide on one another: each
bends about its own mid-surface, so the stack's ``D`` is the sum of the walls' (not the bonded
stack's, which would add each wall's ``A`` times the square of its offset), and so are ``A``
and ``B``. All walls share the normal displacement (they stay in contact) and the mid-surface
strains of the reference surface (the stack's middle); the walls' different radii are not
distinguished in the shell.

Break-in (:func:`broken_in`): use softens the matrix, not the fibres. A damage ``d`` scales
the matrix-dominated moduli ``E2`` and ``G12`` of every ply that breaks in (fibre composites;
not a metal given as a ply) by ``1 - d``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np


@dataclass(frozen=True)
class OrthotropicPly:
    """A unidirectional ply's in-plane elastic constants [Pa, -] and density [kg/m^3]."""

    name: str
    e1: float  # along the fibres [Pa]
    e2: float  # across them [Pa]
    g12: float  # in-plane shear [Pa]
    nu12: float  # strain across per strain along, under stress along [-]
    density: float  # [kg/m^3]
    loss_factor: float = 0.0  # structural loss factor along the fibres [-]
    breaks_in: bool = True  # whether use softens E2 and G12 (a fibre composite) [-]

    def __post_init__(self) -> None:
        if not (self.e1 > 0 and self.e2 > 0 and self.g12 > 0 and self.density > 0):
            raise ValueError(f"ply {self.name!r}: moduli and density must be positive")
        if not 0 <= self.nu12 ** 2 * self.e2 / self.e1 < 1:  # nu12 nu21 < 1: positive definite
            raise ValueError(f"ply {self.name!r}: nu12 = {self.nu12} makes the ply unstable "
                             "(nu12 nu21 must be below 1)")

    def stiffness(self) -> np.ndarray:
        """The reduced stiffness ``Q`` in the ply's axes (1, 2, 12) [Pa], (3, 3)."""
        nu21 = self.nu12 * self.e2 / self.e1
        d = 1.0 - self.nu12 * nu21
        return np.array([[self.e1 / d, self.nu12 * self.e2 / d, 0.0],
                         [self.nu12 * self.e2 / d, self.e2 / d, 0.0],
                         [0.0, 0.0, self.g12]])


    @classmethod
    def isotropic(cls, name: str, youngs_modulus: float, poisson_ratio: float, density: float,
                  loss_factor: float = 0.0) -> OrthotropicPly:
        """An isotropic material (a metal) as a ply: ``E1 = E2``, ``G12 = E / (2 (1 + nu))``,
        and no break-in."""
        e, nu = youngs_modulus, poisson_ratio
        return cls(name, e, e, e / (2 * (1 + nu)), nu, density, loss_factor, breaks_in=False)


@dataclass(frozen=True)
class Layer:
    """One ply of a wall: its material, fibre angle from the bat's axis [rad], thickness [m];
    ``balanced``: fibres at ``+angle`` and ``-angle`` interlaced (module notes)."""

    ply: OrthotropicPly
    angle: float  # [rad], from x (along the bat) toward y (around it)
    thickness: float  # [m]
    balanced: bool = False

    def stiffness(self, damage: float = 0.0) -> np.ndarray:
        """``Qbar`` of the layer in the wall's axes [Pa], (3, 3), with ``damage``
        (:func:`broken_in`)."""
        q = broken_in(self.ply, damage).stiffness()
        if self.balanced:
            return 0.5 * (turned(q, self.angle) + turned(q, -self.angle))
        return turned(q, self.angle)


def broken_in(ply: OrthotropicPly, damage: float) -> OrthotropicPly:
    """``ply`` after break-in ``damage`` (0 new, below 1): ``E2`` and ``G12`` times
    ``1 - damage`` if the ply breaks in (module notes)."""
    if not 0.0 <= damage < 1.0:
        raise ValueError(f"break-in damage must lie in [0, 1), got {damage}")
    if damage == 0.0 or not ply.breaks_in:
        return ply
    keep = 1.0 - damage
    return replace(ply, e2=ply.e2 * keep, g12=ply.g12 * keep)


def turned(q: np.ndarray, angle: float) -> np.ndarray:
    """``Qbar``: the reduced stiffness ``q`` of a ply at ``angle`` [rad] in the wall's axes
    (x, y, xy) [Pa], (3, 3) (Jones Eq. 2.85)."""
    c, s = np.cos(angle), np.sin(angle)
    q11, q12, q22, q66 = q[0, 0], q[0, 1], q[1, 1], q[2, 2]
    c2, s2 = c * c, s * s
    b11 = q11 * c2 * c2 + 2 * (q12 + 2 * q66) * s2 * c2 + q22 * s2 * s2
    b22 = q11 * s2 * s2 + 2 * (q12 + 2 * q66) * s2 * c2 + q22 * c2 * c2
    b12 = (q11 + q22 - 4 * q66) * s2 * c2 + q12 * (s2 * s2 + c2 * c2)
    b66 = (q11 + q22 - 2 * q12 - 2 * q66) * s2 * c2 + q66 * (s2 * s2 + c2 * c2)
    b16 = (q11 - q12 - 2 * q66) * s * c2 * c + (q12 - q22 + 2 * q66) * s2 * s * c
    b26 = (q11 - q12 - 2 * q66) * s2 * s * c + (q12 - q22 + 2 * q66) * s * c2 * c
    return np.array([[b11, b12, b16], [b12, b22, b26], [b16, b26, b66]])


@dataclass(frozen=True)
class Laminate:
    """A wall's stiffness by classical lamination theory (module notes)."""

    a: np.ndarray  # membrane [N/m], (3, 3)
    b: np.ndarray  # membrane-bending coupling [N], (3, 3)
    d: np.ndarray  # bending [N m], (3, 3)
    thickness: float  # [m]
    areal_density: float  # mass per unit area [kg/m^2]

    def law(self) -> np.ndarray:
        """``[[A, B], [B, D]]`` (6, 6) [N/m, N, N m], the shell's wall law."""
        return np.block([[self.a, self.b], [self.b.T, self.d]])

    def couples_shear(self) -> bool:
        """Whether stretching or bending couples with shear or twist (:func:`shear_coupled`)."""
        return bool(shear_coupled(self.law()))


# the entries of a wall law that pair a strain of cos(n theta) with one of sin(n theta): A16,
# A26, B16, B26, D16, D26 and their mirror images
SHEAR_COUPLING = tuple((i, j) for i in (0, 1, 3, 4) for j in (2, 5))


def shear_coupled(law: np.ndarray, rtol: float = 1e-9) -> np.ndarray:
    """Whether each wall law ``[[A, B], [B, D]]`` (..., 6, 6) couples stretching or bending with
    shear or twist: an entry of :data:`SHEAR_COUPLING` above ``rtol`` times the geometric mean
    of its row's and column's diagonal entries. Then a shell harmonic's cos and sin parts no
    longer separate."""
    law = np.asarray(law, dtype=float)
    scale = np.sqrt(np.abs(np.diagonal(law, axis1=-2, axis2=-1)))  # (..., 6)
    out = np.zeros(law.shape[:-2], dtype=bool)
    for i, j in SHEAR_COUPLING:
        out |= np.abs(law[..., i, j]) > rtol * scale[..., i] * scale[..., j]
    return out


def laminate(layers: list[Layer] | tuple[Layer, ...], damage: float = 0.0) -> Laminate:
    """A, B and D of ``layers`` listed from the inner surface outward (module notes), after
    break-in ``damage`` (:func:`broken_in`)."""
    if not layers:
        raise ValueError("a laminate needs at least one ply")
    t = np.array([layer.thickness for layer in layers], dtype=float)
    if np.any(~(t > 0)):
        raise ValueError("every ply's thickness must be positive")
    z = np.concatenate([[0.0], np.cumsum(t)]) - 0.5 * t.sum()  # ply faces from the mid-surface
    a, b, d = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for k, layer in enumerate(layers):
        q = layer.stiffness(damage)
        a += q * (z[k + 1] - z[k])
        b += q * (z[k + 1] ** 2 - z[k] ** 2) / 2.0
        d += q * (z[k + 1] ** 3 - z[k] ** 3) / 3.0
    rho = float(sum(layer.ply.density * layer.thickness for layer in layers))
    return Laminate(a, b, d, float(t.sum()), rho)


@dataclass(frozen=True)
class WallStack:
    """Concentric walls that slide on one another, the innermost first; each wall's layers
    from its inner surface outward (module notes). One wall is an ordinary laminate."""

    walls: tuple[tuple[Layer, ...], ...]

    def __post_init__(self) -> None:
        if not self.walls or not all(self.walls):
            raise ValueError("a wall stack needs at least one wall, each of at least one ply")

    @property
    def thickness(self) -> float:
        """All walls together [m]."""
        return float(sum(layer.thickness for wall in self.walls for layer in wall))

    @property
    def areal_density(self) -> float:
        """All walls' mass per unit area [kg/m^2]."""
        return float(sum(layer.ply.density * layer.thickness for wall in self.walls
                         for layer in wall))

    def laminates(self, damage: float = 0.0) -> list[Laminate]:
        """Each wall's laminate about its own mid-surface, innermost first."""
        return [laminate(wall, damage) for wall in self.walls]

    def law(self, damage: float = 0.0) -> np.ndarray:
        """The stack's ``[[A, B], [B, D]]`` (6, 6) [N/m, N, N m]: the sum of its walls'
        (module notes)."""
        return sum((lam.law() for lam in self.laminates(damage)), np.zeros((6, 6)))

    @property
    def breaks_in(self) -> bool:
        """Whether any ply softens with use."""
        return any(layer.ply.breaks_in for wall in self.walls for layer in wall)
