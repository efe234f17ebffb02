"""The constants of one ETDRK4 step of every impact (Cox & Matthews, J. Comput. Phys. 176 (2002)
430, Eqs. 26-29), for :func:`batcert.engines.kernel.march.march`: the stage responses ``ka``, ``b0``,
``c0``, ``cb``, ``ca``, the rigid/ball update ``w6``, ``v6``, and each block's propagator,
read-out and forcing of the modes. How those are laid out in memory for the step (row by row,
or one matrix per run of rows that share their modes) is :func:`batcert.engines.kernel.modal_update.layout`'s
business, not this module's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert import workspace
from batcert.engines.kernel.coupling import Coupling
from batcert.engines.kernel.linear_system import LinearSystem
from batcert.engines.kernel.modal_update import Block, ModalUpdate, im_weights, layout
from batcert.physics.etd import phi_functions


@dataclass
class Coefficients:
    """Per-impact constants of one ETDRK4 step (Cox & Matthews 2002, Eqs. 26-29), row i for
    impact i, in the scaled coordinates ``Y = c_y Z`` of :func:`coefficients`.

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
    modal: ModalUpdate  # how Y advances and the contact point reads it
    # with a Coupling: ka, c0 (and cb = 2 ka) of each group, (n, G), and the coupling
    group_ka: np.ndarray | None = None
    group_c0: np.ndarray | None = None
    coupling: Coupling | None = None

    def take(self, keep: np.ndarray) -> Coefficients:
        def part(k, v):
            if v is None:
                return None
            return v.take(keep) if k == "modal" else v.rows(keep) if k == "coupling" else v[keep]
        return Coefficients(**{k: part(k, v) for k, v in vars(self).items()})


def _exponentials(lam: np.ndarray, h: float) -> tuple[np.ndarray, ...]:
    """``e^(lam h)``, ``e^(lam h / 2)``, ``phi_1..3(lam h)`` and ``h/2 phi_1(lam h / 2)`` of
    one block's eigenvalues; a single row (a block's shared row) is kept by the active
    workspace (kind ``step-exponentials``: a bat's modes recur in every batch of a run)."""
    if lam.shape[0] == 1:
        return workspace.current().call("step-exponentials", _exponentials_of, lam, float(h))
    return _exponentials_of(lam, h)


# more blocks than this (a Monte Carlo's drawn bats, each a block of its own) have their
# exponentials evaluated in one call over all of them, not one (cached) call per block: the
# phi functions' series cost the same for one row as for thousands
FEW_BLOCKS = 8


def _block_exponentials(lam: np.ndarray, h: float, spans, shared: list[bool]) -> list[tuple]:
    """:func:`_exponentials` of each block: of its one row when its rows share their modes,
    else of every row. The values do not depend on how the blocks are grouped (element by
    element)."""
    rows = [(a, a + 1) if same else (a, b) for (a, b), same in zip(spans, shared, strict=True)]
    if len(rows) <= FEW_BLOCKS:
        return [_exponentials(lam[a:b], h) for a, b in rows]
    every = _exponentials_of(np.concatenate([lam[a:b] for a, b in rows]), h)
    bounds = np.cumsum([0] + [b - a for a, b in rows])
    return [tuple(x[i:j] for x in every) for i, j in zip(bounds[:-1], bounds[1:], strict=True)]


def _exponentials_of(lam: np.ndarray, h: float) -> tuple[np.ndarray, ...]:
    return (np.exp(lam * h), np.exp(lam * h / 2), *phi_functions(lam * h),
            0.5 * h * phi_functions(lam * h / 2)[0])


def coefficients(system: LinearSystem, h: float) -> Coefficients:
    """The step constants of every impact (see :func:`batcert.engines.kernel.march.march`).

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
        group_ka, group_c0 = np.empty((n, n_groups)), np.empty((n, n_groups))
    # the exponentials depend on the frequencies and damping only: once per block of rows
    # that share them (one bat); each block's propagator, read-out and forcing, (1 or rows, ..)
    blocks = []
    spans = system.blocks or ((0, n),)
    shared = [bool(np.all(om[a:b] == om[a:a + 1])) and bool(np.all(zeta[a:b] == zeta[a]))
              for a, b in spans]
    exponentials = _block_exponentials(lam, h, spans, shared)
    for (a, b), same, (e1, e2, p1, p2, p3, q_half) in zip(spans, shared, exponentials,
                                                          strict=True):
        lam_b = lam[a:a + 1] if same else lam[a:b]
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
        blocks.append(Block(a, b, same, e1, read, push))
    inv_mu = system.inv_reduced_mass
    modal = layout(blocks, cg, om, system.zeta,
                   None if coupled is None else np.asarray(coupled.starts))
    return Coefficients(
        ka=ka, b0=-h * h / 4 * inv_mu, c0=c0, cb=2 * ka, ca=-h * h / 2 * inv_mu,
        w6=-h * h / 6 * inv_mu, v6=-h / 6 * inv_mu, c_y=c_y,
        shell_factor=0.5 / (1.0 - system.zeta**2), modal=modal,
        group_ka=None if coupled is None else group_ka,
        group_c0=None if coupled is None else group_c0, coupling=coupled)
