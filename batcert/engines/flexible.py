"""Flexible impact engine: the ball's contact law against a vibrating bat, batched.

Model (Nathan 2000; DESIGN.md Sec. 4). ``x`` runs along the impact normal, positive the way
the bat's impact point moves; the pitched ball comes the other way (``v_p < 0``). The bat is its
mass-normalised modes (:mod:`batcert.physics.modes`), rigid first, then bending modes
``q_j'' + 2 zeta omega_j q_j' + omega_j^2 q_j = -phi_j(z) F`` (``zeta = loss_factor / 2``; rigid
modes undamped); the ball obeys ``m x'' = +F``. The compression ``u = y(z) - x`` (bat surface
minus ball displacement, positive = compressed) gives ``F`` by the ball's contact law
(:mod:`batcert.physics.balls`): the viscoelastic law, whose loss follows the rate of the
squeeze, or Nathan's hysteresis, whose ``e0`` is (``ball_loss="compression"``, default) the
ball's rigid-wall COR at the wall speed that compresses it as far as it has been compressed so
far, or (``"relative-speed"``, batcert 0.1) at ``w1 r - v_p``. Either way a ball that meets a
recoiling bat or a compliant barrel, and compresses less or more slowly, loses less. A law's
stiffness refers to a flat rigid wall; the barrel is a convex cylinder, whose contact is softer
by Hertz's factor (:func:`~batcert.physics.balls.footprint.stiffness_ratio`, 0.84 for a
2 5/8 in barrel; ``contact_surface="flat"`` leaves it out, as Nathan 2000 did).

Before impact the bat rotates about the pivot at ``w1`` (``support="free"``: the pivot is the
instantaneous centre of the free bat, carried by its translation and rotation modes; nothing
constrains it), bending modes are at rest and the ball touches the surface. A point force only
disturbs the rigid motion along ``phi_r(z)``, so the rigid modes act at the impact point as one
free mass ``M_r = 1 / sum_r phi_r(z)^2`` (``I / r^2`` pinned, ``(1/M + d^2/I_cg)^-1`` free),
merged with the ball into ``w = y_rigid - x``: ``w'' = -F (1/m + 1/M_r)``, ``w'(0) = w1 r - v_p``.

Truncated modes: their quasi-static compliance ``c`` (:func:`batcert.physics.residual.residual_compliance`) is kept
as a residual pseudo-mode of gain ``omega_res sqrt(c)`` at ``omega_res`` = twice the highest kept
frequency, a spring in series with the ball that follows the much slower force.

Hollow bats: the wall is a thin shell of revolution (:mod:`batcert.physics.barrel`). Its
circumferential orders 0 and >= 2 (order 1 is the beam's bending above) are more modes of the
bat: the modes below ``shell_max_frequency`` join the beam's, with gain ``c_n W_j`` at the patch,
and the quasi-static compliance of the rest joins the beam's residual. The contact point's
surface moves with the beam and with the wall's normal deflection alike, so each shell mode
enters exactly like a bending mode; no mass is added or counted twice.
One material, one structural loss factor: every (coupled) mode gets ``zeta = eta / 2``.

Integration: all impacts of the batch advance together, arrays shaped (impacts, modes). The
linear dynamics are propagated exactly; only the contact force is approximated, by the
exponential Runge-Kutta scheme ETDRK4 (Cox & Matthews, J. Comput. Phys. 176 (2002) 430,
Eqs. 26-29) in complex modal coordinates ``Z = p - conj(lambda) q``, ``Z' = lambda Z - g F``.
Stiff modes cost nothing in stability: the step only resolves the contact pulse. The default
(12.5 us; Nathan used RK4 at 5 us) keeps exit speeds within 0.01 % of the converged engine
(module constants). An impact ends at separation (the ball law's contact measure falls to zero:
``u = 0`` for Nathan's law, the force itself for the viscoelastic one, while the ball is still
compressed); the exit speed is the ball's velocity then,
``w2`` and the COR come from momentum balance (:func:`rigid.momentum_outcome`: Smith 2001
Eqs. 1 and 3 for a pinned bat; for a free bat its angular velocity about the CG and the impact
point's speed after impact), the rigid-body equivalent of what the vibrating bat did.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert import workspace
from batcert.engines.base import ImpactBatch, ImpactOutcome
from batcert.physics import rigid
from batcert.physics.ball import BallModel
from batcert.physics.balls import footprint
from batcert.physics.balls.hysteresis import PowerLawHysteresis, compression_cor
from batcert.physics.balls.impact1d import wall_mean_compression
from batcert.physics.batmodel import BatModel
from batcert.physics.coupling import Coupling
from batcert.physics.linear_system import LinearSystem, stack_systems
from batcert.physics.march import Separation, march
from batcert.physics.modes import Modes

SUPPORTS = ("pinned", "free")
# the largest barrel deflection, in wall thicknesses, for which the linear wall is taken to hold:
# membrane stretching stiffens a plate by some 5-10 % at half its thickness (von Karman plate
# theory; Timoshenko & Woinowsky-Krieger, Theory of plates and shells, 1959, Sec. 96-97), and
# the runner warns beyond it (docs/physics.md)
LINEAR_WALL = 0.5
# Accuracy-driven defaults: every exit speed and result of the shipped bats under the shipped
# protocols within 0.01 % of the converged engine (48 modes, 2.5 us, shell modes to 16 kHz),
# half the 0.02 % an exit speed needs (measured with the shipped viscoelastic ball: solid
# 7.7e-5, hollow 6.5e-5 at 12.5 us with shell modes to 10 kHz; tests/engines/
# test_convergence.py). The viscoelastic ball's force falls through zero at separation and its
# sweet spot is flat: a 20 us step (batcert 0.2's for a solid bat with Nathan's law) leaves
# 4.4e-4 on a solid bat's BPF at its sweet spot, so both kinds of bat take 12.5 us; shell modes
# to 8 kHz would leave 2e-4. Exception: aluminium-34's wall thinned to 1.8 mm leaves 1.7e-4,
# 1.3e-4 of it from the 10 kHz shell cut, within 0.02 % but not 0.01 % (docs/validation.md).
DEFAULT_MODES = 16
SOLID_STEP, HOLLOW_STEP = 12.5e-6, 12.5e-6  # [s]
DEFAULT_SHELL_FREQUENCY = 10_000.0  # [Hz]
BALL_LOSS = ("compression", "relative-speed")
CONTACT_SURFACES = ("cylinder", "flat")

_PIVOT_CLEARANCE = 1e-3  # an impact closer than this to the pivot is refused [m]
# impacts solved together at most (FlexibleEngine.solve_many): memory bounded whatever the
# batch, each pass's arrays in cache (measured, bench_engine.py)
_PASS_ROWS = 4096


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

    def half_angle(self, compression) -> np.ndarray:
        """Half-angle [rad] of the footprint around the barrel at ``compression`` [m]:
        ``b(u) / R``, at most pi/2 (on a flat surface: Hertz's circle of the same size)."""
        u = np.asarray(compression, dtype=float)
        extra = (1,) * (u.ndim - 1)  # (p, grid): every impact's grid of compressions
        _, around = footprint.ellipse(self.ball_radius, self.surface.reshape(-1, *extra), u)
        return np.minimum(around / self.radius.reshape(-1, *extra), 0.5 * np.pi)


def _mean_compression(ball: BallModel, speed, recoil, scale) -> np.ndarray:
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


class FlexibleEngine:
    """Batched flexible-bat impact engine (Nathan 2000 model; module notes).

    Parameters
    ----------
    n_modes : int
        Bending modes kept [-] (Nathan used up to 18); the rest are residual compliance.
    time_step : float or None
        Integration step [s]; only the contact pulse has to be resolved (module notes). None:
        12.5 us for a solid and a hollow bat alike (module constants).
    refine : int
        Beam elements per bat slice for the modes [-].
    residual : bool
        Keep the truncated modes' quasi-static compliance as a series spring (module notes).
    ball_loss : {"compression", "relative-speed"}
        How Nathan's hysteresis law chooses its ``e0`` (module notes); the viscoelastic law's
        loss follows from the squeeze itself.
    contact_surface : {"cylinder", "flat"}
        The ball meets the bat's round surface (its law's stiffness times Hertz's cylinder
        factor, :func:`~batcert.physics.balls.footprint.stiffness_ratio`) or, as in Nathan
        2000, a flat one.
    shell_max_frequency : float
        Hollow bats: shell modes up to this frequency [Hz] join the engine; the rest is
        quasi-static residual compliance.
    max_contact_time : float
        Safety cap on the integration [s]; impacts still in contact then are reported with
        ``diagnostics["separated"] = False``.
    contact_patch : bool
        Spread the contact force over the ball's footprint (:class:`Patch`): along the bat
        over ``2 a``, Hertz's footprint on the barrel at the compression ``u_rep`` the ball
        has on average (weighted by the force) against a rigid body of the impact's effective
        mass, with the parabolic weight of Hertz's pressure, centred on the impact point (shrunk
        near the bat's ends so it stays on the bat); around a hollow barrel over Hertz's
        ``2 b``. False: a point force along the bat (Nathan 2000).
    patch_points : int
        Sample points along the patch (Gauss-Jacobi for the parabolic weight).
    record_states : bool
        Add the state at separation to the diagnostics (energy checks): ``modal_velocity`` of
        every beam mode [sqrt(kg) m/s], ``bending_displacement`` [sqrt(kg) m],
        ``residual_energy`` and ``barrel_energy`` [J].
    """

    name = "flexible"
    limitations: dict[str, str] = {}

    def __init__(self, n_modes: int = DEFAULT_MODES, time_step: float | None = None,
                 refine: int = 1, residual: bool = True, ball_loss: str = "compression",
                 shell_max_frequency: float = DEFAULT_SHELL_FREQUENCY,
                 max_contact_time: float = 0.02, record_states: bool = False,
                 contact_patch: bool = True, patch_points: int = 15,
                 contact_surface: str = "cylinder") -> None:
        if n_modes < 1 or int(n_modes) != n_modes:
            raise ValueError(f"n_modes must be a positive integer, got {n_modes!r}")
        if time_step is not None and not 0 < time_step <= 1e-4:
            raise ValueError(f"time_step must lie in (0, 1e-4] s, got {time_step!r}")
        if ball_loss not in BALL_LOSS:
            raise ValueError(f"ball_loss must be one of {BALL_LOSS}, got {ball_loss!r}")
        if contact_surface not in CONTACT_SURFACES:
            raise ValueError(f"contact_surface must be one of {CONTACT_SURFACES}, got "
                             f"{contact_surface!r}")
        self.contact_surface = contact_surface
        self.n_modes, self.refine = int(n_modes), int(refine)
        self.time_step = None if time_step is None else float(time_step)
        self.residual, self.ball_loss = bool(residual), ball_loss
        self.shell_max_frequency = float(shell_max_frequency)
        self.max_contact_time, self.record_states = float(max_contact_time), bool(record_states)
        self.contact_patch, self.patch_points = bool(contact_patch), int(patch_points)

    def step_for(self, bat: BatModel) -> float:
        """The integration step for ``bat`` [s] (the given one, or the default for its kind)."""
        if self.time_step is not None:
            return self.time_step
        return HOLLOW_STEP if bat.construction == "hollow" else SOLID_STEP

    def settings(self, bat: BatModel | None = None) -> dict:
        step: float | str
        if bat is not None:
            step = self.step_for(bat)
        elif self.time_step is not None:
            step = self.time_step
        else:
            step = f"{SOLID_STEP:g} (solid), {HOLLOW_STEP:g} (hollow)"
        return {"engine": "flexible", "n_modes": self.n_modes, "time_step": step,
                "refine": self.refine, "residual_compliance": self.residual,
                "max_contact_time": self.max_contact_time,
                "integrator": "ETDRK4 (Cox & Matthews 2002), exact modal propagation",
                "contact": "the ball's law (viscoelastic, or Nathan 2000 hysteresis with " + (
                    "e0 = ball COR at the rigid-wall speed of equal compression)"
                    if self.ball_loss == "compression" else "e0 = ball COR at relative speed)"),
                "contact_surface": ("the barrel's cylinder (Hertz's stiffness factor)"
                                    if self.contact_surface == "cylinder" else "flat"),
                "barrel": f"shell of revolution (Sanders), orders 0 and 2+; modes up to "
                          f"{self.shell_max_frequency:g} Hz, the rest quasi-static",
                "damping": "zeta = material loss factor / 2 on every flexible mode",
                "contact_patch": (f"force spread over Hertz's footprint ({self.patch_points} "
                                  "points along the bat, parabolic weight)"
                                  if self.contact_patch else "point force along the bat")}

    def _surface(self, bat: BatModel, ball: BallModel, z: np.ndarray):
        """The bat's outer radius at each impact [m], the contact surface's radius (inf: flat)
        and the ball law's stiffness factor on it [-]."""
        edges = np.asarray(bat.z_edges, dtype=float)
        s = np.clip(np.searchsorted(edges, z, side="right") - 1, 0, edges.size - 2)
        radius = 0.5 * np.asarray(bat.outer_diameter, dtype=float)[s]
        surface = radius if self.contact_surface == "cylinder" else np.full(z.size, np.inf)
        scale = np.asarray(footprint.stiffness_ratio(ball.radius, surface), dtype=float)
        return radius, surface, np.broadcast_to(scale, z.shape).copy()

    def _patch(self, bat: BatModel, ball: BallModel, z: np.ndarray, speed: np.ndarray,
               recoil: np.ndarray, compression: np.ndarray | None = None) -> Patch:
        """Each impact's :class:`Patch` (the class notes; ``recoil``: the bat's effective-mass
        ratio ``k`` at each impact; ``compression``: ``u_rep`` when already known)."""
        edges = np.asarray(bat.z_edges, dtype=float)
        radius, surface, scale = self._surface(bat, ball, z)
        u_rep = (_mean_compression(ball, speed, recoil, scale) if compression is None
                 else np.asarray(compression, dtype=float))
        along, _ = footprint.ellipse(ball.radius, surface, u_rep)
        if not self.contact_patch:
            return Patch(z[:, None], np.ones((z.size, 1)), radius, surface, scale, u_rep,
                         ball.radius)
        # keep the patch centred on the impact point: shrink it near the bat's ends
        half = np.minimum(along, np.minimum(z - edges[0], edges[-1] - z))
        xi, w = footprint.axial_weights(self.patch_points)
        points = z[:, None] + half[:, None] * xi[None, :]
        return Patch(points, np.broadcast_to(w, points.shape), radius, surface, scale, u_rep,
                     ball.radius)

    def linear_system(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
                      support: str = "pinned", modes: Modes | None = None,
                      compression: np.ndarray | None = None):
        """Check the batch and build each impact's :class:`LinearSystem`.

        Returns ``(system, extras)``; ``extras`` holds what the outputs need (modes, shapes at
        the impacts, barrel data).

        Raises
        ------
        ValueError
            Unknown support, impacts outside the bat or at the pivot, ball and bat not
            approaching, modes of another support or pivot.
        """
        _check_batch(bat, pivot, batch, support)
        z = pivot + batch.impact_location
        if modes is None:
            from batcert.physics.modes import cached_modes
            modes = cached_modes(bat, support, pivot, self.n_modes, self.refine)
        if modes.support != support or (support == "pinned" and abs(modes.pivot - pivot) > 1e-9):
            raise ValueError(f"modes are for support {modes.support!r} at {modes.pivot} m, "
                             f"not {support!r} at {pivot} m")
        zeta = 0.5 * bat.material.loss_factor
        if not 0 <= zeta < 1:
            raise ValueError(f"loss factor {bat.material.loss_factor} out of range [0, 2)")
        recoil = rigid.recoil_factor(bat, ball.mass, pivot, batch.impact_location, support)
        patch = self._patch(bat, ball, z, batch.relative_speed, recoil, compression)
        points, weights = patch.points, patch.weights
        phi, residual = self._beam_at(bat, modes, points, weights)
        nr = modes.n_rigid
        gain, omega = phi[:, nr:], np.broadcast_to(modes.omega[nr:], (z.size, phi.shape[1] - nr))
        rigid_mass = 1.0 / (phi[:, :nr] ** 2).sum(1)
        edges = np.asarray(bat.z_edges, dtype=float)
        s = np.clip(np.searchsorted(edges, z, side="right") - 1, 0, edges.size - 2)
        wall = 0.5 * (np.asarray(bat.outer_diameter) - np.asarray(bat.inner_diameter))[s]
        extras = {"modes": modes, "phi": phi, "n_bending": omega.shape[1], "n_shell": 0,
                  "beam_rigid_mass": rigid_mass, "residual_omega": 0.0,
                  "shell_static": np.zeros(z.size), "contact_scale": patch.scale,
                  "patch_compression": patch.compression, "wall": wall}
        shell = self._shell(bat, patch, extras)
        coupling = None
        if shell is not None:  # the shell's modes, their gains following the footprint's arc
            bpatch, table = shell
            gain = np.concatenate([gain, bpatch.axial], axis=1)
            omega = np.concatenate([omega, np.broadcast_to(bpatch.omega, bpatch.axial.shape)], 1)
            coupling = _coupling(bpatch, table, omega.shape[1], extras["n_bending"],
                                 residual if self.residual else None, patch)
            residual = residual + table["residual"][:, _REFERENCE] if self.residual else residual
        if self.residual:
            om_res = 2.0 * float(omega.max(initial=modes.omega[-1]))
            gain = _column(gain, om_res * np.sqrt(residual))
            omega = _column(omega, np.full(z.size, om_res))
            extras["residual_omega"] = om_res
        shell_cols = np.zeros(omega.shape[1], bool)
        shell_cols[extras["n_bending"]:extras["n_bending"] + extras["n_shell"]] = True
        system = LinearSystem(omega=np.ascontiguousarray(omega), zeta=np.full(z.size, zeta),
                              gain=np.ascontiguousarray(gain), rigid_mass=rigid_mass,
                              ball_mass=np.full(z.size, ball.mass),
                              shell_columns=shell_cols if shell is not None else None,
                              coupling=coupling)
        return system, extras

    def _beam_at(self, bat: BatModel, modes: Modes, points: np.ndarray, weights: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
        """The modes' shapes averaged over each patch, (p, modes), and the truncated modes'
        residual compliance there, (p,) (zero without ``residual``); kept by the active
        workspace (kind ``beam-response``): the patches recur (a barrel's variants, the same
        points in several runs); a batch of more than ``workspace.BATCH_ROWS`` impacts is
        neither looked up nor kept."""
        return workspace.current().call("beam-response", _beam_response, bat, modes, points,
                                        weights, bool(self.residual), rows=points.shape[0])

    def _shell(self, bat: BatModel, patch: Patch, extras: dict):
        """A hollow bat's wall under each impact's footprint (module notes) and, on the grid
        of compressions :data:`_GRID` x ``u_rep``, the footprint's half-angle around the barrel
        and the shell's residual compliance under it; None for a solid bat."""
        if bat.construction != "hollow":
            return None
        from batcert.physics import barrel
        modes = barrel.cached_barrel_modes(bat, self.shell_max_frequency)
        if modes is None:
            return None
        bpatch = barrel.barrel_patch(modes, patch.points, patch.weights)
        angles = patch.half_angle(_GRID[None, :] * patch.compression[:, None])  # (p, grid)
        factors, residual, static = bpatch.over(angles)
        table = {"angle": angles, "factors": factors, "residual": residual}
        extras.update(n_shell=bpatch.omega.size, shell_static=static[:, _REFERENCE],
                      shell_orders=bpatch.mode_orders)
        return bpatch, table

    def solve(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
              support: str = "pinned", modes: Modes | None = None) -> ImpactOutcome:
        """Solve every impact of ``batch`` (model in the module notes).

        Parameters
        ----------
        bat, ball : BatModel, BallModel
        pivot : float
            Pivot from the knob [m]: the pin (``"pinned"``) or the instantaneous centre of the
            free bat's motion before impact (``"free"``).
        batch : ImpactBatch
            Impact locations [m from pivot], pitch speeds [m/s], bat angular speeds [rad/s].
        support : {"pinned", "free"}
        modes : Modes, optional
            Modes to use instead of :func:`batcert.physics.modes.cached_modes` (same support and
            pivot); the residual compliance still comes from ``bat``'s beam.

        Returns
        -------
        ImpactOutcome
            ``exit_speed`` [m/s]; ``bat_angular_speed_after`` [rad/s] and ``cor`` [-] from
            :func:`rigid.momentum_outcome` (Smith 2001 Eqs. 1 and 3 when pinned). Diagnostics:
            ``contact_time`` [s], ``peak_force`` [N], ``max_compression`` of the ball [m],
            ``vibrational_energy`` left in the flexible modes (bending, shell, residual) at
            separation [J], ``ball_energy_loss`` dissipated in the ball [J], ``approach_energy``
            ``m v_rel^2 / (2 (1 + k))``, the kinetic energy of the approach in the impact's
            frame, of which ``cor^2`` stays in the relative motion [J], ``e0`` [-] (the
            contact law's COR parameter at the end), ``separated`` [bool]; hollow bats also
            ``barrel_energy`` left in the shell modes [J], ``barrel_energy_share``, the
            shell's share of the energy stored in ball and shell at the ball's maximum
            compression [-], ``barrel_deflection``, the wall's quasi-static deflection under
            the peak force over the footprint [m], and ``barrel_deflection_ratio``, that over
            the wall's thickness [-] (:data:`LINEAR_WALL` is where the linear wall ends).
        """
        return self.solve_many([(bat, ball, pivot, batch, support, modes)])[0]

    def solve_many(self, jobs) -> list[ImpactOutcome]:
        """Solve several batches, of one bat or of several (and balls, pivots, supports), in
        as few integrations as possible: the batches that share a time step are stacked into
        one (:func:`~batcert.physics.march.stack_systems`). ``jobs`` holds tuples ``(bat,
        ball, pivot, batch, support[, modes])`` as :meth:`solve` takes them; the outcomes come
        back in the same order, each exactly what :meth:`solve` gives for it alone.

        Large batches go through in passes of at most ``_PASS_ROWS`` impacts (a larger batch
        is cut, smaller ones share a pass), so that memory stays bounded whatever the batch
        and each pass's arrays stay in the processor's cache."""
        jobs = [(*job[:3], _flat(job[3]), *job[4:]) for job in jobs]
        passes = _passes([len(job[3]) for job in jobs], _PASS_ROWS)
        if len(passes) == 1:
            return self._solve_pass(jobs)
        parts: list[list[ImpactOutcome]] = [[] for _ in jobs]
        for pieces in passes:
            sub = [(*jobs[i][:3], _rows(jobs[i][3], a, b), *jobs[i][4:]) for i, a, b in pieces]
            for (i, _, _), outcome in zip(pieces, self._solve_pass(sub), strict=True):
                parts[i].append(outcome)
        return [_joined(p) for p in parts]

    def _solve_pass(self, jobs) -> list[ImpactOutcome]:
        """:meth:`solve_many` of jobs of flat batches, in one pass."""
        ready: dict[int, tuple[BatModel, BallModel, float, ImpactBatch, str, LinearSystem,
                               dict]] = {}
        groups = list(self._alike(jobs).values())
        compressions = self._compressions(jobs, groups)
        for members, compression in zip(groups, compressions, strict=True):
            batches = [jobs[i][3] for i in members]
            bat, ball, pivot, _, support, *rest = jobs[members[0]]
            # the jobs of one bat, ball, pivot and support share one linear system (a bat's
            # patches and barrel are read for all their rows at once), split back per job
            system, extras = self.linear_system(bat, ball, pivot, _concatenate(batches),
                                                support, rest[0] if rest else None, compression)
            start = 0
            for i, batch in zip(members, batches, strict=True):
                a, b = start, start + batch.impact_location.size
                start = b
                mine = (system, extras) if len(members) == 1 else (
                    system.rows(a, b),
                    {k: v[a:b] if k in _ROW_EXTRAS else v for k, v in extras.items()})
                ready[i] = (bat, ball, pivot, batch, support, *mine)
        prepared = [ready[i] for i in range(len(jobs))]
        out: list[ImpactOutcome | None] = [None] * len(prepared)
        steps: dict[tuple, list[int]] = {}
        for i, job in enumerate(prepared):  # one march per time step and ball law
            steps.setdefault((self.step_for(job[0]), type(job[1].law)), []).append(i)
        for (step, _), members in steps.items():
            seps = self._integrate([prepared[i] for i in members], step)
            for i, sep in zip(members, seps, strict=True):
                out[i] = self._outcome(*prepared[i], sep)
        return out  # type: ignore[return-value]

    def _compressions(self, jobs, groups: list[list[int]]) -> list[np.ndarray]:
        """Each group's ``u_rep`` (:func:`_mean_compression`), the groups of one ball law in a
        single integration: a Monte Carlo's draws, each a ball of its own, cost one."""
        rows: dict[type, list] = {}  # law class -> [(group, law, mass, speeds)]
        for g, members in enumerate(groups):
            bat, ball, pivot, _, support, *_ = jobs[members[0]]
            batch = _concatenate([jobs[i][3] for i in members])
            z = pivot + batch.impact_location
            recoil = rigid.recoil_factor(bat, ball.mass, pivot, batch.impact_location, support)
            _, _, scale = self._surface(bat, ball, z)
            equal = batch.relative_speed / np.sqrt((1.0 + recoil) * scale)
            rows.setdefault(type(ball.law), []).append((g, ball.law, float(ball.mass), equal))
        out: list[np.ndarray] = [np.empty(0)] * len(groups)
        for parts in rows.values():
            distinct: dict[tuple, int] = {}
            which = np.concatenate([np.full(p[3].size, distinct.setdefault((p[1], p[2]),
                                                                           len(distinct)))
                                    for p in parts])
            u = wall_mean_compression(list(distinct), which, np.concatenate([p[3] for p in parts]))
            start = 0
            for g, _, _, equal in parts:
                out[g] = u[start:start + equal.size]
                start += equal.size
        return out

    @staticmethod
    def _alike(jobs) -> dict[tuple, list[int]]:
        """The jobs (indices) that share bat, ball, pivot, support and given modes."""
        groups: dict[tuple, list[int]] = {}
        for i, (bat, ball, pivot, _, support, *rest) in enumerate(jobs):
            key = (id(bat), ball, float(pivot), support, id(rest[0]) if rest else None)
            groups.setdefault(key, []).append(i)
        return groups

    def _integrate(self, jobs: list, step: float) -> list[Separation]:
        """One march over the stacked rows of ``jobs`` (prepared as in :meth:`solve_many`; their
        balls share one contact law); each job's :class:`Separation`, its modal columns
        unpadded."""
        stacked, columns = stack_systems([j[5] for j in jobs])
        sizes = [j[3].impact_location.size for j in jobs]
        bounds = np.concatenate([[0], np.cumsum(sizes)])
        relative = np.concatenate([j[3].relative_speed for j in jobs])
        scale = np.concatenate([j[6]["contact_scale"] for j in jobs])
        distinct: dict[BallModel, int] = {}
        for j in jobs:
            distinct.setdefault(j[1], len(distinct))
        balls = list(distinct)
        which = np.repeat([distinct[j[1]] for j in jobs], sizes)
        state = type(balls[0].law).state_of([b.law for b in balls], [b.mass for b in balls],
                                            which, scale, self.ball_loss, relative)
        sep = march(stacked, state, relative, step, self.max_contact_time)
        return [Separation(impulse=sep.impulse[a:b], time=sep.time[a:b],
                           separated=sep.separated[a:b], peak_force=sep.peak_force[a:b],
                           max_compression=sep.max_compression[a:b],
                           modal=sep.modal[a:b][:, cols],
                           barrel_share=None if jobs[k][5].shell_columns is None
                           or sep.barrel_share is None else sep.barrel_share[a:b],
                           absorbed=None if sep.absorbed is None else sep.absorbed[a:b])
                for k, (a, b, cols) in enumerate(zip(bounds[:-1], bounds[1:], columns,
                                                      strict=True))]

    def _outcome(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
                 support: str, system: LinearSystem, extras: dict,
                 sep: Separation) -> ImpactOutcome:
        """Exit speed, momentum outcome and diagnostics of one job from its separation state."""
        r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
        vb = vp + sep.impulse / ball.mass
        k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
        w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
        om = system.omega
        zeta = system.zeta[:, None]
        q = sep.modal.imag / (om * np.sqrt(1 - zeta**2))
        p = sep.modal.real - zeta * om * q
        energy = 0.5 * (p**2 + (om * q) ** 2)
        diag = {"contact_time": sep.time, "peak_force": sep.peak_force,
                "max_compression": sep.max_compression, "vibrational_energy": energy.sum(1),
                "approach_energy": 0.5 * ball.mass / (1 + k) * batch.relative_speed**2,
                "separated": sep.separated}
        law = ball.law
        if isinstance(law, PowerLawHysteresis):  # the energy in closed form, and e0
            k1 = law.k1 * extras["contact_scale"]
            e0 = (compression_cor(law, ball.mass, sep.max_compression, k1)
                  if self.ball_loss == "compression"
                  else np.asarray(law.cor_at(batch.relative_speed), dtype=float))
            stored = k1 * sep.max_compression ** (1 + law.alpha) / (1 + law.alpha)
            diag.update(ball_energy_loss=stored * (1 - e0**2), e0=e0)
        else:
            diag["ball_energy_loss"] = sep.absorbed
        if system.shell_columns is not None:
            diag["barrel_energy"] = energy[:, system.shell_columns].sum(1)
            diag["barrel_energy_share"] = sep.barrel_share
            # the wall's quasi-static deflection under the peak force: the linear wall's limit
            deflection = extras["shell_static"] * sep.peak_force
            diag["barrel_deflection"] = deflection
            diag["barrel_deflection_ratio"] = deflection / extras["wall"]
        if self.record_states:
            diag.update(_states(system, extras, sep, q, p, pivot, w1 * r, w1))
        return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k,
                             diagnostics=diag)


# the compressions, in multiples of u_rep, at which a hollow barrel's coupling to the ball is
# tabulated (linear between them, held beyond); _REFERENCE is u_rep itself
_GRID = np.linspace(0.0, 2.0, 41)
_REFERENCE = 20


def _beam_response(bat: BatModel, modes: Modes, points: np.ndarray, weights: np.ndarray,
                   residual: bool) -> tuple[np.ndarray, np.ndarray]:
    """:meth:`FlexibleEngine._beam_at` computed."""
    from batcert.physics.residual import patch_reader, residual_compliance

    reader = patch_reader(modes.z, points, weights)  # (p, nodes), as Modes.at reads
    phi = reader @ modes.shapes.T
    compliance = np.zeros(points.shape[0])
    if residual:
        compliance = residual_compliance(bat, modes, points, weights, reader=reader)
    return phi, compliance


def _coupling(bpatch, table: dict, columns: int, n_bending: int, beam_residual, patch: Patch
              ) -> Coupling:
    """The groups of a hollow bat's columns whose gains follow the footprint
    (:mod:`batcert.physics.coupling`): the beam's modes (fixed), the shell's modes order by
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


# the entries of linear_system's extras that hold one row per impact
_ROW_EXTRAS = ("phi", "beam_rigid_mass", "shell_static", "contact_scale", "patch_compression",
               "wall")


def _flat(batch: ImpactBatch) -> ImpactBatch:
    if batch.impact_location.ndim == 1:
        return batch
    return ImpactBatch(*(np.ravel(a) for a in (batch.impact_location, batch.pitch_speed,
                                               batch.bat_angular_speed)))


def _rows(batch: ImpactBatch, a: int, b: int) -> ImpactBatch:
    return ImpactBatch(batch.impact_location[a:b], batch.pitch_speed[a:b],
                       batch.bat_angular_speed[a:b])


def _passes(sizes: list[int], rows: int) -> list[list[tuple[int, int, int]]]:
    """The jobs' rows as pieces ``(job, start, stop)`` in passes of at most ``rows`` rows, in
    order: a job of more rows is cut, smaller jobs share a pass."""
    passes: list[list[tuple[int, int, int]]] = [[]]
    filled = 0
    for i, n in enumerate(sizes):
        for a in range(0, max(n, 1), rows):
            b = min(a + rows, n)
            if passes[-1] and filled + b - a > rows:
                passes.append([])
                filled = 0
            passes[-1].append((i, a, b))
            filled += b - a
    return passes


def _joined(parts: list[ImpactOutcome]) -> ImpactOutcome:
    """One outcome of the consecutive pieces of a job."""
    if len(parts) == 1:
        return parts[0]

    def cat(arrays):
        return None if arrays[0] is None else np.concatenate(arrays)
    fields = ("exit_speed", "bat_angular_speed_after", "cor", "recoil_factor")
    return ImpactOutcome(**{f: cat([getattr(p, f) for p in parts]) for f in fields},
                         diagnostics={k: cat([p.diagnostics[k] for p in parts])
                                      for k in parts[0].diagnostics})


def _concatenate(batches: list[ImpactBatch]) -> ImpactBatch:
    if len(batches) == 1:
        return batches[0]
    return ImpactBatch(*(np.concatenate([getattr(b, a) for b in batches]) for a in (
        "impact_location", "pitch_speed", "bat_angular_speed")))


def _check_batch(bat: BatModel, pivot: float, batch: ImpactBatch, support: str) -> None:
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


def _states(system: LinearSystem, extras: dict, sep: Separation, q, p, pivot, v_bat, w1):
    """Beam modal velocities and displacements, residual and barrel energies at separation."""
    modes, nb, ns = extras["modes"], extras["n_bending"], extras["n_shell"]
    v_rigid = v_bat - sep.impulse / system.rigid_mass  # rigid speed of the contact point
    shell = slice(nb, nb + ns)
    # rigid modes: rotation about the pivot, changed only along phi_r (point force at z)
    qd_r = w1[:, None] * rigid_mode_velocities(modes, pivot)[None, :] + extras["phi"][
        :, :modes.n_rigid] * (extras["beam_rigid_mass"] * (v_rigid - v_bat))[:, None]
    res = slice(nb + ns, nb + ns + 1) if extras["residual_omega"] > 0 else slice(0, 0)
    return {"modal_velocity": np.concatenate([qd_r, p[:, :nb]], axis=1),
            "bending_displacement": q[:, :nb],
            "barrel_energy": 0.5 * (p[:, shell] ** 2 + (system.omega[:, shell] * q[:, shell]) ** 2
                                    ).sum(1),
            "residual_energy": 0.5 * (p[:, res] ** 2 + (extras["residual_omega"]
                                                        * q[:, res]) ** 2).sum(1)}
