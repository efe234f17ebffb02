"""What the CLI commands do, without the CLI: load inputs, run protocols, inspect bats and balls.

Everything here returns plain data; the click layer (cli.py) only parses options, calls these and
hands results to console.py and the report writers.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from batcert.errors import InputError, Problem
from batcert.physics import rigid
from batcert.physics.engine import get_engine
from batcert.results import RunResult
from batcert.runner.runner import run_protocol
from batcert.specs.ball import BallSpec, load_ball
from batcert.specs.bat import BuiltBat, build_bat, load_bat
from batcert.specs.protocol import ProtocolSpec, load_protocol
from batcert.specs.resolve import NotFound, resolve, shipped_names
from batcert.specs.schema import lookup
from batcert.specs.yamlio import load_yaml


@dataclass(frozen=True)
class ProtocolInputs:
    protocol: ProtocolSpec
    ball: BallSpec


def load_bat_any(value: str) -> BuiltBat:
    """A bat from a path or a shipped name (e.g. ``ash-34``), built and reconciled."""
    return build_bat(load_bat(resolve("bat", value)))


def load_protocol_any(value: str) -> ProtocolInputs:
    return protocol_inputs(load_protocol(resolve("protocol", value)))


def protocol_inputs(protocol: ProtocolSpec) -> ProtocolInputs:
    """A loaded protocol with its ball."""
    return ProtocolInputs(protocol, load_ball(protocol_ball_path(protocol)))


def protocol_ball_path(protocol: ProtocolSpec) -> Path:
    """The protocol's ball file; an unknown ball is invalid input in the protocol file (its
    `ball:` line), not a usage error."""
    try:
        return resolve("ball", protocol.values["ball"], relative_to=Path(protocol.path))
    except NotFound as exc:
        line = lookup(load_yaml(protocol.path), "ball")[0]
        raise InputError([Problem(protocol.path, line, "ball", str(exc))]) from None


def run(bat: BuiltBat, protocols: list[ProtocolInputs], engine: str = "flexible",
        **engine_options) -> list[RunResult]:
    eng = get_engine(engine, **engine_options)
    results = []
    for p in protocols:
        result = run_protocol(bat, p.protocol, p.ball, eng)
        result.extras.update(_modes_info(bat, p.protocol.values["pivot"]))
        results.append(result)
    return results


def inspect_bat(built: BuiltBat, pivot: float | None = None, with_modes: bool = True) -> dict:
    """Mass properties (SI) about the pivot (default: the measured pivot, else 6 in), the COP
    (Smith 2001 Eq. 4), and when available the free-free bending modes."""
    m = built.model
    if pivot is None:
        pivot = built.measured.pivot if built.measured else 0.1524
    moi = m.moi_about(pivot)
    cg = m.cg_from(pivot)
    info = {
        "name": built.spec.name, "file": built.spec.path, "sha256": built.spec.sha256,
        "construction": m.construction, "material": m.material.name,
        "mass": m.mass, "length": m.length, "pivot": pivot, "cg": cg, "moi_pivot": moi,
        "cop": float(rigid.centre_of_percussion(moi, m.mass, cg)),
        "balance_point": m.balance_point, "moi_cg": m.moi_about(m.balance_point),
        "barrel_diameter": m.barrel_outer_diameter(),
        "geometry": {"mass": built.geometry.mass, "cg": built.geometry.cg_from(pivot),
                     "moi_pivot": built.geometry.moi_about(pivot)},
        "reconciliation": {"method": built.reconciliation.method,
                           "description": built.reconciliation.description,
                           "corrections": built.reconciliation.corrections},
    }
    if with_modes:
        info.update(_modes_info(built, pivot))
    return info


def _modes_info(built: BuiltBat, pivot: float) -> dict:
    """Free-free bending frequencies [Hz] and node positions [m from knob] of the first modes;
    for hollow bats the barrel's hoop frequency and spring-mass at the middle of the barrel."""
    from batcert.physics.beam import cached_modes, mode_nodes
    modes = cached_modes(built.model, "free", pivot, 8)
    out: dict = {"modes_hz": modes.frequencies_hz.tolist(),
                 "mode_nodes": [mode_nodes(modes, j).tolist() for j in (1, 2, 3, 4)]}
    m = built.model
    if m.construction == "hollow":
        from batcert.physics import barrel
        z0, z1 = barrel.barrel_region(m)
        zc = 0.5 * (z0 + z1)  # middle of the full-diameter barrel, where the hoop mode peaks
        i = int(np.searchsorted(m.z_edges, zc, side="right") - 1)  # the slice holding zc
        k, mass = barrel.barrel_spring_at(m, [zc])  # what the engine uses there
        out["barrel"] = {"start": z0, "end": z1, "position": zc,
                         "outer_diameter": float(m.outer_diameter[i]),
                         "wall": float(m.wall_thickness[i]),
                         "effective_width": m.barrel_effective_width
                         or barrel.default_effective_width(m),
                         "hoop_frequency_hz": float(barrel.hoop_frequency(
                             0.5 * m.outer_diameter[i], m.wall_thickness[i], m.material)),
                         "stiffness": float(k[0]), "mass": float(mass[0])}
    return out


def inspect_ball(ball: BallSpec, speeds=(1.0, 11.0, 25.9, 45.0, 58.0, 60.0, 67.0)) -> dict:
    """The ball spec and its rigid-wall response against impact speed (SI): COR, contact time,
    99 %-impulse collision time, maximum compression and peak force (Nathan 2000 law with
    e0 = the spec's COR at each speed)."""
    from batcert.physics import contact
    b = ball.model
    wall = contact.ball_wall_impact(b, np.asarray(speeds, dtype=float))
    return {"name": b.name, "file": ball.path, "sha256": ball.sha256, "mass": b.mass,
            "radius": b.radius, "contact_model": b.contact_model, "k1": b.k1, "alpha": b.alpha,
            "cor_points": [list(p) for p in zip(b.cor_speeds, b.cor_values)],
            "speeds": list(map(float, speeds)), "cor": wall.cor.tolist(),
            "contact_time": wall.contact_time.tolist(),
            "collision_time": wall.collision_time.tolist(),
            "max_compression": wall.max_compression.tolist(),
            "peak_force": wall.peak_force.tolist()}


def detect_kind(path: str) -> str:
    """Guess a spec file's kind from its keys (bat, ball, protocol, league)."""
    data = load_yaml(path)
    if "conditions" in data or "metric" in data:
        return "protocol"
    if "rules" in data:
        return "league"
    if "protocols" in data:
        return "study"
    if "construction" in data or "profile" in data:
        return "bat"
    if "cor" in data or "contact" in data:
        return "ball"
    return "bat"


def validate_file(path: str) -> str:
    """Load (and for bats, build and reconcile) a spec; raise InputError on any problem."""
    kind = detect_kind(path)
    if kind == "protocol":
        load_ball(protocol_ball_path(load_protocol(path)))
    elif kind == "ball":
        load_ball(path)
    elif kind == "league":
        from batcert.specs.league import load_league
        load_league(path)
    elif kind == "study":
        from batcert.specs.study import load_study
        load_study(path)
    else:
        build_bat(load_bat(path))
    return kind


def list_protocols() -> list[dict]:
    out = []
    for name, path in shipped_names("protocol").items():
        p = load_protocol(path).values
        out.append({"id": p["id"], "title": p["title"], "metric": p["metric"],
                     "rule": p["impact_location"]["rule"],
                     "limit": p["limit"]["max"] if p["limit"] else None,
                     "conditions": [c["name"] for c in p["conditions"]], "path": str(path)})
    return out
