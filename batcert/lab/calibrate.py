"""The barrel calibrated from measured hits: the barrel stiffness scale at which the model's
metric at the certified location equals the measured value, with its uncertainty, and the
equivalent hoop frequency a bat file can state (``measured.hoop_frequency``).

The model's metric at one impact point is solved with the protocol's stationary-bat condition
(:class:`batcert.runner.bench.Bench`). The scale is found by Brent's method within the
calibration bounds of :mod:`batcert.model.calibrate` (x0.25 to x4); its standard uncertainty is
the measurement's combined standard uncertainty divided by the slope of the model's metric at
the root (first-order propagation, GUM 5.1.2). The metric need not be monotonic in the barrel's
stiffness: every root in the bounds is reported, softest first. Where there is none, the
model's metric over the bounds (its range) says how far the model is from the measurement
(:func:`calibrate_barrel`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from batcert.model.calibrate import BARREL_STIFFNESS_BOUNDS
from batcert.numerics import brent_root


@dataclass(frozen=True)
class BarrelFit:
    scale: float  # barrel stiffness scale [-]
    u_scale: float  # its standard uncertainty [-]
    hoop_frequency: float  # the equivalent measured hoop frequency [Hz]
    u_hoop_frequency: float  # [Hz]
    slope: float  # d metric / d scale at the root [-]


def _model_metrics(session, protocol, ball, engine, location: float, scales) -> list[float]:
    """The model's metric at ``location`` with the barrel stiffness scaled by each of
    ``scales``, the bats solved together (one engine integration)."""
    from batcert.methods.metrics import METRICS
    from batcert.runner.bench import Bench
    from batcert.runner.conditions import conditions_from_spec
    built = session.built
    requests = []
    for scale in scales:
        model = replace(built.model,
                        barrel_stiffness_scale=built.model.barrel_stiffness_scale * scale)
        bench = Bench(replace(built, model=model), ball, engine, protocol.pivot,
                      protocol.support)
        conds = conditions_from_spec(protocol.conditions[:1], model, protocol.pivot)
        requests.append(bench.request(conds, np.array([[location]])))
    outcomes = engine.solve_many([r.job() for r in requests])
    return [float(METRICS[protocol.metric].value(r.finish(out)[0])[0, 0])
            for r, out in zip(requests, outcomes, strict=True)]


@dataclass(frozen=True)
class BarrelCalibration:
    fits: list[BarrelFit]  # every root in the bounds, softest first; [] when none
    span: tuple[float, float] | None  # the model's metric over the bounds' grid (min, max)


def fit_barrel(session, protocol, ball, engine, location: float, measured: float,
               u_measured: float, points: int = 9) -> list[BarrelFit]:
    """Every barrel stiffness scale in the bounds where the model's metric at ``location`` [m
    from the pivot] equals ``measured``; [] for a solid bat or when none does."""
    return calibrate_barrel(session, protocol, ball, engine, location, measured, u_measured,
                            points).fits


def calibrate_barrel(session, protocol, ball, engine, location: float, measured: float,
                     u_measured: float, points: int = 9) -> BarrelCalibration:
    """:func:`fit_barrel` with the model's range over the bounds (``span``; None for a solid
    bat), so that a calibration that finds no root can say why."""
    from batcert.physics import barrel
    if session.built.model.construction != "hollow":
        return BarrelCalibration([], None)
    lo, hi = BARREL_STIFFNESS_BOUNDS
    grid = np.geomspace(lo, hi, points)

    def f(s: float) -> float:
        return _model_metrics(session, protocol, ball, engine, location, [s])[0] - measured

    values = [v - measured for v in _model_metrics(session, protocol, ball, engine, location,
                                                   grid)]
    hoop = barrel.hoop_frequency(session.built.model)
    out = []
    for a, b, fa, fb in zip(grid, grid[1:], values, values[1:], strict=False):
        if (fa >= 0) == (fb >= 0):
            continue
        s = brent_root(f, a, b, xtol=1e-6).x
        h = 1e-4 * s
        slope = (f(s + h) - f(s - h)) / (2 * h)
        u_s = u_measured / abs(slope) if slope else math.inf
        f_hoop = float(hoop) * math.sqrt(s) if hoop else math.nan
        out.append(BarrelFit(s, u_s, f_hoop, f_hoop * 0.5 * u_s / s, slope))
    return BarrelCalibration(out, (min(values) + measured, max(values) + measured))


def with_hoop_frequency(bat_text: str, frequency: float, comment: str) -> str:
    """The bat file's text with ``measured.hoop_frequency`` set to ``frequency`` [Hz] (an
    existing one replaced, else a line added under ``measured:``), every other line kept.
    Raises ``ValueError`` when the file has no top-level ``measured:`` block (a measured
    mass is required before a barrel can be calibrated)."""
    lines = bat_text.splitlines()
    start = next((i for i, ln in enumerate(lines) if ln.startswith("measured:")), None)
    if start is None:
        raise ValueError("the bat file has no measured: block (a calibrated barrel needs the "
                         "measured mass); add one, then hoop_frequency")
    end = next((i for i in range(start + 1, len(lines))
                if lines[i] and not lines[i][0].isspace() and not lines[i].startswith("#")),
               len(lines))
    indent = next((ln[:len(ln) - len(ln.lstrip())] for ln in lines[start + 1:end]
                   if ln.strip() and not ln.lstrip().startswith("#")), "  ")
    new = f"{indent}hoop_frequency: {frequency:.0f} Hz  # {comment}"
    for i in range(start + 1, end):
        if lines[i].lstrip().startswith("hoop_frequency:"):
            lines[i] = new
            break
    else:
        lines.insert(start + 1, new)
    return "\n".join(lines) + "\n"
