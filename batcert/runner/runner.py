"""Run a protocol on a bat: conditions -> engine batches -> located impacts -> metrics -> verdict."""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass

import numpy as np

from batcert import __version__
from batcert.physics import rigid
from batcert.physics.engine import Engine, ImpactBatch
from batcert.results import (ConditionResult, InputFile, MassProperties, RunResult, Sweep)
from batcert.runner.conditions import Condition, conditions_from_spec
from batcert.runner.locate import parabolic_peak, refine_grid, sweep_grid
from batcert.runner.metrics import AGGREGATES, METRICS, ImpactMetrics, impact_metrics
from batcert.specs.ball import BallSpec
from batcert.specs.bat import BuiltBat
from batcert.specs.protocol import ProtocolSpec


class ProtocolError(ValueError):
    """The protocol cannot be applied to this bat (e.g. the window lies outside it)."""


@dataclass(frozen=True)
class _Context:
    built: BuiltBat
    ball: BallSpec
    engine: Engine
    pivot: float
    support: str

    def solve(self, conds: list[Condition], locations: np.ndarray) -> ImpactMetrics:
        """Solve every condition at its row of ``locations`` (shape (n_cond, n_loc)) in one batch."""
        r = np.asarray(locations, float)
        vp, w1 = zip(*(c.speeds(row) for c, row in zip(conds, r)))
        vp, w1 = np.stack(vp), np.stack(w1)
        batch = ImpactBatch(r.ravel(), vp.ravel(), w1.ravel())
        out = self.engine.solve(self.built.model, self.ball.model, self.pivot, batch, self.support)
        k = rigid.recoil_factor(self.built.model, self.ball.model.mass, self.pivot,
                                batch.impact_location, self.support)
        m = impact_metrics(batch.impact_location, batch.pitch_speed, batch.bat_angular_speed,
                           out.exit_speed, out.bat_angular_speed_after, out.cor,
                           self.ball.model.cor, k)
        shape = r.shape
        return ImpactMetrics(**{k: np.asarray(v).reshape(shape) for k, v in vars(m).items()})


def mass_properties(built: BuiltBat, pivot: float) -> MassProperties:
    g, m, meas = built.geometry, built.model, built.measured
    moi = m.moi_about(pivot)
    meas_moi = None
    if meas is not None and meas.moi is not None:  # move the measured MOI to this pivot
        moi_cg = meas.moi - meas.mass * (meas.balance_point - meas.pivot) ** 2
        meas_moi = moi_cg + meas.mass * (meas.balance_point - pivot) ** 2
    return MassProperties(
        length=m.length, pivot=pivot, mass=m.mass, cg=m.cg_from(pivot), moi_pivot=moi,
        cop=rigid.centre_of_percussion(moi, m.mass, m.cg_from(pivot)),
        geometry_mass=g.mass, geometry_cg=g.cg_from(pivot), geometry_moi_pivot=g.moi_about(pivot),
        measured_mass=meas.mass if meas else None,
        measured_cg=(meas.balance_point - pivot) if meas and meas.balance_point is not None else None,
        measured_moi_pivot=meas_moi, reconciliation=built.reconciliation.description,
        corrections=dict(built.reconciliation.corrections),
        geometry_cop=float(rigid.centre_of_percussion(g.moi_about(pivot), g.mass, g.cg_from(pivot))),
        measured_cop=(float(rigid.centre_of_percussion(meas_moi, meas.mass,
                                                       meas.balance_point - pivot))
                      if meas_moi is not None else None))


def run_protocol(built: BuiltBat, protocol: ProtocolSpec, ball: BallSpec, engine: Engine,
                 created: str | None = None) -> RunResult:
    p = protocol.values
    bat = built.model
    pivot, support = p["pivot"], p["support"]
    if not 0 <= pivot < bat.length:
        raise ProtocolError(f"the pivot ({pivot * 100:.1f} cm from the knob) is not on the bat")
    loc = p["impact_location"]
    window = tuple(loc["window"])
    if window[1] >= bat.length - pivot:
        raise ProtocolError(f"the search window reaches {window[1] * 100:.1f} cm from the tip, "
                            f"beyond the pivot of this {bat.length * 100:.1f} cm bat")
    conds = conditions_from_spec(p["conditions"], bat.length, pivot)
    moi = bat.moi_about(pivot)
    ctx = _Context(built, ball, engine, pivot, support)
    mp = mass_properties(built, pivot)
    metric = METRICS[p["metric"]]
    n = len(conds)

    grid = sweep_grid(bat.length, pivot, window, int(loc["sweep_points"]))
    coarse = ctx.solve(conds, np.tile(grid, (n, 1)))
    # refine the exit-speed maximum (sweet spot) and, where needed, the metric maximum together
    targets = [coarse.exit_speed]
    m_coarse = metric(coarse)
    if loc["rule"] == "max-metric":
        targets.append(m_coarse)
    fine_r = np.concatenate([refine_grid(grid, np.argmax(t, axis=1), loc["resolution"])
                             for t in targets])
    fine = ctx.solve(conds * len(targets), fine_r)
    sweet, _ = parabolic_peak(fine_r[:n], fine.exit_speed[:n])
    edge_sweet = np.isin(np.argmax(coarse.exit_speed, axis=1), (0, grid.size - 1))
    flat = np.zeros(n, bool)
    if loc["rule"] == "max-metric":
        chosen, _ = parabolic_peak(fine_r[n:], metric(fine)[n:])
        edge = np.isin(np.argmax(m_coarse, axis=1), (0, grid.size - 1))
        flat = np.ptp(m_coarse, axis=1) <= 1e-9 * np.abs(m_coarse).max(axis=1)
        # a metric that does not vary along the bat has no maximum: use the sweet spot
        chosen, edge = np.where(flat, sweet, chosen), np.where(flat, edge_sweet, edge)
    elif loc["rule"] == "sweet-spot":
        chosen, edge = sweet, edge_sweet
    elif loc["rule"] == "cop":
        chosen, edge = np.full(n, mp.cop), np.zeros(n, bool)
    else:  # fixed-from-tip
        chosen, edge = np.full(n, bat.length - pivot - loc["from_tip"]), np.zeros(n, bool)
    off = (chosen <= 0) | (chosen >= bat.length - pivot)
    if np.any(off):
        bad = float(chosen[np.argmax(off)])
        raise ProtocolError(f"the {loc['rule']} impact point ({bad * 100:.1f} cm from the pivot) is "
                            f"not between the pivot and the tip ({(bat.length - pivot) * 100:.1f} cm)")
    final = ctx.solve(conds, chosen[:, None])
    values = metric(final)[:, 0]

    results, warnings = [], []
    for i, c in enumerate(conds):
        rigid_ss = rigid.rigid_sweet_spot(moi, ball.model.mass, final.pitch_speed[i, 0],
                                          final.bat_angular_speed[i, 0])
        if c.relative_speed is not None:
            rigid_ss = np.nan  # Eq. 7 assumes fixed speeds; matched conditions vary w1 with r
        if flat[i]:
            warnings.append(f"{c.name}: {p['metric']} does not vary with impact location, so it "
                            "has no maximum; the sweet spot (maximum exit speed) is used")
        if edge[i]:
            warnings.append(f"{c.name}: the located impact point lies on the search window's edge "
                            f"({chosen[i] * 100:.1f} cm from the pivot); the true maximum is "
                            "outside the window")
        f = {k: float(np.asarray(v)[i, 0]) for k, v in vars(final).items()}
        results.append(ConditionResult(
            name=c.name, setup=c.setup, pitch_speed=f["pitch_speed"],
            bat_angular_speed=f["bat_angular_speed"], relative_speed=f["relative_speed"],
            impact_location=float(chosen[i]), exit_speed=f["exit_speed"],
            bat_angular_speed_after=f["bat_angular_speed_after"], cor=f["cor"],
            ball_cor=f["ball_cor"], bpf=f["bpf"], besr=f["besr"], bbcor=f["bbcor"],
            collision_efficiency=f["collision_efficiency"], metric_value=float(values[i]),
            cop=mp.cop, sweet_spot=float(sweet[i]),
            rigid_sweet_spot=None if not np.isfinite(rigid_ss) else float(rigid_ss),
            at_window_edge=bool(edge[i]),
            sweep=Sweep(grid.tolist(), coarse.exit_speed[i].tolist(), m_coarse[i].tolist())))

    value = AGGREGATES[p["aggregate"]](values)
    limit = tol = None
    verdict = margin = None
    if p["limit"]:
        limit, tol = p["limit"]["max"], p["limit"]["tolerance"]
        margin = limit + tol - value
        verdict = "pass" if margin >= 0 else "fail"
    if engine.name == "rigid" and p["metric"] == "bpf":
        warnings.append("rigid engine: the ball-bat COR equals the ball's COR, so BPF is 1 by "
                        "construction; use the flexible engine for a meaningful BPF")
    inputs = [InputFile("bat", built.spec.name, built.spec.path, built.spec.sha256),
              InputFile("protocol", protocol.id, protocol.path, protocol.sha256),
              InputFile("ball", ball.name, ball.path, ball.sha256)]
    return RunResult(
        protocol=protocol.id, protocol_title=p["title"], protocol_version=p["version"],
        protocol_reference=p["reference"], protocol_notes=p["notes"] or "", bat=built.spec.name,
        ball=ball.name, metric=p["metric"], aggregate=p["aggregate"], value=value, limit=limit,
        tolerance=tol or 0.0, margin=margin, verdict=verdict, impact_rule=loc["rule"],
        engine=engine.name, engine_settings=engine.settings(), support=support,
        mass_properties=mp, conditions=results, inputs=inputs, batcert_version=__version__,
        created=created or _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        warnings=warnings)
