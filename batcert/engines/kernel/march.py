"""Batched time integration of ball contact against a linear modal structure (flexible engine).

All impacts advance together, arrays shaped (impacts, modes). The linear modal dynamics are
propagated exactly; only the contact force is approximated, by the exponential Runge-Kutta scheme
ETDRK4 (Cox & Matthews, J. Comput. Phys. 176 (2002) 430, Eqs. 26-29) in complex modal
coordinates ``Z = p - conj(lambda) q``, ``Z' = lambda Z - g F``. The contact force comes from
the ball's law (:mod:`batcert.physics.balls`), through its time-stepping state: the force at
each stage of a step, its own internal variables advanced with the step, and a contact measure
whose fall through zero is separation. :mod:`batcert.engines.flexible` builds the
:class:`LinearSystem` of each impact and reads the :class:`Separation`; the
:class:`~batcert.engines.kernel.linear_system.LinearSystem` is the impacts' linear part.

The physics of a step and the speed machinery are apart: :mod:`batcert.engines.kernel.etdrk4` holds
the scheme's constants, :mod:`batcert.engines.kernel.march_step` the step itself, and
:mod:`batcert.engines.kernel.modal_update` how the modal state is laid out in memory and advanced
(:class:`~batcert.engines.kernel.modal_update.ModalUpdate`: row by row, the reference, or one matrix
product per run of rows that share their modes; tests/physics/test_march.py compares them).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from batcert.engines.kernel.etdrk4 import coefficients
from batcert.engines.kernel.linear_system import LinearSystem
from batcert.engines.kernel.march_step import State, step, step_coupled, unscaled
from batcert.physics.balls.law import MarchState

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


def march(system: LinearSystem, law: MarchState, approach_speed, time_step: float, max_time: float,
          chunk: int | None = None) -> Separation:
    """Integrate all impacts from first touch to separation (ETDRK4; module notes).

    State per impact (:class:`State`): complex modal coordinates, kept scaled as ``Y = c_y Z``
    (:func:`_coefficients`) (n, K), the merged
    rigid/ball coordinate ``w`` and its rate ``v``, the impulse on the ball, the largest
    compression so far. The stage compressions of Cox & Matthews' scheme (their Eqs. 26-29,
    linear part exact) are ``u_a = U2 + ka F0``, ``u_b = U2 + ka Fa + b0 F0`` and
    ``u_c = U1 + c0 F0 + cb Fb + ca Fa``, where ``U2``, ``U1`` are the free (force-less)
    motions over h/2 and h; those, and the compression at the step's end, are read from the
    modal coordinates with one matrix product when the step advances them
    (:mod:`batcert.engines.kernel.modal_update`). Finished impacts are recorded and, once they are
    many, dropped from the arrays (:meth:`State.take`). Batches larger than ``chunk`` impacts
    (default: about ``_CHUNK_ENTRIES`` impact-mode entries) are integrated ``chunk`` at a
    time, so that memory stays bounded whatever the batch.

    Parameters
    ----------
    system : LinearSystem
        Linear part of each impact.
    law : MarchState
        The ball law's time-stepping state, one row per impact
        (:class:`~batcert.physics.balls.law.MarchState`, a law's ``march_rows``):
        ``start``, ``half_a``, ``half_b``, ``end`` give the force at a step's stages,
        ``finish`` advances the law over the step and returns its contact measure (the impact
        separates where it falls to zero or below), ``prepare`` runs before each step,
        ``stored``, ``absorbed`` and ``take`` serve the diagnostics and the dropping of
        finished rows. A law whose force
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


def _march(system: LinearSystem, law: MarchState, approach_speed, time_step: float,
           max_time: float) -> Separation:
    h = float(time_step)
    n, k_modes = system.omega.shape
    c = coefficients(system, h)
    shell = _shell_columns(system)
    groups = 1 if system.coupling is None else system.coupling.size
    st = State.start(n, k_modes, approach_speed, groups)
    if system.coupling is not None:
        st.rho = system.coupling.at(np.zeros(n))
    advance = step if system.coupling is None else step_coupled
    live = np.ones(n, dtype=bool)
    out = Separation(impulse=np.zeros(n), time=np.full(n, np.nan), separated=np.zeros(n, bool),
                     peak_force=np.zeros(n), max_compression=np.zeros(n),
                     modal=np.zeros((n, k_modes), dtype=complex),
                     barrel_share=np.zeros(n) if system.shell_columns is not None else None,
                     absorbed=np.zeros(n) if law.absorbed() is not None else None)
    crossing = law.crossing
    t = 0.0
    for _ in range(int(np.ceil(max_time / h))):
        law.prepare(st.u_top, st.rows)  # e.g. Nathan's law: the loss follows u_top
        u_new = advance(st, c, law, h, shell)
        g_new = law.finish(u_new)
        t += h
        done = (g_new <= 0.0) & (st.g > 0.0)  # separation; finished rows are parked at u = -1 m
        if np.count_nonzero(done):
            frac = st.g[done] / (st.g[done] - g_new[done])
            if crossing:  # the last step's impulse up to separation only (module notes)
                st.impulse[done] += 0.5 * st.f0[done] * frac * h - st.dj[done]
            idx = _record(out, st, c, law, done)
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
    out.time[_record(out, st, c, law, live)] = t  # the time cap came first: that state, flagged
    return out


def _shell_columns(system: LinearSystem) -> slice | None:
    """The shell modes' columns (contiguous), or None for a solid bat."""
    if system.shell_columns is None:
        return None
    cols = np.flatnonzero(system.shell_columns)
    if not cols.size:
        return None
    assert np.all(np.diff(cols) == 1), "shell modes must be contiguous columns"
    return slice(int(cols[0]), int(cols[-1]) + 1)


def _record(out: Separation, st: State, c, law, mask: np.ndarray) -> np.ndarray:
    """Copy the state of the rows ``mask`` into ``out``; their indices in the batch."""
    idx = st.rows[mask]
    out.impulse[idx], out.peak_force[idx] = st.impulse[mask], st.f_peak[mask]
    out.max_compression[idx] = st.u_top[mask]
    out.modal[idx] = unscaled(c.modal.current(st.z, mask), c.c_y[mask])
    if out.barrel_share is not None:
        out.barrel_share[idx] = st.share[mask]
    if out.absorbed is not None:
        out.absorbed[idx] = law.absorbed()[mask]
    return idx
