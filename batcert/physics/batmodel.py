"""The bat as a sliced beam: section properties from profile, wall and material.

:class:`BatModel` is what every engine reads. It is built from a validated bat spec by
:func:`batcert.physics.reconcile.build_bat_model` (geometry, then reconciliation to measured mass
properties). Positions ``z`` are measured from the knob end [m].
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from batcert.physics.laminate import WallStack


@dataclass(frozen=True)
class Material:
    name: str
    density: float  # [kg/m^3]
    youngs_modulus: float  # [Pa]
    shear_modulus: float  # [Pa]
    poisson_ratio: float  # [-]
    loss_factor: float = 0.0  # structural loss factor eta [-]; modal damping ratio = eta / 2


@dataclass(frozen=True)
class Layup:
    """The laminated or multi-wall parts of a hollow bat: ``index[i]`` is the stack
    (:class:`~batcert.physics.laminate.WallStack`) of ``stacks`` whose wall slice ``i`` has, or
    -1 where the wall is the bat's ``material``."""

    stacks: tuple[WallStack, ...]
    index: np.ndarray  # per slice, (n,) int

    def stack_of(self, i: int) -> WallStack | None:
        k = int(self.index[i])
        return None if k < 0 else self.stacks[k]


@dataclass(frozen=True)
class BatModel:
    """A bat discretised into slices along its length (knob at z = 0, tip at z = length)."""

    name: str
    construction: str  # "solid" | "hollow"
    length: float  # [m]
    z_edges: np.ndarray  # slice edges from the knob [m], shape (n + 1,)
    outer_diameter: np.ndarray  # per slice [m], shape (n,)
    inner_diameter: np.ndarray  # per slice [m], 0 for solid sections, shape (n,)
    linear_density: np.ndarray  # mass per unit length after reconciliation [kg/m], shape (n,)
    rotary_inertia: np.ndarray  # rotary inertia per unit length, rho * I_area * weight [kg m], (n,)
    bending_stiffness: np.ndarray  # E * I_area [N m^2], shape (n,)
    shear_stiffness: np.ndarray  # kappa * G * A [N], shape (n,)
    point_masses: tuple[tuple[float, float], ...]  # (z from knob [m], mass [kg]) after reconciliation
    material: Material
    # hollow bats: the barrel shell's calibration (batcert.model.calibrate) and its tip end,
    # "closed" (held round by the end cap) or "free" (batcert.physics.barrel)
    barrel_stiffness_scale: float = 1.0  # on the wall's Young's modulus in the shell [-]
    barrel_mass_scale: float = 1.0  # on the wall's density in the shell [-]
    barrel_end: str = "closed"
    extras: dict = field(default_factory=dict)
    layup: Layup | None = None  # hollow bats: their laminated or multi-wall slices
    wall_damage: float = 0.0  # break-in of the layup's plies (batcert.physics.laminate) [-]

    @property
    def z_mid(self) -> np.ndarray:
        """Slice centres from the knob [m]."""
        return 0.5 * (self.z_edges[1:] + self.z_edges[:-1])

    @property
    def dz(self) -> np.ndarray:
        """Slice lengths [m]."""
        return np.diff(self.z_edges)

    @property
    def wall_thickness(self) -> np.ndarray:
        """Wall thickness per slice [m]; half the outer diameter for solid slices."""
        return 0.5 * (self.outer_diameter - self.inner_diameter)

    def slice_at(self, z) -> np.ndarray:
        """The slice holding each point ``z`` [m from knob] (the first and last slice for
        points off the bat's ends); an edge belongs to the slice it starts."""
        edges = np.asarray(self.z_edges, dtype=float)
        return np.clip(np.searchsorted(edges, z, side="right") - 1, 0, edges.size - 2)

    @property
    def slice_masses(self) -> np.ndarray:
        return self.linear_density * self.dz

    @property
    def mass(self) -> float:
        """Total mass [kg]."""
        return float(self.slice_masses.sum() + sum(m for _, m in self.point_masses))

    @property
    def balance_point(self) -> float:
        """Centre of gravity from the knob [m]."""
        first = float((self.slice_masses * self.z_mid).sum() + sum(m * z for z, m in self.point_masses))
        return first / self.mass

    def moi_about(self, z_axis: float) -> float:
        """Moment of inertia about a transverse axis through ``z_axis`` [kg m^2].

        Includes each slice's own inertia (length term dz^2/12 and the rotary term) so that the
        sliced bat matches the continuous one.
        """
        d = self.z_mid - z_axis
        m = self.slice_masses
        own = m * self.dz**2 / 12.0 + self.rotary_inertia * self.dz
        return float((m * d**2 + own).sum() + sum(mp * (z - z_axis) ** 2 for z, mp in self.point_masses))

    def cg_from(self, pivot: float) -> float:
        """CG distance from the pivot [m] (``rbar``)."""
        return self.balance_point - pivot

    def barrel_outer_diameter(self) -> float:
        """Largest outer diameter [m]."""
        return float(self.outer_diameter.max())
