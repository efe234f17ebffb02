"""The ball: mass, size and contact law (a law of :data:`batcert.physics.balls.LAWS`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.balls.law import ContactLaw


@dataclass(frozen=True)
class BallModel:
    name: str
    mass: float  # [kg]
    radius: float  # [m]
    law: ContactLaw  # contact law with its parameters (batcert.physics.balls.LAWS)

    def cor(self, speed: np.ndarray | float) -> np.ndarray | float:
        """Rigid-wall COR at normal impact speed ``speed`` [m/s] (the law's: the spec's points
        for Nathan's law, the integrated wall impact for the viscoelastic law)."""
        return self.law.wall_cor(self.mass, speed)

    @property
    def contact_model(self) -> str:
        """The law's name (the ball file's ``contact.model``)."""
        return self.law.name
