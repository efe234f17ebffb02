"""Batched time integration of ball contact against a linear modal structure (flexible engine).

All impacts advance together, arrays shaped (impacts, modes). The linear modal dynamics are
propagated exactly; only the contact force is approximated, by the exponential Runge-Kutta scheme
ETDRK4 (Cox & Matthews, J. Comput. Phys. 176 (2002) 430, Eqs. 26-29) in complex modal
coordinates ``Z = p - conj(lambda) q``, ``Z' = lambda Z - g F``. The contact law is Nathan's
(2000) power-law hysteresis (:mod:`batcert.physics.contact`). :mod:`batcert.engines.flexible`
builds the :class:`LinearSystem` of each impact and reads the :class:`Separation`;
:mod:`batcert.physics.modal_update` advances the modal state by a step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from batcert.physics import stores
from batcert.physics.modal_update import RowByRow, SharedRuns, im_weights

_TINY = 1e-300  # floor of the compression inside log() [m]
# rows that share their modes are read and forced with one matrix product per run of them when
# the runs average at least this many rows (else row by row; measured, bench_engine.py)
_SHARED_ROWS = 16
# a batch is integrated in chunks of about this many (impact, mode) entries (bounded memory),
# while each step's modal update runs over cache-sized pieces of them (modal_update.py;
# measured, 20,000 random impacts: a hollow bat's 44 modes in 1675-row pieces of 4096-row
# chunks, 5 % more impacts per second than 2234-row chunks updated whole)
_CHUNK_ENTRIES = 196_608


def phi_functions(z):
    """``phi_1``, ``phi_2``, ``phi_3`` of exponential integrators at complex ``z`` [-].

    ``phi_k(z) = sum_j z^j / (j + k)!``: ``phi_1 = (e^z - 1)/z``, ``phi_2 = (e^z - 1 - z)/z^2``,
    ``phi_3 = (e^z - 1 - z - z^2/2)/z^3`` (Cox & Matthews 2002). Taylor series for
    ``|z| < 0.5`` (no cancellation), closed forms elsewhere.
    """
    z = np.asarray(z, dtype=complex)
    small = np.abs(z) < 0.5
    zs = np.where(small, z, 0.0)
    out = []
    for k in (1, 2, 3):
        series = np.zeros_like(z)
        term = np.full_like(z, 1.0 / np.prod(np.arange(1, k + 1)))
        for j in range(1, 30):
            series += term
            term = term * zs / (j + k)
        out.append(series)
    zb = np.where(small, 1.0, z)
    ez = np.exp(zb)
    big = [(ez - 1) / zb, (ez - 1 - zb) / zb**2, (ez - 1 - zb - zb**2 / 2) / zb**3]
    return tuple(np.where(small, s, b) for s, b in zip(out, big, strict=True))


@dataclass
class LinearSystem:
    """The linear part of every impact: merged rigid/ball coordinate and flexible coupled modes.

    Arrays have one row per impact; ``K`` columns of flexible modes. Impacts of several bats
    (and balls) can share one system: ``zeta`` and ``ball_mass`` are per row, and ``blocks``
    names the runs of rows that share their frequencies and damping (one bat each), so that the
    step's exponentials are computed once per block.
    """

    omega: np.ndarray  # coupled angular frequencies [rad/s], (n, K)
    zeta: np.ndarray  # modal damping ratio [-], (n,)
    gain: np.ndarray  # mode shape at the contact point, ``g`` [1/sqrt(kg)], (n, K)
    rigid_mass: np.ndarray  # rigid mass met at the contact point (bat + barrel) [kg], (n,)
    ball_mass: np.ndarray  # [kg], (n,)
    shell_columns: np.ndarray | None = None  # (K,) bool: the hollow barrel's shell modes
    blocks: tuple[tuple[int, int], ...] | None = None  # row ranges [start, stop) of one bat

    def __post_init__(self) -> None:
        n = self.omega.shape[0]
        self.zeta = np.broadcast_to(np.asarray(self.zeta, dtype=float), (n,)).copy()
        self.ball_mass = np.broadcast_to(np.asarray(self.ball_mass, dtype=float), (n,)).copy()
        if self.blocks is None:
            self.blocks = ((0, n),)

    def rows(self, a: int, b: int) -> LinearSystem:
        """Rows ``a:b``, the blocks clipped to them."""
        blocks = tuple((max(s, a) - a, min(e, b) - a) for s, e in self.blocks or ((0, b),)
                       if s < b and e > a)
        return LinearSystem(omega=self.omega[a:b], zeta=self.zeta[a:b], gain=self.gain[a:b],
                            rigid_mass=self.rigid_mass[a:b], ball_mass=self.ball_mass[a:b],
                            shell_columns=self.shell_columns, blocks=blocks)

    @property
    def inv_reduced_mass(self) -> np.ndarray:
        """``1/m + 1/M_r`` [1/kg], (n,)."""
        return 1.0 / self.ball_mass + 1.0 / self.rigid_mass


def stack_systems(systems: list[LinearSystem]) -> tuple[LinearSystem, list[np.ndarray]]:
    """One system of the rows of several (e.g. several bats), and for each the columns its
    modes occupy in it. Columns are aligned by kind, bending modes first, then shell modes,
    then the rest (the residual), each group padded with modes of zero gain that nothing
    drives, so that the shell's columns are common to every row."""
    if len(systems) == 1:
        return systems[0], [np.arange(systems[0].omega.shape[1])]

    def groups(sy: LinearSystem) -> tuple[int, int, int]:
        k = sy.omega.shape[1]
        if sy.shell_columns is None or not sy.shell_columns.any():
            return k, 0, 0
        cols = np.flatnonzero(sy.shell_columns)
        return int(cols[0]), cols.size, k - int(cols[0]) - cols.size

    sizes = [groups(sy) for sy in systems]
    width = [max(g[i] for g in sizes) for i in range(3)]
    offsets = [0, width[0], width[0] + width[1]]
    omega, gain, blocks, columns, start = [], [], [], [], 0
    for sy, g in zip(systems, sizes, strict=True):
        n = sy.omega.shape[0]
        cols = np.concatenate([offsets[i] + np.arange(g[i]) for i in range(3)])
        om = np.ones((n, sum(width)))  # padding: 1 rad/s, zero gain, never driven
        gn = np.zeros((n, sum(width)))
        om[:, cols], gn[:, cols] = sy.omega, sy.gain
        omega.append(om)
        gain.append(gn)
        columns.append(cols)
        blocks += [(start + a, start + b) for a, b in sy.blocks or ((0, n),)]
        start += n
    shell = None
    if width[1]:
        shell = np.zeros(sum(width), bool)
        shell[offsets[1]:offsets[2]] = True
    stacked = LinearSystem(
        omega=np.concatenate(omega), zeta=np.concatenate([sy.zeta for sy in systems]),
        gain=np.concatenate(gain), rigid_mass=np.concatenate([sy.rigid_mass for sy in systems]),
        ball_mass=np.concatenate([sy.ball_mass for sy in systems]), shell_columns=shell,
        blocks=tuple(blocks))
    return stacked, columns


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
    beta: np.ndarray
    ab: np.ndarray  # alpha - beta
    lk1: np.ndarray  # log k1 of each impact's ball
    alpha: np.ndarray  # each impact's compression exponent
    shell_factor: np.ndarray  # 1 / (2 (1 - zeta^2)): shell potential energy per Im(Z)^2
    top_seen: np.ndarray  # the largest compression ``beta`` was last evaluated at [m]
    modal: RowByRow | SharedRuns  # how Y advances and the contact point reads it

    def take(self, keep: np.ndarray) -> _Coefficients:
        kept = {k: v.take(keep) if k == "modal" else v[keep] for k, v in vars(self).items()}
        return _Coefficients(**kept)


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
    share: np.ndarray  # barrel's share of the stored energy at the ball's maximum compression
    base: np.ndarray  # the read-out of Y now (free y after h/2 and h, y', y), (n, 4)
    rows: np.ndarray  # index of each row in the caller's batch

    def take(self, keep: np.ndarray) -> _State:
        return _State(**{k: v[keep] for k, v in vars(self).items()})

    @classmethod
    def start(cls, n: int, k_modes: int, approach_speed) -> _State:
        zeros = np.zeros(n)
        return cls(z=np.zeros((n, k_modes), dtype=complex), w=zeros.copy(),
                   v=np.array(approach_speed, dtype=float).reshape(n), impulse=zeros.copy(),
                   u=zeros.copy(), u_top=np.full(n, _TINY), f_peak=zeros.copy(),
                   u_prev=zeros.copy(), du_prev=zeros.copy(),
                   share=zeros.copy(), base=np.zeros((n, 4)), rows=np.arange(n))


_EXP_CACHE: stores.Memo[tuple, tuple[np.ndarray, ...]] = stores.Memo(128)


def _exponentials(lam: np.ndarray, h: float) -> tuple[np.ndarray, ...]:
    """``e^(lam h)``, ``e^(lam h / 2)``, ``phi_1..3(lam h)`` and ``h/2 phi_1(lam h / 2)`` of
    one block's eigenvalues; memoised (a bat's modes recur in every batch of a run)."""
    key = (lam.shape, float(h), lam.tobytes())
    hit = _EXP_CACHE.look(key)
    if hit is not None:
        return hit
    vals = (np.exp(lam * h), np.exp(lam * h / 2), *phi_functions(lam * h),
            0.5 * h * phi_functions(lam * h / 2)[0])
    if lam.shape[0] == 1:  # only single rows (a block's shared row) are worth keeping
        _EXP_CACHE.keep(key, vals)
    return vals


def _coefficients(system: LinearSystem, h: float, k1, alpha, beta) -> _Coefficients:
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
        blocks.append((a, b, same, e1, read, push))
    inv_mu = system.inv_reduced_mass
    per_row = [np.broadcast_to(np.asarray(x, dtype=float), (n,)).copy() for x in (k1, alpha, beta)]
    k1, alpha, beta = per_row
    modal: RowByRow | SharedRuns
    runs = _runs(blocks, om, system.zeta)
    if runs is not None and len(runs) * _SHARED_ROWS <= max(n, _SHARED_ROWS):
        first = [blocks[i] for i, _, _ in runs]
        modal = SharedRuns(
            e1=np.concatenate([blk[3] for blk in first]),
            R=np.ascontiguousarray(np.concatenate([blk[4] for blk in first]).transpose(0, 2, 1)),
            P=np.ascontiguousarray(np.concatenate([blk[5] for blk in first])).view(float),
            scale=np.repeat(cg, 2, axis=1),
            group=np.repeat(np.arange(len(runs)), [b - a for _, a, b in runs]))
    else:
        def rows(i):  # each row's copy of a block's part
            return np.concatenate([np.broadcast_to(blk[i], (blk[1] - blk[0],) + blk[i].shape[1:])
                                   for blk in blocks])
        modal = RowByRow(e1=rows(3), R=np.ascontiguousarray(rows(4)),
                         B=np.ascontiguousarray(cg[:, None, :] * rows(5)).view(float))
    return _Coefficients(
        ka=ka, b0=-h * h / 4 * inv_mu, c0=c0, cb=2 * ka, ca=-h * h / 2 * inv_mu,
        w6=-h * h / 6 * inv_mu, v6=-h / 6 * inv_mu, c_y=c_y, beta=beta, ab=alpha - beta,
        lk1=np.log(k1), alpha=alpha, shell_factor=0.5 / (1.0 - system.zeta**2),
        top_seen=np.full(n, np.nan), modal=modal)


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


def _force(c: _Coefficients, x: np.ndarray, l_top: np.ndarray) -> np.ndarray:
    """:func:`contact.contact_force` in log form, both branches in one exp [N]."""
    lx = np.log(np.maximum(x, _TINY))
    return np.exp(c.lk1 + c.ab * np.maximum(lx, l_top) + c.beta * lx)


def _unscaled(y: np.ndarray, c_y: np.ndarray) -> np.ndarray:
    """``Z = Y / c_y``; a mode of zero gain is never driven (``Z = 0``)."""
    return np.divide(y, c_y, out=np.zeros_like(y), where=c_y != 0)


def _step(st: _State, c: _Coefficients, h: float, shell: slice | None) -> np.ndarray:
    """Advance every impact by one ETDRK4 step in place; return the compression at its end.

    ``shell`` is the shell modes' columns when the barrel's energy share is tracked, else
    None; a mode's potential energy ``omega^2 q^2 / 2`` is ``shell_factor Im(Z)^2``. The share
    is taken when the ball's compression peaks (the stored energies' largest moment, within the
    shell's lag), where the ball holds ``k1 u_top^(1 + alpha) / (1 + alpha)``.
    """
    base = st.base
    u2 = base[:, 0] + st.w + 0.5 * h * st.v
    u1 = base[:, 1] + st.w + h * st.v
    du = st.v + base[:, 2]
    turned = (st.du_prev > 0) & (du <= 0) & (st.u > 0)
    if np.count_nonzero(turned):  # the maximum compression fell inside the last step: refine u_top
        top = _hermite_max(st.u_prev[turned], st.du_prev[turned], st.u[turned], du[turned], h)
        if shell is not None:  # the shell's share of the stored energy at the ball's maximum
            rows = np.flatnonzero(turned)[top >= st.u_top[turned]]  # the largest maximum
            top_rows = top[top >= st.u_top[turned]]
            a1 = 1.0 + c.alpha[rows]
            ball = np.exp(c.lk1[rows] + a1 * np.log(top_rows)) / a1
            z = _unscaled(c.modal.current(st.z, rows)[:, shell], c.c_y[rows, shell])
            barrel = c.shell_factor[rows] * (z.imag ** 2).sum(1)
            st.share[rows] = barrel / (ball + barrel)
        st.u_top[turned] = np.maximum(st.u_top[turned], top)
    st.u_prev, st.du_prev = st.u, du
    l_top = np.log(st.u_top)
    f = np.empty((du.size, 3))
    f0 = f[:, 0] = _force(c, st.u, l_top)
    fa = _force(c, u2 + c.ka * f0, l_top)
    fb = _force(c, u2 + c.ka * fa + c.b0 * f0, l_top)
    fc = f[:, 2] = _force(c, u1 + c.c0 * f0 + c.cb * fb + c.ca * fa, l_top)
    fab = f[:, 1] = fa + fb
    st.base = c.modal.advance(st.z, f)
    s4 = f0 + 2.0 * fab + fc
    st.w = st.w + h * st.v + c.w6 * (f0 + fab)
    u_new = st.base[:, 3] + st.w  # y = sum Im(Y), u = y + w
    st.v = st.v + c.v6 * s4
    st.impulse = st.impulse + (h / 6.0) * s4
    st.f_peak = np.maximum(st.f_peak, f0)
    st.u_top = np.maximum(st.u_top, u_new)
    return u_new


def march(system: LinearSystem, k1, alpha, beta, approach_speed, time_step: float,
          max_time: float, restitution=None, chunk: int | None = None) -> Separation:
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
    k1, alpha : array_like
        Contact law of each impact's ball, compression branch [N/m^alpha], [-]; scalars or (n,).
    beta : array_like
        Restitution exponent per impact [-], (n,).
    approach_speed : array_like
        Initial compression rate ``w1 r - v_p`` [m/s], (n,), > 0.
    time_step : float
        Step [s].
    max_time : float
        Safety cap on the contact time [s].
    restitution : callable, optional
        ``beta(u_top, rows)``: the restitution exponent of impacts ``rows`` (indices into the
        batch) as a function of their largest compression so far [m]
        (:func:`contact.compression_restitution`), re-evaluated every step; without it ``beta``
        stays as given.
    """
    n, k_modes = system.omega.shape
    if chunk is None:
        chunk = max(256, _CHUNK_ENTRIES // max(k_modes, 1))
    if n <= chunk:
        return _march(system, k1, alpha, beta, approach_speed, time_step, max_time, restitution)
    k1, alpha, beta, speed = (np.broadcast_to(np.asarray(x, dtype=float), (n,))
                              for x in (k1, alpha, beta, approach_speed))
    parts = []
    for a in range(0, n, chunk):
        b = min(a + chunk, n)
        parts.append(_march(system.rows(a, b), k1[a:b], alpha[a:b], beta[a:b], speed[a:b],
                            time_step, max_time,
                            None if restitution is None else _offset(restitution, a)))
    return Separation.concatenate(parts)


def _offset(restitution, start: int):
    return lambda u_top, rows: restitution(u_top, rows + start)


def _march(system: LinearSystem, k1, alpha, beta, approach_speed, time_step: float,
           max_time: float, restitution=None) -> Separation:
    h = float(time_step)
    n, k_modes = system.omega.shape
    c = _coefficients(system, h, k1, alpha, beta)
    shell = None
    if system.shell_columns is not None:
        cols = np.flatnonzero(system.shell_columns)
        if cols.size:
            assert np.all(np.diff(cols) == 1), "shell modes must be contiguous columns"
            shell = slice(int(cols[0]), int(cols[-1]) + 1)
    hollow = system.shell_columns is not None

    st = _State.start(n, k_modes, approach_speed)
    live = np.ones(n, dtype=bool)
    out = Separation(impulse=np.zeros(n), time=np.full(n, np.nan), separated=np.zeros(n, bool),
                     peak_force=np.zeros(n), max_compression=np.zeros(n),
                     modal=np.zeros((n, k_modes), dtype=complex),
                     barrel_share=np.zeros(n) if hollow else None)

    def record(mask):
        idx = st.rows[mask]
        out.impulse[idx], out.peak_force[idx] = st.impulse[mask], st.f_peak[mask]
        out.max_compression[idx] = st.u_top[mask]
        out.modal[idx] = _unscaled(c.modal.current(st.z, mask), c.c_y[mask])
        if out.barrel_share is not None:
            out.barrel_share[idx] = st.share[mask]
        return idx

    t = 0.0
    for _ in range(int(np.ceil(max_time / h))):
        if restitution is not None:  # the ball's loss follows its compression so far
            _restitute(c, st, restitution)
        u_new = _step(st, c, h, shell)
        t += h
        done = (u_new <= 0.0) & (st.u > 0.0)  # separation; finished rows are parked at u = -1 m
        if np.count_nonzero(done):
            idx = record(done)
            out.time[idx] = t - h + h * st.u[done] / (st.u[done] - u_new[done])
            out.separated[idx] = True
            live &= ~done
            st.w[done], st.v[done], u_new[done] = -1.0, 0.0, -1.0
            n_live = int(live.sum())
            if n_live == 0:
                return out
            if n_live < 0.6 * live.size:  # drop finished rows
                keep = np.flatnonzero(live)
                st.u = u_new
                st, c, live = st.take(keep), c.take(keep), live[keep]
                continue
        st.u = u_new
    out.time[record(live)] = t  # the time cap came first: report that state, flagged
    return out


def _restitute(c: _Coefficients, st: _State, restitution) -> None:
    """Re-evaluate ``beta`` where the largest compression has grown since it was last
    evaluated (all rows while the balls compress, none once they all recover)."""
    grew = st.u_top != c.top_seen
    changed = np.count_nonzero(grew)
    if changed == grew.size:
        c.beta, c.top_seen = restitution(st.u_top, st.rows), st.u_top.copy()
        c.ab = c.alpha - c.beta
    elif changed:
        rows = np.flatnonzero(grew)
        c.beta[rows] = restitution(st.u_top[rows], st.rows[rows])
        c.top_seen[rows] = st.u_top[rows]
        c.ab[rows] = c.alpha[rows] - c.beta[rows]


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
