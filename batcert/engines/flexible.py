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

import numpy as np

from batcert.engines import passes
from batcert.engines.base import ImpactBatch, ImpactOutcome, Job
from batcert.engines.flexible_family import linear_systems
from batcert.engines.flexible_outcome import Prepared, outcome
from batcert.engines.flexible_system import (
    SUPPORTS,
    Extras,
    Patch,
    SystemSettings,
    group_compressions,
    rigid_mode_velocities,
)
from batcert.engines.flexible_system import linear_system as build_system
from batcert.engines.kernel.linear_system import LinearSystem, stack_systems
from batcert.engines.kernel.march import Separation, march
from batcert.physics.ball import BallModel
from batcert.physics.balls.footprint_rules import DEFAULT_RULE, rule
from batcert.physics.batmodel import BatModel
from batcert.physics.modes import Modes

__all__ = ["BALL_LOSS", "CONTACT_SURFACES", "DEFAULT_MODES", "DEFAULT_SHELL_FREQUENCY",
           "FlexibleEngine", "HOLLOW_STEP", "LINEAR_WALL", "Patch", "SOLID_STEP", "SUPPORTS",
           "rigid_mode_velocities"]

# the largest barrel deflection, in wall thicknesses, for which the linear wall is taken to hold:
# a clamped plate's membrane stretching changes its stiffness by some 5-10 % at half its
# thickness (von Karman plate theory; Timoshenko & Woinowsky-Krieger, Theory of plates and
# shells, 1959, Sec. 96-97), and the runner warns beyond it (docs/physics.md). For a barrel's
# ovalling (hoop) modes the direction is not established: the nonlinear-shell literature
# (Amabili's work on circular cylindrical shells) reports softening for such modes
LINEAR_WALL = 0.5
# Accuracy-driven defaults: every exit speed and result of the shipped bats under the shipped
# protocols within 0.01 % of the converged engine (48 modes, 2.5 us, shell modes to 16 kHz),
# half the 0.02 % an exit speed needs (measured with the shipped viscoelastic ball: solid
# 7.7e-5, hollow 6.5e-5 at 12.5 us with shell modes to 10 kHz, batcert 0.3's one-time ball;
# with the two-time ball the shell cut rose to 12 kHz: 2.4e-5 on aluminium-34; tests/engines/
# test_convergence.py). The viscoelastic ball's force falls through zero at separation and its
# sweet spot is flat: a 20 us step (batcert 0.2's for a solid bat with Nathan's law) leaves
# 4.4e-4 on a solid bat's BPF at its sweet spot, so both kinds of bat take 12.5 us; shell modes
# to 8 kHz would leave 2e-4. Exception: aluminium-34's wall thinned to 1.8 mm leaves 1.7e-4,
# 1.3e-4 of it from the 10 kHz shell cut (now 1.6e-4 at 12 kHz with the two-time ball), within
# 0.02 % but not 0.01 % (docs/validation.md).
DEFAULT_MODES = 16
SOLID_STEP, HOLLOW_STEP = 12.5e-6, 12.5e-6  # [s]
DEFAULT_SHELL_FREQUENCY = 12_000.0  # [Hz] (the barrel's MAX_FREQUENCY: why 12 kHz there)
BALL_LOSS = ("compression", "relative-speed")
CONTACT_SURFACES = ("cylinder", "flat")

# impacts solved together at most (FlexibleEngine.solve_many): memory bounded whatever the
# batch, each pass's arrays in cache (measured, bench_engine.py)
_PASS_ROWS = 4096


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
        The ball meets the bat's round surface (its law's stiffness times the cylinder factor,
        :func:`~batcert.physics.balls.footprint.stiffness_ratio`, at ``u_rep``) or, as in
        Nathan 2000, a flat one.
    footprint : str
        The footprint rule (:data:`~batcert.physics.balls.footprint_rules.RULES`):
        ``fe-finite-strain`` (Hertz's footprint and cylinder factor corrected by a 3-D
        finite-strain sphere) or ``hertz`` (batcert 0.2's).
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
    models_barrel = True
    construction_warning: str | None = None
    limitations: dict[str, str] = {}

    def __init__(self, n_modes: int = DEFAULT_MODES, time_step: float | None = None,
                 refine: int = 1, residual: bool = True, ball_loss: str = "compression",
                 shell_max_frequency: float = DEFAULT_SHELL_FREQUENCY,
                 max_contact_time: float = 0.02, record_states: bool = False,
                 contact_patch: bool = True, patch_points: int = 15,
                 contact_surface: str = "cylinder", footprint: str = DEFAULT_RULE) -> None:
        if n_modes < 1 or int(n_modes) != n_modes:
            raise ValueError(f"n_modes must be a positive integer, got {n_modes!r}")
        if time_step is not None and not 0 < time_step <= 1e-4:
            raise ValueError(f"time_step must lie in (0, 1e-4] s, got {time_step!r}")
        if ball_loss not in BALL_LOSS:
            raise ValueError(f"ball_loss must be one of {BALL_LOSS}, got {ball_loss!r}")
        if contact_surface not in CONTACT_SURFACES:
            raise ValueError(f"contact_surface must be one of {CONTACT_SURFACES}, got "
                             f"{contact_surface!r}")
        self.contact_surface, self.footprint = contact_surface, rule(footprint).name
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
                "contact_surface": ("the barrel's cylinder (stiffness factor of the footprint "
                                    "rule)" if self.contact_surface == "cylinder" else "flat"),
                "footprint": rule(self.footprint).title,
                "barrel": f"shell of revolution (Sanders), orders 0 and 2+; modes up to "
                          f"{self.shell_max_frequency:g} Hz, the rest quasi-static",
                "damping": "zeta = material loss factor / 2 on every flexible mode",
                "contact_patch": (f"force spread over Hertz's footprint ({self.patch_points} "
                                  "points along the bat, parabolic weight)"
                                  if self.contact_patch else "point force along the bat")}

    def system_settings(self) -> SystemSettings:
        """The settings that shape the linear system."""
        return SystemSettings(self.n_modes, self.refine, self.residual, self.shell_max_frequency,
                              self.contact_surface, self.contact_patch, self.patch_points,
                              self.footprint)

    def linear_system(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
                      support: str = "pinned", modes: Modes | None = None,
                      compression: np.ndarray | None = None) -> tuple[LinearSystem, Extras]:
        """Check the batch and build each impact's :class:`LinearSystem`
        (:func:`batcert.engines.flexible_system.linear_system`).

        Returns ``(system, extras)``; ``extras`` holds what the outcomes need (modes, shapes at
        the impacts, barrel data).

        Raises
        ------
        ValueError
            Unknown support, impacts outside the bat or at the pivot, ball and bat not
            approaching, modes of another support or pivot.
        """
        return build_system(self.system_settings(), bat, ball, pivot, batch, support, modes,
                            compression)

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
        return self.solve_many([Job(bat, ball, pivot, batch, support, modes)])[0]

    def solve_many(self, jobs: list[Job]) -> list[ImpactOutcome]:
        """Solve several jobs (:class:`~batcert.engines.base.Job`: batches of one bat or of
        several, and balls, pivots, supports, given modes), in as few integrations as possible:
        the batches that share a time step are stacked into one
        (:func:`~batcert.engines.kernel.linear_system.stack_systems`). The outcomes come back in the
        same order, each exactly what :meth:`solve` gives for it alone.

        Large batches go through in passes of at most ``_PASS_ROWS`` impacts (a larger batch
        is cut, smaller ones share a pass, :mod:`batcert.engines.passes`), so that memory
        stays bounded whatever the batch and each pass's arrays stay in the processor's
        cache."""
        flat = [j.with_batch(passes.flat(j.batch)) for j in map(Job.of, jobs)]
        cut = passes.passes([len(j.batch) for j in flat], _PASS_ROWS)
        if len(cut) == 1:
            return self._solve_pass(flat)
        parts: list[list[ImpactOutcome]] = [[] for _ in flat]
        for pieces in cut:
            sub = [flat[i].with_batch(passes.rows(flat[i].batch, a, b)) for i, a, b in pieces]
            for (i, _, _), got in zip(pieces, self._solve_pass(sub), strict=True):
                parts[i].append(got)
        return [passes.joined(p) for p in parts]

    def _solve_pass(self, jobs: list[Job]) -> list[ImpactOutcome]:
        """:meth:`solve_many` of jobs of flat batches, in one pass."""
        prepared = self._prepare(jobs)
        out: list[ImpactOutcome | None] = [None] * len(prepared)
        steps: dict[tuple, list[int]] = {}
        for i, ready in enumerate(prepared):  # one march per time step and ball law
            steps.setdefault((self.step_for(ready.job.bat), type(ready.job.ball.law)),
                             []).append(i)
        for (step, _), members in steps.items():
            seps = self._integrate([prepared[i] for i in members], step)
            for i, sep in zip(members, seps, strict=True):
                out[i] = outcome(prepared[i], sep, self.ball_loss, self.record_states)
        return out  # type: ignore[return-value]

    def _prepare(self, jobs: list[Job]) -> list[Prepared]:
        """Each job with its linear system: the jobs of one bat, ball, pivot and support share
        one (a bat's patches and barrel are read for all their rows at once), split back per
        job; the bats of a family (a Monte Carlo's draws) are built together
        (:mod:`batcert.engines.flexible_family`)."""
        ready: dict[int, Prepared] = {}
        groups = list(self._alike(jobs).values())
        compressions = group_compressions(self.system_settings(), jobs, groups)
        merged = [jobs[m[0]].with_batch(passes.concatenate([jobs[i].batch for i in m]))
                  for m in groups]
        built = linear_systems(self.system_settings(), merged, compressions)
        for members, (system, extras) in zip(groups, built, strict=True):
            start = 0
            for i in members:
                a, b = start, start + len(jobs[i].batch)
                start = b
                ready[i] = (Prepared(jobs[i], system, extras) if len(members) == 1 else
                            Prepared(jobs[i], system.rows(a, b), extras.rows(a, b)))
        return [ready[i] for i in range(len(jobs))]

    @staticmethod
    def _alike(jobs: list[Job]) -> dict[tuple, list[int]]:
        """The jobs (indices) that share bat, ball, pivot, support and given modes (the bat and
        the modes by identity: the same object, the same content; a batching choice only)."""
        groups: dict[tuple, list[int]] = {}
        for i, j in enumerate(jobs):
            key = (id(j.bat), j.ball, float(j.pivot), j.support,
                   None if j.modes is None else id(j.modes))
            groups.setdefault(key, []).append(i)
        return groups

    def _integrate(self, jobs: list[Prepared], step: float) -> list[Separation]:
        """One march over the stacked rows of ``jobs`` (prepared as in :meth:`solve_many`; their
        balls share one contact law); each job's :class:`Separation`, its modal columns
        unpadded."""
        stacked, columns = stack_systems([j.system for j in jobs])
        sizes = [len(j.job.batch) for j in jobs]
        bounds = np.concatenate([[0], np.cumsum(sizes)])
        relative = np.concatenate([j.job.batch.relative_speed for j in jobs])
        scale = np.concatenate([j.extras.contact_scale for j in jobs])
        distinct: dict[BallModel, int] = {}
        for j in jobs:
            distinct.setdefault(j.job.ball, len(distinct))
        balls = list(distinct)
        which = np.repeat([distinct[j.job.ball] for j in jobs], sizes)
        state = type(balls[0].law).state_of([b.law for b in balls], [b.mass for b in balls],
                                            which, scale, self.ball_loss, relative)
        sep = march(stacked, state, relative, step, self.max_contact_time)
        return [Separation(impulse=sep.impulse[a:b], time=sep.time[a:b],
                           separated=sep.separated[a:b], peak_force=sep.peak_force[a:b],
                           max_compression=sep.max_compression[a:b],
                           modal=sep.modal[a:b][:, cols],
                           barrel_share=None if jobs[k].system.shell_columns is None
                           or sep.barrel_share is None else sep.barrel_share[a:b],
                           absorbed=None if sep.absorbed is None else sep.absorbed[a:b])
                for k, (a, b, cols) in enumerate(zip(bounds[:-1], bounds[1:], columns,
                                                      strict=True))]
