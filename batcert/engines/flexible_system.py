"""The linear part of each impact for the flexible engine (:mod:`batcert.engines.flexible`, whose
module notes give the model): where the ball presses on the bat (:class:`Patch`), the beam's
and the hollow barrel's modes read there, the truncated modes' residual compliance, and for a
hollow bat the coupling of the shell modes that follows the footprint's arc around the barrel.
:func:`linear_system` assembles them into a :class:`~batcert.engines.kernel.linear_system.LinearSystem`
and the :class:`Extras` the outcome needs.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from batcert import workspace
from batcert.engines.base import ImpactBatch
from batcert.engines.kernel.coupling import Coupling
from batcert.engines.kernel.linear_system import LinearSystem
from batcert.physics import rigid
from batcert.physics.ball import BallModel
from batcert.physics.balls import footprint
from batcert.physics.balls.impact1d import wall_mean_compression
from batcert.physics.batmodel import BatModel
from batcert.physics.modes import Modes, beam_of

SUPPORTS = ("pinned", "free")
_PIVOT_CLEARANCE = 1e-3  # an impact closer than this to the pivot is refused [m]
# the compressions, in multiples of u_rep, at which a hollow barrel's coupling to the ball is
# tabulated (linear between them, held beyond); _REFERENCE is u_rep itself
_GRID = np.linspace(0.0, 2.0, 41)
_REFERENCE = 20


@dataclass(frozen=True)
class SystemSettings:
    """The engine's settings that shape the linear system (:class:`~batcert.engines.flexible.
    FlexibleEngine` documents each)."""

    n_modes: int
    refine: int
    residual: bool
    shell_max_frequency: float
    contact_surface: str
    contact_patch: bool
    patch_points: int
    footprint: str = "fe-finite-strain"  # the footprint rule (footprint_rules.RULES)


@dataclass(frozen=True)
class Extras:
    """What an impact's outcome needs beyond its linear system; the arrays hold one row per
    impact (:meth:`rows` takes some)."""

    modes: Modes  # the beam's modes
    phi: np.ndarray  # the beam's modes read over each patch, rigid first, (p, modes)
    n_bending: int  # bending modes among the system's columns (first)
    beam_rigid_mass: np.ndarray  # the rigid modes as one mass at each impact [kg], (p,)
    contact_scale: np.ndarray  # the ball law's stiffness factor on the surface [-], (p,)
    wall: np.ndarray  # the wall's thickness at each impact [m], (p,) (half the diameter where solid)
    shell_static: np.ndarray  # the barrel's static compliance under the footprint [m/N], (p,)
    n_shell: int = 0  # shell modes among the columns (after the bending modes)
    residual_omega: float = 0.0  # the residual pseudo-mode's frequency [rad/s]; 0: none

    def rows(self, a: int, b: int) -> Extras:
        """The impacts ``a .. b`` only."""
        return replace(self, **{f.name: getattr(self, f.name)[a:b] for f in fields(self)
                                if f.name in _ROW_FIELDS})


_ROW_FIELDS = ("phi", "beam_rigid_mass", "contact_scale", "wall", "shell_static")


def rigid_mode_velocities(modes: Modes, pivot: float) -> np.ndarray:
    """Rigid-mode velocities that give rotation about ``pivot`` at 1 rad/s [sqrt(kg) m/s].

    Solves ``sum_r qdot_r phi_r(z) = z - pivot`` at the mode nodes (least squares; exact, since
    the rigid modes span linear motions). For a free bat this expresses rotation about the
    instantaneous centre ``pivot`` in the translation and rotation modes. Shape (n_rigid,).
    """
    shapes = modes.shapes[:modes.n_rigid].T  # (nodes, n_rigid)
    sol, *_ = np.linalg.lstsq(shapes, modes.z - pivot, rcond=None)
    return sol


@dataclass(frozen=True)
class Patch:
    """Where the ball presses on the bat at each of ``p`` impacts (:mod:`~batcert.physics.
    balls.footprint`): Hertz's elliptical footprint of the ball on the barrel. Along the bat
    the force is spread with the parabolic weight of Hertz's pressure over ``2 a``, at the
    compression ``u_rep`` that the ball has on average (weighted by the force) against a rigid
    body of the impact's effective mass; around a hollow barrel over the arc ``2 b(u)``.

    The footprint's size along the bat changes the exit speed by at most about 1e-3 between
    its smallest and largest extent during an impact (docs/validation.md), so it is held at
    ``u_rep``; around the barrel it changes the shell modes' coupling by tens of per cent."""

    points: np.ndarray  # axial sample points [m from knob], (p, K)
    weights: np.ndarray  # their weights, each row summing to 1, (p, K)
    radius: np.ndarray  # the bat's outer radius at each impact [m], (p,)
    surface: np.ndarray  # the contact surface's radius (inf: flat) [m], (p,)
    scale: np.ndarray  # the ball law's stiffness factor on that surface [-], (p,)
    compression: np.ndarray  # u_rep [m], (p,)
    ball_radius: float  # [m]
    rule: str = "hertz"  # the footprint rule (footprint_rules.RULES)

    def half_angle(self, compression) -> np.ndarray:
        """Half-angle [rad] of the footprint around the barrel at ``compression`` [m]:
        ``b(u) / R``, at most pi/2 (on a flat surface: Hertz's circle of the same size)."""
        u = np.asarray(compression, dtype=float)
        extra = (1,) * (u.ndim - 1)  # (p, grid): every impact's grid of compressions
        _, around = footprint.ellipse(self.ball_radius, self.surface.reshape(-1, *extra), u,
                                      self.rule)
        return np.minimum(around / self.radius.reshape(-1, *extra), 0.5 * np.pi)


def mean_compression(ball: BallModel, speed, recoil, scale) -> np.ndarray:
    """Where the footprint along the bat is taken [m], (n,): the impulse-weighted mean
    compression of the ball fired at a rigid flat wall at ``v / sqrt((1 + k) gamma)``, the
    speed at which the wall squeezes it as the impact's rigid body of effective-mass ratio
    ``k`` and surface factor ``gamma`` does (the same for a rate-free elastic law: the same
    ``mu v^2 / (gamma k0)``), integrated for the distinct speeds
    (:func:`~batcert.physics.balls.impact1d.wall_mean_compression`)."""
    equal = np.asarray(speed, float) / np.sqrt((1.0 + np.asarray(recoil, float))
                                               * np.asarray(scale, float))
    unique, which = np.unique(equal, return_inverse=True)
    u = wall_mean_compression([(ball.law, float(ball.mass))], np.zeros(unique.size, int), unique)
    return u[np.asarray(which).ravel()]


def surface(s: SystemSettings, bat: BatModel, ball: BallModel, z: np.ndarray):
    """The bat's outer radius at each impact [m], the contact surface's radius (inf: flat)
    and the ball law's stiffness factor on it [-] in the small-compression limit (Hertz's;
    :func:`scale_at` at the impact's compression)."""
    radius = 0.5 * np.asarray(bat.outer_diameter, dtype=float)[bat.slice_at(z)]
    on = radius if s.contact_surface == "cylinder" else np.full(z.size, np.inf)
    scale = np.asarray(footprint.stiffness_ratio(ball.radius, on), dtype=float)
    return radius, on, np.broadcast_to(scale, z.shape).copy()


def scale_at(rule: str, ball: BallModel, on: np.ndarray, compression) -> np.ndarray:
    """The ball law's stiffness factor on the surfaces ``on`` [-] at the compressions ``u_rep``
    [m] (the footprint rule's, :func:`~batcert.physics.balls.footprint.stiffness_ratio`): the
    factor is held over an impact, at the compression where its footprint is taken."""
    return np.asarray(footprint.stiffness_ratio(ball.radius, on, compression, rule),
                      dtype=float).reshape(np.shape(on))


def patch_compression(rule: str, ball: BallModel, on: np.ndarray, scale0: np.ndarray,
                      speed, recoil) -> tuple[np.ndarray, np.ndarray]:
    """``u_rep`` [m] and the stiffness factor there [-] of each impact: :func:`mean_compression`
    with Hertz's factor ``scale0``, the rule's factor there, and ``u_rep`` again with it (one
    fixed-point pass: the factor moves ``u_rep`` by a few per cent, which moves the factor by
    a few tenths of one). With the footprint ``rule`` ``hertz``: ``u_rep`` with ``scale0``.
    The rigid engine takes its factor here too."""
    u = mean_compression(ball, speed, recoil, scale0)
    if rule == "hertz":
        return u, scale0
    u = mean_compression(ball, speed, recoil, scale_at(rule, ball, on, u))
    return u, scale_at(rule, ball, on, u)


def group_compressions(s: SystemSettings, jobs: list, groups: list[list[int]]) -> list[np.ndarray]:
    """Each group's ``u_rep`` (:func:`patch_compression`; ``jobs``: the engine's jobs, ``groups``:
    lists of their indices sharing bat, ball, pivot and support), the groups of one ball law
    in a single integration per pass: a Monte Carlo's draws, each a ball of its own, cost one."""
    from batcert.engines import passes
    setup = []  # per group: ball, speed, recoil, surface radius, Hertz's factor
    for members in groups:
        j = jobs[members[0]]
        batch = passes.concatenate([jobs[i].batch for i in members])
        z = j.pivot + batch.impact_location
        recoil = rigid.recoil_factor(j.bat, j.ball.mass, j.pivot, batch.impact_location, j.support)
        _, on, scale = surface(s, j.bat, j.ball, z)
        setup.append((j.ball, batch.relative_speed, recoil, on, scale))
    u = _wall_compressions(setup, [g[4] for g in setup])
    if s.footprint == "hertz":
        return u
    return _wall_compressions(setup, [scale_at(s.footprint, g[0], g[3], ug)
                                      for g, ug in zip(setup, u, strict=True)])


def _wall_compressions(setup: list, scales: list[np.ndarray]) -> list[np.ndarray]:
    """:func:`mean_compression` of every group of ``setup`` with its ``scales``, one
    integration per ball law."""
    rows: dict[type, list] = {}  # law class -> [(group, law, mass, speeds)]
    for g, ((ball, speed, recoil, _, _), scale) in enumerate(zip(setup, scales, strict=True)):
        equal = speed / np.sqrt((1.0 + recoil) * scale)
        rows.setdefault(type(ball.law), []).append((g, ball.law, float(ball.mass), equal))
    out: list[np.ndarray] = [np.empty(0)] * len(setup)
    for parts in rows.values():
        distinct: dict[tuple, int] = {}
        which = np.concatenate([np.full(p[3].size, distinct.setdefault((p[1], p[2]), len(distinct)))
                                for p in parts])
        u = wall_mean_compression(list(distinct), which, np.concatenate([p[3] for p in parts]))
        start = 0
        for g, _, _, equal in parts:
            out[g] = u[start:start + equal.size]
            start += equal.size
    return out


def patch_of(s: SystemSettings, bat: BatModel, ball: BallModel, z: np.ndarray,
             speed: np.ndarray, recoil: np.ndarray, compression: np.ndarray | None = None
             ) -> Patch:
    """Each impact's :class:`Patch` (the class notes; ``recoil``: the bat's effective-mass
    ratio ``k`` at each impact; ``compression``: ``u_rep`` when already known)."""
    edges = np.asarray(bat.z_edges, dtype=float)
    radius, on, scale = surface(s, bat, ball, z)
    if compression is None:
        u_rep, scale = patch_compression(s.footprint, ball, on, scale, speed, recoil)
    else:
        u_rep = np.asarray(compression, dtype=float)
        scale = scale_at(s.footprint, ball, on, u_rep)
    along, _ = footprint.ellipse(ball.radius, on, u_rep, s.footprint)
    if not s.contact_patch:
        return Patch(z[:, None], np.ones((z.size, 1)), radius, on, scale, u_rep, ball.radius,
                     s.footprint)
    # keep the patch centred on the impact point: shrink it near the bat's ends
    half = np.minimum(along, np.minimum(z - edges[0], edges[-1] - z))
    xi, w = footprint.axial_weights(s.patch_points)
    points = z[:, None] + half[:, None] * xi[None, :]
    return Patch(points, np.broadcast_to(w, points.shape), radius, on, scale, u_rep,
                 ball.radius, s.footprint)


def linear_system(s: SystemSettings, bat: BatModel, ball: BallModel, pivot: float,
                  batch: ImpactBatch, support: str = "pinned", modes: Modes | None = None,
                  compression: np.ndarray | None = None) -> tuple[LinearSystem, Extras]:
    """Check the batch and build each impact's :class:`LinearSystem` and :class:`Extras`
    (:meth:`batcert.engines.flexible.FlexibleEngine.linear_system`)."""
    check_batch(bat, pivot, batch, support)
    z = pivot + batch.impact_location
    modes = checked_modes(s, bat, support, pivot, modes)
    recoil = rigid.recoil_factor(bat, ball.mass, pivot, batch.impact_location, support)
    patch = patch_of(s, bat, ball, z, batch.relative_speed, recoil, compression)
    phi, residual = workspace.current().call(  # the beam alone: barrel variants share it
        "beam-response", beam_response, beam_of(bat), modes, patch.points, patch.weights,
        bool(s.residual), rows=patch.points.shape[0])
    shell = None
    if bat.construction == "hollow":
        from batcert.physics import barrel
        walls = barrel.cached_barrel_modes(bat, s.shell_max_frequency)
        if walls is not None:
            shell = shell_table(barrel.barrel_patch(walls, patch.points, patch.weights), patch)
    nr = modes.n_rigid
    system, om_res = assemble(s, patch, phi, residual, shell,
                              np.broadcast_to(modes.omega[nr:], (z.size, phi.shape[1] - nr)),
                              np.full(z.size, damping_ratio(bat)), np.full(z.size, ball.mass))
    return system, extras_of(modes, phi, system, patch, bat.wall_thickness[bat.slice_at(z)],
                             shell, float(om_res[0]) if om_res.size else 0.0)


def extras_of(modes: Modes, phi: np.ndarray, system: LinearSystem, patch: Patch,
              wall: np.ndarray, shell, residual_omega: float) -> Extras:
    """The :class:`Extras` of impacts whose ``system`` :func:`assemble` built from ``phi`` and
    ``shell`` (its :func:`shell_table`; None for a solid bat); ``wall``: the wall's thickness
    at each impact [m]."""
    return Extras(modes, phi, phi.shape[1] - modes.n_rigid, system.rigid_mass, patch.scale,
                  wall, np.zeros(phi.shape[0]) if shell is None else shell[2],
                  0 if shell is None else shell[0].axial.shape[1], residual_omega)


def checked_modes(s: SystemSettings, bat: BatModel, support: str, pivot: float,
                  modes: Modes | None) -> Modes:
    """``modes``, or the bat's own (cached) when None; refuses modes of another support or
    pivot."""
    if modes is None:
        from batcert.physics.modes import cached_modes
        modes = cached_modes(bat, support, pivot, s.n_modes, s.refine)
    if modes.support != support or (support == "pinned" and abs(modes.pivot - pivot) > 1e-9):
        raise ValueError(f"modes are for support {modes.support!r} at {modes.pivot} m, "
                         f"not {support!r} at {pivot} m")
    return modes


def damping_ratio(bat: BatModel) -> float:
    """Every flexible mode's ``zeta``, half the material's loss factor (module notes)."""
    zeta = 0.5 * bat.material.loss_factor
    if not 0 <= zeta < 1:
        raise ValueError(f"loss factor {bat.material.loss_factor} out of range [0, 2)")
    return zeta


def assemble(s: SystemSettings, patch: Patch, phi: np.ndarray, residual: np.ndarray, shell,
             bending: np.ndarray, zeta: np.ndarray, ball_mass: np.ndarray
             ) -> tuple[LinearSystem, np.ndarray]:
    """The :class:`LinearSystem` of impacts whose beam modes read ``phi`` (rigid first) over
    their patches, with frequencies ``bending`` (p, bending modes), the beam's residual
    compliance, and a hollow barrel's :func:`shell_table` (None: solid); and each row's
    residual pseudo-mode frequency [rad/s], (p,) (zeros without ``s.residual``)."""
    p = phi.shape[0]
    nr = phi.shape[1] - bending.shape[1]
    gain, omega = phi[:, nr:], bending
    n_bending = omega.shape[1]
    coupling, n_shell = None, 0
    if shell is not None:  # the shell's modes, their gains following the footprint's arc
        bpatch, table, _ = shell
        n_shell = bpatch.axial.shape[1]
        gain = np.concatenate([gain, bpatch.axial], axis=1)
        omega = np.concatenate([omega, np.broadcast_to(bpatch.omega, bpatch.axial.shape)], 1)
        coupling = _coupling(bpatch, table, omega.shape[1], n_bending,
                             residual if s.residual else None, patch)
        residual = residual + table["residual"][:, _REFERENCE] if s.residual else residual
    om_res = np.zeros(p)
    if s.residual:
        om_res = 2.0 * np.concatenate([omega, bending[:, -1:]], axis=1).max(axis=1)
        gain = _column(gain, om_res * np.sqrt(residual))
        omega = _column(omega, om_res)
    shell_cols = np.zeros(omega.shape[1], bool)
    shell_cols[n_bending:n_bending + n_shell] = True
    return LinearSystem(omega=np.ascontiguousarray(omega), zeta=zeta,
                        gain=np.ascontiguousarray(gain), rigid_mass=1.0 / (phi[:, :nr] ** 2).sum(1),
                        ball_mass=ball_mass, shell_columns=shell_cols if shell is not None else None,
                        coupling=coupling), om_res


def beam_response(bat: BatModel, modes: Modes, points: np.ndarray, weights: np.ndarray,
                  residual: bool) -> tuple[np.ndarray, np.ndarray]:
    """The modes' shapes averaged over each patch, (p, modes), and the truncated modes'
    residual compliance there, (p,) (zero without ``residual``). :func:`linear_system` has it
    kept by the active workspace (kind ``beam-response``): the patches recur (a barrel's
    variants, the same points in several runs)."""
    from batcert.physics.residual import patch_reader, residual_compliance

    reader = patch_reader(modes.z, points, weights)  # (p, nodes), as Modes.at reads
    phi = reader @ modes.shapes.T
    compliance = np.zeros(points.shape[0])
    if residual:
        compliance = residual_compliance(bat, modes, points, weights, reader=reader)
    return phi, compliance


def shell_table(bpatch, patch: Patch):
    """A hollow bat's wall under each impact's footprint (module notes of the engine): its
    :class:`~batcert.physics.barrel.BarrelPatch`, on the grid of compressions :data:`_GRID` x
    ``u_rep`` the footprint's half-angle around the barrel, every order's factor and the
    shell's residual compliance under it, and its static compliance at ``u_rep``."""
    angles = patch.half_angle(_GRID[None, :] * patch.compression[:, None])  # (p, grid)
    factors, residual, static = bpatch.over(angles)
    table = {"angle": angles, "factors": factors, "residual": residual}
    return bpatch, table, static[:, _REFERENCE]


def _coupling(bpatch, table: dict, columns: int, n_bending: int, beam_residual, patch: Patch
              ) -> Coupling:
    """The groups of a hollow bat's columns whose gains follow the footprint
    (:mod:`batcert.engines.kernel.coupling`): the beam's modes (fixed), the shell's modes order by
    order (factor ``c_n(beta(u))`` of the arc around the barrel; their gains are the axial
    averages, ``c_n = 1``), and the residual pseudo-mode (the square root of the total
    residual compliance at ``u`` over that at ``u_rep``, where its gain is taken)."""
    orders = [int(n) for n in bpatch.mode_orders]
    labels: list = ["beam"]
    starts = [0]
    for i, n in enumerate(orders):
        if i == 0 or n != orders[i - 1]:
            labels.append(("shell", n))
            starts.append(n_bending + i)
    p, points = table["angle"].shape
    factors = [np.ones((p, points))]
    order_row = {n: i for i, n in enumerate(bpatch.orders)}
    for label in labels[1:]:
        factors.append(table["factors"][order_row[label[1]]])
    if beam_residual is not None:
        labels.append("residual")
        starts.append(columns)
        total = beam_residual[:, None] + table["residual"]
        factors.append(np.sqrt(total / total[:, _REFERENCE:_REFERENCE + 1]))
        columns += 1
    spacing = np.maximum(patch.compression, 1e-9) * (_GRID[1] - _GRID[0])
    return Coupling(tuple(labels), (*starts, columns), np.stack(factors, axis=1), spacing)


def check_batch(bat: BatModel, pivot: float, batch: ImpactBatch, support: str) -> None:
    """Refuse what the engine cannot solve: an unknown support, impacts off the bat or at the
    pivot, ball and bat not approaching."""
    if support not in SUPPORTS:
        raise ValueError(f"support must be one of {SUPPORTS}, got {support!r}")
    r = batch.impact_location
    z = pivot + r
    lo, hi = float(bat.z_edges[0]), float(bat.z_edges[-1])
    bad = ~((z >= lo) & (z <= hi))
    if np.any(bad):
        raise ValueError(f"impact location(s) {np.round(r[bad], 4).tolist()} m from the pivot "
                         f"lie outside the bat ({lo - pivot:.4f} to {hi - pivot:.4f} m from "
                         "the pivot)")
    if np.any(np.abs(r) < _PIVOT_CLEARANCE):
        raise ValueError("an impact at the pivot is not defined (the bat cannot recoil and "
                         "Smith 2001 Eqs. 1 and 3 degenerate): keep impacts at least "
                         f"{_PIVOT_CLEARANCE * 1e3:.0f} mm from the pivot")
    if np.any(~(batch.relative_speed > 0)):
        raise ValueError("ball and bat must approach each other: w1 r - v_p must be > 0")


def _column(a, col):
    """``a`` (n, k) with ``col`` (n,) appended as a last column."""
    return np.concatenate([a, np.asarray(col, dtype=float)[:, None]], axis=1)
