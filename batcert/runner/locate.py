"""Impact-location search: coarse sweep over the window, then refinement to the resolution.

All conditions are searched together: one engine batch for the coarse sweep (conditions x
locations) and one for the refinement around each condition's maximum.
"""

from __future__ import annotations

import numpy as np


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
