"""The ball: mass, size, speed-dependent rigid-wall COR and contact-law parameters."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class BallModel:
    name: str
    mass: float  # [kg]
    radius: float  # [m]
    cor_speeds: tuple[float, ...]  # impact speeds of the COR points, ascending [m/s]
    cor_values: tuple[float, ...]  # rigid-wall COR at those speeds [-]
    contact_model: str = "power-law-hysteresis"
    k1: float = 6.53e7  # compression stiffness of F = k1 u^alpha [N / m^alpha] (Nathan 2000)
    alpha: float = 1.84  # compression exponent [-] (Nathan 2000)

    def cor(self, speed: np.ndarray | float) -> np.ndarray:
        """Rigid-wall COR at normal impact speed ``speed`` [m/s].

        Piecewise linear in speed between the spec's points and held constant beyond the first
        and last point (no extrapolation). A single point gives a speed-independent COR.
        """
        v = np.abs(np.asarray(speed, dtype=float))
        return np.interp(v, self.cor_speeds, self.cor_values)
