"""Ball contact law: Nathan's power-law hysteresis, and the ball against a rigid wall.

The law (Nathan, Am. J. Phys. 68 (2000) 979)
--------------------------------------------
The ball is a nonlinear, lossy spring of compression ``u`` [m] (positive = compressed):

* compression (``u`` at its running maximum): ``F = k1 u^alpha``;
* restitution (``u`` below the maximum ``u_m`` reached so far):
  ``F = k2 u^beta = k1 u_m^alpha (u / u_m)^beta``, so both branches meet at ``u_m``, with
  ``beta = (1 + alpha) / e0^2 - 1``;
* ``F = 0`` for ``u <= 0`` (the ball only pushes).

The work done on the ball during compression is ``k1 u_m^(1+alpha) / (1+alpha)``, the work it
returns is ``k1 u_m^(1+alpha) / (1+beta)``; their ratio ``(1+alpha)/(1+beta) = e0^2`` does not
depend on ``u_m``, so against a rigid wall the COR is ``e0`` at every impact speed.

How the parameters come from the spec
-------------------------------------
``k1`` and ``alpha`` are taken from the ball spec (:class:`~batcert.physics.ball.BallModel`;
Nathan's ball: ``k1 = 6.53e7 N/m^1.84``, ``alpha = 1.84``). Real balls lose COR with speed, which a
single ``e0`` cannot express; the spec instead lists the rigid-wall COR at one or more speeds
(``BallModel.cor(speed)``, piecewise linear, constant outside the listed range).

Which ``e0`` an impact gets: by default the ball's loss follows its own deformation. Against a
rigid wall at speed ``v`` the ball compresses to ``u_m(v)`` (:func:`max_compression`) and keeps
``ball.cor(v)^2`` of the energy it stored. Against a bat it is squeezed less: the bat recoils
(reduced mass ``m M / (m + M)``) and a hollow barrel takes part of the deformation (the
trampoline). batcert gives each impact ``e0 = ball.cor(v_eq)`` with ``v_eq`` the wall speed that
compresses the ball as far as the impact does so far (:func:`compression_cor`), re-evaluated as
the ball compresses, so ``e0`` is fixed once the compression has peaked; the restitution branch
that follows uses it. A ball fired at a rigid wall therefore still rebounds with exactly
``ball.cor(v)``, and a ball that meets a compliant barrel loses less, which is the mechanism of
the 2001 study. For a rigid pivoted bat the peak compression is that of a wall impact at
``v_rel / sqrt(1 + k)`` (``k`` the recoil factor), which the rigid engine uses in closed form.
(batcert 0.1 used ``ball.cor(v_rel)`` whatever the compression; the flexible engine keeps that
as ``ball_loss="relative-speed"``.) Energy stored in the *bat's* own compliance escapes the
ball's loss, so even a very stiff bat returns a ball-bat COR slightly above ``e0``.

Units: SI throughout ([m], [N], [s], [kg]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.physics.ball import BallModel

__all__ = ["RigidWallImpact", "ball_wall_impact", "compression_cor", "compression_restitution",
           "contact_force", "deformation_work", "equivalent_wall_speed", "max_compression",
           "peak_force", "restitution_exponent", "rigid_wall_impact"]


def restitution_exponent(alpha, e0):
    """Restitution exponent ``beta = (1 + alpha) / e0^2 - 1`` [-] (Nathan 2000).

    Parameters
    ----------
    alpha : float or array_like
        Compression exponent [-].
    e0 : float or array_like
        Rigid-wall COR the law is to reproduce [-], in (0, 1].

    Returns
    -------
    numpy.ndarray
        ``beta`` [-].

    References
    ----------
    A. M. Nathan, Am. J. Phys. 68 (2000) 979.

    Examples
    --------
    Nathan's ball at 58 m/s (alpha = 1.84, e0 = 0.53): beta = 2.84 / 0.2809 - 1 = 9.11
    (docs/references.md, derived).

    >>> round(float(restitution_exponent(1.84, 0.53)), 2)
    9.11
    """
    e0 = np.asarray(e0, dtype=float)
    if np.any((e0 <= 0) | (e0 > 1)):
        raise ValueError(f"the ball's COR e0 must lie in (0, 1], got {e0}")
    return (1.0 + alpha) / e0**2 - 1.0


def contact_force(u, u_max, k1, alpha, beta):
    """Contact force of the hysteresis law [N] (Nathan 2000).

    Parameters
    ----------
    u : array_like
        Compression [m], positive = compressed.
    u_max : array_like
        Largest compression reached so far [m] (0 before contact). Where ``u >= u_max`` the
        compression branch applies.
    k1 : float
        Compression stiffness [N / m^alpha].
    alpha, beta : float or array_like
        Compression and restitution exponents [-].

    Returns
    -------
    numpy.ndarray
        ``F >= 0`` [N]: ``k1 u^alpha`` on compression, ``k1 u_m^alpha (u/u_m)^beta`` on
        restitution, 0 for ``u <= 0``.
    """
    u = np.clip(np.asarray(u, dtype=float), 0.0, None)
    top = np.maximum(np.asarray(u_max, dtype=float), u)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(top > 0, u / np.where(top > 0, top, 1.0), 0.0)
    return k1 * top**alpha * ratio**beta


def deformation_work(u, u_max, k1, alpha, beta):
    """Net work done on the ball so far, ``integral F du`` along its path [J].

    On compression it is ``k1 u^(1+alpha) / (1+alpha)``; on restitution the energy already
    returned, ``k1 u_m^(1+alpha) (1 - (u/u_m)^(1+beta)) / (1+beta)``, is subtracted. At separation
    (``u = 0``) what is left is the energy the ball dissipated. For a lossless ball
    (``e0 = 1``, ``beta = alpha``) it is the stored elastic energy.
    """
    u = np.clip(np.asarray(u, dtype=float), 0.0, None)
    top = np.maximum(np.asarray(u_max, dtype=float), u)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(top > 0, u / np.where(top > 0, top, 1.0), 0.0)
    stored = k1 * top ** (1.0 + alpha) / (1.0 + alpha)
    returned = k1 * top ** (1.0 + alpha) * (1.0 - ratio ** (1.0 + beta)) / (1.0 + beta)
    return stored - returned


def max_compression(speed, mass, k1, alpha):
    """Largest compression of a ball hitting a rigid wall [m]:
    ``u_m = ((1 + alpha) m v^2 / (2 k1))^(1 / (1 + alpha))`` (energy balance of the compression
    branch). For a ball hitting a body of effective mass ``M``, pass the reduced mass
    ``m M / (m + M)`` and the relative speed.

    Parameters
    ----------
    speed : array_like
        Normal impact speed [m/s].
    mass : float
        Ball (or reduced) mass [kg].
    k1 : float
        Compression stiffness [N / m^alpha].
    alpha : float
        Compression exponent [-].

    Returns
    -------
    numpy.ndarray
        ``u_m`` [m].

    References
    ----------
    A. M. Nathan, Am. J. Phys. 68 (2000) 979 (the compression law).

    Examples
    --------
    Nathan's ball (0.145 kg, k1 = 6.53e7 N/m^1.84) against a rigid wall at 58 m/s compresses
    17.7 mm (docs/references.md, derived):

    >>> round(float(max_compression(58.0, 0.145, 6.53e7, 1.84)) * 1e3, 1)
    17.7
    """
    v = np.abs(np.asarray(speed, dtype=float))
    return ((1.0 + alpha) * mass * v**2 / (2.0 * k1)) ** (1.0 / (1.0 + alpha))


def equivalent_wall_speed(compression, mass, k1, alpha):
    """The rigid-wall impact speed that compresses the ball by ``compression`` [m/s]:
    ``v = sqrt(2 k1 u^(1+alpha) / ((1+alpha) m))``, the inverse of :func:`max_compression`
    (the ball has then stored the same energy, ``k1 u^(1+alpha) / (1+alpha)``).

    Parameters
    ----------
    compression : array_like
        Largest compression of the ball [m].
    mass : float
        Ball mass [kg].
    k1, alpha : float
        Compression law [N/m^alpha], [-].
    """
    u = np.maximum(np.asarray(compression, dtype=float), 0.0)
    return np.sqrt(2.0 * k1 * u ** (1.0 + alpha) / ((1.0 + alpha) * mass))


def compression_cor(ball: BallModel, compression) -> np.ndarray:
    """The ball's COR for a collision in which it is compressed by ``compression`` [m]: its
    rigid-wall COR (``ball.cor``) at the :func:`equivalent_wall_speed`.

    A ball's loss grows with how hard it is squeezed; its COR is measured against a rigid wall,
    where all the relative kinetic energy goes into the ball. Against a recoiling bat (reduced
    mass ``m M / (m + M)``) or a compliant barrel the ball is squeezed less and, by this rule,
    loses the fraction of its stored energy that a wall impact storing the same energy loses.
    """
    return np.asarray(ball.cor(equivalent_wall_speed(compression, ball.mass, ball.k1,
                                                     ball.alpha)), dtype=float)


def compression_restitution(ball: BallModel):
    """``beta(u_top, rows)``: the restitution exponent of :func:`restitution_exponent` for the
    :func:`compression_cor` at the largest compression so far, for :func:`march` to re-evaluate
    as the ball compresses (fixed once the compression has peaked); ``rows`` (which impacts)
    does not matter for one ball."""
    def beta(u_top, rows=None):
        e0 = compression_cor(ball, u_top)
        return (1.0 + ball.alpha) / e0**2 - 1.0
    return beta


def compression_restitution_rows(k1: float, alpha: float, speeds, mass, values):
    """:func:`compression_restitution` for balls that share a contact law (``k1``, ``alpha``)
    and the speeds of their COR points but differ, row by row, in ``mass`` [kg], shape
    (rows,), and COR values ``values`` [-], shape (rows, points): a ball lot's spread.
    Between the points the COR is linear in speed and it is held beyond them, as
    :meth:`BallModel.cor`."""
    sp = np.asarray(speeds, dtype=float)
    mass, values = np.asarray(mass, dtype=float), np.asarray(values, dtype=float)

    def beta(u_top, rows):
        v = equivalent_wall_speed(u_top, mass[rows], k1, alpha)
        if sp.size == 1:
            e0 = values[rows, 0]
        else:
            i = np.clip(np.searchsorted(sp, v, side="right") - 1, 0, sp.size - 2)
            t = np.clip((v - sp[i]) / (sp[i + 1] - sp[i]), 0.0, 1.0)
            e0 = (1.0 - t) * values[rows, i] + t * values[rows, i + 1]
        return (1.0 + alpha) / e0**2 - 1.0
    return beta


def peak_force(speed, mass, k1, alpha):
    """Peak force ``k1 u_m^alpha`` of a rigid-wall impact [N] (see :func:`max_compression`)."""
    return k1 * max_compression(speed, mass, k1, alpha) ** alpha


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
    # impulse fraction f delivered: ball velocity (+ toward the wall) is v (1 - f (1 + e0))
    lo, hi = 0.5 * (1.0 - fraction), 0.5 * (1.0 + fraction)
    cor = rebound / v

    def time_at(f):
        vel = 1.0 - f * (1.0 + cor)  # / v; > 0 still compressing
        comp = vel > 0
        s_c = np.clip(1.0 - np.where(comp, vel, 0.0) ** 2, 0.0, 1.0) ** (1.0 / pc)
        s_r = np.clip(1.0 - np.where(comp, 0.0, -vel / cor) ** 2, 0.0, 1.0) ** (1.0 / pr)
        return np.where(comp, t_comp - um / v * _quarter_time(pc, s_c),
                        t_comp + um / rebound * _quarter_time(pr, s_r))

    return RigidWallImpact(speed=v, e0=e0, cor=cor, max_compression=um,
                           peak_force=k1 * um**alpha, compression_time=t_comp,
                           contact_time=t_comp + t_rest,
                           collision_time=time_at(hi) - time_at(lo), fraction=fraction)


def ball_wall_impact(ball: BallModel, speed, fraction: float = 0.99) -> RigidWallImpact:
    """:func:`rigid_wall_impact` for a ball spec, with ``e0 = ball.cor(speed)`` at each speed
    (for ``batcert inspect`` on a ball)."""
    v = np.abs(np.asarray(speed, dtype=float))
    return rigid_wall_impact(v, ball.mass, ball.k1, ball.alpha, ball.cor(v), fraction)
