"""What every ball contact law provides (:data:`batcert.physics.balls.LAWS`): the interface the
engines, the fit, the runner and ``inspect`` use, so that none of them names a law.

A new law is a frozen dataclass of its parameters with these methods, its time-stepping state
(``march_rows``, a :class:`MarchState`), and an
entry in :data:`~batcert.physics.balls.LAWS`; the ball file's fields for it are
:mod:`batcert.specs.ball`'s.
"""

from __future__ import annotations

from typing import Any, ClassVar, Protocol

import numpy as np


class MarchState(Protocol):
    """A ball law's state through a batched time integration, one row per impact: what
    :func:`batcert.engines.kernel.march.march` and the ball against a rigid body
    (:func:`batcert.physics.balls.impact1d.body_impact`) ask of it (a law's ``march_rows``
    and ``state_of`` make one). Forces [N], compressions [m], arrays (n,) for the rows now
    integrated.

    A step is :meth:`prepare`, then the force at its four stages (:meth:`start` with the
    largest compression so far, :meth:`half_a`, :meth:`half_b`, :meth:`end`, each at the
    stage's compression), then :meth:`finish` at the step's end compression."""

    # the force falls through zero with a finite slope (a viscoelastic ball leaves still
    # compressed): the march takes the last step's impulse up to the separation only
    crossing: bool

    def for_step(self, h) -> MarchState:
        """The state with the step ``h`` [s] (a scalar, or one per row) fixed: the constants
        its stages use."""
        ...

    def prepare(self, u_top: np.ndarray, rows: np.ndarray) -> None:
        """Before each step: what follows the largest compression so far ``u_top`` (Nathan's
        restitution exponent); ``rows``: the rows' indices in the whole batch. May do nothing."""
        ...

    def start(self, u: np.ndarray, u_top: np.ndarray) -> np.ndarray:
        """The force at the step's start."""
        ...

    def half_a(self, u: np.ndarray) -> np.ndarray:
        """The force at the first half-step stage."""
        ...

    def half_b(self, u: np.ndarray) -> np.ndarray:
        """The force at the second half-step stage."""
        ...

    def end(self, u: np.ndarray) -> np.ndarray:
        """The force at the step's end stage."""
        ...

    def finish(self, u_new: np.ndarray) -> np.ndarray:
        """Advance over the step; the contact measure at its end (the impact separates where it
        falls to zero or below)."""
        ...

    def stored(self, rows: np.ndarray, top: np.ndarray) -> np.ndarray:
        """The energy the ball holds at its largest compression ``top`` [J], for ``rows``."""
        ...

    def absorbed(self) -> np.ndarray | None:
        """The work done on the ball so far [J], or None where the engine has the ball's loss
        in closed form (:meth:`ContactLaw.separation_loss`)."""
        ...

    def take(self, keep) -> MarchState:
        """The rows ``keep`` (indices, a mask or a slice)."""
        ...

    def offset(self, start: int) -> MarchState:
        """These rows as rows ``start`` on of a larger batch."""
        ...


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
                   speed=None) -> MarchState:
        """Its state for ``n`` rows of a batched time integration."""
        ...

    @staticmethod
    def state_of(laws, masses, which, scale=1.0, rule: str = "compression",
                 speed=None) -> MarchState:
        """The time-stepping state of rows of balls of this law (``which``: each row's ball
        among ``laws``, ``masses``)."""
        ...

    def separation_loss(self, mass: float, max_compression: np.ndarray, scale: np.ndarray,
                        relative_speed: np.ndarray, rule: str) -> dict[str, np.ndarray] | None:
        """The energy the ball lost in an impact that compressed it to ``max_compression`` and
        its loss parameter, in closed form (``ball_energy_loss`` [J], ``e0`` [-]), or None
        where the time integration measures the loss (the flexible engine's diagnostics)."""
        ...
