"""Impact-location search: coarse sweep over the window, then refinement to the resolution.

All conditions are searched together: one engine batch for the coarse sweep (conditions x
locations) and one for the refinement around each condition's maximum (of the exit speed, and of
the metric when the impact rule needs it), a five-point stencil half the resolution apart
around the peak that the coarse sweep's parabola predicts.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from batcert.methods.metrics import ImpactMetrics, Metric
from batcert.methods.rules import Peaks

if TYPE_CHECKING:
    from batcert.runner.bench import Bench
    from batcert.runner.conditions import Condition
    from batcert.specs.protocol import LocationSpec


def sweep_grid(bat_length: float, pivot: float, window_from_tip: tuple[float, float],
               points: int) -> np.ndarray:
    """Impact locations [m from pivot] evenly spread over the window, nearest the pivot first."""
    near, far = window_from_tip
    return np.linspace(bat_length - pivot - far, bat_length - pivot - near, int(points))


STENCIL = 5  # refinement points around each estimated peak, half the resolution apart
MAX_ROUNDS = 6  # refinement rounds at most (a peak found on a stencil's edge moves it)


def stencil(centre: np.ndarray, resolution: float, lo: float, hi: float) -> np.ndarray:
    """Rows of :data:`STENCIL` points half the resolution apart, centred on ``centre`` and
    shifted to stay within ``[lo, hi]`` [m from pivot]."""
    offsets = (np.arange(STENCIL) - STENCIL // 2) * 0.5 * resolution
    c = np.clip(centre, lo - offsets[0], hi - offsets[-1])
    return c[:, None] + offsets[None, :]


def parabolic_peak(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Location of the maximum of each row, refined by a parabola through the best three points
    (rows of x must be evenly spaced). Returns (x_peak, index of the best sample)."""
    i = np.argmax(y, axis=1)
    rows = np.arange(y.shape[0])
    inner = (i > 0) & (i < y.shape[1] - 1)
    ic = np.clip(i, 1, y.shape[1] - 2)
    y0, y1, y2 = y[rows, ic - 1], y[rows, ic], y[rows, ic + 1]
    denom = y0 - 2 * y1 + y2
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(inner & (denom < 0), 0.5 * (y0 - y2) / denom, 0.0)
    shift = np.clip(shift, -0.5, 0.5)
    dx = x[:, 1] - x[:, 0]
    return x[rows, i] + shift * dx, i


def _on_edge(values: np.ndarray) -> np.ndarray:
    return np.isin(np.argmax(values, axis=1), (0, values.shape[1] - 1))


@dataclass(frozen=True)
class Search:
    """The coarse sweep of every condition and the peaks located from it."""

    grid: np.ndarray  # sweep locations [m from pivot], (n_loc,)
    coarse: ImpactMetrics  # every metric on the grid, (n_cond, n_loc)
    coarse_metric: np.ndarray  # the protocol metric on the grid, (n_cond, n_loc)
    peaks: Peaks


def locate_steps(bench: Bench, conds: list[Condition], location: LocationSpec, metric: Metric,
                 needs_metric_peak: bool, cop: float):
    """Sweep the window and locate each condition's sweet spot (and metric maximum), as
    steps for :func:`batcert.runner.bench.drive`: the coarse sweep, then a small stencil
    around each peak estimated from it (a parabola through the best three coarse points), the
    peak taken by a parabola through the stencil's best three; a stencil whose best point is on
    its edge is moved there and solved again. Returns the :class:`Search`."""
    bat = bench.built.model
    tip = bat.length - bench.pivot
    n = len(conds)
    grid = sweep_grid(bat.length, bench.pivot, location.window, location.sweep_points)
    ((coarse, _),) = yield [bench.request(conds, np.tile(grid, (n, 1)))]
    m_coarse = metric.value(coarse)
    values = [coarse.exit_speed] + ([m_coarse] if needs_metric_peak else [])
    # the peaks to refine: (target, condition) rows
    which = [(t, i) for t in range(len(values)) for i in range(n)]
    coarse_x = np.tile(grid, (len(which), 1))
    estimate, _ = parabolic_peak(coarse_x, np.concatenate(values))
    peak = estimate.copy()
    todo = np.arange(len(which))
    for _ in range(MAX_ROUNDS):
        points = stencil(estimate[todo], location.resolution, grid[0], grid[-1])
        rows = [which[k] for k in todo]
        ((fine, _),) = yield [bench.request([conds[i] for _, i in rows], points)]
        fine_metric = metric.value(fine) if needs_metric_peak else fine.exit_speed
        got = np.stack([fine.exit_speed[j] if t == 0 else fine_metric[j]
                        for j, (t, _) in enumerate(rows)])
        x, best = parabolic_peak(points, got)
        peak[todo] = x
        on_edge = ((best == 0) & (points[:, 0] > grid[0])) | (
            (best == STENCIL - 1) & (points[:, -1] < grid[-1]))
        if not on_edge.any():
            break
        estimate[todo[on_edge]] = points[on_edge, best[on_edge]]  # move the stencil there
        todo = todo[on_edge]
    sweet = peak[:n]
    sweet_edge = _on_edge(coarse.exit_speed)
    metric_peak, peak_edge, flat = sweet, sweet_edge, np.zeros(n, bool)
    if needs_metric_peak:
        metric_peak = peak[n:]
        peak_edge = _on_edge(m_coarse)
        flat = np.ptp(m_coarse, axis=1) <= 1e-9 * np.abs(m_coarse).max(axis=1)
    peaks = Peaks(sweet, sweet_edge, metric_peak, peak_edge, flat, cop, tip, location.from_tip)
    return Search(grid, coarse, m_coarse, peaks)
