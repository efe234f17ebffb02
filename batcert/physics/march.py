"""Batched time integration of ball contact against a linear modal structure (flexible engine).

All impacts advance together, arrays shaped (impacts, modes). The linear modal dynamics are
propagated exactly; only the contact force is approximated, by the exponential Runge-Kutta scheme
ETDRK4 (Cox & Matthews, J. Comput. Phys. 176 (2002) 430, Eqs. 26-29) in complex modal
coordinates ``Z = p - conj(lambda) q``, ``Z' = lambda Z - g F``. The contact force comes from
the ball's law (:mod:`batcert.physics.balls`), through its time-stepping state: the force at
each stage of a step, its own internal variables advanced with the step, and a contact measure
whose fall through zero is separation. :mod:`batcert.engines.flexible` builds the
:class:`LinearSystem` of each impact and reads the :class:`Separation`;
:mod:`batcert.physics.modal_update` advances the modal state by a step; the
:class:`~batcert.physics.linear_system.LinearSystem` is the impacts' linear part.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from batcert import workspace
from batcert.physics.coupling import Coupling, extrapolate
from batcert.physics.etd import phi_functions
from batcert.physics.linear_system import LinearSystem
from batcert.physics.modal_update import RowByRow, SharedRuns, im_weights

# rows that share their modes are read and forced with one matrix product per run of them when
# the runs average at least this many rows (else row by row; measured, bench_engine.py)
_SHARED_ROWS = 16
# a batch is integrated in chunks of about this many (impact, mode) entries (bounded memory),
# while each step's modal update runs over cache-sized pieces of them (modal_update.py;
# measured, 20,000 random impacts: a hollow bat's 44 modes in 1675-row pieces of 4096-row
# chunks, 5 % more impacts per second than 2234-row chunks updated whole)
_CHUNK_ENTRIES = 196_608


@dataclass
class Separation:
    """State of every impact at separation (or at the time cap)."""

    impulse: np.ndarray  # contact impulse on the ball, integral F dt [N s], (n,)
    time: np.ndarray  # contact time [s], (n,)
    separated: np.ndarray  # False where the time cap came first, (n,)
    peak_force: np.ndarray  # [N], (n,)
    max_compression: np.ndarray  # [m], (n,)
    modal: np.ndarray  # complex modal coordinates Z = p - conj(lambda) q, (n, K)
    barrel_share: np.ndarray | None  # shell's share of the stored energy at the ball's
    # maximum compression [-], (n,)
    absorbed: np.ndarray | None = None  # work done on the ball, int F du [J], (n,); None where
    # the law has it in closed form

    @classmethod
    def concatenate(cls, parts: list[Separation]) -> Separation:
        def cat(name: str) -> Any:
            first = getattr(parts[0], name)
            return None if first is None else np.concatenate([getattr(p, name) for p in parts])
        return cls(**{name: cat(name) for name in vars(parts[0])})


@dataclass
class _Coefficients:
    """Per-impact constants of one ETDRK4 step (Cox & Matthews 2002, Eqs. 26-29), row i for
    impact i, in the scaled coordinates ``Y = c_y Z`` of :func:`_coefficients`.

    ``modal`` advances ``Y`` by a step and reads the contact point's free motion from it: row
    by row, or with one matrix product per run of rows that share their modes."""

    ka: np.ndarray
    b0: np.ndarray
    c0: np.ndarray
    cb: np.ndarray
    ca: np.ndarray
    w6: np.ndarray
    v6: np.ndarray
    c_y: np.ndarray  # contact-point displacement per Im(Z): g / omega_d, (n, K)
    shell_factor: np.ndarray  # 1 / (2 (1 - zeta^2)): shell potential energy per Im(Z)^2
    modal: RowByRow | SharedRuns  # how Y advances and the contact point reads it
    # with a Coupling: ka, c0 (and cb = 2 ka) of each group, (n, G), and the coupling
    group_ka: np.ndarray | None = None
    group_c0: np.ndarray | None = None
    coupling: Coupling | None = None

    def take(self, keep: np.ndarray) -> _Coefficients:
        def part(k, v):
            if v is None:
                return None
            return v.take(keep) if k == "modal" else v.rows(keep) if k == "coupling" else v[keep]
        return _Coefficients(**{k: part(k, v) for k, v in vars(self).items()})


@dataclass
class _State:
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

    def take(self, keep: np.ndarray) -> _State:
        return _State(**{k: v[keep] for k, v in vars(self).items()})

    @classmethod
    def start(cls, n: int, k_modes: int, approach_speed, groups: int = 1) -> _State:
        zeros = np.zeros(n)
        return cls(z=np.zeros((n, k_modes), dtype=complex), w=zeros.copy(),
                   v=np.array(approach_speed, dtype=float).reshape(n), impulse=zeros.copy(),
                   u=zeros.copy(), u_top=np.full(n, 1e-300), f_peak=zeros.copy(),
                   u_prev=zeros.copy(), du_prev=zeros.copy(), g=zeros.copy(),
                   share=zeros.copy(), base=np.zeros((n, 4 * groups)), rows=np.arange(n),
                   rho=np.ones((n, groups)), drift=zeros.copy(), f0=zeros.copy(),
                   dj=zeros.copy())


def _exponentials(lam: np.ndarray, h: float) -> tuple[np.ndarray, ...]:
    """``e^(lam h)``, ``e^(lam h / 2)``, ``phi_1..3(lam h)`` and ``h/2 phi_1(lam h / 2)`` of
    one block's eigenvalues; a single row (a block's shared row) is kept by the active
    workspace (kind ``step-exponentials``: a bat's modes recur in every batch of a run)."""
    if lam.shape[0] == 1:
        return workspace.current().call("step-exponentials", _exponentials_of, lam, float(h))
    return _exponentials_of(lam, h)


def _exponentials_of(lam: np.ndarray, h: float) -> tuple[np.ndarray, ...]:
    return (np.exp(lam * h), np.exp(lam * h / 2), *phi_functions(lam * h),
            0.5 * h * phi_functions(lam * h / 2)[0])


def _coefficients(system: LinearSystem, h: float) -> _Coefficients:
    """The step constants of every impact (see :func:`march`).

    The modal coordinates are kept scaled, ``Y = c_y Z`` with ``c_y = g / omega_d`` the
    contact-point displacement per ``Im(Z)``: the free motion of the contact point is then
    ``Im(sum w Y)`` with weights ``w`` (``e^(lam h/2)``, ``e^(lam h)``, ``lam``, 1) that depend
    on a row's modes only, so that runs of rows sharing them (one bat) read it with one matrix
    product; the forcing of ``Y``, ``-c_y g (...)``, is that run's matrix scaled per row.
    """
    om, g = system.omega, system.gain
    n = om.shape[0]
    zeta = system.zeta[:, None]
    om_d = om * np.sqrt(1.0 - zeta**2)
    lam = -zeta * om + 1j * om_d
    c_y = g / om_d  # contact-point displacement y = sum c_y Im(Z) = sum Im(Y)
    cg = c_y * g
    ka, c0 = np.empty(n), np.empty(n)
    coupled = system.coupling
    if coupled is not None:  # each group's part of ka and c0, its columns of the read-out
        n_groups = coupled.size
        first = np.asarray(coupled.starts[:-1])
        member = np.repeat(np.arange(n_groups), np.diff(coupled.starts))
        mask = (member[None, :] == np.arange(n_groups)[:, None]).astype(float)  # (G, K)
        group_ka, group_c0 = np.empty((n, n_groups)), np.empty((n, n_groups))
    # the exponentials depend on the frequencies and damping only: once per block of rows
    # that share them (one bat); each block's propagator, read-out and forcing, (1 or rows, ..)
    blocks = []
    for a, b in system.blocks or ((0, n),):
        same = bool(np.all(om[a:b] == om[a:a + 1])) and bool(np.all(zeta[a:b] == zeta[a]))
        lam_b = lam[a:a + 1] if same else lam[a:b]
        e1, e2, p1, p2, p3, q_half = _exponentials(lam_b, h)
        ka[a:b] = -(cg[a:b] * q_half.imag).sum(1)
        c0[a:b] = -(cg[a:b] * (e2 * q_half).imag).sum(1) - ka[a:b]
        # Z_new = e1 Z + forcing @ (F0, Fa + Fb, Fc)  (Cox & Matthews 2002, Eq. 26)
        push = -np.stack([h * (p1 - 3 * p2 + 4 * p3), 2 * h * (p2 - 2 * p3),
                          h * (4 * p3 - p2)], axis=1)  # forcing of Z per unit g, (., 3, K)
        # read-outs: free y after h/2 and h, y' (= Im(sum lam Y)) and y (= Im(sum Y))
        read = im_weights(np.stack([e2, e1, lam_b, np.ones_like(e1)], axis=1))
        if coupled is not None:
            group_ka[a:b] = -np.add.reduceat(cg[a:b] * q_half.imag, first, axis=1)
            group_c0[a:b] = (-np.add.reduceat(cg[a:b] * (e2 * q_half).imag, first, axis=1)
                             - group_ka[a:b])
        blocks.append((a, b, same, e1, read, push))
    inv_mu = system.inv_reduced_mass
    modal: RowByRow | SharedRuns
    runs = _runs(blocks, om, system.zeta)
    if runs is not None and len(runs) * _SHARED_ROWS <= max(n, _SHARED_ROWS):
        heads = [blocks[i] for i, _, _ in runs]
        read = np.concatenate([blk[4] for blk in heads])  # (runs, 4, 2K)
        push = np.concatenate([blk[5] for blk in heads])  # (runs, 3, K)
        if coupled is not None:  # by group: forcing rows s G + g, read-out columns r G + g
            push = (push[:, :, None, :] * mask).reshape(push.shape[0], -1, push.shape[2])
            read = (read[:, :, None, :] * np.repeat(mask, 2, axis=1)).reshape(
                read.shape[0], -1, read.shape[2])
        modal = SharedRuns(
            e1=np.concatenate([blk[3] for blk in heads]),
            R=np.ascontiguousarray(read.transpose(0, 2, 1)),
            P=np.ascontiguousarray(push).view(float),
            scale=np.repeat(cg, 2, axis=1),
            group=np.repeat(np.arange(len(runs)), [b - a for _, a, b in runs]))
    else:
        def rows(i):  # each row's copy of a block's part
            return np.concatenate([np.broadcast_to(blk[i], (blk[1] - blk[0],) + blk[i].shape[1:])
                                   for blk in blocks])
        modal = RowByRow(e1=rows(3), R=np.ascontiguousarray(rows(4)),
                         B=np.ascontiguousarray(cg[:, None, :] * rows(5)).view(float),
                         starts=None if coupled is None else 2 * first)
    return _Coefficients(
        ka=ka, b0=-h * h / 4 * inv_mu, c0=c0, cb=2 * ka, ca=-h * h / 2 * inv_mu,
        w6=-h * h / 6 * inv_mu, v6=-h / 6 * inv_mu, c_y=c_y,
        shell_factor=0.5 / (1.0 - system.zeta**2), modal=modal,
        group_ka=None if coupled is None else group_ka,
        group_c0=None if coupled is None else group_c0, coupling=coupled)


def _runs(blocks: list, om: np.ndarray, zeta: np.ndarray) -> list[tuple[int, int, int]] | None:
    """Runs of consecutive blocks that share their modes, ``(first block, start, stop)``; None
    if some block's rows have modes of their own."""
    runs: list[tuple[int, int, int]] = []
    for i, (a, b, same, *_) in enumerate(blocks):
        if not same:
            return None
        if runs and np.array_equal(om[a], om[runs[-1][1]]) and zeta[a] == zeta[runs[-1][1]]:
            runs[-1] = (runs[-1][0], runs[-1][1], b)
        else:
            runs.append((i, a, b))
    return runs


def _unscaled(y: np.ndarray, c_y: np.ndarray) -> np.ndarray:
    """``Z = Y / c_y``; a mode of zero gain is never driven (``Z = 0``)."""
    return np.divide(y, c_y, out=np.zeros_like(y), where=c_y != 0)


def _step(st: _State, c: _Coefficients, law, h: float, shell: slice | None) -> np.ndarray:
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


def _close_step(st: _State, c: _Coefficients, f0: np.ndarray, s4: np.ndarray,
                u_new: np.ndarray, h: float) -> None:
    """What every step ends with: the rigid/ball rate and the impulse from the stages' forces
    (``s4 = F0 + 2 (Fa + Fb) + Fc``), the largest force and compression so far."""
    st.v = st.v + c.v6 * s4
    st.dj = (h / 6.0) * s4
    st.impulse = st.impulse + st.dj
    st.f_peak = np.maximum(st.f_peak, f0)
    st.f0 = f0
    st.u_top = np.maximum(st.u_top, u_new)


def _peak(st: _State, c: _Coefficients, law, turned: np.ndarray, du: np.ndarray, h: float,
          shell: slice | None) -> None:
    """The compression peaked inside the last step at the rows ``turned``: refine ``u_top``
    there, and take the shell's share of the stored energy at the ball's (largest) maximum."""
    top = _hermite_max(st.u_prev[turned], st.du_prev[turned], st.u[turned], du[turned], h)
    if shell is not None:
        rows = np.flatnonzero(turned)[top >= st.u_top[turned]]  # the largest maximum
        ball = law.stored(rows, top[top >= st.u_top[turned]])
        z = _unscaled(c.modal.current(st.z, rows)[:, shell], c.c_y[rows, shell])
        barrel = c.shell_factor[rows] * (z.imag ** 2).sum(1)
        st.share[rows] = barrel / (ball + barrel)
    st.u_top[turned] = np.maximum(st.u_top[turned], top)


def _step_coupled(st: _State, c: _Coefficients, law, h: float, shell: slice | None
                  ) -> np.ndarray:
    """:func:`_step` for gains that follow the ball's compression (a
    :class:`~batcert.physics.coupling.Coupling` of ``G`` groups).

    Every group is read and forced with its factor ``rho`` at each stage's time, ``rho`` of the
    compression predicted for it from the last two steps
    (:func:`~batcert.physics.coupling.extrapolate`); a stage's response to a force is each
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


def march(system: LinearSystem, law, approach_speed, time_step: float, max_time: float,
          chunk: int | None = None) -> Separation:
    """Integrate all impacts from first touch to separation (ETDRK4; module notes).

    State per impact (:class:`_State`): complex modal coordinates, kept scaled as ``Y = c_y Z``
    (:func:`_coefficients`) (n, K), the merged
    rigid/ball coordinate ``w`` and its rate ``v``, the impulse on the ball, the largest
    compression so far. The stage compressions of Cox & Matthews' scheme (their Eqs. 26-29,
    linear part exact) are ``u_a = U2 + ka F0``, ``u_b = U2 + ka Fa + b0 F0`` and
    ``u_c = U1 + c0 F0 + cb Fb + ca Fa``, where ``U2``, ``U1`` are the free (force-less)
    motions over h/2 and h; those, and the compression at the step's end, are read from the
    modal coordinates with one matrix product when the step advances them
    (:mod:`batcert.physics.modal_update`). Finished impacts are recorded and, once they are
    many, dropped from the arrays (:meth:`_State.take`). Batches larger than ``chunk`` impacts
    (default: about ``_CHUNK_ENTRIES`` impact-mode entries) are integrated ``chunk`` at a
    time, so that memory stays bounded whatever the batch.

    Parameters
    ----------
    system : LinearSystem
        Linear part of each impact.
    law
        The ball law's time-stepping state, one row per impact (a law's ``march_rows``, e.g.
        :class:`~batcert.physics.balls.hysteresis.HysteresisMarch`): ``start``, ``half_a``,
        ``half_b``, ``end`` give the force at a step's stages, ``finish`` advances the law over
        the step and returns its contact measure (the impact separates where it falls to zero
        or below), ``prepare`` (optional) runs before each step, ``stored``, ``absorbed`` and
        ``take`` serve the diagnostics and the dropping of finished rows. A law whose force
        falls through zero with a finite slope (``crossing``, the viscoelastic law) has the
        impulse of its last step taken up to the separation only, the force falling linearly
        to zero (trapezoidal): the clipped stages past it would leave an error of the step's
        second order, 3e-4 of a stationary-bat exit speed at a 20 us step.
    approach_speed : array_like
        Initial compression rate ``w1 r - v_p`` [m/s], (n,), > 0.
    time_step : float
        Step [s].
    max_time : float
        Safety cap on the contact time [s].
    """
    n, k_modes = system.omega.shape
    if chunk is None:
        chunk = max(256, _CHUNK_ENTRIES // max(k_modes, 1))
    law = law.for_step(float(time_step))
    if n <= chunk:
        return _march(system, law, approach_speed, time_step, max_time)
    speed = np.broadcast_to(np.asarray(approach_speed, dtype=float), (n,))
    parts = []
    for a in range(0, n, chunk):
        b = min(a + chunk, n)
        parts.append(_march(system.rows(a, b), law.take(slice(a, b)).offset(a), speed[a:b],
                            time_step, max_time))
    return Separation.concatenate(parts)


def _march(system: LinearSystem, law, approach_speed, time_step: float,
           max_time: float) -> Separation:
    h = float(time_step)
    n, k_modes = system.omega.shape
    c = _coefficients(system, h)
    shell = None
    if system.shell_columns is not None:
        cols = np.flatnonzero(system.shell_columns)
        if cols.size:
            assert np.all(np.diff(cols) == 1), "shell modes must be contiguous columns"
            shell = slice(int(cols[0]), int(cols[-1]) + 1)
    hollow = system.shell_columns is not None

    groups = 1 if system.coupling is None else system.coupling.size
    st = _State.start(n, k_modes, approach_speed, groups)
    if system.coupling is not None:
        st.rho = system.coupling.at(np.zeros(n))
    step = _step if system.coupling is None else _step_coupled
    live = np.ones(n, dtype=bool)
    absorbs = law.absorbed() is not None
    out = Separation(impulse=np.zeros(n), time=np.full(n, np.nan), separated=np.zeros(n, bool),
                     peak_force=np.zeros(n), max_compression=np.zeros(n),
                     modal=np.zeros((n, k_modes), dtype=complex),
                     barrel_share=np.zeros(n) if hollow else None,
                     absorbed=np.zeros(n) if absorbs else None)
    prepares = hasattr(law, "prepare")
    crossing = getattr(law, "crossing", False)

    def record(mask):
        idx = st.rows[mask]
        out.impulse[idx], out.peak_force[idx] = st.impulse[mask], st.f_peak[mask]
        out.max_compression[idx] = st.u_top[mask]
        out.modal[idx] = _unscaled(c.modal.current(st.z, mask), c.c_y[mask])
        if out.barrel_share is not None:
            out.barrel_share[idx] = st.share[mask]
        if out.absorbed is not None:
            out.absorbed[idx] = law.absorbed()[mask]
        return idx

    t = 0.0
    for _ in range(int(np.ceil(max_time / h))):
        if prepares:  # e.g. Nathan's law: the loss follows the compression so far
            law.prepare(st.u_top, st.rows)
        u_new = step(st, c, law, h, shell)
        g_new = law.finish(u_new)
        t += h
        done = (g_new <= 0.0) & (st.g > 0.0)  # separation; finished rows are parked at u = -1 m
        if np.count_nonzero(done):
            frac = st.g[done] / (st.g[done] - g_new[done])
            if crossing:  # the last step's impulse up to separation only (module notes)
                st.impulse[done] += 0.5 * st.f0[done] * frac * h - st.dj[done]
            idx = record(done)
            out.time[idx] = t - h + h * frac
            out.separated[idx] = True
            live &= ~done
            st.w[done], st.v[done], u_new[done], g_new[done] = -1.0, 0.0, -1.0, -1.0
            n_live = int(live.sum())
            if n_live == 0:
                return out
            if n_live < 0.6 * live.size:  # drop finished rows
                keep = np.flatnonzero(live)
                st.u, st.g = u_new, g_new
                st, c, live, law = st.take(keep), c.take(keep), live[keep], law.take(keep)
                continue
        st.u, st.g = u_new, g_new
    out.time[record(live)] = t  # the time cap came first: report that state, flagged
    return out


def _hermite_max(u0, d0, u1, d1, h):
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
