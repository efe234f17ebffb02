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
(z_k^3 - z_(k-1)^3) / 3)`` (engineering shear strain; Jones Eq. 4.24). Not yet used by the
shell: what a laminate does to the barrel's modes is the rest of issue 26.
"""

from __future__ import annotations

from dataclasses import dataclass

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


@dataclass(frozen=True)
class Layer:
    """One ply of a wall: its material, fibre angle from the bat's axis [rad], thickness [m]."""

    ply: OrthotropicPly
    angle: float  # [rad], from x (along the bat) toward y (around it)
    thickness: float  # [m]


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

    def couples_shear(self, rtol: float = 1e-9) -> bool:
        """Whether stretching or bending couples with shear or twist (``A16``, ``A26``,
        ``B16``, ``B26``, ``D16``, ``D26`` not zero against ``A11``, ``A11 h``, ``D11``): then
        a shell harmonic's cos and sin parts no longer separate."""
        scale = (self.a[0, 0], self.a[0, 0] * self.thickness, self.d[0, 0])
        return any(abs(m[i, 2]) > rtol * s for m, s in zip((self.a, self.b, self.d), scale,
                                                          strict=True) for i in (0, 1))


def laminate(layers: list[Layer] | tuple[Layer, ...]) -> Laminate:
    """A, B and D of ``layers`` listed from the inner surface outward (module notes)."""
    if not layers:
        raise ValueError("a laminate needs at least one ply")
    t = np.array([layer.thickness for layer in layers], dtype=float)
    if np.any(~(t > 0)):
        raise ValueError("every ply's thickness must be positive")
    z = np.concatenate([[0.0], np.cumsum(t)]) - 0.5 * t.sum()  # ply faces from the mid-surface
    a, b, d = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for k, layer in enumerate(layers):
        q = turned(layer.ply.stiffness(), layer.angle)
        a += q * (z[k + 1] - z[k])
        b += q * (z[k + 1] ** 2 - z[k] ** 2) / 2.0
        d += q * (z[k + 1] ** 3 - z[k] ** 3) / 3.0
    rho = float(sum(layer.ply.density * layer.thickness for layer in layers))
    return Laminate(a, b, d, float(t.sum()), rho)
