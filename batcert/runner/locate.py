"""Impact-location search: coarse sweep over the window, then refinement to the resolution.

All conditions are searched together: one engine batch for the coarse sweep (conditions x
locations) and one for the refinement around each condition's maximum (of the exit speed, and of
the metric when the impact rule needs it).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from batcert.methods.metrics import ImpactMetrics, Metric
from batcert.methods.rules import Peaks

if TYPE_CHECKING:
    from batcert.runner.conditions import Condition
    from batcert.runner.runner import Bench
    from batcert.specs.protocol import LocationSpec


def sweep_grid(bat_length: float, pivot: float, window_from_tip: tuple[float, float],
               points: int) -> np.ndarray:
    """Impact locations [m from pivot] evenly spread over the window, nearest the pivot first."""
    near, far = window_from_tip
    return np.linspace(bat_length - pivot - far, bat_length - pivot - near, int(points))


def refine_grid(grid: np.ndarray, index: np.ndarray, resolution: float) -> np.ndarray:
    """Fine grids (one row per condition) spanning one coarse step either side of ``index``,
    spaced at most half the resolution."""
    step = grid[1] - grid[0]
    n = int(np.ceil(2 * step / (0.5 * resolution))) + 1
    lo = grid[np.clip(index - 1, 0, grid.size - 1)]
    hi = grid[np.clip(index + 1, 0, grid.size - 1)]
    t = np.linspace(0.0, 1.0, n)
    return lo[:, None] + (hi - lo)[:, None] * t[None, :]


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
    """Sweep the window and locate each condition's sweet spot (and metric maximum): two steps
    for :func:`batcert.runner.runner.drive`, the coarse sweep and the refinement. Returns the
    :class:`Search`."""
    bat = bench.built.model
    tip = bat.length - bench.pivot
    n = len(conds)
    grid = sweep_grid(bat.length, bench.pivot, location.window, location.sweep_points)
    ((coarse, _),) = yield [bench.request(conds, np.tile(grid, (n, 1)))]
    m_coarse = metric.value(coarse)
    targets = [coarse.exit_speed] + ([m_coarse] if needs_metric_peak else [])
    fine_r = np.concatenate([refine_grid(grid, np.argmax(t, axis=1), location.resolution)
                             for t in targets])
    ((fine, _),) = yield [bench.request(conds * len(targets), fine_r)]
    sweet, _ = parabolic_peak(fine_r[:n], fine.exit_speed[:n])
    sweet_edge = _on_edge(coarse.exit_speed)
    peak, peak_edge, flat = sweet, sweet_edge, np.zeros(n, bool)
    if needs_metric_peak:
        peak, _ = parabolic_peak(fine_r[n:], metric.value(fine)[n:])
        peak_edge = _on_edge(m_coarse)
        flat = np.ptp(m_coarse, axis=1) <= 1e-9 * np.abs(m_coarse).max(axis=1)
    peaks = Peaks(sweet, sweet_edge, peak, peak_edge, flat, cop, tip, location.from_tip)
    return Search(grid, coarse, m_coarse, peaks)
