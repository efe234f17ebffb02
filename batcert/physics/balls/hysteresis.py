"""Nathan's (2000) power-law hysteresis ball, and that ball against a rigid wall.

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
from typing import ClassVar

import numpy as np

__all__ = ["HysteresisMarch", "PowerLawHysteresis", "RigidWallImpact", "compression_cor",
           "compression_restitution", "compression_restitution_rows", "contact_force",
           "deformation_work", "equivalent_wall_speed", "max_compression", "peak_force",
           "restitution_exponent", "rigid_wall_impact"]

_TINY = 1e-300  # floor of the compression inside log() [m]


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


def compression_cor(law: PowerLawHysteresis, mass: float, compression, k1=None) -> np.ndarray:
    """The ball's COR for a collision in which it is compressed by ``compression`` [m]: its
    rigid-wall COR (``law.cor_at``) at the :func:`equivalent_wall_speed`.

    A ball's loss grows with how hard it is squeezed; its COR is measured against a rigid wall,
    where all the relative kinetic energy goes into the ball. Against a recoiling bat (reduced
    mass ``m M / (m + M)``) or a compliant barrel the ball is squeezed less and, by this rule,
    loses the fraction of its stored energy that a wall impact storing the same energy loses.
    ``k1`` [N/m^alpha], default the law's: the stiffness the impact's contact has (a convex
    surface's, :mod:`batcert.physics.balls.footprint`), which sets the energy stored.
    """
    k1 = law.k1 if k1 is None else k1
    return np.asarray(law.cor_at(equivalent_wall_speed(compression, mass, k1, law.alpha)),
                      dtype=float)


def compression_restitution(law: PowerLawHysteresis, mass: float, k1=None):
    """``beta(u_top, rows)``: the restitution exponent of :func:`restitution_exponent` for the
    :func:`compression_cor` at the largest compression so far, for the time stepping to
    re-evaluate as the ball compresses (fixed once the compression has peaked); ``k1`` as in
    :func:`compression_cor`, a scalar or one per row (then indexed by ``rows``)."""
    k1 = law.k1 if k1 is None else np.asarray(k1, dtype=float)

    def beta(u_top, rows=None):
        k = k1 if np.ndim(k1) == 0 or rows is None else k1[rows]
        e0 = compression_cor(law, mass, u_top, k)
        return (1.0 + law.alpha) / e0**2 - 1.0
    return beta


def compression_restitution_rows(k1, alpha: float, speeds, mass, values):
    """:func:`compression_restitution` for balls that share a contact law (``alpha`` and the
    speeds of their COR points) but differ, row by row, in ``mass`` [kg], shape (rows,), COR
    values ``values`` [-], shape (rows, points), and ``k1`` [N/m^alpha] (a scalar or one per
    row): a ball lot's spread. Between the points the COR is linear in speed and it is held
    beyond them, as :meth:`PowerLawHysteresis.cor_at`."""
    sp = np.asarray(speeds, dtype=float)
    mass, values = np.asarray(mass, dtype=float), np.asarray(values, dtype=float)
    k1 = np.asarray(k1, dtype=float)

    def beta(u_top, rows):
        k = k1 if k1.ndim == 0 else k1[rows]
        v = equivalent_wall_speed(u_top, mass[rows], k, alpha)
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


@dataclass(frozen=True)
class PowerLawHysteresis:
    """Parameters of Nathan's (2000) law (module notes): ``k1`` [N/m^alpha], ``alpha`` [-], and
    the rigid-wall COR at the ``cor_speeds`` [m/s], ``cor_values`` [-] that set ``e0``
    (piecewise linear in speed, held beyond the first and last point)."""

    k1: float
    alpha: float
    cor_speeds: tuple[float, ...]
    cor_values: tuple[float, ...]
    name: ClassVar[str] = "power-law-hysteresis"

    def cor_at(self, speed) -> np.ndarray:
        """The law's rigid-wall COR ``e0`` at normal impact speed ``speed`` [m/s]: the points,
        linear between them, constant beyond the first and last (a single point: one COR)."""
        v = np.abs(np.asarray(speed, dtype=float))
        return np.interp(v, self.cor_speeds, self.cor_values)

    def wall_cor(self, mass: float, speed) -> np.ndarray:
        """Rigid-wall COR at ``speed`` [m/s]: ``e0`` itself, whatever the mass (the law's
        COR does not depend on the compression's size)."""
        return self.cor_at(speed)

    def body_cor(self, mass: float, speed, recoil, rule: str = "compression") -> np.ndarray:
        """COR against a rigid body of effective-mass ratio ``recoil`` [-] at approach speed
        ``speed`` [m/s]: ``e0`` at the wall speed of equal compression, ``v / sqrt(1 + k)``
        (``rule="compression"``: the ball stores the approach energy of the reduced mass), or
        at ``v`` itself (``"relative-speed"``, batcert 0.1)."""
        v = np.abs(np.asarray(speed, dtype=float))
        if rule == "compression":
            v = v / np.sqrt(1.0 + np.asarray(recoil, dtype=float))
        return self.cor_at(v)

    def quasi_static_force(self, u):
        """Force of a slow squeeze to ``u`` [m]: the compression branch, ``k1 u^alpha`` [N]
        (the law has no rate)."""
        return self.k1 * np.maximum(np.asarray(u, dtype=float), 0.0) ** self.alpha

    def wall_impact(self, mass: float, speed, fraction: float = 0.99) -> RigidWallImpact:
        """:func:`rigid_wall_impact` of this ball, ``e0 = cor_at(speed)`` at each speed."""
        v = np.abs(np.asarray(speed, dtype=float))
        return rigid_wall_impact(v, mass, self.k1, self.alpha, self.cor_at(v), fraction)

    def body_impact(self, mass: float, speed, recoil=0.0, history: bool = True, scale=1.0,
                    rule: str = "compression", steps: int | None = None):
        """The ball fired at ``speed`` [m/s] at a rigid body of effective-mass ratio
        ``recoil`` [-] (``scale``: the surface's stiffness factor), integrated
        (:func:`~batcert.physics.balls.impact1d.body_impact`; the closed forms above give the
        same COR and compressions)."""
        from batcert.physics.balls.impact1d import STEPS, body_impact, contact_time_estimate

        v, k, s = (np.ravel(x) for x in np.broadcast_arrays(
            np.abs(np.asarray(speed, dtype=float)), np.asarray(recoil, dtype=float),
            np.asarray(scale, dtype=float)))
        state = HysteresisMarch.of([self], [mass], np.zeros(v.size, int), s, rule, v)
        times = contact_time_estimate(v, mass / (1.0 + k), self.k1 * s, self.alpha)
        return body_impact(state, mass, v, k, times, history=history, steps=steps or STEPS)

    @staticmethod
    def state_of(laws, masses, which, scale=1.0, rule: str = "compression", speed=None):
        """The time-stepping state of rows of several balls of this law
        (:meth:`HysteresisMarch.of`)."""
        return HysteresisMarch.of(laws, masses, which, scale, rule, speed)

    def contact_time(self, mass: float, speed, recoil=0.0):
        """A scale of the contact time [s] (the compression branch's):
        :func:`~batcert.physics.balls.impact1d.contact_time_estimate`."""
        from batcert.physics.balls.impact1d import contact_time_estimate

        mu = mass / (1.0 + np.asarray(recoil, dtype=float))
        return contact_time_estimate(speed, mu, self.k1, self.alpha)

    def describe(self) -> dict:
        """The parameters (SI) for reports and ``inspect``."""
        return {"model": self.name, "k1": self.k1, "alpha": self.alpha,
                "cor_points": [[float(v), float(e)] for v, e in
                               zip(self.cor_speeds, self.cor_values, strict=True)]}

    def march_rows(self, n: int, mass: float, scale=1.0, rule: str = "compression",
                   speed=None) -> HysteresisMarch:
        """The time-stepping state of ``n`` impacts of this ball (``scale``: the contact's
        stiffness factor per impact); ``rule`` as :meth:`body_cor`, ``speed`` the relative
        speeds for ``"relative-speed"``."""
        return HysteresisMarch.of([self], [mass], np.zeros(n, int), scale, rule, speed)


class HysteresisMarch:
    """Nathan's law during a batched integration, one row per impact: the stages of a step
    (:meth:`start` with the largest compression so far, :meth:`half_a`, :meth:`half_b`,
    :meth:`end`) evaluate :func:`contact_force` in log form (both branches in one exp), and the
    restitution exponent follows the largest compression (:meth:`prepare`, the
    ``"compression"`` rule), fixed once it has peaked. The contact measure is the compression
    itself (the force vanishes exactly when it does)."""

    def __init__(self, k1, alpha, beta, restitution=None):
        self.lk1 = np.log(np.asarray(k1, dtype=float))
        self.alpha = np.asarray(alpha, dtype=float)
        self.beta = np.asarray(beta, dtype=float)
        self.ab = self.alpha - self.beta
        self.restitution = restitution
        self.top_seen = np.full(self.lk1.shape, np.nan)
        self.l_top = np.zeros(self.lk1.shape)

    @classmethod
    def of(cls, laws: list[PowerLawHysteresis], masses, which, scale=1.0,
           rule: str = "compression", speed=None) -> HysteresisMarch:
        """Rows of several hysteresis balls: row ``i`` is ``laws[which[i]]`` of mass
        ``masses[which[i]]``, its ``k1`` times ``scale[i]``."""
        which = np.asarray(which, dtype=int)
        n = which.size
        scale = np.broadcast_to(np.asarray(scale, dtype=float), (n,))
        k1 = np.array([law.k1 for law in laws])[which] * scale
        alpha = np.array([law.alpha for law in laws])[which].astype(float)
        if rule != "compression":
            e0 = np.array([float(laws[w].cor_at(v)) for w, v in
                           zip(which, np.broadcast_to(np.asarray(speed, float), (n,)), strict=True)])
            return cls(k1, alpha, restitution_exponent(alpha, e0))
        restitution = _restitution_rows(laws, masses, which, k1)
        return cls(k1, alpha, restitution(np.full(n, 1e-12), np.arange(n)), restitution)

    def for_step(self, h) -> HysteresisMarch:
        return self

    def prepare(self, u_top, rows) -> None:
        """Re-evaluate ``beta`` where the largest compression has grown since it was last
        evaluated (all rows while the balls compress, none once they all recover); ``rows``
        are the impacts' indices in the whole batch."""
        if self.restitution is None:
            return
        grew = u_top != self.top_seen
        changed = np.count_nonzero(grew)
        if changed == grew.size:
            self.beta, self.top_seen = self.restitution(u_top, rows), u_top.copy()
            self.ab = self.alpha - self.beta
        elif changed:
            idx = np.flatnonzero(grew)
            self.beta[idx] = self.restitution(u_top[idx], rows[idx])
            self.top_seen[idx] = u_top[idx]
            self.ab[idx] = self.alpha[idx] - self.beta[idx]

    def _force(self, x):
        lx = np.log(np.maximum(x, _TINY))
        return np.exp(self.lk1 + self.ab * np.maximum(lx, self.l_top) + self.beta * lx)

    def start(self, u, u_top):
        self.l_top = np.log(u_top)
        return self._force(u)

    def half_a(self, u):
        return self._force(u)

    half_b = end = half_a

    def finish(self, u_new):
        return u_new

    def absorbed(self):
        """None: the engine has the energy in closed form (:meth:`stored`, ``e0``)."""
        return None

    def stored(self, rows, top):
        """Energy stored in the ball at compression ``top`` [m] on the compression branch,
        ``k1 u^(1 + alpha) / (1 + alpha)`` [J], for ``rows``."""
        a1 = 1.0 + self.alpha[rows]
        return np.exp(self.lk1[rows] + a1 * np.log(top)) / a1

    def take(self, keep) -> HysteresisMarch:
        """The rows ``keep`` (indices, a mask or a slice)."""
        out = HysteresisMarch.__new__(HysteresisMarch)
        for name, value in vars(self).items():
            setattr(out, name, value[keep] if isinstance(value, np.ndarray) else value)
        return out

    def offset(self, start: int) -> HysteresisMarch:
        """These rows as rows ``start`` on of a larger batch (what ``prepare``'s rows mean to
        the restitution law, which was built for the whole batch)."""
        if self.restitution is not None and start:
            whole = self.restitution
            self.restitution = lambda u_top, rows: whole(u_top, rows + start)
        return self


def _restitution_rows(laws: list[PowerLawHysteresis], masses, which, k1):
    """``beta(u_top, rows)`` of the ``"compression"`` rule for rows of several balls (row
    ``i`` is ``laws[which[i]]`` of mass ``masses[which[i]]``, its contact stiffness ``k1[i]``):
    one law per ball, and one vectorised law for the balls that share ``alpha`` and the speeds
    of their COR points but differ in mass or COR (the draws of a ball lot)."""
    families: dict[tuple, list[int]] = {}
    for j, law in enumerate(laws):
        families.setdefault((law.alpha, law.cor_speeds), []).append(j)
    parts = []
    for (alpha, speeds), members in families.items():
        rows = np.isin(which, members)
        if len(members) == 1:
            j = members[0]
            parts.append((rows, compression_restitution(laws[j], float(masses[j]), k1)))
            continue
        values = np.ones((which.size, len(speeds)))
        table = {j: laws[j].cor_values for j in members}
        values[rows] = np.array([table[w] for w in which[rows]], dtype=float)
        mass = np.array(masses, dtype=float)[which]
        parts.append((rows, compression_restitution_rows(k1, alpha, speeds, mass, values)))
    if len(parts) == 1:
        return parts[0][1]

    def beta(u_top, rows):
        out = np.empty(rows.size)
        for mine_all, law in parts:
            mine = mine_all[rows]
            if mine.any():
                out[mine] = law(u_top[mine], rows[mine])
        return out
    return beta
