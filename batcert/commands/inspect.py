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
    if with_modes:
        info.update(bat_dynamics(built, pivot))
    return rounded(info)


SIGNIFICANT = 6  # digits kept by inspect: more than the inputs (3-4 digits) or the engine carry


def rounded(data, digits: int = SIGNIFICANT):
    """Every float in ``data`` rounded to ``digits`` significant digits, so that printed numbers
    show what they carry (0.429, not 0.4289999999999998)."""
    return map_floats(data, lambda x: float(f"{x:.{digits}g}") if np.isfinite(x) else x)


def inspect_ball(ball: BallSpec, speeds=(1.0, 11.0, 25.9, 45.0, 58.0, 60.0, 67.0)) -> dict:
    """The ball spec and its rigid-wall response against impact speed (SI): COR, contact time,
    99 %-impulse collision time, maximum compression and peak force (Nathan 2000 law with
    e0 = the spec's COR at each speed)."""
    from batcert.physics import contact
    b = ball.model
    wall = contact.ball_wall_impact(b, np.asarray(speeds, dtype=float))
    return rounded({"name": b.name, "file": ball.path, "sha256": ball.sha256, "mass": b.mass,
            "radius": b.radius, "contact_model": b.contact_model, "k1": b.k1, "alpha": b.alpha,
            "cor_points": [list(p) for p in zip(b.cor_speeds, b.cor_values, strict=True)],
            "speeds": list(map(float, speeds)), "cor": wall.cor.tolist(),
            "contact_time": wall.contact_time.tolist(),
            "collision_time": wall.collision_time.tolist(),
            "max_compression": wall.max_compression.tolist(),
            "peak_force": wall.peak_force.tolist()})
