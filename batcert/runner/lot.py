"""A ball lot calibrated on a reference bat, as labs check their lots.

A ball file may carry a reference bat's measurement with the lot (``reference_bat``: a bat, the
protocol it was measured under, the value with its standard uncertainty). The ball's law is
first fitted to its ball tests (:mod:`batcert.physics.balls.fit`); the lot is then moved along
the fit's lot direction (every COR test up or down together by ``k`` of its standard
uncertainties, :meth:`~batcert.physics.balls.fit.BallFit.moved`) until the model's metric for
the reference bat under that protocol, on the flexible engine with its default settings,
equals the measured value (the secant method on ``k``, each step a full protocol run with its
location search; the runs of one step solved together).

The calibration is an INPUT, not a result: it makes the reference bat come out at its measured
value by construction, so that bat (and bats like it) are no longer a validation of the model.
It is made once per ball and kept (workspace kind ``ball-lot``, also on disk); every command
that loads the ball uses the calibrated lot, whichever engine it then runs (the lot is a
property of the balls, not of an engine). The standard uncertainty of the shift is the
measurement's divided by the slope of the metric in ``k`` (GUM 5.1.2).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from batcert import workspace
from batcert.engines import get_engine
from batcert.errors import InputError, Problem
from batcert.model.build import build_bat
from batcert.runner.runner import run_protocols
from batcert.specs.ball import BallSpec
from batcert.specs.bat import load_bat
from batcert.specs.common import sha256_of
from batcert.specs.protocol import load_protocol

SHIFT_BOUNDS = (-8.0, 8.0)  # [standard uncertainties of the COR tests] the lot may move
TOLERANCE = 1e-5  # [metric] the reference bat's value is met to this
MAX_STEPS = 8


@dataclass(frozen=True)
class LotCalibration:
    """The calibration of a ball lot on its reference bat (module notes)."""

    shift: float  # [standard uncertainties of the COR tests] (negative: a deader lot)
    u_shift: float  # its standard uncertainty, from the measurement's
    model_value: float  # the model's metric for the reference bat at the shift
    slope: float  # d metric / d shift there


def calibrated_lot(ball: BallSpec) -> BallSpec:
    """``ball`` with its lot calibrated on its reference bat (module notes), or ``ball``
    itself when it has none. An input error at the ball file's ``reference_bat`` when the lot
    cannot reach the measured value within :data:`SHIFT_BOUNDS`."""
    ref, fit = ball.reference, ball.fit
    if ref is None or fit is None:
        return ball
    cal = workspace.current().call(
        "ball-lot", _calibrate, ball.path, ball.sha256, ref.bat, sha256_of(ref.bat),
        ref.protocol, sha256_of(ref.protocol),
        save=lambda c: {"lot": np.array([c.shift, c.u_shift, c.model_value, c.slope])},
        load=lambda a: LotCalibration(*(float(x) for x in a["lot"])))
    if not np.isfinite(cal.shift):
        raise InputError([Problem(ball.path, ref.line, "reference_bat", _unreachable(cal, ref))])
    law = fit.moved(cal.shift)
    return replace(ball, model=replace(ball.model, law=law), fit=replace(fit, law=law), lot=cal)


def _unreachable(cal: LotCalibration, ref) -> str:
    return (f"the ball lot cannot be calibrated on its reference bat: moving every COR test by "
            f"{SHIFT_BOUNDS[0]:g} to {SHIFT_BOUNDS[1]:+g} standard uncertainties gives the "
            f"reference bat {cal.model_value:.4f} at best, against the measured "
            f"{ref.value:.4f}")


def _calibrate(ball_path: str, ball_sha: str, bat: str, bat_sha: str, protocol: str,
               protocol_sha: str) -> LotCalibration:
    """The shift (module notes) of the ball file at ``ball_path`` on its reference bat (the
    files' checksums key the kept result); NaN with the nearest value reached when none meets
    it."""
    from batcert.specs.ball import load_ball

    ball = load_ball(Path(ball_path))
    ref, fit = ball.reference, ball.fit
    assert ref is not None and fit is not None
    built = build_bat(load_bat(Path(bat)))
    spec = load_protocol(Path(protocol))
    engine = get_engine("flexible")

    def values(shifts: list[float]) -> list[float]:
        balls = [replace(ball, model=replace(ball.model, law=fit.moved(k)), reference=None)
                 for k in shifts]
        return [r.value for r in run_protocols([(built, spec, b) for b in balls], engine)]

    k0, k1 = 0.0, -1.0
    v0, v1 = values([k0, k1])
    for _ in range(MAX_STEPS):
        slope = (v1 - v0) / (k1 - k0)
        if not slope > 0:
            break
        k2 = float(np.clip(k1 + (ref.value - v1) / slope, *SHIFT_BOUNDS))
        if k2 == k1:  # at a bound, and the value lies beyond it
            break
        (v2,) = values([k2])
        k0, v0, k1, v1 = k1, v1, k2, v2
        if abs(v2 - ref.value) <= TOLERANCE:
            return LotCalibration(k2, ref.uncertainty / slope, v2, slope)
    return LotCalibration(float("nan"), float("nan"), v1, float("nan"))
