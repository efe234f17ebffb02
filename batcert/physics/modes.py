"""Bending modes of a :class:`~batcert.physics.batmodel.BatModel` (interface; see beam.py)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


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

    def at(self, z_points: np.ndarray) -> np.ndarray:
        """Mode shapes at arbitrary positions from the knob, shape (n_points, n_modes)."""
        z_points = np.atleast_1d(np.asarray(z_points, dtype=float))
        return np.stack([np.interp(z_points, self.z, s) for s in self.shapes], axis=-1)

    @property
    def frequencies_hz(self) -> np.ndarray:
        """Bending frequencies [Hz], rigid modes excluded, ascending."""
        return self.omega[self.n_rigid:] / (2 * np.pi)
