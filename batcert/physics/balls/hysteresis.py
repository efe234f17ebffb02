"""Nathan's (2000) power-law hysteresis ball: its parameters (:class:`PowerLawHysteresis`, the
registry's ``power-law-hysteresis``), the ``e0`` each impact gets, and its state in a batched
time integration (:class:`HysteresisMarch`).

The law's equations are in :mod:`batcert.physics.balls.power_law` (``F = k1 u^alpha`` on
compression, ``k1 u_m^alpha (u / u_m)^beta`` on restitution, ``beta = (1 + alpha) / e0^2 - 1``:
against a rigid wall the COR is ``e0`` at every impact speed), the closed-form rigid-wall impact
in :mod:`batcert.physics.balls.wall_impact`; both are importable from here too.

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

from batcert.physics.balls.law import MarchState
from batcert.physics.balls.power_law import (
    contact_force,
    deformation_work,
    equivalent_wall_speed,
    max_compression,
    peak_force,
    restitution_exponent,
)
from batcert.physics.balls.wall_impact import RigidWallImpact, rigid_wall_impact

__all__ = ["HysteresisMarch", "PowerLawHysteresis", "RigidWallImpact", "compression_cor",
           "compression_restitution", "compression_restitution_rows", "contact_force",
           "deformation_work", "equivalent_wall_speed", "max_compression", "peak_force",
           "restitution_exponent", "rigid_wall_impact"]

_TINY = 1e-300  # floor of the compression inside log() [m]


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
    def state_of(laws, masses, which, scale=1.0, rule: str = "compression",
                 speed=None) -> MarchState:
        """The time-stepping state of rows of several balls of this law
        (:meth:`HysteresisMarch.of`)."""
        return HysteresisMarch.of(laws, masses, which, scale, rule, speed)

    def contact_time(self, mass: float, speed, recoil=0.0):
        """A scale of the contact time [s] (the compression branch's):
        :func:`~batcert.physics.balls.impact1d.contact_time_estimate`."""
        from batcert.physics.balls.impact1d import contact_time_estimate

        mu = mass / (1.0 + np.asarray(recoil, dtype=float))
        return contact_time_estimate(speed, mu, self.k1, self.alpha)

    def separation_loss(self, mass: float, max_compression, scale, relative_speed,
                        rule: str) -> dict[str, np.ndarray]:
        """The energy the ball lost [J] and its ``e0`` in closed form: the loop of an impact
        that compressed it to ``max_compression`` on a surface of stiffness factor ``scale``
        stores ``k1 u^(1 + alpha) / (1 + alpha)`` and loses ``1 - e0^2`` of it, ``e0`` by
        ``rule`` (:func:`compression_cor`, or the COR at ``relative_speed``)."""
        k1 = self.k1 * scale
        e0 = (compression_cor(self, mass, max_compression, k1) if rule == "compression"
              else np.asarray(self.cor_at(relative_speed), dtype=float))
        stored = k1 * max_compression ** (1 + self.alpha) / (1 + self.alpha)
        return {"ball_energy_loss": stored * (1 - e0**2), "e0": e0}

    def summary(self) -> str:
        """The law and its parameters in one line (``inspect``)."""
        return f"power-law hysteresis: k1 = {self.k1:.4g} N/m^alpha, alpha = {self.alpha:g}"

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

    crossing = False  # the force vanishes with the compression (MarchState)

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
