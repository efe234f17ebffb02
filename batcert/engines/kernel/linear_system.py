"""The linear part of a batch of impacts, and several batches stacked into one.

Each impact (row) is a merged rigid/ball coordinate and ``K`` flexible modes coupled to the
ball through their gains at the contact (:mod:`batcert.engines.kernel.march` integrates them); the
gains may follow the ball's compression, group by group (:mod:`batcert.engines.kernel.coupling`).
Units: SI.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.engines.kernel import coupling as coupling_module
from batcert.engines.kernel.coupling import Coupling


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
    # how the gains follow the ball's compression (groups of columns; None: fixed gains)
    coupling: Coupling | None = None

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
                            shell_columns=self.shell_columns, blocks=blocks,
                            coupling=None if self.coupling is None
                            else self.coupling.rows(slice(a, b)))

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
    if any(sy.coupling is not None for sy in systems):
        return _stack_coupled(systems)

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


def _stack_coupled(systems: list[LinearSystem]) -> tuple[LinearSystem, list[np.ndarray]]:
    """:func:`stack_systems` of systems with a :class:`~batcert.engines.kernel.coupling.Coupling`:
    the columns aligned by its groups (:func:`batcert.engines.kernel.coupling.stack`)."""
    coupling, columns = coupling_module.stack(
        [sy.coupling for sy in systems], [sy.omega.shape[1] for sy in systems],
        [sy.omega.shape[0] for sy in systems])
    assert coupling is not None
    width = coupling.starts[-1]
    omega, gain, blocks, start = [], [], [], 0
    for sy, cols in zip(systems, columns, strict=True):
        n = sy.omega.shape[0]
        om = np.ones((n, width))  # padding: 1 rad/s, zero gain, never driven
        gn = np.zeros((n, width))
        om[:, cols], gn[:, cols] = sy.omega, sy.gain
        omega.append(om)
        gain.append(gn)
        blocks += [(start + a, start + b) for a, b in sy.blocks or ((0, n),)]
        start += n
    shell = np.zeros(width, bool)
    for i, label in enumerate(coupling.labels):
        if isinstance(label, tuple) and label[0] == "shell":
            shell[coupling.starts[i]:coupling.starts[i + 1]] = True
    stacked = LinearSystem(
        omega=np.concatenate(omega), zeta=np.concatenate([sy.zeta for sy in systems]),
        gain=np.concatenate(gain), rigid_mass=np.concatenate([sy.rigid_mass for sy in systems]),
        ball_mass=np.concatenate([sy.ball_mass for sy in systems]),
        shell_columns=shell if shell.any() else None, blocks=tuple(blocks), coupling=coupling)
    return stacked, columns


