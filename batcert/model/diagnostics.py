"""What a built bat's dynamics look like: free-free bending modes with their nodes and, for a
hollow bat, the barrel's hoop spring. Shown by ``inspect`` and recorded with every run."""

from __future__ import annotations

import numpy as np

from batcert.model.build import BuiltBat


def bat_dynamics(built: BuiltBat, pivot: float) -> dict:
    """Free-free bending frequencies [Hz] and node positions [m from knob] of the first modes;
    for hollow bats the barrel's hoop frequency and spring-mass at the middle of the barrel."""
    from batcert.physics.modes import cached_modes, mode_nodes
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
