"""A ball lot calibrated on a reference bat, as labs check their lots.

A ball file may carry a reference bat's measurement with the lot (``reference_bat``: a bat, the
protocol it was measured under, the value with its standard uncertainty). The ball's law is
first fitted to its ball tests (:mod:`batcert.physics.balls.fit`). The lot is the ball whose
every COR test lies ``k`` of its standard uncertainties from the tested balls' (a livelier or
deader lot, the same notion ``run --uncertainty`` draws), its law moved along the fit's
linearisation (:meth:`~batcert.physics.balls.fit.BallFit.moved`: smooth in ``k``, where a refit
of the moved tests is rough at about 1e-4 in a bat's metric); ``k`` is found where the model's
metric for the reference bat under that protocol, on the flexible engine with its default
settings, equals the measured value. The search: the secant method from ``k = 0`` and ``-1``;
where it fails (far from the tests the linearisation need not keep the metric monotonic in
``k``), a grid over :data:`SHIFT_BOUNDS` in one batch and Brent's method
(:func:`batcert.numerics.brent_root`, as the lab's barrel calibration does) in the sign change
nearest ``k = 0``. Every evaluation is a full protocol run with its location search.

The calibration is an INPUT, not a result: it makes the reference bat come out at its measured
value by construction, so that bat (and bats like it) are no longer a validation of the model.
It is made once per ball and kept (workspace kind ``ball-lot``, also on disk); every command
that loads the ball uses the calibrated lot, whichever engine it then runs (the lot is a
property of the balls, not of an engine). The standard uncertainty of ``k`` is the
measurement's divided by the slope of the metric in ``k`` (GUM 5.1.2).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from batcert import workspace
from batcert.engines import get_engine
from batcert.errors import InputError, Problem
from batcert.model.build import build_bat
from batcert.numerics import brent_root
from batcert.runner.runner import run_protocols
from batcert.specs.ball import BallSpec, ReferenceBat
from batcert.specs.bat import load_bat
from batcert.specs.common import sha256_of
from batcert.specs.protocol import load_protocol

SHIFT_BOUNDS = (-8.0, 8.0)  # [standard uncertainties of the COR tests] the lot may move
TOLERANCE = 1e-5  # [metric] the reference bat's value is met to this
MAX_STEPS = 12


@dataclass(frozen=True)
class LotCalibration:
    """The calibration of a ball lot on its reference bat (module notes)."""

    shift: float  # [standard uncertainties of the COR tests] (negative: a deader lot)
    u_shift: float  # its standard uncertainty, from the measurement's
    model_value: float  # the model's metric for the reference bat at the shift
    slope: float  # d metric / d shift there
    tested: Any = field(default=None, compare=False)  # the tested balls' fit (not kept)


def calibrated_lot(ball: BallSpec, reference: ReferenceBat | None = None) -> BallSpec:
    """``ball`` with its lot calibrated on a reference bat (module notes), or ``ball`` itself
    when there is none. ``reference``: a measurement that replaces the ball file's own
    ``reference_bat`` (a lab session's reference bat, :mod:`batcert.lab.lot`). An input error
    at the reference's line (the ball file's ``reference_bat``, or the file ``reference.path``
    names) when no lot within :data:`SHIFT_BOUNDS` reaches the measured value."""
    ref, fit = reference or ball.reference, ball.fit
    if ref is None or fit is None:
        return ball
    cal = workspace.current().call(
        "ball-lot", _calibrate, ball.path, ball.sha256, ref.bat, sha256_of(ref.bat),
        ref.protocol, sha256_of(ref.protocol), ref.value, ref.uncertainty,
        save=lambda c: {"lot": np.array([c.shift, c.u_shift, c.model_value, c.slope])},
        load=lambda a: LotCalibration(*(float(x) for x in a["lot"])))
    if not np.isfinite(cal.shift):
        raise InputError([Problem(ref.path or ball.path, ref.line, ref.field,
                                  _unreachable(cal, ref))])
    law = fit.moved(cal.shift)
    return replace(ball, model=replace(ball.model, law=law), fit=replace(fit, law=law),
                   reference=ref, lot=replace(cal, tested=fit))


def _unreachable(cal: LotCalibration, ref) -> str:
    return (f"the ball lot cannot be calibrated on its reference bat: a lot whose COR tests lie "
            f"{SHIFT_BOUNDS[0]:g} to {SHIFT_BOUNDS[1]:+g} standard uncertainties from the tested "
            f"balls' comes nearest at {cal.model_value:.4f}, against the measured "
            f"{ref.value:.4f}")


def _calibrate(ball_path: str, ball_sha: str, bat: str, bat_sha: str, protocol: str,
               protocol_sha: str, value: float, uncertainty: float) -> LotCalibration:
    """The shift (module notes) of the ball file at ``ball_path`` that makes the model's metric
    for the reference bat ``bat`` under ``protocol`` equal ``value`` (standard uncertainty
    ``uncertainty``; the files' checksums key the kept result); NaN with the nearest value
    reached when none meets it."""
    from batcert.specs.ball import load_ball

    ball = load_ball(Path(ball_path))
    fit = ball.fit
    assert fit is not None
    built = build_bat(load_bat(Path(bat)))
    spec = load_protocol(Path(protocol))
    engine = get_engine("flexible")

    def gaps(shifts) -> np.ndarray:
        """The model's value less the measured one at each shift (NaN where the moved law
        leaves its plausible range)."""
        laws: list[Any] = []
        for k in shifts:
            try:
                laws.append(fit.moved(float(k)))
            except ValueError:
                laws.append(None)
        balls = [replace(ball, model=replace(ball.model, law=law), reference=None)
                 for law in laws if law is not None]
        got = iter(r.value for r in run_protocols([(built, spec, b) for b in balls], engine))
        return np.array([next(got) - value if law is not None else np.nan for law in laws])

    def found(k: float, slope: float, gap: float) -> LotCalibration:
        return LotCalibration(float(k), float(uncertainty / abs(slope)), float(value + gap),
                              float(slope))

    k = _secant(gaps)
    if k is not None:
        return found(*k)
    return _bracketed(gaps, found, value)


def _secant(gaps) -> tuple[float, float, float] | None:
    """The secant method from 0 and -1: ``(shift, slope, gap)``, None where it does not
    converge within the bounds."""
    k0, k1 = 0.0, -1.0
    g0, g1 = gaps([k0, k1])
    for _ in range(MAX_STEPS):
        slope = (g1 - g0) / (k1 - k0)
        if not slope > 0:
            return None
        k2 = float(np.clip(k1 - g1 / slope, *SHIFT_BOUNDS))
        if k2 == k1:
            return None
        (g2,) = gaps([k2])
        if not np.isfinite(g2):
            return None
        k0, g0, k1, g1 = k1, g1, k2, g2
        if abs(g2) <= TOLERANCE:
            return k2, (g1 - g0) / (k1 - k0) if k1 != k0 else slope, g2
    return None


def _bracketed(gaps, found, value: float) -> LotCalibration:
    """A grid over the bounds in one batch, then Brent's method in the sign change nearest 0
    (the slope there by central differences); NaN with the nearest value reached where the
    grid has no sign change."""
    grid = np.linspace(*SHIFT_BOUNDS, 17)
    g = gaps(grid)
    change = [i for i in range(grid.size - 1) if np.isfinite(g[i]) and np.isfinite(g[i + 1])
              and g[i] * g[i + 1] <= 0]
    if not change:
        nearest = float(g[int(np.nanargmin(np.abs(g)))]) if np.any(np.isfinite(g)) else np.nan
        return LotCalibration(float("nan"), float("nan"), value + nearest, float("nan"))
    i = min(change, key=lambda j: abs(grid[j] + grid[j + 1]))

    def gap(k: float) -> float:
        return float(gaps([k])[0])

    k = brent_root(gap, float(grid[i]), float(grid[i + 1]), xtol=1e-5).x
    h = 1e-3  # [standard uncertainties]
    return found(k, (gap(k + h) - gap(k - h)) / (2 * h), gap(k))
