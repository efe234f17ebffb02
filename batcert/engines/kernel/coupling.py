"""How the modes' coupling to the ball follows the ball's compression (the footprint's size).

The ball's footprint grows and shrinks with its compression ``u``
(:mod:`batcert.physics.balls.footprint`), and with it how each mode of the bat feels the force
and moves the contact point: its gain ``g_j(u)``. The modes fall into groups whose gains scale
together, ``g_j(u) = g_j rho_G(u)`` for every mode ``j`` of group ``G``: a hollow barrel's
shell modes of circumferential order ``n`` by the factor ``c_n(beta(u))`` of the footprint's
arc around the barrel, the residual pseudo-mode by the square root of the quasi-static
compliance under the footprint; the beam's bending modes, which feel only the force's
resultant along the bat, form one group with ``rho = 1``. A :class:`Coupling` holds each
group's columns (contiguous) and, per impact, ``rho`` tabulated on a grid of compressions;
the time stepping (:mod:`batcert.engines.kernel.march`) reads each group's share of the contact
point's motion and forces each group by ``rho F``, at each stage of a step with ``rho`` of the
compression predicted for that stage's time. Units: SI.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Coupling:
    """Groups of columns whose gains scale together, and each group's factor ``rho`` over the
    compression, per impact (module notes).

    ``labels`` name the groups in column order (e.g. ``"beam"``, ``("shell", 2)``,
    ``"residual"``); ``starts`` are their first columns, plus the column count at the end.
    ``table[i, G, k]`` is ``rho_G`` of impact ``i`` at the compression ``k * spacing[i]`` [m]
    (held beyond the last point)."""

    labels: tuple[Hashable, ...]
    starts: tuple[int, ...]
    table: np.ndarray  # (n, G, points)
    spacing: np.ndarray  # (n,) [m]
    # the table laid out for :meth:`at` and :meth:`slope`: each impact's points one after
    # another, each point's G factors contiguous, and the differences to the next point,
    # (n * points, G) each; derived from ``table`` (a gather of whole rows, where
    # ``table[rows, :, k]`` gathers single numbers G apart: 1.3 ms a call for 2,000 impacts,
    # a fourth of a hollow step)
    _level: np.ndarray = field(init=False, repr=False, compare=False)
    _rise: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        n, groups, points = self.table.shape
        by_point = np.ascontiguousarray(self.table.transpose(0, 2, 1))  # (n, points, G)
        rise = np.zeros_like(by_point)
        rise[:, :-1] = by_point[:, 1:] - by_point[:, :-1]
        self._level = by_point.reshape(n * points, groups)
        self._rise = rise.reshape(n * points, groups)

    @property
    def size(self) -> int:
        return len(self.labels)

    def rows(self, keep) -> Coupling:
        """The impacts ``keep`` (indices, a mask or a slice)."""
        return Coupling(self.labels, self.starts, self.table[keep], self.spacing[keep])

    def _locate(self, u):
        """Each impact's row of the laid-out table below ``u`` [m] and the fraction of the
        way to the next point."""
        points = self.table.shape[2]
        x = np.clip(np.asarray(u, dtype=float) / self.spacing, 0.0, points - 1.0)
        k = np.minimum(x.astype(int), points - 2)
        return k + points * np.arange(k.size), x - k

    def at(self, u) -> np.ndarray:
        """``rho`` of every group at each impact's compression ``u`` [m], (n, G): linear
        between the table's points."""
        row, t = self._locate(u)
        out = self._level.take(row, axis=0)
        out += t[:, None] * self._rise.take(row, axis=0)
        return out

    def slope(self, u) -> np.ndarray:
        """``d rho / d u`` of every group at ``u`` [1/m], (n, G)."""
        row, _ = self._locate(u)
        return self._rise.take(row, axis=0) / self.spacing[:, None]


def stack(couplings: list[Coupling | None], columns: list[int], rows: list[int]
          ) -> tuple[Coupling | None, list[np.ndarray]]:
    """One coupling for the rows of several systems (one bat each) and, for each, the columns
    its modes take in the stacked system: the groups aligned by label (the union of labels, in
    the order ``"beam"``, shell orders ascending, ``"residual"``; a system without coupling is
    one ``"beam"`` group), each as wide as its widest, padded with columns that nothing drives.
    ``columns`` and ``rows``: each system's column and row count."""
    groups: list[dict[Hashable, tuple[int, int]]] = []
    for c, k in zip(couplings, columns, strict=True):
        if c is None:
            groups.append({"beam": (0, k)})
        else:
            groups.append({lab: (c.starts[i], c.starts[i + 1]) for i, lab in enumerate(c.labels)})
    order = sorted({lab for g in groups for lab in g}, key=_rank)
    width = {lab: max(g[lab][1] - g[lab][0] if lab in g else 0 for g in groups) for lab in order}
    starts = np.concatenate([[0], np.cumsum([width[lab] for lab in order])]).astype(int)
    place = {lab: int(starts[i]) for i, lab in enumerate(order)}
    cols = []
    for g in groups:
        cols.append(np.concatenate([place[lab] + np.arange(b - a) for lab, (a, b) in
                                    sorted(g.items(), key=lambda item: item[1][0])]))
    if all(c is None for c in couplings):
        return None, cols
    points = max(c.table.shape[2] for c in couplings if c is not None)
    table, spacing = [], []
    for c, n in zip(couplings, rows, strict=True):
        t = np.ones((n, len(order), points))
        s = np.ones(n)
        if c is not None:
            for i, lab in enumerate(c.labels):
                t[:, order.index(lab), :c.table.shape[2]] = c.table[:, i, :]
                t[:, order.index(lab), c.table.shape[2]:] = c.table[:, i, -1:]
            s = c.spacing
        table.append(t)
        spacing.append(s)
    return (Coupling(tuple(order), tuple(int(x) for x in starts), np.concatenate(table),
                     np.concatenate(spacing)), cols)


def _rank(label: Hashable) -> tuple:
    if label == "beam":
        return (0, 0)
    if label == "residual":
        return (2, 0)
    return (1, label[1] if isinstance(label, tuple) else 0)


def extrapolate(u_prev, du_prev, u, du, h: float) -> tuple[np.ndarray, np.ndarray]:
    """The compression half a step and a step ahead [m]: the cubic Hermite interpolant through
    the last two steps' compressions and rates (``u_prev``, ``du_prev`` a step back; ``u``,
    ``du`` now), continued; at least zero."""
    half = u_prev + h * (0.375 * du_prev + 1.125 * du)
    whole = 5.0 * u_prev + 2.0 * h * du_prev - 4.0 * u + 4.0 * h * du
    return np.maximum(half, 0.0), np.maximum(whole, 0.0)
