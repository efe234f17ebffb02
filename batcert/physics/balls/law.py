"""What every ball contact law provides (:data:`batcert.physics.balls.LAWS`): the interface the
engines, the fit, the runner and ``inspect`` use, so that none of them names a law.

A new law is a frozen dataclass of its parameters with these methods, its time-stepping state
(``march_rows``, :func:`batcert.engines.kernel.march.march` documents what a state provides), and an
entry in :data:`~batcert.physics.balls.LAWS`; the ball file's fields for it are
:mod:`batcert.specs.ball`'s.
"""

from __future__ import annotations

from typing import Any, ClassVar, Protocol

import numpy as np


class ContactLaw(Protocol):
    """A ball's contact law with its parameters."""

    name: ClassVar[str]  # the ball file's ``contact.model`` and the LAWS key

    def wall_cor(self, mass: float, speed) -> np.ndarray | float:
        """The COR of the ball fired at a rigid flat wall at ``speed`` [m/s]."""
        ...

    def body_cor(self, mass: float, speed, recoil, rule: str = "compression") -> np.ndarray:
        """The COR against a rigid body of effective-mass ratio ``recoil`` (the rigid
        engine); ``rule``: the flexible engine's ``ball_loss``."""
        ...

    def body_impact(self, mass: float, speed, recoil=0.0, history: bool = True, scale=1.0,
                    rule: str = "compression", steps: int | None = None) -> Any:
        """The ball against a rigid body, integrated (COR, contact time, compression)."""
        ...

    def wall_impact(self, mass: float, speed, fraction: float = 0.99) -> Any:
        """The ball against a rigid flat wall: force, compression and times."""
        ...

    def contact_time(self, mass: float, speed, recoil=0.0) -> Any:
        """The contact time against a rigid body [s]."""
        ...

    def quasi_static_force(self, u) -> Any:
        """The force of a slow squeeze to compression ``u`` [N] (the compression test)."""
        ...

    def summary(self) -> str:
        """The law and its parameters in one line (``inspect``)."""
        ...

    def describe(self) -> dict:
        """Its parameters for reports and JSON."""
        ...

    def march_rows(self, n: int, mass: float, scale=1.0, rule: str = "compression",
                   speed=None) -> Any:
        """Its state for ``n`` rows of a batched time integration."""
        ...

    @staticmethod
    def state_of(laws, masses, which, scale=1.0, rule: str = "compression", speed=None) -> Any:
        """The time-stepping state of rows of balls of this law (``which``: each row's ball
        among ``laws``, ``masses``)."""
        ...

    def separation_loss(self, mass: float, max_compression: np.ndarray, scale: np.ndarray,
                        relative_speed: np.ndarray, rule: str) -> dict[str, np.ndarray] | None:
        """The energy the ball lost in an impact that compressed it to ``max_compression`` and
        its loss parameter, in closed form (``ball_energy_loss`` [J], ``e0`` [-]), or None
        where the time integration measures the loss (the flexible engine's diagnostics)."""
        ...
