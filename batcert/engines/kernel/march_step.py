"""One ETDRK4 step of every impact in contact (:func:`batcert.engines.kernel.march.march`): the
state that evolves per impact, the stage forces from the ball's law, the modal update, and the
refinement of the largest compression inside a step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.engines.kernel.coupling import extrapolate
from batcert.engines.kernel.etdrk4 import Coefficients


@dataclass
class State:
    """Everything that evolves per impact, row i for impact i; :meth:`take` keeps rows
    together, so no array can be left out when finished impacts are dropped."""

    z: np.ndarray  # complex modal coordinates (n, K)
    w: np.ndarray  # merged rigid/ball coordinate [m]
    v: np.ndarray  # its rate [m/s]
    impulse: np.ndarray  # on the ball so far [N s]
    u: np.ndarray  # compression at the step start [m]
    u_top: np.ndarray  # largest compression so far [m]
    f_peak: np.ndarray  # largest force so far [N]
    u_prev: np.ndarray  # compression one step earlier [m]
    du_prev: np.ndarray  # compression rate one step earlier [m/s]
    g: np.ndarray  # the law's contact measure at the step start (separation: it falls to <= 0)
    share: np.ndarray  # barrel's share of the stored energy at the ball's maximum compression
    # the read-out of Y now (free y after h/2 and h, y', y), (n, 4); with a coupling of G
    # groups each group's, (n, 4 G) (read-out r of group g at r G + g)
    base: np.ndarray
    rows: np.ndarray  # index of each row in the caller's batch
    rho: np.ndarray  # each group's coupling factor now, (n, G)
    drift: np.ndarray  # what the footprint's growth alone changed in the weighted displacement
    f0: np.ndarray  # the force at the last step's start [N]
    dj: np.ndarray  # the last step's impulse [N s]

    def take(self, keep: np.ndarray) -> State:
        return State(**{k: v[keep] for k, v in vars(self).items()})

    @classmethod
    def start(cls, n: int, k_modes: int, approach_speed, groups: int = 1) -> State:
        zeros = np.zeros(n)
        return cls(z=np.zeros((n, k_modes), dtype=complex), w=zeros.copy(),
                   v=np.array(approach_speed, dtype=float).reshape(n), impulse=zeros.copy(),
                   u=zeros.copy(), u_top=np.full(n, 1e-300), f_peak=zeros.copy(),
                   u_prev=zeros.copy(), du_prev=zeros.copy(), g=zeros.copy(),
                   share=zeros.copy(), base=np.zeros((n, 4 * groups)), rows=np.arange(n),
                   rho=np.ones((n, groups)), drift=zeros.copy(), f0=zeros.copy(),
                   dj=zeros.copy())


def unscaled(y: np.ndarray, c_y: np.ndarray) -> np.ndarray:
    """``Z = Y / c_y``; a mode of zero gain is never driven (``Z = 0``)."""
    return np.divide(y, c_y, out=np.zeros_like(y), where=c_y != 0)


def step(st: State, c: Coefficients, law, h: float, shell: slice | None) -> np.ndarray:
    """Advance every impact by one ETDRK4 step in place; return the compression at its end.

    ``law`` is the ball law's time-stepping state (its forces at the stages). ``shell`` is the
    shell modes' columns when the barrel's energy share is tracked, else None; a mode's
    potential energy ``omega^2 q^2 / 2`` is ``shell_factor Im(Z)^2``. The share is taken when
    the ball's compression peaks (the stored energies' largest moment, within the shell's lag),
    against the energy the ball holds then (``law.stored``).
    """
    base = st.base
    u2 = base[:, 0] + st.w + 0.5 * h * st.v
    u1 = base[:, 1] + st.w + h * st.v
    du = st.v + base[:, 2]
    turned = (st.du_prev > 0) & (du <= 0) & (st.u > 0)
    if np.count_nonzero(turned):  # the maximum compression fell inside the last step
        _peak(st, c, law, turned, du, h, shell)
    st.u_prev, st.du_prev = st.u, du
    f = np.empty((du.size, 3))
    f0 = f[:, 0] = law.start(st.u, st.u_top)
    fa = law.half_a(u2 + c.ka * f0)
    fb = law.half_b(u2 + c.ka * fa + c.b0 * f0)
    fc = f[:, 2] = law.end(u1 + c.c0 * f0 + c.cb * fb + c.ca * fa)
    fab = f[:, 1] = fa + fb
    st.base = c.modal.advance(st.z, f)
    s4 = f0 + 2.0 * fab + fc
    st.w = st.w + h * st.v + c.w6 * (f0 + fab)
    u_new = st.base[:, 3] + st.w  # y = sum Im(Y), u = y + w
    _close_step(st, c, f0, s4, u_new, h)
    return u_new


def _close_step(st: State, c: Coefficients, f0: np.ndarray, s4: np.ndarray,
                u_new: np.ndarray, h: float) -> None:
    """What every step ends with: the rigid/ball rate and the impulse from the stages' forces
    (``s4 = F0 + 2 (Fa + Fb) + Fc``), the largest force and compression so far."""
    st.v = st.v + c.v6 * s4
    st.dj = (h / 6.0) * s4
    st.impulse = st.impulse + st.dj
    st.f_peak = np.maximum(st.f_peak, f0)
    st.f0 = f0
    st.u_top = np.maximum(st.u_top, u_new)


def _peak(st: State, c: Coefficients, law, turned: np.ndarray, du: np.ndarray, h: float,
          shell: slice | None) -> None:
    """The compression peaked inside the last step at the rows ``turned``: refine ``u_top``
    there, and take the shell's share of the stored energy at the ball's (largest) maximum."""
    top = hermite_max(st.u_prev[turned], st.du_prev[turned], st.u[turned], du[turned], h)
    if shell is not None:
        rows = np.flatnonzero(turned)[top >= st.u_top[turned]]  # the largest maximum
        ball = law.stored(rows, top[top >= st.u_top[turned]])
        z = unscaled(c.modal.current(st.z, rows)[:, shell], c.c_y[rows, shell])
        barrel = c.shell_factor[rows] * (z.imag ** 2).sum(1)
        st.share[rows] = barrel / (ball + barrel)
    st.u_top[turned] = np.maximum(st.u_top[turned], top)


def step_coupled(st: State, c: Coefficients, law, h: float, shell: slice | None
                  ) -> np.ndarray:
    """:func:`step` for gains that follow the ball's compression (a
    :class:`~batcert.engines.kernel.coupling.Coupling` of ``G`` groups).

    Every group is read and forced with its factor ``rho`` at each stage's time, ``rho`` of the
    compression predicted for it from the last two steps
    (:func:`~batcert.engines.kernel.coupling.extrapolate`); a stage's response to a force is each
    group's part of ``ka``, ``c0``, ``cb`` scaled by the factors of the force's and the
    reading's times: the same scheme, the couplings frozen at ``rho`` through a step's stages.

    The compression changes as the bodies move, ``u' = w' + sum rho_G y_G'``: the footprint's
    growth moves the force over the surface but does no work by itself, so that energy and
    momentum are both conserved. It is kept as ``u = w + sum rho_G y_G + d``, where
    ``d = -integral sum rho_G' y_G dt`` (trapezoidal over each step) carries what the growth
    of the footprint alone would change in the weighted displacement."""
    coupling = c.coupling
    assert coupling is not None and c.group_ka is not None and c.group_c0 is not None
    n, groups = st.rho.shape
    base = st.base.reshape(n, 4, groups)
    rho0 = st.rho
    y0 = base[:, 3]
    du = st.v + (rho0 * base[:, 2]).sum(1)
    turned = (st.du_prev > 0) & (du <= 0) & (st.u > 0)
    if np.count_nonzero(turned):
        _peak(st, c, law, turned, du, h, shell)
    u_half, u_end = extrapolate(st.u_prev, st.du_prev, st.u, du, h)
    rho_h, rho1 = coupling.at(u_half), coupling.at(u_end)
    st.u_prev, st.du_prev = st.u, du
    # the free motion at h/2 and h, with the drift of the footprint's growth so far
    u2 = (rho_h * base[:, 0] - 0.5 * (rho_h - rho0) * (y0 + base[:, 0])).sum(1)
    u1 = (rho1 * base[:, 1] - 0.5 * (rho1 - rho0) * (y0 + base[:, 1])).sum(1)
    u2 += st.w + 0.5 * h * st.v + st.drift
    u1 += st.w + h * st.v + st.drift
    ka, c0 = c.group_ka, c.group_c0
    f0 = law.start(st.u, st.u_top)
    fa = law.half_a(u2 + (rho_h * rho0 * ka).sum(1) * f0)
    fb = law.half_b(u2 + (rho_h * rho_h * ka).sum(1) * fa + c.b0 * f0)
    fc = law.end(u1 + (rho1 * rho0 * c0).sum(1) * f0 + (rho1 * rho_h * 2.0 * ka).sum(1) * fb
                 + c.ca * fa)
    fab = fa + fb
    forces = np.concatenate([rho0 * f0[:, None], rho_h * fab[:, None], rho1 * fc[:, None]],
                            axis=1)  # (n, 3 G): stage s, group g at s G + g
    st.base = c.modal.advance(st.z, forces)
    y1 = st.base.reshape(n, 4, groups)[:, 3]
    st.drift = st.drift - 0.5 * ((rho1 - rho0) * (y0 + y1)).sum(1)
    s4 = f0 + 2.0 * fab + fc
    st.w = st.w + h * st.v + c.w6 * (f0 + fab)
    u_new = (rho1 * y1).sum(1) + st.w + st.drift
    _close_step(st, c, f0, s4, u_new, h)
    st.rho = rho1
    return u_new


def hermite_max(u0, d0, u1, d1, h):
    """Largest value on [0, h] of the cubic Hermite interpolant of ``u`` with slopes ``d``
    (``d0 > 0 >= d1``): the turning point of the compression inside a step [m]."""
    a = 3 * (2 * u0 + h * d0 - 2 * u1 + h * d1)
    b = -6 * u0 - 4 * h * d0 + 6 * u1 - 2 * h * d1
    c = h * d0
    disc = np.sqrt(np.maximum(b * b - 4 * a * c, 0.0))
    # root of a s^2 + b s + c with the slope going from + to - (stable form)
    q = -0.5 * (b + np.copysign(disc, b))
    with np.errstate(divide="ignore", invalid="ignore"):
        roots = np.stack([q / a, c / q])
    s = np.where(np.isfinite(roots), np.clip(roots, 0.0, 1.0), 0.0)  # both roots at once
    val = ((2 * s**3 - 3 * s**2 + 1) * u0 + (s**3 - 2 * s**2 + s) * h * d0
           + (-2 * s**3 + 3 * s**2) * u1 + (s**3 - s**2) * h * d1)
    return np.maximum(np.maximum(u0, u1), val.max(axis=0))
