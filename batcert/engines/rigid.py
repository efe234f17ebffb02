"""The rigid engine: the closed forms of :mod:`batcert.physics.rigid` behind the engine interface."""

from __future__ import annotations

from batcert.engines.base import ImpactBatch, ImpactOutcome
from batcert.physics import rigid
from batcert.physics.ball import BallModel
from batcert.physics.batmodel import BatModel


class RigidEngine:
    """Closed-form rigid-bat engine: exact and instant; the stiff limit of the flexible engine.

    The ball-bat COR is the ball's rigid-wall COR at the impact's relative normal speed.
    ``support="pinned"`` uses k = m r^2 / I about the pivot; ``"free"`` the free-bat k.
    """

    name = "rigid"
    limitations = {"bpf": "rigid engine: the ball-bat COR equals the ball's COR, so BPF is 1 by "
                          "construction; use the flexible engine for a meaningful BPF"}

    def settings(self) -> dict:
        return {"engine": "rigid", "cor": "ball rigid-wall COR at the relative speed"}

    def solve(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
              support: str = "pinned") -> ImpactOutcome:
        r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
        e = ball.cor(batch.relative_speed)
        k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
        vb = rigid.exit_speed(e, k, vp, w1 * r)
        w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
        return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k)
