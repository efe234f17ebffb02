"""Flexible impact engine: the ball's hysteresis contact against a vibrating bat, batched.

Model (Nathan 2000; DESIGN.md Sec. 4). ``x`` runs along the impact normal, positive the way
the bat's impact point moves; the pitched ball comes the other way (``v_p < 0``). The bat is its
mass-normalised modes (:mod:`batcert.physics.modes`), rigid first, then bending modes
``q_j'' + 2 zeta omega_j q_j' + omega_j^2 q_j = -phi_j(z) F`` (``zeta = loss_factor / 2``; rigid
modes undamped); the ball obeys ``m x'' = +F``. The compression ``u = y(z) - x`` (bat surface
minus ball displacement, positive = compressed) gives ``F`` by :func:`contact.contact_force`. The
ball's loss follows its own deformation (``ball_loss="compression"``, default): ``e0`` is the
ball's rigid-wall COR at the wall speed that compresses it as far as it has been compressed so
far (:func:`contact.compression_restitution`), so a ball that meets a recoiling bat or a
compliant barrel, and compresses less, loses less; ``"relative-speed"`` takes
``e0 = ball.cor(w1 r - v_p)`` per impact (batcert 0.1).

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
Stiff modes cost nothing in stability: the step only resolves the contact pulse. The defaults
(20 us for a solid bat, 12.5 us for a hollow one, whose contact force has sharper kinks; Nathan
used RK4 at 5 us) keep exit speeds within 0.01 % of the converged engine (module constants). An impact ends at
separation (``u <= 0`` after maximum compression); the exit speed is the ball's velocity then,
``w2`` and the COR come from momentum balance (:func:`rigid.momentum_outcome`: Smith 2001
Eqs. 1 and 3 for a pinned bat; for a free bat its angular velocity about the CG and the impact
point's speed after impact), the rigid-body equivalent of what the vibrating bat did.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from batcert.engines.base import ImpactBatch, ImpactOutcome
from batcert.physics import contact, rigid, stores
from batcert.physics.ball import BallModel
from batcert.physics.batmodel import BatModel
from batcert.physics.march import LinearSystem, Separation, march, stack_systems
from batcert.physics.modes import Modes

SUPPORTS = ("pinned", "free")
# Accuracy-driven defaults: every exit speed of the shipped bats under the shipped protocols
# within 0.01 % of the converged engine (48 modes, 2.5 us, shell modes to 16 kHz), half the
# 0.02 % an exit speed needs (measured: solid 4.7e-5 at 20 us, hollow 2.4e-5 at 12.5 us with
# shell modes to 10 kHz; tests/engines/test_convergence.py). A hollow barrel's contact force
# has sharper kinks, hence its shorter step (20 us: 1.3e-4); shell modes to 8 kHz would leave
# 2e-4. Exception: aluminium-34's wall thinned to 1.8 mm leaves 1.4e-4 on a stationary-bat
# exit speed, from the 10 kHz shell cut, within 0.02 % but not 0.01 % (docs/validation.md).
DEFAULT_MODES = 16
SOLID_STEP, HOLLOW_STEP = 20e-6, 12.5e-6  # [s]
DEFAULT_SHELL_FREQUENCY = 10_000.0  # [Hz]
BALL_LOSS = ("compression", "relative-speed")
_PIVOT_CLEARANCE = 1e-3  # an impact closer than this to the pivot is refused [m]
_BEAM_CACHE: stores.Memo[tuple, tuple] = stores.Memo(256)  # (modes, result): FlexibleEngine._beam_at
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


class FlexibleEngine:
    """Batched flexible-bat impact engine (Nathan 2000 model; module notes).

    Parameters
    ----------
    n_modes : int
        Bending modes kept [-] (Nathan used up to 18); the rest are residual compliance.
    time_step : float or None
        Integration step [s]; only the contact pulse has to be resolved (module notes). None:
        20 us for a solid bat, 12.5 us for a hollow one (module constants).
    refine : int
        Beam elements per bat slice for the modes [-].
    residual : bool
        Keep the truncated modes' quasi-static compliance as a series spring (module notes).
    ball_loss : {"compression", "relative-speed"}
        How the contact law's ``e0`` is chosen (module notes).
    shell_max_frequency : float
        Hollow bats: shell modes up to this frequency [Hz] join the engine; the rest is
        quasi-static residual compliance.
    max_contact_time : float
        Safety cap on the integration [s]; impacts still in contact then are reported with
        ``diagnostics["separated"] = False``.
    contact_patch : bool
        Spread the contact force along the bat over the ball's flattened contact length
        ``2 a``, ``a = sqrt(2 R u_m - u_m^2)`` with ``u_m`` the ball's maximum compression against
        a rigid wall at the impact's relative speed, with a semicircular (Hertz-like) weight,
        centred on the impact point (shrunk near the bat's ends so it stays on the bat).
        False: a point force at the impact location (Nathan 2000).
    patch_points : int
        Sample points across the patch (Gauss-Chebyshev of the second kind).
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
                 contact_patch: bool = True, patch_points: int = 15) -> None:
        if n_modes < 1 or int(n_modes) != n_modes:
            raise ValueError(f"n_modes must be a positive integer, got {n_modes!r}")
        if time_step is not None and not 0 < time_step <= 1e-4:
            raise ValueError(f"time_step must lie in (0, 1e-4] s, got {time_step!r}")
        if ball_loss not in BALL_LOSS:
            raise ValueError(f"ball_loss must be one of {BALL_LOSS}, got {ball_loss!r}")
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
                "contact": "Nathan 2000 power-law hysteresis, " + (
                    "e0 = ball COR at the rigid-wall speed of equal compression"
                    if self.ball_loss == "compression" else "e0 = ball COR at relative speed"),
                "barrel": f"shell of revolution (Sanders), orders 0 and 2+; modes up to "
                          f"{self.shell_max_frequency:g} Hz, the rest quasi-static",
                "damping": "zeta = material loss factor / 2 on every flexible mode",
                "contact_patch": (f"force spread over the ball's flattened contact length "
                                  f"({self.patch_points} points, semicircular weight)"
                                  if self.contact_patch else "point force")}

    def _patch(self, bat: BatModel, ball: BallModel, z: np.ndarray, speed: np.ndarray):
        """Sample points (p, K) [m from knob] and weights (p, K) of the contact force along
        the bat, and the half-length of the contact (around the bat) [m], (p,)."""
        u = np.minimum(contact.max_compression(speed, ball.mass, ball.k1, ball.alpha), ball.radius)
        contact_half = np.sqrt(2.0 * ball.radius * u - u**2)  # around the bat too
        if not self.contact_patch:
            return z[:, None], np.ones((z.size, 1)), contact_half
        # keep the patch centred on the impact point: shrink it near the bat's ends
        half = np.minimum(contact_half, np.minimum(z - bat.z_edges[0], bat.z_edges[-1] - z))
        k = np.arange(1, self.patch_points + 1)
        xi = np.cos(k * np.pi / (self.patch_points + 1))
        w = np.sin(k * np.pi / (self.patch_points + 1)) ** 2
        points = z[:, None] + half[:, None] * xi[None, :]
        return points, np.broadcast_to(w / w.sum(), points.shape), contact_half

    def linear_system(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
                      support: str = "pinned", modes: Modes | None = None):
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
        points, weights, half = self._patch(bat, ball, z, batch.relative_speed)
        phi, residual = self._beam_at(bat, modes, points, weights)
        nr = modes.n_rigid
        gain, omega = phi[:, nr:], np.broadcast_to(modes.omega[nr:], (z.size, phi.shape[1] - nr))
        rigid_mass = 1.0 / (phi[:, :nr] ** 2).sum(1)
        extras = {"modes": modes, "phi": phi, "n_bending": omega.shape[1], "n_shell": 0,
                  "beam_rigid_mass": rigid_mass, "residual_omega": 0.0,
                  "shell_static": np.zeros(z.size)}
        shell = self._shell(bat, points, weights, half, extras)
        if shell is not None:
            gain = np.concatenate([gain, shell.gain], axis=1)
            omega = np.concatenate([omega, np.broadcast_to(shell.omega, shell.gain.shape)], 1)
            residual = residual + (shell.residual if self.residual else 0.0)
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
                              shell_columns=shell_cols if shell is not None else None)
        return system, extras

    def _beam_at(self, bat: BatModel, modes: Modes, points: np.ndarray, weights: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
        """The modes' shapes averaged over each patch, (p, modes), and the truncated modes'
        residual compliance there, (p,) (zero without ``residual``); memoised on the modes and
        the patches, which recur (a barrel's variants, the same points in several runs); a
        batch of more than ``stores.MEMO_ROWS`` impacts is neither looked up nor kept."""
        return _BEAM_CACHE.batch(modes, (self.residual, points.shape), (points, weights),
                                 lambda: self._beam_computed(bat, modes, points, weights))

    def _beam_computed(self, bat: BatModel, modes: Modes, points: np.ndarray,
                       weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_beam_at` computed."""
        from batcert.physics.residual import patch_reader, residual_compliance

        reader = patch_reader(modes.z, points, weights)  # (p, nodes), as Modes.at reads
        phi = reader @ modes.shapes.T
        residual = np.zeros(points.shape[0])
        if self.residual:
            residual = residual_compliance(bat, modes, points, weights, reader=reader)
        return phi, residual

    def _shell(self, bat: BatModel, points, weights, half, extras: dict):
        """A hollow bat's wall at each impact (module notes), or None for a solid bat."""
        if bat.construction != "hollow":
            return None
        from batcert.physics import barrel
        modes = barrel.cached_barrel_modes(bat, self.shell_max_frequency)
        if modes is None:
            return None
        z = points.mean(axis=1)
        response = barrel.barrel_response(modes, points, weights,
                                          barrel.patch_half_angle(bat, z, half))
        extras.update(n_shell=response.omega.size, shell_static=response.static,
                      shell_orders=response.orders)
        return response

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
            ``barrel_energy`` left in the shell modes [J] and ``barrel_energy_share``, the
            shell's share of the energy stored in ball and shell at the ball's maximum compression [-].
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
        for members in self._alike(jobs).values():
            batches = [jobs[i][3] for i in members]
            bat, ball, pivot, _, support, *rest = jobs[members[0]]
            # the jobs of one bat, ball, pivot and support share one linear system (a bat's
            # patches and barrel are read for all their rows at once), split back per job
            system, extras = self.linear_system(bat, ball, pivot, _concatenate(batches),
                                                support, rest[0] if rest else None)
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
        steps: dict[float, list[int]] = {}
        for i, job in enumerate(prepared):
            steps.setdefault(self.step_for(job[0]), []).append(i)
        for step, members in steps.items():
            seps = self._integrate([prepared[i] for i in members], step)
            for i, sep in zip(members, seps, strict=True):
                out[i] = self._outcome(*prepared[i], sep)
        return out  # type: ignore[return-value]

    @staticmethod
    def _alike(jobs) -> dict[tuple, list[int]]:
        """The jobs (indices) that share bat, ball, pivot, support and given modes."""
        groups: dict[tuple, list[int]] = {}
        for i, (bat, ball, pivot, _, support, *rest) in enumerate(jobs):
            key = (id(bat), ball, float(pivot), support, id(rest[0]) if rest else None)
            groups.setdefault(key, []).append(i)
        return groups

    def _integrate(self, jobs: list, step: float) -> list[Separation]:
        """One march over the stacked rows of ``jobs`` (prepared as in :meth:`solve_many`);
        each job's :class:`Separation`, its modal columns unpadded."""
        stacked, columns = stack_systems([j[5] for j in jobs])
        sizes = [j[3].impact_location.size for j in jobs]
        bounds = np.concatenate([[0], np.cumsum(sizes)])
        balls = [j[1] for j in jobs]
        per_row = [np.repeat([getattr(b, a) for b in balls], sizes) for a in ("k1", "alpha")]
        relative = np.concatenate([j[3].relative_speed for j in jobs])
        restitution: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None
        if self.ball_loss == "compression":
            laws, owner = _laws(balls, sizes)

            def by_ball(u_top, rows):
                beta = np.empty(rows.size)
                for k, law in enumerate(laws):
                    mine = owner[rows] == k
                    if mine.any():
                        beta[mine] = law(u_top[mine], rows[mine])
                return beta
            restitution = laws[0] if len(laws) == 1 else by_ball
            beta = by_ball(np.full(bounds[-1], 1e-12), np.arange(bounds[-1]))
        else:
            beta = np.concatenate([contact.restitution_exponent(b.alpha, b.cor(j[3].relative_speed))
                                   for b, j in zip(balls, jobs, strict=True)])
        sep = march(stacked, per_row[0], per_row[1], beta, relative, step,
                    self.max_contact_time, restitution)
        return [Separation(impulse=sep.impulse[a:b], time=sep.time[a:b],
                           separated=sep.separated[a:b], peak_force=sep.peak_force[a:b],
                           max_compression=sep.max_compression[a:b],
                           modal=sep.modal[a:b][:, cols],
                           barrel_share=None if jobs[k][5].shell_columns is None
                           or sep.barrel_share is None else sep.barrel_share[a:b])
                for k, (a, b, cols) in enumerate(zip(bounds[:-1], bounds[1:], columns,
                                                      strict=True))]

    def _outcome(self, bat: BatModel, ball: BallModel, pivot: float, batch: ImpactBatch,
                 support: str, system: LinearSystem, extras: dict,
                 sep: Separation) -> ImpactOutcome:
        """Exit speed, momentum outcome and diagnostics of one job from its separation state."""
        r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
        e0 = (contact.compression_cor(ball, sep.max_compression)
              if self.ball_loss == "compression"
              else np.asarray(ball.cor(batch.relative_speed), dtype=float))
        vb = vp + sep.impulse / ball.mass
        k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
        w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
        om = system.omega
        zeta = system.zeta[:, None]
        q = sep.modal.imag / (om * np.sqrt(1 - zeta**2))
        p = sep.modal.real - zeta * om * q
        energy = 0.5 * (p**2 + (om * q) ** 2)
        stored = ball.k1 * sep.max_compression ** (1 + ball.alpha) / (1 + ball.alpha)
        diag = {"contact_time": sep.time, "peak_force": sep.peak_force,
                "max_compression": sep.max_compression,
                "vibrational_energy": energy.sum(1), "ball_energy_loss": stored * (1 - e0**2),
                "approach_energy": 0.5 * ball.mass / (1 + k) * batch.relative_speed**2,
                "e0": e0, "separated": sep.separated}
        if system.shell_columns is not None:
            diag["barrel_energy"] = energy[:, system.shell_columns].sum(1)
            diag["barrel_energy_share"] = sep.barrel_share
        if self.record_states:
            diag.update(_states(system, extras, sep, q, p, pivot, w1 * r, w1))
        return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k,
                             diagnostics=diag)


# the entries of linear_system's extras that hold one row per impact
_ROW_EXTRAS = ("phi", "beam_rigid_mass", "shell_static")


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


def _laws(balls: list[BallModel], sizes: list[int]) -> tuple[list, np.ndarray]:
    """The restitution laws of the jobs' balls and the law of each row: one law per distinct
    ball (a run's jobs usually share one), and one vectorised law for the balls that share a
    contact law and COR speeds but differ in mass or COR (the samples of a ball lot)."""
    families: dict[tuple, dict[BallModel, int]] = {}
    for b in balls:
        families.setdefault((b.k1, b.alpha, b.cor_speeds), {}).setdefault(b, 0)
    laws: list = []
    law_of: dict[BallModel, tuple[int, int | None]] = {}
    for (k1, alpha, speeds), members in families.items():
        if len(members) == 1:
            (b,) = members
            law_of[b] = (len(laws), None)
            laws.append(contact.compression_restitution(b))
            continue
        family = list(members)
        for i, b in enumerate(family):
            law_of[b] = (len(laws), i)
        laws.append((family, k1, alpha, speeds))
    owner = np.repeat([law_of[b][0] for b in balls], sizes)
    member = np.repeat([-1 if law_of[b][1] is None else law_of[b][1] for b in balls], sizes)
    out = []
    for law in laws:
        if callable(law):
            out.append(law)
            continue
        family, k1, alpha, speeds = law
        rows = owner == len(out)
        mass = np.zeros(owner.size)
        values = np.ones((owner.size, len(speeds)))
        mass[rows] = np.array([b.mass for b in family])[member[rows]]
        values[rows] = np.array([b.cor_values for b in family], dtype=float)[member[rows]]
        out.append(contact.compression_restitution_rows(k1, alpha, speeds, mass, values))
    return out, owner


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
