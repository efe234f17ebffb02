"""The rigid engine: the closed forms of :mod:`batcert.physics.rigid` behind the engine interface."""

from __future__ import annotations

import numpy as np

from batcert.engines.base import ImpactBatch, ImpactOutcome, Job
from batcert.physics import rigid
from batcert.physics.ball import BallModel
from batcert.physics.balls import LAWS, footprint
from batcert.physics.balls.footprint_rules import DEFAULT_RULE
from batcert.physics.balls.footprint_rules import rule as footprint_rule
from batcert.physics.batmodel import BatModel

BALL_LOSS = ("compression", "relative-speed")
CONTACT_SURFACES = ("cylinder", "flat")


class RigidEngine:
    """Rigid-bat engine: Smith 2001's closed forms with the ball's COR against a rigid body;
    the stiff limit of the flexible engine.

    The ball-bat COR is the ball's against a rigid body of the bat's effective mass at the
    impact point (recoil factor ``k``; ``support="pinned"`` uses k = m r^2 / I about the pivot,
    ``"free"`` the free-bat k): for Nathan's hysteresis its rigid-wall COR at the wall speed that
    compresses the ball as far as this impact does, ``v_rel / sqrt(1 + k)``
    (``ball_loss="compression"``, as the flexible engine), or at the relative speed itself
    (``"relative-speed"``); for the viscoelastic ball the integrated impact
    (:mod:`batcert.physics.balls.impact1d`, on the bat's round surface unless
    ``contact_surface="flat"``, as the flexible engine), its stiffness scaled on the barrel by
    the factor of the footprint rule (``footprint``, as the flexible engine: at the impact's
    ``u_rep``, :func:`~batcert.engines.flexible_system.patch_compression`).
    """

    name = "rigid"
    models_barrel = False
    construction_warning: str | None = (
        "rigid engine: the ball-bat COR is the ball's own COR at the relative speed, so BBCOR, "
        "BPF and COR do not depend on the bat's construction or material; performance "
        "verdicts need the flexible engine")
    limitations = {"bpf": "rigid engine: the bat neither vibrates nor flexes, so BPF only "
                          "reflects the ball's lower loss when it compresses less against a "
                          "recoiling bat; use the flexible engine for a meaningful BPF"}

    def __init__(self, ball_loss: str = "compression", contact_surface: str = "cylinder",
                 footprint: str = DEFAULT_RULE) -> None:
        if ball_loss not in BALL_LOSS:
            raise ValueError(f"ball_loss must be one of {BALL_LOSS}, got {ball_loss!r}")
        if contact_surface not in CONTACT_SURFACES:
            raise ValueError(f"contact_surface must be one of {CONTACT_SURFACES}, got "
                             f"{contact_surface!r}")
        self.ball_loss, self.contact_surface = ball_loss, contact_surface
        self.footprint = footprint_rule(footprint).name

    def settings(self, bat: BatModel | None = None) -> dict:
        return {"engine": "rigid", "cor": (
            "the ball's COR against a rigid body of the bat's effective mass (Nathan 2000 "
            "hysteresis: its rigid-wall COR at " + (
                "the wall speed of equal compression, v_rel / sqrt(1 + k))"
                if self.ball_loss == "compression" else "the relative speed)")),
            "contact_surface": ("the barrel's cylinder (stiffness factor of the footprint rule)"
                                if self.contact_surface == "cylinder" else "flat"),
            "footprint": footprint_rule(self.footprint).title}

    def solve_many(self, jobs: list[Job]) -> list[ImpactOutcome]:
        """Closed forms cost nothing per call: :meth:`solve` for each job (a given job's
        modes do not matter to a rigid bat)."""
        return [self.solve(j.bat, j.ball, j.pivot, j.batch, j.support)
                for j in map(Job.of, jobs)]

    def solve(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
              support: str = "pinned") -> ImpactOutcome:
        r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
        k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
        scale: float | np.ndarray = 1.0
        if self.contact_surface == "cylinder":
            scale = self._scale(ball, 0.5 * bat.outer_diameter[bat.slice_at(r + pivot)],
                                batch.relative_speed, k)
        e = _body_cor(ball, batch.relative_speed, k, scale, self.ball_loss)
        vb = rigid.exit_speed(e, k, vp, w1 * r)
        w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
        return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k)

    def _scale(self, ball: BallModel, on: np.ndarray, speed, recoil) -> np.ndarray:
        """The ball law's stiffness factor on the barrels ``on`` [m] [-]: the footprint rule's
        at each impact's ``u_rep``, as the flexible engine (Hertz's for the rule ``hertz`` and
        for a law whose COR does not see the surface, Nathan's)."""
        from batcert.engines.flexible_system import patch_compression

        scale = np.asarray(footprint.stiffness_ratio(ball.radius, on), dtype=float)
        if self.footprint == "hertz" or LAWS[ball.law.name].closed_form_cor:
            return scale
        speed, recoil = np.broadcast_arrays(np.asarray(speed, float), np.asarray(recoil, float))
        on = np.broadcast_to(np.asarray(on, float), speed.shape)
        return patch_compression(self.footprint, ball, on, np.broadcast_to(scale, speed.shape),
                                 speed, recoil)[1]


def _body_cor(ball: BallModel, speed, recoil, scale, rule: str) -> np.ndarray:
    """The ball's COR against rigid bodies, computed once per distinct impact (a sweep's
    conditions repeat speeds and recoil factors)."""
    speed, recoil = np.broadcast_arrays(np.asarray(speed, float), np.asarray(recoil, float))
    scale = np.broadcast_to(np.asarray(scale, float), speed.shape)
    if LAWS[ball.law.name].closed_form_cor:  # Nathan's law: the surface does not matter
        return ball.law.body_cor(ball.mass, speed, recoil, rule)
    key = np.stack([speed.ravel(), recoil.ravel(), scale.ravel()], axis=1)
    unique, which = np.unique(key, axis=0, return_inverse=True)
    cor = ball.law.body_impact(ball.mass, unique[:, 0], unique[:, 1], history=False,
                               scale=unique[:, 2]).cor
    return cor[np.asarray(which).ravel()].reshape(speed.shape)
