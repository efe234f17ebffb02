"""Batted-ball speed along the barrel in play: a free bat swung about an axis near the knob.

During the millisecond of contact the batter's hands do not hold the bat against the ball: the
study (Smith 2001) and Nathan (2000) show that the bat's support does not matter then, so the
bat is free, moving before impact as a rotation about the swing axis at the rate the batter's
swing law gives it (:func:`batcert.physics.swing.swing_speed`). Every bat, swing scenario and
impact location is one engine batch; the peak is refined with the location search's parabola.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.engines.base import Engine, ImpactBatch, Job
from batcert.model.build import BuiltBat
from batcert.physics.ball import BallModel
from batcert.runner.locate import parabolic_peak
from batcert.units import INCH, MPH

__all__ = ["BarrelSweep", "Swung", "SweetZone", "barrel_grid", "sweet_zone", "swing_barrels"]

WINDOW_FROM_TIP = (0.5 * INCH, 12.0 * INCH)  # impact locations searched [m from the tip]
POINTS = 47  # a quarter inch apart


def barrel_grid(window: tuple[float, float] = WINDOW_FROM_TIP, points: int = POINTS
                ) -> np.ndarray:
    """Impact locations [m from the tip], tip first."""
    return np.linspace(window[0], window[1], points)


@dataclass(frozen=True)
class Swung:
    """One bat to swing: its model, the swing axis and, per scenario, its rate and the pitch."""

    built: BuiltBat
    axis_from_knob: float  # [m]
    angular_speed: np.ndarray  # per scenario [rad/s]
    pitch_speed: np.ndarray  # per scenario, toward the bat [m/s]


@dataclass(frozen=True)
class BarrelSweep:
    """Batted-ball speeds of one bat, arrays (n_scenarios, n_locations)."""

    from_tip: np.ndarray  # (n_loc,) [m]
    exit_speed: np.ndarray  # [m/s]
    bat_speed: np.ndarray  # the bat's speed at each impact point before impact [m/s]
    collision_efficiency: np.ndarray  # e_A = (v_exit - v_bat) / (v_pitch + v_bat) [-]


def swing_barrels(engine: Engine, ball: BallModel, bats: list[Swung],
                  from_tip: np.ndarray) -> list[BarrelSweep]:
    """Every bat at every scenario and location ``from_tip`` [m], free, in one engine call."""
    jobs = []
    for s in bats:
        r = s.built.model.length - s.axis_from_knob - from_tip  # from the axis [m]
        w = np.asarray(s.angular_speed, float)[:, None]
        vp = -np.asarray(s.pitch_speed, float)[:, None]
        batch = ImpactBatch(np.broadcast_to(r, (w.size, r.size)).ravel(),
                            np.broadcast_to(vp, (w.size, r.size)).ravel(),
                            np.broadcast_to(w, (w.size, r.size)).ravel())
        jobs.append(Job(s.built.model, ball, s.axis_from_knob, batch, "free"))
    out = []
    for s, job, solved in zip(bats, jobs, engine.solve_many(jobs), strict=True):
        shape = (np.size(s.angular_speed), from_tip.size)
        exit_speed = np.asarray(solved.exit_speed, float).reshape(shape)
        v_bat = (job.batch.bat_angular_speed * job.batch.impact_location).reshape(shape)
        v_pitch = -job.batch.pitch_speed.reshape(shape)
        out.append(BarrelSweep(from_tip, exit_speed, v_bat,
                               (exit_speed - v_bat) / (v_pitch + v_bat)))
    return out


@dataclass(frozen=True)
class SweetZone:
    """The best batted-ball speed along the barrel and the barrel length near it."""

    best: np.ndarray  # best exit speed per scenario [m/s]
    at: np.ndarray  # its location from the tip [m]
    length_1: np.ndarray  # barrel length within `drops[0]` of the best [m]
    length_5: np.ndarray  # within `drops[1]` [m]
    open: np.ndarray  # the wider zone reaches an end of the window (its length a lower bound)


def _crossing(x: np.ndarray, y: np.ndarray, level: float, start: int, step: int
              ) -> tuple[float, bool]:
    """Walking from ``start`` by ``step``, where ``y`` first falls below ``level`` (linear
    between samples); the window's end (and True) if it never does."""
    i = start
    while 0 <= i + step < y.size:
        j = i + step
        if y[j] < level:
            return float(x[i] + (x[j] - x[i]) * (y[i] - level) / (y[i] - y[j])), False
        i = j
    return float(x[i]), True


def _parabola_value(x: np.ndarray, y: np.ndarray, index: np.ndarray, at: np.ndarray
                    ) -> np.ndarray:
    """Each row's parabola through the samples around ``index``, evaluated at ``at``."""
    ic = np.clip(index, 1, x.size - 2)
    rows = np.arange(y.shape[0])
    xs = [x[ic - 1], x[ic], x[ic + 1]]
    ys = [y[rows, ic - 1], y[rows, ic], y[rows, ic + 1]]
    out = np.zeros(y.shape[0])
    for j in range(3):
        term = ys[j]
        for k in range(3):
            if k != j:
                term = term * (at - xs[k]) / (xs[j] - xs[k])
        out += term
    return np.maximum(out, y[rows, index])


def sweet_zone(from_tip: np.ndarray, exit_speed: np.ndarray,
               drops: tuple[float, float] = (1.0 * MPH, 5.0 * MPH)) -> SweetZone:
    """The best exit speed of each row of ``exit_speed`` (n, n_loc) along ``from_tip`` [m]
    (parabola through the best three samples) and the length of the contiguous barrel around it
    where the speed stays within each of ``drops`` [m/s] (default 1 and 5 mph) of the best."""
    y = np.atleast_2d(np.asarray(exit_speed, float))
    x = np.tile(from_tip, (y.shape[0], 1))
    at, index = parabolic_peak(x, y)
    best = _parabola_value(from_tip, y, index, at)
    lengths, open_ = [], np.zeros(len(y), bool)
    for drop in drops:
        got = []
        for k, (row, i) in enumerate(zip(y, index, strict=True)):
            lo, lo_open = _crossing(from_tip, row, best[k] - drop, int(i), -1)
            hi, hi_open = _crossing(from_tip, row, best[k] - drop, int(i), +1)
            got.append(hi - lo)
            open_[k] |= lo_open or hi_open
        lengths.append(np.array(got))
    return SweetZone(best, at, lengths[0], lengths[1], open_)
