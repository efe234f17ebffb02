"""The viscoelastic ball: a nonlinear standard linear solid (Zener) contact law.

The law
-------
The ball's contact force follows its compression ``u`` [m] (positive = compressed) through the
hereditary integral of a relaxation function against the elastic "Hertz-like" measure
``x = u^a`` (Lee & Radok, J. Appl. Mech. 27 (1960) 438, for a viscoelastic sphere):

    F(t) = integral_0^t psi(t - t') dx/dt' dt',    psi(t) = k_inf + k_1 exp(-t / tau),

with ``k0 = k_inf + k_1`` the instantaneous and ``k_inf = r k0`` the relaxed (quasi-static)
stiffness. With one relaxation time the integral is a Maxwell branch with internal variable
``s`` (the branch's relaxed part of ``x``):

    F = k0 x - k_1 s,    ds/dt = (x - s) / tau,    s(0) = 0,

and ``F >= 0``: the ball only pushes. The ball separates when the force falls to zero, while it
is still compressed (``u > 0``): the Maxwell branch has not yet recovered (Cross, Am. J. Phys. 67
(1999) 222: balls leave a surface still compressed, their loss is the relaxation of internal
stresses, not a velocity-dependent force; the force is zero at first touch). The peak force
comes before the maximum compression.

This is the reduced form of the finite-element balls of the 2001 study and its authors
(Shenoy, Smith & Axtell, Compos. Struct. 52 (2001) 397: a linear viscoelastic solid with shear
relaxation ``G(t) = G_inf + (G0 - G_inf) e^(-beta t)``): the same single-exponential relaxation,
carried by a contact measure ``u^a`` instead of a mesh. The COR follows from the pulse's
duration against ``tau``: it falls with speed while the contact time (which shortens as the
ball stiffens, ``a > 1``) approaches ``tau``, and a ball that is squeezed more slowly or less
(by a compliant barrel) loses less. Nothing about a bat enters the law; its four parameters
come from ball tests (:mod:`batcert.physics.balls.fit`).

Parameters: ``stiffness`` ``k0`` [N/m^a], ``exponent`` ``a`` [-], ``relaxed_fraction``
``r = k_inf / k0`` [-], ``relaxation_time`` ``tau`` [s]. Units: SI throughout.

Time stepping (:class:`ViscoelasticMarch`): the internal variable obeys a linear equation with
the compression as its forcing, ``ds/dt = -s / tau + x(u) / tau``; the batched integrators
(:func:`batcert.engines.kernel.march.march`, :func:`batcert.physics.balls.impact1d.body_impact`) give
it the stages of the exponential Runge-Kutta scheme ETDRK4 (Cox & Matthews, J. Comput. Phys.
176 (2002) 430, Eqs. 26-29) at the compressions of their own stages, so its relaxation is exact
and the step only has to resolve the pulse.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from batcert.physics.balls.law import MarchState
from batcert.physics.etd import phi_functions

_TINY = 1e-300  # floor of the compression inside log() [m]


@dataclass(frozen=True)
class Viscoelastic:
    """Parameters of the viscoelastic (Zener) ball law (module notes).

    Attributes
    ----------
    stiffness : float
        Instantaneous stiffness ``k0`` of ``F = k0 u^a`` for a sudden squeeze [N/m^a].
    exponent : float
        ``a`` of the contact measure ``x = u^a`` [-].
    relaxed_fraction : float
        ``r = k_inf / k0``: the quasi-static stiffness as a fraction of the instantaneous [-].
    relaxation_time : float
        ``tau`` of the Maxwell branch [s].
    """

    stiffness: float
    exponent: float
    relaxed_fraction: float
    relaxation_time: float
    name: ClassVar[str] = "viscoelastic"
    # the parameters in order, and each one's coordinate in a fit (batcert.physics.balls.fit):
    # "log" for a positive scale, "logit" for a fraction in (0, 1), "" for the number itself
    PARAMETERS: ClassVar[tuple[str, ...]] = ("stiffness", "exponent", "relaxed_fraction",
                                             "relaxation_time")
    COORDINATES: ClassVar[tuple[str, ...]] = ("log", "", "logit", "log")

    def __post_init__(self) -> None:
        if not (self.stiffness > 0 and 1.0 <= self.exponent <= 3.0
                and 0.0 < self.relaxed_fraction <= 1.0 and self.relaxation_time > 0):
            raise ValueError(f"viscoelastic ball parameters out of range: {self}")

    def branches(self) -> tuple[tuple[float, ...], ...]:
        """The Maxwell branches: ``(k_j / k0 [-], relaxation time tau_j [s])`` each, the
        fractions adding up to ``1 - relaxed_fraction``."""
        return ((1.0 - self.relaxed_fraction, self.relaxation_time),)

    @property
    def relaxed_stiffness(self) -> float:
        """``k_inf = r k0`` [N/m^a]: the stiffness of a slow (quasi-static) squeeze."""
        return self.relaxed_fraction * self.stiffness

    def force(self, u, s):
        """Contact force [N] at compression ``u`` [m] and branch variable ``s`` [m^a]."""
        x = np.maximum(np.asarray(u, dtype=float), 0.0) ** self.exponent
        return np.maximum(self.stiffness * x - self.stiffness * (1 - self.relaxed_fraction) * s,
                          0.0)

    def quasi_static_force(self, u):
        """Force of a squeeze slow enough for the branch to relax: ``k_inf u^a`` [N]."""
        return self.relaxed_stiffness * np.maximum(np.asarray(u, dtype=float), 0.0) ** self.exponent

    def separation_loss(self, mass: float, max_compression, scale, relative_speed,
                        rule: str) -> None:
        """None: the loss follows the rate of the squeeze, so the time integration measures
        it (the flexible engine's ``absorbed``)."""
        return None

    def summary(self) -> str:
        """The law and its parameters in one line (``inspect``)."""
        return (f"viscoelastic: k0 = {self.stiffness:.4g} N/m^a, a = {self.exponent:.4g}, "
                f"k_inf / k0 = {self.relaxed_fraction:.3g}, tau = "
                f"{self.relaxation_time * 1e6:.1f} us")

    def describe(self) -> dict:
        """The parameters (SI) for reports and ``inspect``."""
        return {"model": self.name, "stiffness": self.stiffness, "exponent": self.exponent,
                "relaxed_fraction": self.relaxed_fraction,
                "relaxation_time": self.relaxation_time,
                "relaxed_stiffness": self.relaxed_stiffness}

    def march_rows(self, n: int, mass: float, scale=1.0, rule: str = "compression",
                   speed=None) -> ViscoelasticMarch:
        """The time-stepping state of ``n`` impacts of this ball; ``scale`` multiplies the
        stiffness per impact (the contact geometry, :mod:`batcert.physics.balls.footprint`).
        ``rule`` and ``speed`` (how Nathan's law picks its COR) do not apply."""
        return ViscoelasticMarch.of([self], [mass], np.zeros(n, int), scale)

    def contact_time(self, mass: float, speed, recoil=0.0):
        """A scale of the contact time [s] (the relaxed spring's, the longest):
        :func:`~batcert.physics.balls.impact1d.contact_time_estimate`."""
        from batcert.physics.balls.impact1d import contact_time_estimate

        mu = mass / (1.0 + np.asarray(recoil, dtype=float))
        return contact_time_estimate(speed, mu, self.relaxed_stiffness, self.exponent)

    def body_impact(self, mass: float, speed, recoil=0.0, history: bool = True, scale=1.0,
                    rule: str = "compression", steps: int | None = None):
        """The ball fired at ``speed`` [m/s] at a rigid body of effective-mass ratio
        ``recoil`` [-] (0: a rigid wall; ``scale``: the surface's stiffness factor),
        integrated (:func:`~batcert.physics.balls.impact1d.body_impact`; ``rule`` does not
        apply)."""
        from batcert.physics.balls.impact1d import STEPS, body_impact

        v, k, s = (np.ravel(x) for x in np.broadcast_arrays(
            np.abs(np.asarray(speed, dtype=float)), np.asarray(recoil, dtype=float),
            np.asarray(scale, dtype=float)))
        return body_impact(self.march_rows(v.size, mass, s), mass, v, k,
                           self.contact_time(mass, v, k) / np.sqrt(s), history=history,
                           steps=steps or STEPS)

    @staticmethod
    def state_of(laws, masses, which, scale=1.0, rule: str = "compression",
                 speed=None) -> MarchState:
        """The time-stepping state of rows of several balls of this law
        (:meth:`ViscoelasticMarch.of`)."""
        return ViscoelasticMarch.of(laws, masses, which, scale, rule, speed)

    def wall_impact(self, mass: float, speed, fraction: float = 0.99):
        """The ball against a rigid flat wall at ``speed`` [m/s]: COR, contact and collision
        times, compressions, peak force (a ``BodyImpact``)."""
        from batcert.physics.balls.impact1d import body_impact

        v = np.abs(np.asarray(speed, dtype=float)).ravel()
        return body_impact(self.march_rows(v.size, mass), mass, v, 0.0,
                           self.contact_time(mass, v), fraction=fraction)

    def wall_cor(self, mass: float, speed) -> np.ndarray | float:
        """Rigid-wall COR at ``speed`` [m/s]: the integrated wall impact, read from a table of
        the ball (:func:`~batcert.physics.balls.impact1d.wall_table`; within about 4e-7 of
        the integration) from 0.1 to 300 m/s, integrated directly outside it."""
        from batcert.physics.balls.impact1d import from_wall_table

        return from_wall_table(self, mass, speed, "cor")

    def body_cor(self, mass: float, speed, recoil, rule: str = "compression") -> np.ndarray:
        """COR against a rigid body of effective-mass ratio ``recoil`` [-] at approach speed
        ``speed`` [m/s], integrated (the rigid engine; ``rule`` does not apply: the loss
        follows from the squeeze itself)."""
        v = np.abs(np.asarray(speed, dtype=float))
        out = self.body_impact(mass, v, np.broadcast_to(recoil, v.shape), history=False).cor
        return out.reshape(v.shape)


def _branch_step(tau, h) -> tuple[np.ndarray, ...]:
    """ETDRK4 constants of ``ds/dt = (x - s) / tau`` over a step ``h`` (Cox & Matthews 2002,
    Eqs. 26-29 with ``L = -1/tau`` and ``N = x / tau``), per row: ``e^(Lh/2)``, ``e^(Lh)``, the
    half-step forcing ``(h/2) phi_1(Lh/2) / tau`` and the full step's three weights
    ``h (phi_1 - 3 phi_2 + 4 phi_3) / tau``, ``2 h (phi_2 - 2 phi_3) / tau``,
    ``h (4 phi_3 - phi_2) / tau``."""
    tau, h = np.broadcast_arrays(np.asarray(tau, dtype=float), np.asarray(h, dtype=float))
    z = -h / tau
    p1, p2, p3 = phi_functions(z)
    q_half = 0.5 * h * phi_functions(z / 2)[0]
    return (np.exp(z / 2), np.exp(z), q_half / tau, h * (p1 - 3 * p2 + 4 * p3) / tau,
            2 * h * (p2 - 2 * p3) / tau, h * (4 * p3 - p2) / tau)


class ViscoelasticMarch:
    """The viscoelastic law's state during a batched integration, one row per impact.

    A step (of length ``h``, fixed by :meth:`for_step`) is taken in the order of the scheme's
    stages: :meth:`start` (force at the step's start), :meth:`half_a` and :meth:`half_b` (the two
    half-step stages), :meth:`end` (the full-step stage), then :meth:`finish` with the
    compression at the step's end, which advances the branch and returns the contact measure
    ``k0 x - k_1 s`` (the force before clipping; its sign change marks separation). The work
    done on the ball, ``integral F du``, is kept (trapezoidal in ``u``) for the diagnostics: at
    separation it is the energy the ball took and did not return.
    """

    crossing = True  # the force falls through zero with a finite slope (engines/kernel/march.py)

    def __init__(self, k0, k1, a, tau, h=None):
        # k0, a: (n,); k1, tau, s: (n, branches)
        self.k0, self.k1, self.a, self.tau = k0, k1, a, tau
        n = k0.size
        self.s = np.zeros(k1.shape)
        self.work = np.zeros(n)
        self.u_last = np.zeros(n)
        self.f_last = np.zeros(n)
        self.h = h
        self._coef: tuple[np.ndarray, ...] | None = None

    @classmethod
    def of(cls, laws: list[Viscoelastic], masses, which, scale=1.0, rule: str = "compression",
           speed=None) -> ViscoelasticMarch:
        """Rows of several viscoelastic balls: row ``i`` is ``laws[which[i]]``, its stiffness
        times ``scale[i]`` (``masses``, ``rule``, ``speed``: as for Nathan's law, unused). Balls
        with fewer Maxwell branches than the most get branches of zero stiffness (which add
        exactly nothing)."""
        which = np.asarray(which, dtype=int)
        n_branches = max(len(law.branches()) for law in laws)
        k1 = np.zeros((len(laws), n_branches))
        tau = np.ones((len(laws), n_branches))
        for i, law in enumerate(laws):
            for j, (k, t) in enumerate(law.branches()):
                k1[i, j], tau[i, j] = k, t
        factor = np.broadcast_to(np.asarray(scale, dtype=float), which.shape)
        k0 = np.array([law.stiffness for law in laws])[which] * factor
        a = np.array([law.exponent for law in laws])[which]
        return cls(k0, k0[:, None] * k1[which], a, tau[which])

    def for_step(self, h) -> ViscoelasticMarch:
        """Fix the step ``h`` [s] (scalar, or one per row) and compute the stage constants."""
        h = np.broadcast_to(np.asarray(h, dtype=float), self.k0.shape)
        self._coef = _branch_step(self.tau, h[:, None])
        self.h = h
        return self

    def _pull(self, s):
        """The branches' force ``sum_j k_j s_j`` [N], (n,)."""
        return (self.k1 * s).sum(axis=1)

    def _x(self, u):
        return np.exp(self.a * np.log(np.maximum(u, _TINY))) * (u > 0)

    def _g(self, x, s):
        """The contact measure ``k0 u^a - sum_j k_j s_j`` (before clipping) [N], (n,)."""
        return self.k0 * x - self._pull(s)

    def prepare(self, u_top, rows) -> None:
        """Nothing follows the largest compression (MarchState)."""

    def start(self, u, u_top=None):
        e2, _, q, *_ = self._coef  # type: ignore[misc]
        self._x0 = x0 = self._x(u)
        self._sa = e2 * self.s + q * x0[:, None]
        return np.maximum(self._g(x0, self.s), 0.0)

    def half_a(self, u):
        e2, _, q, *_ = self._coef  # type: ignore[misc]
        self._xa = xa = self._x(u)
        f = np.maximum(self._g(xa, self._sa), 0.0)
        self._sb = e2 * self.s + q * xa[:, None]
        return f

    def half_b(self, u):
        e2, _, q, *_ = self._coef  # type: ignore[misc]
        self._xb = xb = self._x(u)
        f = np.maximum(self._g(xb, self._sb), 0.0)
        self._sc = e2 * self._sa + q * (2.0 * xb - self._x0)[:, None]
        return f

    def end(self, u):
        self._xc = xc = self._x(u)
        return np.maximum(self._g(xc, self._sc), 0.0)

    def finish(self, u_new):
        """Advance the branches over the step; the contact measure at its end [N], (n,)."""
        _, e1, _, w1, w2, w3 = self._coef  # type: ignore[misc]
        self.s = (e1 * self.s + w1 * self._x0[:, None] + w2 * (self._xa + self._xb)[:, None]
                  + w3 * self._xc[:, None])
        g = self._g(self._x(u_new), self.s)
        f = np.maximum(g, 0.0)
        self.work = self.work + 0.5 * (self.f_last + f) * (u_new - self.u_last)
        self.u_last, self.f_last = u_new, f
        return g

    def absorbed(self):
        """Work done on the ball so far, ``integral F du`` [J], (n,)."""
        return self.work

    def offset(self, start: int) -> ViscoelasticMarch:
        """These rows as part of a larger batch (nothing depends on their place in it)."""
        return self

    def stored(self, rows, top):
        """Energy the ball holds at its largest compression: the work done on it so far [J]
        (the branch's loss included; the law has no potential energy of ``u`` alone)."""
        return self.work[rows]

    def take(self, keep) -> ViscoelasticMarch:
        """The rows ``keep`` (indices, a mask or a slice)."""
        out = ViscoelasticMarch.__new__(ViscoelasticMarch)
        for name, value in vars(self).items():
            if isinstance(value, np.ndarray) and value.ndim and value.shape[0] == self.k0.shape[0]:
                value = value[keep]
            elif name == "_coef" and value is not None:
                value = tuple(c[keep] for c in value)
            setattr(out, name, value)
        return out


@dataclass(frozen=True)
class TwoTimeViscoelastic(Viscoelastic):
    """The viscoelastic law with two relaxation times (a two-term Prony series, the
    generalised Maxwell solid): ``F = k0 x - k_s s_s - k_f s_f``, ``ds_j/dt = (x - s_j) /
    tau_j``, ``k_s + k_f = k0 - k_inf``.

    One relaxation time puts the ball's loss at one time scale: its COR falls with speed only
    while the contact time approaches ``tau`` and rises again beyond (measured on the one-time
    law fitted to the collegiate ball: flat from 20 to 50 m/s, rising above). A slow branch
    (``tau`` about the low-speed contact time) holds the loss of slow impacts, a fast one
    (``tau_f`` below the contact time at bat speed) a loss that keeps growing as the contact
    shortens: the COR can fall over the whole range, as ball tests say it does.

    Attributes (besides :class:`Viscoelastic`'s; ``relaxation_time`` is the slow branch's)
    ----------
    fast_share : float
        ``k_f / (k0 - k_inf)``: the fast branch's share of the relaxing stiffness [-].
    fast_relaxation_time : float
        ``tau_f`` of the fast branch [s].
    """

    fast_share: float
    fast_relaxation_time: float
    name: ClassVar[str] = "viscoelastic-2"
    PARAMETERS: ClassVar[tuple[str, ...]] = Viscoelastic.PARAMETERS + (
        "fast_share", "fast_relaxation_time")
    COORDINATES: ClassVar[tuple[str, ...]] = Viscoelastic.COORDINATES + ("logit", "log")

    def __post_init__(self) -> None:
        super().__post_init__()
        if not (0.0 < self.fast_share < 1.0 and self.fast_relaxation_time > 0):
            raise ValueError(f"viscoelastic ball parameters out of range: {self}")

    def branches(self) -> tuple[tuple[float, float], ...]:
        loss = 1.0 - self.relaxed_fraction
        return ((loss * (1.0 - self.fast_share), self.relaxation_time),
                (loss * self.fast_share, self.fast_relaxation_time))

    def summary(self) -> str:
        return (f"viscoelastic, two relaxation times: k0 = {self.stiffness:.4g} N/m^a, "
                f"a = {self.exponent:.4g}, k_inf / k0 = {self.relaxed_fraction:.3g}, "
                f"tau = {self.relaxation_time * 1e6:.1f} us (share {1 - self.fast_share:.3g}), "
                f"tau_f = {self.fast_relaxation_time * 1e6:.1f} us "
                f"(share {self.fast_share:.3g})")

    def describe(self) -> dict:
        return {**super().describe(), "fast_share": self.fast_share,
                "fast_relaxation_time": self.fast_relaxation_time}
