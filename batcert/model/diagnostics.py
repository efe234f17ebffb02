"""What a built bat's dynamics look like: free-free bending modes with their nodes and, for a
hollow bat, its barrel shell. Shown by ``inspect`` and recorded with every run."""

from __future__ import annotations

import numpy as np

from batcert.model.build import BuiltBat


def bat_dynamics(built: BuiltBat, pivot: float, barrel: bool = True) -> dict:
    """Free-free bending frequencies [Hz] and node positions [m from knob] of the first modes;
    for hollow bats the barrel (:func:`barrel_summary`) unless ``barrel`` is false (an engine
    without one: the shell is then not built)."""
    from batcert.physics.modes import cached_modes, mode_nodes
    modes = cached_modes(built.model, "free", pivot, 8)
    out: dict = {"modes_hz": modes.frequencies_hz.tolist(),
                 "mode_nodes": [mode_nodes(modes, j).tolist() for j in (1, 2, 3, 4)]}
    if barrel and built.model.construction == "hollow":
        out["barrel"] = barrel_summary(built)
    return out


SUMMARY_MAX_FREQUENCY = 12_000.0  # the summary lists modes up to this [Hz]


def barrel_summary(built: BuiltBat) -> dict:
    """The barrel shell of a hollow bat (SI): its extent, wall and diameter in the middle of the
    full-diameter barrel, the model's lowest frequencies per circumferential order (free bat), the hoop
    (n = 2) frequency against the measured one, the thin-ring frequency for comparison, and
    the calibration applied."""
    from batcert.physics import barrel
    m = built.model
    sh = barrel.barrel_shell(m)
    assert sh is not None  # a hollow bat has a wall
    hollow_outer = np.where(m.inner_diameter > 0, m.outer_diameter, -np.inf)
    full = np.flatnonzero(hollow_outer >= 0.99 * hollow_outer.max())  # full-diameter slices
    i = int(full[full.size // 2])  # the middle of the barrel
    wall = float(m.wall_thickness[i])
    outer = float(m.outer_diameter[i])
    modes = barrel.cached_barrel_modes(m, SUMMARY_MAX_FREQUENCY)  # the engine's, cut higher
    assert modes is not None
    orders = {f"n={n}": (modes.omega[modes.mode_orders == n][:3] / (2 * np.pi)).tolist()
              for n in (0, 2, 3, 4)}
    measured = built.spec.measured
    return {"start": float(sh.z[0]), "end": float(sh.z[-1]), "tip_end": m.barrel_end,
            "outer_diameter": outer, "wall": wall,
            "hoop_frequency_hz": barrel.hoop_frequency(m),
            "measured_hoop_frequency_hz": measured.hoop_frequency if measured else None,
            "ring_frequency_hz": _ring(m, i),
            "modes_hz": orders, "stiffness_scale": m.barrel_stiffness_scale,
            "mass_scale": m.barrel_mass_scale,
            "calibrated": bool(measured and (measured.hoop_frequency is not None
                                             or measured.barrel_compression is not None))}


def _ring(m, i: int) -> float:
    """The thin-ring frequency of slice ``i``'s wall (its layup's ``D22`` and nominal mass per
    area where it has one, else the material's), with the barrel's calibration [Hz]."""
    from batcert.physics import shell
    wall, outer = float(m.wall_thickness[i]), float(m.outer_diameter[i])
    stack = m.layup.stack_of(i) if m.layup is not None else None
    if stack is None:
        return float(shell.ring_frequency(
            0.5 * (outer - wall), wall, m.material.youngs_modulus * m.barrel_stiffness_scale,
            m.material.density * m.barrel_mass_scale, m.material.poisson_ratio))
    return float(shell.ring_frequency_of(0.5 * (outer - wall),
                                         stack.law(m.wall_damage)[4, 4] * m.barrel_stiffness_scale,
                                         stack.areal_density * m.barrel_mass_scale))
