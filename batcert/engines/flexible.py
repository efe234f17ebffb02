"""Flexible impact engine: the ball's hysteresis contact against a vibrating bat, batched.

Model (Nathan 2000; DESIGN.md Sec. 4). ``x`` runs along the impact normal, positive the way
the bat's impact point moves; the pitched ball comes the other way (``v_p < 0``). The bat is its
mass-normalised modes (:mod:`batcert.physics.modes`), rigid first, then bending modes
``q_j'' + 2 zeta omega_j q_j' + omega_j^2 q_j = -phi_j(z) F`` (``zeta = loss_factor / 2``; rigid
modes undamped); the ball obeys ``m x'' = +F``. The compression ``u = y(z) - x`` (bat surface
minus ball displacement, positive = compressed) gives ``F`` by :func:`contact.contact_force`, with
``e0 = ball.cor(w1 r - v_p)`` per impact (see :mod:`batcert.physics.contact`).

Before impact the bat rotates about the pivot at ``w1`` (``support="free"``: the pivot is the
instantaneous centre of the free bat, carried by its translation and rotation modes; nothing
constrains it), bending modes are at rest and the ball touches the surface. A point force only
disturbs the rigid motion along ``phi_r(z)``, so the rigid modes act at the impact point as one
free mass ``M_r = 1 / sum_r phi_r(z)^2`` (``I / r^2`` pinned, ``(1/M + d^2/I_cg)^-1`` free),
merged with the ball into ``w = y_rigid - x``: ``w'' = -F (1/m + 1/M_r)``, ``w'(0) = w1 r - v_p``.

Truncated modes: their quasi-static compliance ``c`` (:func:`batcert.physics.residual.residual_compliance`) is kept
as a residual pseudo-mode of gain ``omega_res sqrt(c)`` at ``omega_res`` = twice the highest kept
frequency, a spring in series with the ball that follows the much slower force.

Hollow bats: the hoop mode of :func:`barrel.barrel_spring_at` (``k_h``, ``m_h``) sits between ball
and beam. ``barrel_model="series"``: a separate barrel mass ``W`` on the
spring ``k_h (y - W)``, which pushes the beam; the linear part of each impact is diagonalised once
(undamped coupled modes, ``eigh``). The beam already holds the shell's mass, so ``m_h`` is counted
twice, and near the barrel's ends, where the (2, 1) hoop mode's mass m_h / sin^2 grows large,
that extra mass makes Eq. 3 (which uses the bat's MOI without it) meaningless, even above 1:
kept for comparison only. ``"modal"`` (default): the hoop deflection ``s`` is one more mode of
the bat (``m_h s'' + k_h s = F``, contact point at ``y - s``), the Lagrangian reduction of the
ring's n = 2 mode, no mass added.
One material, one structural loss factor: every (coupled) mode gets ``zeta = eta / 2``.

Integration: all impacts of the batch advance together, arrays shaped (impacts, modes). The
linear dynamics are propagated exactly; only the contact force is approximated, by the
exponential Runge-Kutta scheme ETDRK4 (Cox & Matthews, J. Comput. Phys. 176 (2002) 430,
Eqs. 26-29) in complex modal coordinates ``Z = p - conj(lambda) q``, ``Z' = lambda Z - g F``.
Stiff modes cost nothing in stability: the step only resolves the contact pulse (at the default
10 us, halving the step moves exit speeds by ~1e-5 for solid bats and up to ~1e-3 for thin hollow
barrels, whose contact force has sharper kinks; Nathan used RK4 at 5 us). An impact ends at
separation (``u <= 0`` after maximum compression); the exit speed is the ball's velocity then,
``w2`` and the COR come from momentum balance (:func:`rigid.momentum_outcome`: Smith 2001
Eqs. 1 and 3 for a pinned bat; for a free bat its angular velocity about the CG and the impact
point's speed after impact), the rigid-body equivalent of what the vibrating bat did.
"""

from __future__ import annotations

import numpy as np

from batcert.engines.base import ImpactBatch, ImpactOutcome
from batcert.physics import contact, rigid
from batcert.physics.ball import BallModel
from batcert.physics.batmodel import BatModel
from batcert.physics.march import LinearSystem, Separation, march
from batcert.physics.modes import Modes

SUPPORTS = ("pinned", "free")
BARREL_MODELS = ("series", "modal")
_PIVOT_CLEARANCE = 1e-3  # an impact closer than this to the pivot is refused [m]


def rigid_mode_velocities(modes: Modes, pivot: float) -> np.ndarray:
    """Rigid-mode velocities that give rotation about ``pivot`` at 1 rad/s [sqrt(kg) m/s].

    Solves ``sum_r qdot_r phi_r(z) = z - pivot`` at the mode nodes (least squares; exact, since
    the rigid modes span linear motions). For a free bat this expresses rotation about the
    instantaneous centre ``pivot`` in the translation and rotation modes. Shape (n_rigid,).
    """
    shapes = modes.shapes[:modes.n_rigid].T  # (nodes, n_rigid)
    sol, *_ = np.linalg.lstsq(shapes, modes.z - pivot, rcond=None)
    return sol


def _couple_barrel(omega_b, phi_b, rigid_mass, k_h, m_h):
    """Undamped coupled modes of (beam rigid mass, bending modes, series barrel) per impact.

    Coordinates ``(y_r, q_1..q_k, W)`` with masses ``(M_r, 1, .., 1, m_h)``, stiffness
    ``diag(0, omega^2, 0)`` plus the barrel spring ``k_h (y_r + phi . q - W)^2 / 2``. Returns,
    for the ``k + 1`` flexible coupled modes (the rigid one, ``y_r = W``, dropped): angular
    frequencies [rad/s] (n, k+1), mass-normalised shapes (n, k+2, k+1) and the barrel compression
    ``y_r + phi . q - W`` per modal coordinate (n, k+1).
    """
    n, k = phi_b.shape
    inv_sqrt_m = np.concatenate([1 / np.sqrt(rigid_mass)[:, None], np.ones((n, k)),
                                 1 / np.sqrt(m_h)[:, None]], axis=1)
    d = np.concatenate([np.ones((n, 1)), phi_b, -np.ones((n, 1))], axis=1) * inv_sqrt_m
    stiff = k_h[:, None, None] * d[:, :, None] * d[:, None, :]
    idx = np.arange(1, k + 1)
    stiff[:, idx, idx] += omega_b**2
    lam, vec = np.linalg.eigh(stiff)
    lam, vec = lam[:, 1:], vec[:, :, 1:]  # ascending: the zero (rigid) mode first
    readout = np.einsum("nd,ndk->nk", d, vec)
    return np.sqrt(np.clip(lam, 0.0, None)), vec * inv_sqrt_m[:, :, None], readout


class FlexibleEngine:
    """Batched flexible-bat impact engine (Nathan 2000 model; module notes).

    Parameters
    ----------
    n_modes : int
        Bending modes kept [-] (Nathan used up to 18).
    time_step : float
        Integration step [s]; only the contact pulse has to be resolved (module notes).
    refine : int
        Beam elements per bat slice for the modes [-].
    residual : bool
        Keep the truncated modes' quasi-static compliance as a series spring (module notes).
    barrel_model : {"series", "modal"}
        How a hollow barrel's hoop mode joins the bat (module notes).
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
        ``residual_energy``, ``barrel_energy`` and ``barrel_energy_before`` [J].
    """

    name = "flexible"
    limitations: dict[str, str] = {}

    def __init__(self, n_modes: int = 24, time_step: float = 1e-5, refine: int = 1,
                 residual: bool = True, barrel_model: str = "modal",
                 max_contact_time: float = 0.02, record_states: bool = False,
                 contact_patch: bool = True, patch_points: int = 15) -> None:
        if n_modes < 1 or int(n_modes) != n_modes:
            raise ValueError(f"n_modes must be a positive integer, got {n_modes!r}")
        if not 0 < time_step <= 1e-4:
            raise ValueError(f"time_step must lie in (0, 1e-4] s, got {time_step!r}")
        if barrel_model not in BARREL_MODELS:
            raise ValueError(f"barrel_model must be one of {BARREL_MODELS}, got {barrel_model!r}")
        self.n_modes, self.time_step, self.refine = int(n_modes), float(time_step), int(refine)
        self.residual, self.barrel_model = bool(residual), barrel_model
        self.max_contact_time, self.record_states = float(max_contact_time), bool(record_states)
        self.contact_patch, self.patch_points = bool(contact_patch), int(patch_points)

    def settings(self) -> dict:
        return {"engine": "flexible", "n_modes": self.n_modes, "time_step": self.time_step,
                "refine": self.refine, "residual_compliance": self.residual,
                "barrel_model": self.barrel_model, "max_contact_time": self.max_contact_time,
                "integrator": "ETDRK4 (Cox & Matthews 2002), exact modal propagation",
                "contact": "Nathan 2000 power-law hysteresis, e0 = ball COR at relative speed",
                "damping": "zeta = material loss factor / 2 on every flexible mode",
                "contact_patch": (f"force spread over the ball's flattened contact length "
                                  f"({self.patch_points} points, semicircular weight)"
                                  if self.contact_patch else "point force")}

    def _patch(self, bat: BatModel, ball: BallModel, z: np.ndarray, speed: np.ndarray):
        """Sample points (p, K) [m from knob] and weights (p, K) of the contact force."""
        if not self.contact_patch:
            return z[:, None], np.ones((z.size, 1))
        u = np.minimum(contact.max_compression(speed, ball.mass, ball.k1, ball.alpha), ball.radius)
        half = np.sqrt(2.0 * ball.radius * u - u**2)
        # keep the patch centred on the impact point: shrink it near the bat's ends
        half = np.minimum(half, np.minimum(z - bat.z_edges[0], bat.z_edges[-1] - z))
        k = np.arange(1, self.patch_points + 1)
        xi = np.cos(k * np.pi / (self.patch_points + 1))
        w = np.sin(k * np.pi / (self.patch_points + 1)) ** 2
        points = z[:, None] + half[:, None] * xi[None, :]
        return points, np.broadcast_to(w / w.sum(), points.shape)

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
        points, weights = self._patch(bat, ball, z, batch.relative_speed)
        phi = (modes.at(points.ravel()).reshape(*points.shape, -1) * weights[..., None]).sum(1)
        nr = modes.n_rigid
        gain, omega = phi[:, nr:], np.broadcast_to(modes.omega[nr:], (z.size, phi.shape[1] - nr))
        rigid_mass = 1.0 / (phi[:, :nr] ** 2).sum(1)
        extras = {"modes": modes, "phi": phi, "n_bending": omega.shape[1],
                  "beam_rigid_mass": rigid_mass, "residual_omega": 0.0}
        if self.residual:
            om_res = 2.0 * float(modes.omega[-1])
            from batcert.physics.residual import residual_compliance
            res = residual_compliance(bat, modes, points, weights)
            gain = _column(gain, om_res * np.sqrt(res))
            omega = _column(omega, np.full(z.size, om_res))
            extras["residual_omega"] = om_res
        system = LinearSystem(omega=np.ascontiguousarray(omega), zeta=zeta,
                              gain=np.ascontiguousarray(gain), rigid_mass=rigid_mass,
                              ball_mass=ball.mass)
        return self._add_barrel(system, extras, bat, z)

    def _add_barrel(self, system: LinearSystem, extras: dict, bat: BatModel, z: np.ndarray):
        """A hollow bat's hoop mode joined to each impact's system (module notes)."""
        from batcert.physics import barrel
        spring = barrel.barrel_spring_at(bat, z)
        if spring is None:
            return system, extras
        has = np.isfinite(spring[0]) & (spring[1] > 0)
        k_h, m_h = np.where(has, spring[0], 0.0), np.where(has, spring[1], 0.0)
        om_h = np.sqrt(k_h / np.where(has, m_h, 1.0))
        extras.update(barrel_stiffness=k_h, barrel_mass=m_h, barrel_omega=om_h)
        gain, rigid_mass = system.gain, system.rigid_mass
        n, k = gain.shape
        omega, readout = _column(system.omega, np.where(has, om_h, 1.0)), np.zeros((n, k + 1))
        if self.barrel_model == "modal":  # the hoop is one more mode: contact at y - s
            gain = _column(gain, np.where(has, -1.0 / np.sqrt(np.where(has, m_h, 1.0)), 0.0))
            readout[:, -1] = -gain[:, -1]
        else:
            shapes = np.zeros((n, k + 2, k + 1))
            shapes[:, 1:k + 1, :k] = np.eye(k)
            gain = _column(gain, np.zeros(n))
            if np.any(has):
                o, sh, rd = _couple_barrel(omega[has, :k], gain[has, :k], rigid_mass[has],
                                           k_h[has], m_h[has])
                omega[has], shapes[has], gain[has], readout[has] = o, sh, sh[:, -1, :], rd
            system.rigid_mass = rigid_mass + m_h
            extras["coupled_shapes"] = shapes
        system.omega, system.gain = omega, gain
        system.barrel_readout, system.barrel_stiffness = readout, k_h
        return system, extras

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
            ``contact_time`` [s], ``peak_force`` [N], ``max_compression`` [m],
            ``vibrational_energy`` left in the flexible modes (bending, residual, barrel) at
            separation [J], ``e0`` [-], ``separated`` [bool]; hollow bats also
            ``barrel_energy_share`` (barrel spring's share of the stored energy at its peak) [-]
            and ``barrel_frequency`` [Hz].
        """
        if batch.impact_location.ndim != 1:
            batch = ImpactBatch(*(np.ravel(a) for a in (
                batch.impact_location, batch.pitch_speed, batch.bat_angular_speed)))
        system, extras = self.linear_system(bat, ball, pivot, batch, support, modes)
        r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
        e0 = np.asarray(ball.cor(batch.relative_speed), dtype=float)
        beta = contact.restitution_exponent(ball.alpha, e0)
        sep = march(system, ball.k1, ball.alpha, beta, batch.relative_speed, self.time_step,
                    self.max_contact_time)
        vb = vp + sep.impulse / ball.mass
        k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
        w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
        om = system.omega
        q = sep.modal.imag / (om * np.sqrt(1 - system.zeta**2))
        p = sep.modal.real - system.zeta * om * q
        diag = {"contact_time": sep.time, "peak_force": sep.peak_force,
                "max_compression": sep.max_compression,
                "vibrational_energy": 0.5 * (p**2 + (om * q) ** 2).sum(1), "e0": e0,
                "separated": sep.separated}
        if system.barrel_stiffness is not None:
            diag["barrel_energy_share"] = sep.barrel_share
            diag["barrel_frequency"] = np.where(extras["barrel_mass"] > 0,
                                                extras["barrel_omega"] / (2 * np.pi), np.nan)
        if self.record_states:
            diag.update(_states(system, extras, sep, q, p, pivot, w1 * r, w1))
        return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k,
                             diagnostics=diag)




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
    modes, nb, k_h = extras["modes"], extras["n_bending"], system.barrel_stiffness
    shapes = extras.get("coupled_shapes")
    v_rigid = v_bat - sep.impulse / system.rigid_mass  # rigid speed of the contact point
    out = {"barrel_energy": np.zeros(q.shape[0]), "barrel_energy_before": np.zeros(q.shape[0])}
    if shapes is None:  # coupled = beam coordinates (bending, residual, modal hoop)
        beam_q, beam_p, yr_dot = q, p, v_rigid
        if k_h is not None:
            out["barrel_energy"] = 0.5 * (p[:, -1] ** 2 + (system.omega[:, -1] * q[:, -1]) ** 2)
    else:  # series barrel: coupled shapes over (y_r, q_1..q_k, W)
        k = shapes.shape[1] - 2
        beam_q, beam_p = (np.einsum("njk,nk->nj", shapes[:, 1:k + 1], x) for x in (q, p))
        yr_dot = v_rigid + np.einsum("nk,nk->n", shapes[:, 0], p)
        w_dot = v_rigid + np.einsum("nk,nk->n", shapes[:, -1], p)
        assert system.barrel_readout is not None  # a series barrel always has its read-out
        s = np.einsum("nk,nk->n", system.barrel_readout, q)
        m_h = extras["barrel_mass"]
        out["barrel_energy"] = 0.5 * (m_h * w_dot**2 + k_h * s**2)
        out["barrel_energy_before"] = 0.5 * m_h * v_bat**2
    # rigid modes: rotation about the pivot, changed only along phi_r (point force at z)
    qd_r = w1[:, None] * rigid_mode_velocities(modes, pivot)[None, :] + extras["phi"][
        :, :modes.n_rigid] * (extras["beam_rigid_mass"] * (yr_dot - v_bat))[:, None]
    res = slice(nb, nb + 1) if extras["residual_omega"] > 0 else slice(nb, nb)
    out.update(modal_velocity=np.concatenate([qd_r, beam_p[:, :nb]], axis=1),
               bending_displacement=beam_q[:, :nb],
               residual_energy=0.5 * (beam_p[:, res] ** 2 + (extras["residual_omega"]
                                                              * beam_q[:, res]) ** 2).sum(1))
    return out
