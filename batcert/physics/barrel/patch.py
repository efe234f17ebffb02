"""A hollow bat's wall under the ball's contact patch (:mod:`batcert.physics.barrel`): the kept
modes averaged over each patch and each order's static flexibility under it, from which the
engine forms the response to a load spread around the barrel over the footprint's arc.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from batcert import workspace
from batcert.physics.balls.footprint import circumferential_factors
from batcert.physics.barrel.wall import (
    PATCH_SPAN,
    BarrelModes,
)
from batcert.physics.batmodel import BatModel
from batcert.physics.shell import (
    ShellOfRevolution,
    normal_weights,
)


@dataclass(frozen=True)
class PatchLoads:
    """Each impact's patch as W-space load (unit resultant), banded: row ``i`` loads the
    unknowns ``start[i] .. start[i] + width`` with ``f[i]`` (a patch covers a few nodes), in
    the layout of ``size`` unknowns (``u_z``, ``u_r``, ``W'`` per node)."""

    start: np.ndarray  # (p,) int
    f: np.ndarray  # (p, width)
    size: int

    def dense(self) -> np.ndarray:
        """The loads as full rows, (p, size)."""
        g = np.zeros((self.f.shape[0], self.size))
        np.put_along_axis(g, self.start[:, None] + np.arange(self.f.shape[1]), self.f, axis=1)
        return g

    @cached_property
    def by_start(self) -> list[tuple[int, np.ndarray]]:
        """``(s, rows)`` for each window start ``s``: the rows (indices) that start there
        (found once; the patch flexibility and the mode shapes both read by start)."""
        order = np.argsort(self.start, kind="stable")
        starts, first = np.unique(self.start[order], return_index=True)
        bounds = np.append(first, order.size)
        return [(int(s), order[a:b]) for s, a, b in zip(starts, bounds[:-1], bounds[1:],
                                                         strict=True)]


def _w_load(shell: ShellOfRevolution, points: np.ndarray, weights: np.ndarray) -> PatchLoads:
    """Each impact's patch as W-space load (the nodes' ``u_z``, ``u_r``, ``W'``, three per node):
    the weights with which :func:`~batcert.physics.shell.normal_weights` reads ``W`` at each
    point, gathered into one window per patch (the widest patch's width, the window moved
    inside the wall at its ends); a patch off the wall loads nothing."""
    p = points.shape[0]
    e, h = normal_weights(shell, points)
    w_cols = (3 * e[..., None] + np.arange(6)).reshape(p, -1)  # node e's three, then e + 1's
    values = (h * weights[..., None]).reshape(p, -1)
    size = 3 * shell.z.size
    live = values != 0
    lo = np.where(live, w_cols, size).min(axis=1)
    hi = np.where(live, w_cols, -1).max(axis=1)
    on = hi >= 0
    width = int((hi - lo)[on].max(initial=0)) + 1
    start = np.where(on, np.clip(lo, 0, size - width), 0)
    # a point's zero weights land anywhere in its own row's window (adding zero changes nothing)
    local = np.clip(w_cols - start[:, None], 0, width - 1)
    f = np.bincount((np.arange(p)[:, None] * width + local).ravel(), values.ravel(),
                    p * width).reshape(p, width)
    return PatchLoads(start, f, size)


def patch_half_angle(bat: BatModel, z: np.ndarray, half_length: np.ndarray) -> np.ndarray:
    """Half-angle [rad] of the ball's contact arc, ``a / R_outer`` at each impact, at most pi/2."""
    return np.minimum(half_length / (0.5 * bat.outer_diameter[bat.slice_at(z)]), 0.5 * np.pi)


@dataclass(frozen=True)
class BarrelResponse:
    """The barrel as the ball meets it at each of ``p`` impacts."""

    omega: np.ndarray  # kept modes [rad/s], (m,)
    gain: np.ndarray  # normal displacement per modal coordinate at the patch [1/sqrt(kg)], (p, m)
    residual: np.ndarray  # quasi-static compliance of everything left out [m/N], (p,)
    static: np.ndarray  # total quasi-static compliance of the patch load [m/N], (p,)
    orders: np.ndarray  # order n of each kept mode, (m,)


@dataclass(frozen=True)
class BarrelPatch:
    """The barrel under each of ``p`` patches of given axial extent, for any extent around the
    barrel: the kept modes' axial patch averages and each order's patch flexibility, from which
    :meth:`at` forms the response to a load spread over a half-angle ``beta``."""

    omega: np.ndarray  # kept modes [rad/s], (m,)
    axial: np.ndarray  # sum_k weights W_j(points): each mode over each patch [1/sqrt(kg)], (p, m)
    flexibility: np.ndarray  # f^T K_n^-1 f of each order over each patch [m/N], (orders, p)
    orders: tuple[int, ...]  # the orders of ``flexibility``: 0, 2 .. STATIC_ORDERS
    mode_orders: np.ndarray  # order n of each kept mode, (m,)

    def factors(self, half_angle) -> np.ndarray:
        """:func:`~batcert.physics.balls.footprint.circumferential_factor` of every order at
        each patch's ``half_angle`` [rad], (orders, p)."""
        beta = np.broadcast_to(np.asarray(half_angle, dtype=float), (self.axial.shape[0],))
        angles, which = np.unique(beta, return_inverse=True)  # often one patch size
        return _factors(self.orders, angles)[:, which.ravel()]

    def over(self, half_angle: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`at` for a grid of half-angles per patch, ``half_angle`` (p, g) [rad]: every
        order's factor (orders, p, g), the residual compliance (p, g) and the static
        compliance (p, g) [m/N]."""
        c = circumferential_factors(self.orders, half_angle)
        c2 = c**2
        static = np.einsum("npg,np->pg", c2, self.flexibility)
        # the kept modes' sum (gain / omega)^2, order by order: a mode's factor is its order's,
        # so each order's modes are summed first (a few orders, against some 40 modes)
        order_row = {n: i for i, n in enumerate(self.orders)}
        kept = sorted(set(int(n) for n in self.mode_orders))
        energy = (self.axial / self.omega) ** 2  # (p, m)
        by_order = np.stack([energy[:, self.mode_orders == n].sum(axis=1) for n in kept],
                            axis=1)  # (p, kept orders)
        modal = np.einsum("npg,pn->pg", c2[[order_row[n] for n in kept]], by_order)
        return c, np.clip(static - modal, 0.0, None), static

    def at(self, half_angle) -> BarrelResponse:
        """The response to loads spread around the barrel over ``+-half_angle`` [rad], (p,):
        ``gain[i, j] = c_n(beta_i) axial[i, j]``; ``static`` is ``sum_n c_n^2 flexibility_n``
        over the orders 0, 2..STATIC_ORDERS; ``residual`` is ``static`` minus the kept modes'
        ``sum (gain / omega)^2``."""
        c = self.factors(half_angle)
        static = (c**2 * self.flexibility).sum(axis=0)
        order_row = {n: i for i, n in enumerate(self.orders)}
        gain = c[[order_row[n] for n in self.mode_orders]].T * self.axial
        modal = (gain**2 / self.omega**2).sum(axis=1)
        return BarrelResponse(self.omega, gain, np.clip(static - modal, 0.0, None), static,
                              self.mode_orders)


def barrel_patch(barrel: BarrelModes, points: np.ndarray, weights: np.ndarray) -> BarrelPatch:
    """The barrel under patch loads of the given axial extent (:class:`BarrelPatch`).

    Parameters
    ----------
    barrel : BarrelModes
        From :func:`cached_barrel_modes`.
    points : numpy.ndarray
        Axial sample points of each impact's patch [m from knob], shape (p, K).
    weights : numpy.ndarray
        Their weights, each row summing to 1, shape (p, K).
    """
    loads = _w_load(barrel.shell, points, weights)
    flexibility = barrel.green_scale * _patch_flexibility(barrel.green, loads)
    shapes = np.empty((loads.f.shape[0], barrel.shapes.shape[1]))  # W_j over each patch
    width = loads.f.shape[1]
    for s0, rows in loads.by_start:
        shapes[rows] = loads.f[rows] @ barrel.shapes[s0:s0 + width]
    return BarrelPatch(barrel.omega, shapes, flexibility, barrel.orders, barrel.mode_orders)


def barrel_response(barrel: BarrelModes, points: np.ndarray, weights: np.ndarray,
                    half_angle: np.ndarray) -> BarrelResponse:
    """Modal gains and residual compliance for patch loads: :func:`barrel_patch` at
    ``half_angle`` [rad], (p,), the circumferential half-angle of each patch."""
    return barrel_patch(barrel, points, weights).at(half_angle)


def _factors(orders: tuple[int, ...], angles: np.ndarray) -> np.ndarray:
    """:func:`~batcert.physics.balls.footprint.circumferential_factor` of every order at every
    angle, (orders, angles), read-only; kept by the active workspace (kind ``patch-factors``):
    a barrel's variants and the runner's repeated points ask for the same patch sizes."""
    angles = np.ascontiguousarray(angles, dtype=float).ravel()
    return workspace.current().call("patch-factors", _factors_of, tuple(orders), angles,
                                    rows=angles.size)


def _factors_of(orders: tuple[int, ...], angles: np.ndarray) -> np.ndarray:
    c = circumferential_factors(orders, angles)
    c.setflags(write=False)
    return c


def _patch_flexibility(green: np.ndarray, loads: PatchLoads) -> np.ndarray:
    """``q[n, i] = g_i^T G_n g_i`` for every order and patch, (orders, p).

    A patch loads only the few nodes it covers, a contiguous band of the W space, so each patch
    reads a band of every order's flexibility; patches with the same band are done together.
    Kept by the active workspace (kind ``patch-flexibility``, batches of at most
    ``workspace.BATCH_ROWS``): a scaled wall shares its nominal flexibility, and the runner
    asks again for the same points.
    """
    return workspace.current().call("patch-flexibility", _patch_flexibility_of, green, loads,
                                    rows=loads.f.shape[0])


def _patch_flexibility_of(green: np.ndarray, loads: PatchLoads) -> np.ndarray:
    """:func:`_patch_flexibility` computed: each patch's load ``f`` read over its window of
    ``L`` unknowns from the start ``s``, ``q_n = f^T G_n(s:s+L, s:s+L) f`` (``G`` symmetric,
    stored as its upper band); per start, one matrix product of the loads with every order's
    window, then each product dotted with its own load."""
    width = loads.f.shape[1]
    if width > green.shape[2]:
        raise ValueError(f"a contact patch is longer than {PATCH_SPAN} m")
    k = np.arange(width)
    row, lag = np.minimum.outer(k, k), np.abs(np.subtract.outer(k, k))  # G(s+k, s+j) in band
    q = np.empty((green.shape[0], loads.f.shape[0]))
    for s, rows in loads.by_start:
        window = green[:, s + row, lag].transpose(1, 0, 2).reshape(width, -1)  # (L, orders L)
        f = loads.f[rows]
        q[:, rows] = np.einsum("pnk,pk->np", (f @ window).reshape(rows.size, -1, width), f)
    return q
