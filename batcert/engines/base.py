"""The impact-engine interface shared by the rigid and flexible tiers.

An engine solves a batch of impacts (impact locations x conditions flattened to one axis) of one
bat and one ball in one call, vectorised over the batch. Engines are listed in
:data:`batcert.engines.ENGINES`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from batcert.physics.ball import BallModel
from batcert.physics.batmodel import BatModel

if TYPE_CHECKING:
    from batcert.physics.modes import Modes


@dataclass(frozen=True)
class ImpactBatch:
    """Impacts to solve, all arrays of one shape (n,). Bat motion before impact is rotation about
    the pivot at ``bat_angular_speed``; the ball moves along the normal to the bat."""

    impact_location: np.ndarray  # [m from pivot]
    pitch_speed: np.ndarray  # ball speed before impact [m/s], negative toward the bat
    bat_angular_speed: np.ndarray  # [rad/s], positive swings the bat toward the ball

    def __post_init__(self) -> None:
        r, vp, w = np.broadcast_arrays(np.asarray(self.impact_location, float),
                                       np.asarray(self.pitch_speed, float),
                                       np.asarray(self.bat_angular_speed, float))
        object.__setattr__(self, "impact_location", np.ascontiguousarray(r))
        object.__setattr__(self, "pitch_speed", np.ascontiguousarray(vp))
        object.__setattr__(self, "bat_angular_speed", np.ascontiguousarray(w))

    @property
    def relative_speed(self) -> np.ndarray:
        """Normal approach speed at the impact point, w1 r - v_p [m/s]."""
        return self.bat_angular_speed * self.impact_location - self.pitch_speed

    def __len__(self) -> int:
        return int(self.impact_location.size)


@dataclass(frozen=True)
class Job:
    """One batch of impacts of one bat and ball about one pivot: what :meth:`Engine.solve_many`
    takes, a list of them (the runner's batches of many protocols and bats)."""

    bat: BatModel
    ball: BallModel
    pivot: float  # [m from knob]
    batch: ImpactBatch
    support: str = "pinned"  # "pinned" or "free"
    modes: Modes | None = None  # the flexible engine: modes to use instead of the bat's own

    @classmethod
    def of(cls, job: Job | tuple[Any, ...]) -> Job:
        """``job``, or a tuple ``(bat, ball, pivot, batch[, support[, modes]])`` as a Job."""
        return job if isinstance(job, Job) else cls(*job)

    def with_batch(self, batch: ImpactBatch) -> Job:
        """The same job with another batch of impacts."""
        return replace(self, batch=batch)


@dataclass(frozen=True)
class ImpactOutcome:
    """What an engine returns for a batch, arrays of shape (n,)."""

    exit_speed: np.ndarray  # ball speed after impact [m/s]
    bat_angular_speed_after: np.ndarray  # from momentum balance (Smith 2001 Eq. 1) [rad/s]
    cor: np.ndarray  # ball-bat COR, Smith 2001 Eq. 3 [-]
    recoil_factor: np.ndarray  # effective-mass ratio k of the bat at each impact [-]
    diagnostics: dict[str, np.ndarray] = field(default_factory=dict)  # per impact, SI


class Engine(Protocol):
    """What the runner needs of an engine tier."""

    name: str
    #: whether the engine models a hollow bat's barrel shell (a run then records the barrel's
    #: modes and range; an engine that does not never builds the shell)
    models_barrel: bool
    #: what a result of this engine does not show of a bat, as one warning line: the rigid
    #: engine's does not depend on the bat's construction or material (None: it does). Shown
    #: wherever bats' constructions are compared or varied (a league, a sweep, a design)
    construction_warning: str | None
    #: metric name -> warning: metrics that this engine cannot resolve (e.g. a rigid bat's
    #: BPF reflects only the ball's loss, not the bat)
    limitations: dict[str, str]

    def solve(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
              support: str = "pinned") -> ImpactOutcome:
        """Solve every impact of ``batch``; ``pivot`` is measured from the knob [m];
        ``support`` is "pinned" (bat pinned at the pivot) or "free"."""
        ...

    def solve_many(self, jobs: list[Job]) -> list[ImpactOutcome]:
        """Solve several jobs at once (the runner's batches of many protocols and bats); the
        same outcomes as :meth:`solve` one by one. A tuple ``(bat, ball, pivot, batch[,
        support[, modes]])`` is taken for a :class:`Job`."""
        ...

    def settings(self, bat: BatModel | None = None) -> dict:
        """Engine settings recorded in the results (time step, modes, ...), for ``bat`` when
        given (a setting may depend on the bat)."""
        ...
