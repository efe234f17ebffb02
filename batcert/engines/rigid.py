"""The rigid engine: the closed forms of :mod:`batcert.physics.rigid` behind the engine interface."""

from __future__ import annotations

import numpy as np

from batcert.engines.base import ImpactBatch, ImpactOutcome
from batcert.physics import rigid
from batcert.physics.ball import BallModel
from batcert.physics.batmodel import BatModel

BALL_LOSS = ("compression", "relative-speed")


class RigidEngine:
    """Closed-form rigid-bat engine: exact and instant; the stiff limit of the flexible engine.

    The ball-bat COR is the ball's rigid-wall COR at the wall speed that compresses the ball as
    far as this impact does, ``v_rel / sqrt(1 + k)`` for a rigid bat of recoil factor ``k``
    (``ball_loss="compression"``, as the flexible engine; :mod:`batcert.physics.contact`), or at
    the relative speed itself (``"relative-speed"``). ``support="pinned"`` uses k = m r^2 / I
    about the pivot; ``"free"`` the free-bat k.
    """

    name = "rigid"
    limitations = {"bpf": "rigid engine: the bat neither vibrates nor flexes, so BPF only "
                          "reflects the ball's lower loss when it compresses less against a "
                          "recoiling bat; use the flexible engine for a meaningful BPF"}

    def __init__(self, ball_loss: str = "compression") -> None:
        if ball_loss not in BALL_LOSS:
            raise ValueError(f"ball_loss must be one of {BALL_LOSS}, got {ball_loss!r}")
        self.ball_loss = ball_loss

    def settings(self, bat: BatModel | None = None) -> dict:
        return {"engine": "rigid", "cor": (
            "ball rigid-wall COR at the wall speed of equal compression, v_rel / sqrt(1 + k)"
            if self.ball_loss == "compression" else "ball rigid-wall COR at the relative speed")}

    def solve_many(self, jobs: list[tuple]) -> list[ImpactOutcome]:
        """Closed forms cost nothing per call: :meth:`solve` for each job."""
        return [self.solve(*job) for job in jobs]

    def solve(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
              support: str = "pinned") -> ImpactOutcome:
        r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
        k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
        speed = batch.relative_speed
        if self.ball_loss == "compression":
            speed = speed / np.sqrt(1.0 + k)
        e = ball.cor(speed)
        vb = rigid.exit_speed(e, k, vp, w1 * r)
        w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
        return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k)
