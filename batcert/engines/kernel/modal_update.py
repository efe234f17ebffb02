"""How a step of :func:`~batcert.engines.kernel.march.march` advances the modal state and reads
the contact point's free motion from it.

The state is ``Y = c_y Z`` (n, K) complex, one row per impact (:mod:`batcert.engines.kernel.march`).
Each step advances it by the free modes' exact propagation and the forcing of the step's
contact forces (F0, Fa + Fb, Fc), and reads four numbers per row: the free ``y`` after h/2 and
h, ``y'`` and ``y``.
:class:`RowByRow` does this for rows with modes of their own; :class:`SharedRuns` for runs of
rows that share their modes (one bat each), with matrix products over cache-sized pieces of
the rows and the state kept in frames that turn with the free modes (:class:`Turns`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

# rows that share their modes are read and forced with one matrix product per run of them when
# the runs average at least this many rows (else row by row; measured, bench_engine.py)
SHARED_ROWS = 16

# each step's modal update runs over pieces of rows of about this many impact-mode entries, so
# that a piece's state, forcing and read-out stay in the processor's cache while the per-impact
# arithmetic runs over the whole chunk (measured, 20,000 random impacts: pieces of 512-1675
# hollow rows alike; a solid bat's 18 modes fastest whole, 4096 rows, 4 % ahead of 2503-row
# pieces). ("pieces", not "blocks": a LinearSystem's blocks are the rows of one bat.)
PIECE_ENTRIES = 73_728
# runs of shared modes keep their state in a frame turning with the free modes (Turns), folded
# back at most every FRAME_STEPS steps, and before a damped mode's growth 1/|e1^k| exceeds
# e^FRAME_GROWTH (far from overflow, and without loss of precision: the state is read as
# e1^k X, relative to its latest forcing)
FRAME_STEPS = 32
FRAME_GROWTH = 50.0


class ModalUpdate(Protocol):
    """The one interface of the batched kernel's modal update: how a step of
    :func:`~batcert.engines.kernel.march.march` advances ``Y`` (n, K) under the step's forces and
    reads the contact point's free motion from it. :class:`RowByRow` is the plain reference
    (every row its own propagation, forcing and read-out; ``SHARED_ROWS`` set above the batch
    size makes :func:`layout` choose it); :class:`SharedRuns` the fast one, which
    tests/physics/test_march.py holds to the reference to rounding."""

    def advance(self, z: np.ndarray, f: np.ndarray) -> np.ndarray:
        """Advance the state ``z`` in place under the forces ``f``; the read-out, (n, 4 G)."""
        ...

    def current(self, z: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """``Y`` of ``rows`` (indices or a mask) from the state ``z``."""
        ...

    def take(self, keep: np.ndarray) -> ModalUpdate:
        """The update of the rows ``keep`` only (finished impacts dropped)."""
        ...


@dataclass(frozen=True)
class Block:
    """The step constants of the rows ``start .. stop`` of one bat
    (:func:`batcert.engines.kernel.etdrk4.coefficients`): ``shared`` when every row has the block's
    modes, then ``e1`` (1, K), ``read`` (1, 4, 2K) and ``push`` (1, 3, K) are the block's; else
    one row each."""

    start: int
    stop: int
    shared: bool
    e1: np.ndarray  # propagator e^(lam h)
    read: np.ndarray  # read-out weights of Y as floats: free y after h/2 and h, y', y
    push: np.ndarray  # forcing of Z per unit gain by (F0, Fa + Fb, Fc), complex


def layout(blocks: list[Block], cg: np.ndarray, om: np.ndarray, zeta: np.ndarray,
           group_starts: np.ndarray | None) -> ModalUpdate:
    """The modal update of ``blocks``' rows: :class:`SharedRuns` when the blocks form runs of
    shared modes of on average at least :data:`SHARED_ROWS` rows, else :class:`RowByRow`.
    ``cg``: each row's ``c_y g`` (n, K); ``om``, ``zeta``: its modes; ``group_starts``: the
    columns where a coupling's groups start, and the end (G + 1,), or None."""
    n = cg.shape[0]
    runs = _runs(blocks, om, zeta)
    if runs is not None and len(runs) * SHARED_ROWS <= max(n, SHARED_ROWS):
        return _shared_runs([blocks[i] for i, _, _ in runs], runs, cg, group_starts)
    return _row_by_row(blocks, cg, group_starts)


def _runs(blocks: list[Block], om: np.ndarray, zeta: np.ndarray
          ) -> list[tuple[int, int, int]] | None:
    """Runs of consecutive blocks that share their modes, ``(first block, start, stop)``; None
    if some block's rows have modes of their own."""
    runs: list[tuple[int, int, int]] = []
    for i, blk in enumerate(blocks):
        a, b = blk.start, blk.stop
        if not blk.shared:
            return None
        if runs and np.array_equal(om[a], om[runs[-1][1]]) and zeta[a] == zeta[runs[-1][1]]:
            runs[-1] = (runs[-1][0], runs[-1][1], b)
        else:
            runs.append((i, a, b))
    return runs


def _shared_runs(heads: list[Block], runs: list[tuple[int, int, int]], cg: np.ndarray,
                 group_starts: np.ndarray | None) -> SharedRuns:
    read = np.concatenate([blk.read for blk in heads])  # (runs, 4, 2K)
    push = np.concatenate([blk.push for blk in heads])  # (runs, 3, K)
    if group_starts is not None:  # by group: forcing rows s G + g, read-out columns r G + g
        groups = group_starts.size - 1
        member = np.repeat(np.arange(groups), np.diff(group_starts))
        mask = (member[None, :] == np.arange(groups)[:, None]).astype(float)  # (G, K)
        push = (push[:, :, None, :] * mask).reshape(push.shape[0], -1, push.shape[2])
        read = (read[:, :, None, :] * np.repeat(mask, 2, axis=1)).reshape(
            read.shape[0], -1, read.shape[2])
    return SharedRuns(
        e1=np.concatenate([blk.e1 for blk in heads]),
        R=np.ascontiguousarray(read.transpose(0, 2, 1)),
        P=np.ascontiguousarray(push).view(float),
        scale=np.repeat(cg, 2, axis=1),
        group=np.repeat(np.arange(len(runs)), [b - a for _, a, b in runs]))


def _row_by_row(blocks: list[Block], cg: np.ndarray, group_starts: np.ndarray | None
                ) -> RowByRow:
    def rows(part: str) -> np.ndarray:  # each row's copy of a block's part
        return np.concatenate([np.broadcast_to(getattr(blk, part), (blk.stop - blk.start,)
                                               + getattr(blk, part).shape[1:])
                               for blk in blocks])
    return RowByRow(e1=rows("e1"), R=np.ascontiguousarray(rows("read")),
                    B=np.ascontiguousarray(cg[:, None, :] * rows("push")).view(float),
                    starts=None if group_starts is None else 2 * group_starts[:-1])


@dataclass
class RowByRow:
    """Each row's own propagator ``e1`` (n, K), read-out ``R`` (n, 4, 2K) and forcing ``B``
    (n, 3, 2K) of ``Y`` (``R`` and ``B`` on ``Y`` as floats): the free ``y`` after h/2 and h,
    ``y'`` and ``y`` now; the change of ``Y`` per (F0, Fa + Fb, Fc).

    With groups of columns whose coupling follows the ball (:mod:`batcert.engines.kernel.coupling`;
    ``starts``, their first float columns): the forces come per group, ``f[:, s G + g]``, and
    the read-out goes out per group, ``out[:, r G + g]``."""

    e1: np.ndarray
    R: np.ndarray
    B: np.ndarray
    starts: np.ndarray | None = None

    def advance(self, z: np.ndarray, f: np.ndarray) -> np.ndarray:
        """Advance ``z`` (``Y``, (n, K) complex) by one step in place under the forces ``f``
        (n, 3 G); return the read-out of the new ``Y``, (n, 4 G)."""
        z *= self.e1
        y = z.view(float)
        if self.starts is None:
            y += np.matmul(f[:, None, :], self.B)[:, 0, :]
            return np.matmul(self.R, y[:, :, None])[:, :, 0]
        n, width = y.shape
        groups = self.starts.size
        member = np.repeat(np.arange(groups), np.diff(np.append(self.starts, width)))
        forcing = f.reshape(n, 3, groups)[:, :, member]  # each column's group's forces
        y += (forcing * self.B).sum(axis=1)
        out = np.add.reduceat(self.R * y[:, None, :], self.starts, axis=2)  # (n, 4, G)
        return out.reshape(n, 4 * groups)

    def current(self, z: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """``Y`` of ``rows`` (indices or a mask): the state itself."""
        return z[rows]

    def take(self, keep: np.ndarray) -> RowByRow:
        return RowByRow(self.e1[keep], self.R[keep], self.B[keep], self.starts)


@dataclass
class SharedRuns:
    """:class:`RowByRow` for runs of rows that share their modes (one bat each): one
    propagator ``e1`` (runs, K), read-out ``R`` (runs, 2K, 4 G) and forcing ``P``
    (runs, 3 G, 2K) per run (``G`` groups of columns, 1 without a coupling), applied with one
    matrix product per piece of a run's rows (at most about ``PIECE_ENTRIES`` impact-mode
    entries); the forcing scaled per row by ``scale`` = ``c_y g`` (n, 2K).

    Each run's state is kept in a frame that turns with its free modes (:class:`Turns`):
    ``z`` holds ``X = Y / e1^k``, ``k`` steps after the run's state was last folded back to
    ``Y``, so that a step only forces and reads the state and never propagates it;
    :meth:`current` gives ``Y``."""

    e1: np.ndarray
    R: np.ndarray
    P: np.ndarray
    scale: np.ndarray
    group: np.ndarray  # each row's run, (n,)
    turns: Turns | None = None  # the frames' forcing and read-out (built from e1, R, P)
    k: list[int] | None = None  # each run's steps since its state was last folded back

    def __post_init__(self) -> None:
        cuts = np.flatnonzero(np.diff(self.group)) + 1
        bounds = np.concatenate([[0], cuts, [self.group.size]])
        rows = max(1, PIECE_ENTRIES // max(self.e1.shape[1], 1))
        self.pieces = [(a, min(a + rows, int(b)), int(self.group[a0]))
                       for a0, b in zip(bounds[:-1], bounds[1:], strict=True)
                       for a in range(int(a0), int(b), rows)]
        if self.turns is None:
            self.turns = Turns.of(self.e1, self.R, self.P)
        if self.k is None:
            self.k = [0] * self.e1.shape[0]

    def advance(self, z: np.ndarray, f: np.ndarray) -> np.ndarray:
        """:meth:`RowByRow.advance`, the state ``z`` kept in the runs' frames."""
        y = z.view(float)
        turns, k = self.turns, self.k
        assert turns is not None and k is not None
        if len(self.pieces) == 1:  # the common small batch: no slicing (the replay's steps)
            g = self.pieces[0][2]
            push = f @ turns.P[k[g], g]
            push *= self.scale
            y += push
            out = y @ turns.R[k[g], g]
        else:
            out = np.empty((y.shape[0], turns.R.shape[-1]))
            for a, b, g in self.pieces:
                push = f[a:b] @ turns.P[k[g], g]
                push *= self.scale[a:b]
                y[a:b] += push
                np.matmul(y[a:b], turns.R[k[g], g], out=out[a:b])
        for g, steps in enumerate(turns.steps):
            k[g] += 1
            if k[g] == steps:  # fold the run's frame back: z holds its Y again
                for a, b, run in self.pieces:
                    if run == g:
                        z[a:b] *= turns.turn[steps, g]
                k[g] = 0
        return out

    def current(self, z: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """``Y`` of ``rows`` (indices or a mask) from the state ``z``."""
        assert self.turns is not None and self.k is not None
        g = self.group[rows]
        return z[rows] * self.turns.turn[np.asarray(self.k)[g], g]

    def take(self, keep: np.ndarray) -> SharedRuns:
        return SharedRuns(self.e1, self.R, self.P, self.scale[keep], self.group[keep],
                          self.turns, self.k)


@dataclass(frozen=True)
class Turns:
    """The forcing and read-out of :class:`SharedRuns`'s turning frames ``X = Y / e1^k``:
    ``Y_(k+1) = e1 Y_k + scale (f P)`` is ``X_(k+1) = X_k + scale (f P_k)`` with
    ``P_k = P / e1^(k+1)``, and ``Y_(k+1)`` is read from ``X_(k+1)`` with ``R_k = R e1^(k+1)``
    (the scale is real, so it commutes with the turn). This leaves out the elementwise complex
    propagation of every row's state at every step, the modal update's most expensive part
    (measured, docs/performance.md). A run's state is folded back every ``steps`` steps of its
    own: at most ``FRAME_STEPS``, and few enough that its most damped mode's ``|1/e1^k|``
    stays below ``e^FRAME_GROWTH`` (so a run's rounding does not depend on what it is stacked
    with).
    """

    turn: np.ndarray  # e1^k for k = 0 .. max(steps), (max(steps) + 1, runs, K)
    P: np.ndarray  # forcing of X over the step from k to k + 1, (max(steps), runs, 3, 2K)
    R: np.ndarray  # read-out of Y_(k+1) from X_(k+1), (max(steps), runs, 2K, 4)
    steps: tuple[int, ...]  # each run's steps between folds

    @classmethod
    def of(cls, e1: np.ndarray, R: np.ndarray, P: np.ndarray) -> Turns:
        decay = np.max(-np.log(np.abs(e1)), axis=1, initial=0.0)  # per step, (runs,)
        steps = np.clip(FRAME_GROWTH // np.maximum(decay, 1e-300), 1, FRAME_STEPS).astype(int)
        longest = int(steps.max(initial=1))
        turn = np.ones((longest + 1,) + e1.shape, dtype=complex)
        np.cumprod(np.broadcast_to(e1, (longest,) + e1.shape), axis=0, out=turn[1:])
        push = np.ascontiguousarray(P).view(complex)  # (runs, 3, K)
        forcing = np.ascontiguousarray(push[None] / turn[1:, :, None, :]).view(float)
        weights = R[:, 1::2, :] + 1j * R[:, 0::2, :]  # Im(sum w Y) = R . Y as floats, (runs, K, 4)
        turned = weights[None] * turn[1:, ..., None]  # (steps, runs, K, 4)
        read = np.ascontiguousarray(im_weights(turned.swapaxes(-1, -2)).swapaxes(-1, -2))
        return cls(turn, forcing, read, tuple(int(n) for n in steps))


def im_weights(coef: np.ndarray) -> np.ndarray:
    """Weights ``wt`` with ``Im(sum coef Y) = wt . Y.view(float)``, (..., 2K)."""
    wt = np.empty(coef.shape[:-1] + (2 * coef.shape[-1],))
    wt[..., 0::2], wt[..., 1::2] = coef.imag, coef.real
    return wt
