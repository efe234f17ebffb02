"""Nathan's (2000) hysteresis ball against a rigid wall, in closed form: its COR, largest
compression, peak force and the times of the impact (:func:`rigid_wall_impact`; the law:
:mod:`batcert.physics.balls.power_law`).

Units: SI throughout ([m], [N], [s], [kg]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.balls.power_law import max_compression, restitution_exponent

__all__ = ["RigidWallImpact", "rigid_wall_impact"]


def _quarter_time(p, s_from):
    """``integral_{s_from}^1 ds / sqrt(1 - s^p)`` [-], via the regularised incomplete beta
    function: with ``x = s^p`` it is ``B(1/p, 1/2) (1 - I_{s_from^p}(1/p, 1/2)) / p``."""
    a = 1.0 / p
    from scipy.special import beta as beta_function  # lazy: ~0.5 s to import
    from scipy.special import betainc

    return beta_function(a, 0.5) * (1.0 - betainc(a, 0.5, np.asarray(s_from, float) ** p)) / p


@dataclass(frozen=True)
class RigidWallImpact:
    """A ball hitting a rigid wall normally, from the closed-form solution of the law."""

    speed: np.ndarray  # impact speed [m/s]
    e0: np.ndarray  # law parameter used [-]
    cor: np.ndarray  # rebound / impact speed [-]
    max_compression: np.ndarray  # [m]
    peak_force: np.ndarray  # [N]
    compression_time: np.ndarray  # contact start to maximum compression [s]
    contact_time: np.ndarray  # contact start to separation [s]
    collision_time: np.ndarray  # time over which the central `fraction` of the impulse acts [s]
    fraction: float  # impulse fraction of `collision_time` [-]


def rigid_wall_impact(speed, mass, k1, alpha, e0, fraction: float = 0.99) -> RigidWallImpact:
    """Closed-form rigid-wall impact of the hysteresis law (Nathan 2000).

    With ``p = 1 + alpha`` (compression) or ``1 + beta`` (restitution), energy conservation on
    each branch gives the speed as a function of compression, ``v(u) = v_0 sqrt(1 - (u/u_m)^p)``
    with ``v_0 = v`` on compression and ``e0 v`` on restitution, so each branch lasts
    ``(u_m / v_0) integral ds / sqrt(1 - s^p)`` (an incomplete beta function). The rebound speed
    follows from the energy the restitution branch returns, ``k1 u_m^(1+alpha) / (1+beta)``,
    hence ``cor = sqrt((1+alpha)/(1+beta)) = e0``.

    The *collision time* is the interval over which the central ``fraction`` of the impulse
    ``m v (1 + e0)`` is delivered (from ``(1-fraction)/2`` to ``(1+fraction)/2`` of it), the weak
    tails at contact start and separation being left out; the ball's momentum fixes the
    compression at both instants.

    Parameters
    ----------
    speed : array_like
        Normal impact speed [m/s].
    mass : float
        Ball mass [kg].
    k1 : float
        Compression stiffness [N / m^alpha].
    alpha : float
        Compression exponent [-].
    e0 : array_like
        Law COR parameter [-] (e.g. ``ball.cor(speed)``).
    fraction : float
        Impulse fraction defining the collision time [-].

    Returns
    -------
    RigidWallImpact
    """
    v = np.abs(np.asarray(speed, dtype=float))
    e0 = np.broadcast_to(np.asarray(e0, dtype=float), v.shape)
    if not 0 < fraction < 1:
        raise ValueError(f"fraction must lie in (0, 1), got {fraction}")
    if np.any(v <= 0):
        raise ValueError("impact speed must be positive")
    beta = restitution_exponent(alpha, e0)
    um = max_compression(v, mass, k1, alpha)
    pc, pr = 1.0 + alpha, 1.0 + beta
    rebound = np.sqrt(2.0 * k1 * um ** (1.0 + alpha) / (mass * pr))
    t_comp = um / v * _quarter_time(pc, 0.0)
    t_rest = um / rebound * _quarter_time(pr, 0.0)
    lo, hi = 0.5 * (1.0 - fraction), 0.5 * (1.0 + fraction)
    branches = _Branches(v, rebound / v, um, rebound, t_comp, pc, pr)
    return RigidWallImpact(speed=v, e0=e0, cor=branches.cor, max_compression=um,
                           peak_force=k1 * um**alpha, compression_time=t_comp,
                           contact_time=t_comp + t_rest,
                           collision_time=branches.time_at(hi) - branches.time_at(lo),
                           fraction=fraction)


@dataclass(frozen=True)
class _Branches:
    """The two branches of a rigid-wall impact (:func:`rigid_wall_impact`): compression from
    ``speed`` [m/s] to rest at ``max_compression`` [m] in ``compression_time`` [s], restitution
    from it to separation at ``rebound`` = ``cor`` ``speed`` [m/s]; ``pc = 1 + alpha`` and
    ``pr = 1 + beta`` [-], the exponents of ``v(u)`` on each."""

    speed: np.ndarray
    cor: np.ndarray
    max_compression: np.ndarray
    rebound: np.ndarray
    compression_time: np.ndarray
    pc: float
    pr: np.ndarray

    def time_at(self, f):
        """Time from contact start [s] at which the fraction ``f`` [-] of the impulse
        ``m v (1 + cor)`` has been delivered: the ball's velocity (+ toward the wall) is then
        ``v (1 - f (1 + cor))``, which fixes its compression on one branch or the other."""
        v, cor, um, pc, pr = self.speed, self.cor, self.max_compression, self.pc, self.pr
        vel = 1.0 - f * (1.0 + cor)  # / v; > 0 still compressing
        comp = vel > 0
        s_c = np.clip(1.0 - np.where(comp, vel, 0.0) ** 2, 0.0, 1.0) ** (1.0 / pc)
        s_r = np.clip(1.0 - np.where(comp, 0.0, -vel / cor) ** 2, 0.0, 1.0) ** (1.0 / pr)
        t_comp = self.compression_time
        return np.where(comp, t_comp - um / v * _quarter_time(pc, s_c),
                        t_comp + um / self.rebound * _quarter_time(pr, s_r))
