"""A ball against a rigid body, integrated: rigid-wall tests, and the rigid engine's COR.

The ball (mass ``m``) meets a rigid body whose effective mass at the contact is ``m / k``
(``k = 0``: a massive rigid wall; a rigid bat: the recoil factor ``k``,
:func:`batcert.physics.rigid.recoil_factor`). The compression ``u`` then obeys
``mu u'' = -F`` with the reduced mass ``mu = m / (1 + k)``, ``u(0) = 0``, ``u'(0) = v``, and the
contact law gives ``F`` (any law of :mod:`batcert.physics.balls`, through its time-stepping
state). Each impact ends when the force falls to zero (a viscoelastic ball then is still
compressed). From the impulse ``J``: the COR ``e = J / (mu v) - 1`` (the rebound's relative
speed over the approach's).

Integration: the classical fourth-order Runge-Kutta scheme for ``(u, u')``, whose stage
compressions the contact law's own state follows (its exponential stages, e.g.
:class:`~batcert.physics.balls.viscoelastic.ViscoelasticMarch`), with each impact's step a
fraction ``1 / STEPS`` of an estimate of its contact time, so that slow and fast impacts are
resolved alike. Separation is interpolated linearly in the contact measure within its step.
All impacts advance together (arrays of one row per impact). Units: SI.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert import workspace
from batcert.physics.balls.law import MarchState

STEPS = 300  # steps per estimated contact time (COR converged to about 1e-7, tests)
_MAX_STEPS_FACTOR = 12  # give up (flagged, not separated) after this many contact times


@dataclass(frozen=True)
class BodyImpact:
    """Outcome of ball impacts on rigid bodies, arrays of one value per impact (SI)."""

    speed: np.ndarray  # approach speed [m/s]
    recoil: np.ndarray  # effective-mass ratio k of the body (0: wall) [-]
    cor: np.ndarray  # rebound / approach relative speed [-]
    contact_time: np.ndarray  # first touch to separation [s]
    collision_time: np.ndarray  # time over which the central `fraction` of the impulse acts [s]
    fraction: float  # impulse fraction of `collision_time` [-]
    max_compression: np.ndarray  # [m]
    peak_force: np.ndarray  # [N]
    mean_compression: np.ndarray  # impulse-weighted mean compression, int F u dt / int F dt [m]
    separation_compression: np.ndarray  # compression when the force falls to zero [m]
    separated: np.ndarray  # False where the step cap came first


def contact_time_estimate(speed, reduced_mass, stiffness, exponent):
    """About the contact time [s] of an elastic ``F = k u^a`` spring hit at ``speed``:
    ``3 u_m / v`` with ``u_m = ((1 + a) mu v^2 / (2 k))^(1 / (1 + a))`` (the step's scale)."""
    v = np.abs(np.asarray(speed, dtype=float))
    um = ((1.0 + exponent) * reduced_mass * v**2 / (2.0 * stiffness)) ** (1.0 / (1.0 + exponent))
    return 3.0 * um / v


def body_impact(state: MarchState, mass: float, speed, recoil=0.0, time_scale=None,
                fraction: float = 0.99, steps: int = STEPS, history: bool = True) -> BodyImpact:
    # long (about 90 lines, a third of them the docstring): one loop of the classical RK4 with
    # the separation caught inside it; cut into functions, the per-step state (compression,
    # speed, impulse, work, peaks, the four stages) would travel through a dozen arguments
    """Integrate ball impacts on rigid bodies (module notes).

    Parameters
    ----------
    state
        The contact law's time-stepping state for these impacts, one row each (a law's
        ``march_rows``).
    mass : float or array_like
        Ball mass ``m`` [kg] (or one per impact).
    speed : array_like
        Approach speed ``v > 0`` [m/s], (n,).
    recoil : array_like
        Effective-mass ratio ``k`` of the body [-], (n,); 0 for a rigid wall.
    time_scale : array_like
        An estimate of each contact time [s] (:func:`contact_time_estimate`); the step is
        ``time_scale / steps``.
    fraction : float
        Impulse fraction of the collision time [-].
    steps : int
        Steps per ``time_scale``.
    history : bool
        Keep the impulse's history for the collision time (else it is NaN).

    Returns
    -------
    BodyImpact
    """
    v0 = np.abs(np.asarray(speed, dtype=float)).ravel()
    n = v0.size
    k = np.broadcast_to(np.asarray(recoil, dtype=float), (n,)).astype(float)
    inv_mu = (1.0 + k) / np.broadcast_to(np.asarray(mass, dtype=float), (n,))
    h = np.broadcast_to(np.asarray(time_scale, dtype=float), (n,)) / steps
    state = state.for_step(h)
    u, v = np.zeros(n), v0.copy()
    imp, fu = np.zeros(n), np.zeros(n)
    u_top, f_peak = np.full(n, 1e-300), np.zeros(n)
    g_prev = np.zeros(n)
    done = np.zeros(n, bool)
    out_imp, out_fu, out_t = np.zeros(n), np.zeros(n), np.full(n, np.nan)
    out_top, out_peak, out_sep = np.zeros(n), np.zeros(n), np.zeros(n)
    history_t, history_j = [np.zeros(n)], [np.zeros(n)]
    rows = np.arange(n)
    crossing = state.crossing
    for step in range(1, steps * _MAX_STEPS_FACTOR + 1):
        state.prepare(u_top, rows)
        f0 = state.start(u, u_top)
        ua, va = u + 0.5 * h * v, v - 0.5 * h * inv_mu * f0
        fa = state.half_a(ua)
        ub, vb = u + 0.5 * h * va, v - 0.5 * h * inv_mu * fa
        fb = state.half_b(ub)
        uc, vc = u + h * vb, v - h * inv_mu * fb
        fc = state.end(uc)
        s4 = f0 + 2.0 * (fa + fb) + fc
        u_new = u + h / 6.0 * (v + 2.0 * (va + vb) + vc)
        v = v - h / 6.0 * inv_mu * s4
        dj = h / 6.0 * s4
        imp = imp + dj
        fu = fu + h / 6.0 * (f0 * u + 2.0 * (fa * ua + fb * ub) + fc * uc)
        f_peak = np.maximum(f_peak, np.maximum(np.maximum(f0, fa), np.maximum(fb, fc)))
        u_top = np.maximum(u_top, np.maximum(u_new, np.maximum(ub, uc)))
        g = state.finish(u_new)
        if history:
            history_t.append(step * h)
            history_j.append(imp.copy())
        sep = (g <= 0) & (g_prev > 0) & ~done
        if np.any(sep):
            frac = g_prev[sep] / (g_prev[sep] - g[sep])
            out_t[sep] = (step - 1 + frac) * h[sep]
            out_imp[sep], out_fu[sep] = imp[sep], fu[sep]
            if crossing:  # the last step's impulse up to separation only (engines/kernel/march.py)
                out_imp[sep] += 0.5 * f0[sep] * frac * h[sep] - dj[sep]
            out_top[sep], out_peak[sep] = u_top[sep], f_peak[sep]
            out_sep[sep] = u[sep] + frac * (u_new[sep] - u[sep])
            done |= sep
            if done.all():
                break
        u, g_prev = u_new, g
    left = ~done
    out_imp[left], out_fu[left], out_top[left], out_peak[left] = (
        imp[left], fu[left], u_top[left], f_peak[left])
    out_t[left] = step * h[left]
    cor = out_imp * inv_mu / v0 - 1.0
    collision = (_collision_times(history_t, history_j, out_imp, fraction) if history
                 else np.full(n, np.nan))
    with np.errstate(invalid="ignore", divide="ignore"):
        mean_u = np.where(out_imp > 0, out_fu / out_imp, 0.0)
    return BodyImpact(speed=v0, recoil=k, cor=cor, contact_time=out_t,
                      collision_time=collision, fraction=fraction, max_compression=out_top,
                      peak_force=out_peak, mean_compression=mean_u,
                      separation_compression=out_sep, separated=done)


def _collision_times(history_t: list, history_j: list, impulse: np.ndarray,
                     fraction: float) -> np.ndarray:
    """The time each impact took to deliver the middle ``fraction`` of its ``impulse``, from
    the impulse's history [s]."""
    times, impulses = np.array(history_t), np.array(history_j)
    lo, hi = 0.5 * (1.0 - fraction), 0.5 * (1.0 + fraction)
    return np.array([np.interp(hi * impulse[i], impulses[:, i], times[:, i])
                     - np.interp(lo * impulse[i], impulses[:, i], times[:, i])
                     for i in range(impulse.size)])


# above this many distinct balls in one batch (a Monte Carlo's drawn balls), one batched
# integration of every row beats a wall table per ball (321 speeds each)
MANY_BALLS = 4


def wall_mean_compression(balls: list, which, speed, steps: int = STEPS) -> np.ndarray:
    """The impulse-weighted mean compression [m] of rows of balls (``balls``: (law, mass)
    pairs of one law class; row ``i`` is ``balls[which[i]]``) fired at a rigid flat wall at
    ``speed`` [m/s]: from each ball's :func:`wall_table` where they are few, else all rows in
    one integration (``steps`` per contact time); the two agree to about 2e-6, the
    integration's own accuracy at :data:`STEPS`."""
    which = np.asarray(which, dtype=int).ravel()
    if len(balls) > MANY_BALLS:
        return _walls(balls, which, speed, steps).mean_compression
    v = np.abs(np.asarray(speed, dtype=float)).ravel()
    out = np.empty(v.size)
    for j, (law, mass) in enumerate(balls):
        rows = which == j
        if np.any(rows):
            out[rows] = from_wall_table(law, float(mass), v[rows], "mean_compression")
    return out


def wall_cors(balls: list, which, speed, steps: int = STEPS) -> np.ndarray:
    """The rigid-wall COR of rows of balls (as :func:`wall_mean_compression`), in one
    integration (to about 2e-7): the drawn balls of a Monte Carlo, each of its own."""
    return _walls(balls, which, speed, steps).cor


def _walls(balls: list, which, speed, steps: int) -> BodyImpact:
    which = np.asarray(which, dtype=int)
    v = np.abs(np.asarray(speed, dtype=float)).ravel()
    laws = [law for law, _ in balls]
    masses = np.array([m for _, m in balls], dtype=float)
    state = type(laws[0]).state_of(laws, list(masses), which, 1.0, "compression", v)
    times = np.empty(v.size)
    for j, law in enumerate(laws):
        rows = which == j
        times[rows] = law.contact_time(masses[j], v[rows])
    return body_impact(state, masses[which], v, 0.0, times, steps=steps, history=False)


# a ball's rigid-wall table: log-spaced speeds [m/s]
TABLE_SPEEDS = np.exp(np.linspace(np.log(0.1), np.log(300.0), 321))
_LOG_SPEEDS = np.log(TABLE_SPEEDS)


def wall_table(law, mass: float) -> dict[str, np.ndarray]:
    """The ball (``law``, ``mass`` [kg]) against a rigid flat wall at :data:`TABLE_SPEEDS`:
    its COR and impulse-weighted mean compression (one batched integration, about 20 ms),
    read-only; kept by the active workspace (kind ``ball-wall``, also in its disk store where
    one is attached: every run of the ball reads it)."""
    return workspace.current().call("ball-wall", _wall_table_of, law, float(mass),
                                    save=dict, load=_wall_table_from)


def _wall_table_of(law, mass: float) -> dict[str, np.ndarray]:
    res = law.body_impact(mass, TABLE_SPEEDS, 0.0, history=False)
    return _read_only_table({"cor": res.cor, "mean_compression": res.mean_compression})


def _wall_table_from(a: dict | None) -> dict[str, np.ndarray] | None:
    if a is None or any(k not in a or np.shape(a[k]) != TABLE_SPEEDS.shape
                        for k in ("cor", "mean_compression")):
        return None
    return _read_only_table({k: np.array(a[k], dtype=float) for k in ("cor", "mean_compression")})


def _read_only_table(table: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    for values in table.values():
        values.setflags(write=False)
    return table


def from_wall_table(law, mass: float, speed, column: str) -> np.ndarray | float:
    """``column`` of :func:`wall_table` at ``speed`` [m/s] (four-point Lagrange interpolation
    in log speed; the mean compression in log too), integrated directly outside the table."""
    v = np.abs(np.asarray(speed, dtype=float))
    inside = (v >= TABLE_SPEEDS[0]) & (v <= TABLE_SPEEDS[-1])
    out = np.empty(v.shape)
    if np.any(inside):
        values = wall_table(law, mass)[column]
        logged = column != "cor"
        got = _cubic(np.log(v[inside]), _LOG_SPEEDS, np.log(values) if logged else values)
        out[inside] = np.exp(got) if logged else got
    if not np.all(inside):
        res = law.body_impact(mass, v[~inside], 0.0, history=False)
        out[~inside] = getattr(res, column)
    return out if out.ndim else float(out)


def _cubic(x, nodes, values):
    """Four-point Lagrange interpolation of ``values`` at uniform ``nodes``, at ``x``."""
    step = nodes[1] - nodes[0]
    i = np.clip(np.floor((x - nodes[0]) / step).astype(int) - 1, 0, nodes.size - 4)
    t = (x - nodes[i]) / step  # in [0, 3]: between the 2nd and 3rd node inside
    y0, y1, y2, y3 = (values[i + j] for j in range(4))
    return (-y0 * (t - 1) * (t - 2) * (t - 3) / 6 + y1 * t * (t - 2) * (t - 3) / 2
            - y2 * t * (t - 1) * (t - 3) / 2 + y3 * t * (t - 1) * (t - 2) / 6)
