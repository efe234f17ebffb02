"""The linear systems of many bats built together when they form a family: bats with the same
mesh of given modes, the same shape and the same wall but for a uniform scale of its density,
and balls of one size and kind (a Monte Carlo's drawn bats and balls,
:mod:`batcert.uncertainty.propagate`). Each member's system is what
:func:`~batcert.engines.flexible_system.linear_system` builds for it alone, to rounding
(tests/engines/test_flexible_family.py); only the work is shared:

- the footprints of all members' impacts in one call;
- the barrel's patch read once on the nominal wall they share
  (:func:`~batcert.physics.barrel.shared_wall`) and scaled per member (exact: a wall whose
  density is scaled has the same modes, their frequencies and gains scaled), instead of a
  barrel looked up per member;
- the shell's coupling tables of all rows together;
- no cache lookups for the members' own modes, which recur nowhere.

Other jobs, and a family whose members turn out not to share their wall, are built one by one.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from batcert.engines.base import Job
from batcert.engines.flexible_system import (
    Extras,
    SystemSettings,
    assemble,
    beam_response,
    check_batch,
    checked_modes,
    damping_ratio,
    extras_of,
    linear_system,
    patch_of,
    shell_table,
)
from batcert.engines.kernel.linear_system import LinearSystem
from batcert.physics import rigid

Built = tuple[LinearSystem, Extras]


def linear_systems(s: SystemSettings, jobs: list[Job], compressions: list[np.ndarray]
                   ) -> list[Built]:
    """Each job's :func:`~batcert.engines.flexible_system.linear_system` (its batch flat,
    ``compressions[i]`` its ``u_rep``), the jobs of one family built together (module
    notes)."""
    out: list[Built | None] = [None] * len(jobs)
    families: dict[tuple, list[int]] = {}
    for i, job in enumerate(jobs):
        families.setdefault(_family_key(job, i), []).append(i)
    for members in families.values():
        built = None
        if len(members) > 1:
            built = _family([jobs[i] for i in members], s, [compressions[i] for i in members])
        if built is None:
            built = [linear_system(s, jobs[i].bat, jobs[i].ball, jobs[i].pivot, jobs[i].batch,
                                   jobs[i].support, jobs[i].modes, compressions[i])
                     for i in members]
        for i, b in zip(members, built, strict=True):
            out[i] = b
    return out  # type: ignore[return-value]


def _family_key(job: Job, index: int) -> tuple:
    """Jobs with the same key may form a family (checked further by :func:`_family`): given
    modes on one mesh (the same node array), one support and pivot, the same shape of bat and
    size and kind of ball."""
    if job.modes is None:
        return ("alone", index)
    bat, ball = job.bat, job.ball
    return (job.support, float(job.pivot), id(job.modes.z), job.modes.omega.size,
            bat.construction, float(ball.radius), type(ball.law),
            *(np.asarray(a, dtype=float).tobytes()
              for a in (bat.z_edges, bat.outer_diameter, bat.wall_thickness)))


def _family(jobs: list[Job], s: SystemSettings, compressions: list[np.ndarray]
            ) -> list[Built] | None:
    """The members' systems built together, or None if their walls differ otherwise than by a
    density scale (module notes). Hollow members that keep different shell modes below the
    cut (a drawn mass moves a mode across it) are built in one group per set of kept modes."""
    if jobs[0].bat.construction != "hollow":
        return _built(jobs, s, compressions, None)
    from batcert.physics import barrel
    shared = barrel.shared_wall([j.bat for j in jobs], s.shell_max_frequency)
    if shared is None:
        return None
    base, stiffness, masses = shared
    omega = base.omega[None, :] * np.sqrt(stiffness / masses)[:, None]  # (members, modes)
    keeps = omega <= 2 * np.pi * s.shell_max_frequency
    groups: dict[bytes, list[int]] = {}
    for i, keep in enumerate(keeps):
        groups.setdefault(keep.tobytes(), []).append(i)
    out: list[Built | None] = [None] * len(jobs)
    for members in groups.values():
        keep = keeps[members[0]]
        wall = (base, stiffness, masses[members], omega[members][:, keep], keep)
        for i, b in zip(members, _built([jobs[i] for i in members], s,
                                        [compressions[i] for i in members], wall),
                        strict=True):
            out[i] = b
    return out  # type: ignore[return-value]


def _built(jobs: list[Job], s: SystemSettings, compressions: list[np.ndarray], wall
           ) -> list[Built]:
    """The members' systems (``wall``: their shared wall, stiffness and mass scales, kept
    shell frequencies and which modes those are; None for solid bats)."""
    first = jobs[0]
    sizes = np.array([len(j.batch) for j in jobs])
    bounds = np.concatenate([[0], np.cumsum(sizes)])
    which = np.repeat(np.arange(len(jobs)), sizes)
    modes = []
    for j in jobs:
        check_batch(j.bat, j.pivot, j.batch, j.support)
        modes.append(checked_modes(s, j.bat, j.support, j.pivot, j.modes))
    r = np.concatenate([j.batch.impact_location for j in jobs])
    recoil = np.concatenate([rigid.recoil_factor(j.bat, j.ball.mass, j.pivot,
                                                 j.batch.impact_location, j.support)
                             for j in jobs])
    patch = patch_of(s, first.bat, first.ball, first.pivot + r,
                     np.concatenate([j.batch.relative_speed for j in jobs]), recoil,
                     np.concatenate(compressions))
    beam = [beam_response(j.bat, m, patch.points[a:b], patch.weights[a:b], bool(s.residual))
            for j, m, a, b in zip(jobs, modes, bounds[:-1], bounds[1:], strict=True)]
    phi = np.concatenate([p for p, _ in beam])
    residual = np.concatenate([c for _, c in beam])
    shell = None if wall is None else _shared_shell(wall, patch, which)
    nr = modes[0].n_rigid
    bending = np.stack([m.omega[nr:] for m in modes])[which]
    system, om_res = assemble(s, patch, phi, residual, shell, bending,
                              np.array([damping_ratio(j.bat) for j in jobs])[which],
                              np.array([j.ball.mass for j in jobs], dtype=float)[which])
    extras = extras_of(modes[0], phi, system, patch,
                       first.bat.wall_thickness[first.bat.slice_at(first.pivot + r)], shell, 0.0)
    return [(system.rows(a, b), replace(extras.rows(a, b), modes=m,
                                        residual_omega=float(om_res[a])))
            for m, a, b in zip(modes, bounds[:-1], bounds[1:], strict=True)]


def _shared_shell(wall, patch, which: np.ndarray):
    """:func:`~batcert.engines.flexible_system.shell_table` of every row, its barrel the shared
    nominal wall scaled by its member's mass (:meth:`BarrelModes.scaled`: frequencies by
    ``sqrt(stiffness / mass)``, gains by ``1 / sqrt(mass)``, flexibility by ``1 /
    stiffness``)."""
    from batcert.physics.barrel import BarrelPatch, barrel_patch
    base, stiffness, masses, omega, keep = wall
    nominal = barrel_patch(base, patch.points, patch.weights)
    bpatch = BarrelPatch(omega[which], nominal.axial[:, keep] / np.sqrt(masses)[which, None],
                         nominal.flexibility / stiffness, nominal.orders,
                         base.mode_orders[keep])
    return shell_table(bpatch, patch)
