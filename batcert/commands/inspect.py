"""``batcert inspect``: a bat's mass properties and modes, or a ball's rigid-wall response."""

from __future__ import annotations

from dataclasses import asdict

import numpy as np

from batcert.conventions import DEFAULT_PIVOT
from batcert.errors import UsageProblem
from batcert.model.build import BuiltBat
from batcert.model.diagnostics import bat_dynamics
from batcert.model.mass import mass_properties, pivot_problem
from batcert.results.serialise import map_floats
from batcert.specs.ball import BallSpec


def inspect_bat(built: BuiltBat, pivot: float | None = None, with_modes: bool = True) -> dict:
    """Mass properties (SI) about the pivot (default: the measured pivot, else 6 in), the COP
    (Smith 2001 Eq. 4), and when available the free-free bending modes."""
    m = built.model
    wrong = pivot_problem(built.model, pivot) if pivot is not None else None
    if wrong:
        raise UsageProblem(f"--pivot: {wrong}")
    if pivot is None:  # the measured pivot, unless it is no test pivot (e.g. beyond the CG)
        pivot = built.measured.pivot if built.measured else DEFAULT_PIVOT
        if pivot_problem(built.model, pivot):
            pivot = DEFAULT_PIVOT
    mp = mass_properties(built, pivot)
    info = {
        "name": built.spec.name, "file": built.spec.path, "sha256": built.spec.sha256,
        "construction": m.construction, "material": m.material.name,
        "mass": mp.mass, "length": m.length, "pivot": pivot, "cg": mp.cg,
        "moi_pivot": mp.moi_pivot, "cop": float(mp.cop), "balance_point": m.balance_point,
        "moi_cg": m.moi_about(m.balance_point), "barrel_diameter": m.barrel_outer_diameter(),
        "geometry": {"mass": mp.geometry_mass, "cg": mp.geometry_cg,
                     "moi_pivot": mp.geometry_moi_pivot},
        "reconciliation": {k: v for k, v in asdict(built.reconciliation).items()},
    }
    if built.spec.layup:
        info["layup"] = layup_summary(built)
    if with_modes:
        info.update(bat_dynamics(built, pivot))
    return rounded(info)


def layup_summary(built: BuiltBat) -> list[dict]:
    """Each ``layup`` span of the bat: its walls and plies as the file gives them, and the
    stack's thickness, mass per area and wall law (A [N/m], B [N], D [N m]; x along the bat,
    y around it) new and after the model's break-in."""
    out = []
    for start, end, stack in built.spec.layup:
        law = stack.law(built.model.wall_damage)
        out.append({
            "start": start, "end": end, "thickness": stack.thickness,
            "areal_density": stack.areal_density,
            "walls": [[{"material": layer.ply.name, "angle_deg": float(np.degrees(layer.angle)),
                        "balanced": layer.balanced, "thickness": layer.thickness}
                       for layer in wall] for wall in stack.walls],
            "a": law[:3, :3].tolist(), "b": law[:3, 3:].tolist(), "d": law[3:, 3:].tolist()})
    return out


SIGNIFICANT = 6  # digits kept by inspect: more than the inputs (3-4 digits) or the engine carry


def rounded(data, digits: int = SIGNIFICANT):
    """Every float in ``data`` rounded to ``digits`` significant digits, so that printed numbers
    show what they carry (0.429, not 0.4289999999999998)."""
    return map_floats(data, lambda x: float(f"{x:.{digits}g}") if np.isfinite(x) else x)


# the cylinder inspect sets beside the flat wall: the largest barrel of the baseball rules
# (2 5/8 in, NCAA/NFHS BBCOR), the surface of a BBCOR test
CYLINDER_DIAMETER = 2.625 * 0.0254  # [m]


def inspect_ball(ball: BallSpec, speeds=(1.0, 5.0, 11.0, 20.0, 25.9, 26.8, 30.0, 40.0, 45.0,
                                         50.0, 58.0, 60.8, 67.0, 70.0)) -> dict:
    """The ball spec, its contact law (and fit), each ball test beside the law's value, and
    the ball against a rigid flat wall and a rigid 2 5/8 in cylinder against impact speed
    (SI): COR, contact time, 99 %-impulse collision time, maximum compression, compression at
    separation and peak force (flat), COR, contact time, compression and peak force
    (cylinder)."""
    from batcert.physics.balls.fit import test_values
    from batcert.physics.balls.footprint import stiffness_ratio
    from batcert.specs.ball import ball_tests
    from batcert.specs.resolve import display_path

    b = ball.model
    v = np.asarray(speeds, dtype=float)
    wall = b.law.wall_impact(b.mass, v)  # Nathan's law in closed form, else integrated
    cylinder = b.law.body_impact(b.mass, v, 0.0, history=False,
                                 scale=stiffness_ratio(b.radius, 0.5 * CYLINDER_DIAMETER))
    left = getattr(wall, "separation_compression", np.zeros(v.size))
    tests = ball_tests(ball.tests)
    model = test_values(b.law, tests, b.mass, b.radius) if ball.fit is None else ball.fit.model
    rows = []
    for (key, point), t, m in zip(ball.tests, tests, model, strict=True):
        rows.append({"test": key, "condition": t.condition, "value": t.value,
                     "uncertainty": t.uncertainty or None,
                     "surface_diameter": None if not np.isfinite(t.surface_diameter)
                     else t.surface_diameter, "model": float(m),
                     "residual": float((m - t.value) / t.uncertainty) if t.uncertainty else None,
                     "line": point.line})
    fit = None
    if ball.fit is not None:
        fit = {"chi2": ball.fit.chi2, "dof": ball.fit.dof,
               "parameter_uncertainty": dict(ball.fit.uncertainty),
               "held": list(ball.fit.held)}
    lot = None
    if ball.lot is not None and ball.reference is not None and ball.fit is not None:
        ref = ball.reference
        tested = ball.lot.tested.law.wall_impact(b.mass, v)
        lot = {"bat": display_path(ref.bat), "protocol": display_path(ref.protocol),
               "value": ref.value, "uncertainty": ref.uncertainty, "source": ref.source,
               "shift": ball.lot.shift, "u_shift": ball.lot.u_shift,
               "model_value": ball.lot.model_value, "tested_cor": tested.cor.tolist()}
    return rounded({"name": b.name, "file": ball.path, "sha256": ball.sha256, "mass": b.mass,
                    "radius": b.radius, "contact_model": b.contact_model,
                    "law": {**b.law.describe(), "summary": b.law.summary()}, "fit": fit,
                    "lot_calibration": lot, "tests": rows,
                    "speeds": list(map(float, speeds)), "cor": wall.cor.tolist(),
                    "contact_time": wall.contact_time.tolist(),
                    "collision_time": wall.collision_time.tolist(),
                    "max_compression": wall.max_compression.tolist(),
                    "separation_compression": np.asarray(left).tolist(),
                    "peak_force": wall.peak_force.tolist(),
                    "cylinder": {"diameter": CYLINDER_DIAMETER, "cor": cylinder.cor.tolist(),
                                 "contact_time": cylinder.contact_time.tolist(),
                                 "max_compression": cylinder.max_compression.tolist(),
                                 "peak_force": cylinder.peak_force.tolist()}})
