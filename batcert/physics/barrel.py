r"""A hollow bat's barrel as a thin shell of revolution: its modes, its compliance under the
ball, its hoop frequency and its compression stiffness.

The wall of a hollow bat (every contiguous hollow slice around the largest diameter: handle,
taper, barrel) is a shell of revolution (:mod:`batcert.physics.shell`) with the bat's mid-surface
radius, wall and reconciled density along it, and its ends held round by the knob and the end
cap (``closed``) or left open (``BatModel.barrel_end``). Its deformation is expanded in
circumferential orders: ``n = 1`` moves each cross-section as a whole and is the beam's bending
(:mod:`batcert.physics.beam`), so the barrel contributes the orders ``n = 0`` (breathing) and
``n >= 2`` (ovalling and higher). These are orthogonal to the beam's motion, so the two add
without counting any mass twice.

The ball presses on a patch (:mod:`batcert.physics.balls.footprint`): along the bat the
parabolic weight over ``2 a`` of the beam's contact patch, around it the same weight over the
arc ``2 b`` of the outer surface (half-angle ``beta = b / R_outer``). Order ``n`` feels the
load through the factor ``c_n = 3 j_1(n beta) / (n beta)``
(:func:`~batcert.physics.balls.footprint.circumferential_factor`).

What the engine uses per impact (:func:`barrel_response`): the modes of orders
``0, 2 .. dynamic_orders`` below ``max_frequency`` as extra modes of the bat (gain
``c_n W_j`` averaged over the patch), and the quasi-static compliance of everything left out
(higher modes of those orders, and the orders up to ``static_orders``), a spring in series with
the ball like the beam's residual compliance. Nothing here is fitted: the shell comes from the
profile, the wall and the material; a measured hoop frequency or barrel compression scales its
stiffness (and mass) through ``BatModel.barrel_stiffness_scale`` / ``barrel_mass_scale``
(:mod:`batcert.model.calibrate`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from batcert import workspace
from batcert.physics.balls.footprint import circumferential_factors
from batcert.physics.banded import inverse_band, lower_band
from batcert.physics.batmodel import BatModel
from batcert.physics.shell import (
    Assembler,
    HarmonicSystem,
    ShellOfRevolution,
    assemble,
    harmonic_modes,
    normal_reader,
    normal_weights,
    static_solve,
)

DYNAMIC_ORDERS = 6  # highest order whose modes join the engine (0, 2..6)
# highest order summed into the quasi-static residual: the orders above it hold under 3e-6 of
# the barrel's compliance under a ball's patch, even for a 1 m/s impact's 9 mm patch (measured
# against 40 orders on aluminium-34; 1e-7 at game speeds)
STATIC_ORDERS = 24
MAX_FREQUENCY = 10_000.0  # modes above this [Hz] respond quasi-statically (the engine default)
# the longest contact patch along the bat [m]: twice the largest ball radius that a ball spec
# accepts (100 mm, batcert.specs.ball); the stored flexibility covers every pair of unknowns
# that one patch can load together, and no others
PATCH_SPAN = 0.2


def barrel_shell(bat: BatModel) -> ShellOfRevolution | None:
    """The hollow wall of ``bat`` as a shell of revolution, or None for a solid bat.

    The contiguous run of hollow slices around the largest hollow diameter; nodes at the slice
    edges with the mid-surface radius interpolated from the slice centres; per element the
    slice's wall, its reconciled density (``linear_density / area``) times
    ``barrel_mass_scale``, and ``E`` times ``barrel_stiffness_scale``. The knob end is held
    round (a knob plug); the tip end as ``bat.barrel_end`` says.
    """
    inner = np.asarray(bat.inner_diameter, dtype=float)
    hollow = inner > 0
    if bat.construction != "hollow" or not np.any(hollow):
        return None
    outer = np.asarray(bat.outer_diameter, dtype=float)
    i = int(np.argmax(np.where(hollow, outer, -np.inf)))
    lo = hi = i
    while lo > 0 and hollow[lo - 1]:
        lo -= 1
    while hi < outer.size - 1 and hollow[hi + 1]:
        hi += 1
    sl = slice(lo, hi + 1)
    mid_radius = 0.25 * (outer[sl] + inner[sl])  # (outer - wall) / 2
    z_mid = bat.z_mid[sl]
    z = bat.z_edges[lo:hi + 2]
    r = np.interp(z, z_mid, mid_radius)
    area = 0.25 * np.pi * (outer[sl] ** 2 - inner[sl] ** 2)
    density = bat.linear_density[sl] / area * bat.barrel_mass_scale
    young = np.full(z_mid.size, bat.material.youngs_modulus * bat.barrel_stiffness_scale)
    return ShellOfRevolution(z, r, 0.5 * (outer[sl] - inner[sl]), density, young,
                             bat.material.poisson_ratio, ("closed", bat.barrel_end))


@dataclass(frozen=True)
class BarrelModes:
    """Everything the engine needs of a barrel, computed once per bat (cached).

    Loads and read-outs of the normal displacement only touch the ``u_z``, ``u_r`` and ``W'``
    unknowns of the nodes, so each order is reduced to them ("W space", ``3 N`` unknowns for
    ``N`` nodes,
    the same for every order): ``green[o]`` is the static flexibility between them (order 0
    with inertia relief) within the band that one contact patch reads (:data:`PATCH_SPAN`),
    ``green[o, i, d]`` between unknowns ``i`` and ``i + d``; ``shapes`` holds the kept modes'
    ``u_z``, ``u_r``, ``W'`` at the nodes.
    """

    shell: ShellOfRevolution
    orders: tuple[int, ...]  # 0, 2 .. static_orders
    green: np.ndarray  # (orders, 3N, band + 1) upper band, times green_scale
    omega: np.ndarray  # kept modes, order by order [rad/s], (m,)
    mode_orders: np.ndarray  # the order of each kept mode, (m,)
    shapes: np.ndarray  # W space shapes of the kept modes, mass-normalised, (3N, m)
    max_frequency: float  # modes up to this frequency are kept [Hz]
    green_scale: float = 1.0  # the flexibility is green_scale * green (a scaled wall)

    def scaled(self, shell: ShellOfRevolution, stiffness: float, mass: float,
               max_frequency: float) -> BarrelModes:
        """The same wall with its stiffness and mass scaled (``E`` x ``stiffness``, ``rho`` x
        ``mass``): ``K`` and ``M`` scale, the shapes do not, so ``omega`` scales with
        ``sqrt(stiffness / mass)``, mass-normalised shapes with ``1 / sqrt(mass)`` and the
        flexibility with ``1 / stiffness``; modes above ``max_frequency`` are dropped (they go
        to the residual). ``shell`` is the scaled wall."""
        omega = self.omega * np.sqrt(stiffness / mass)
        keep = omega <= 2 * np.pi * max_frequency
        return BarrelModes(shell, self.orders, self.green, omega[keep], self.mode_orders[keep],
                           self.shapes[:, keep] / np.sqrt(mass), max_frequency,
                           self.green_scale / stiffness)


def _orders(highest: int) -> list[int]:
    return [0] + list(range(2, highest + 1))


def _w_space(system: HarmonicSystem, n_nodes: int) -> np.ndarray:
    """Full-vector dof of ``u_z``, ``u_r``, ``W'`` at every node, in W-space order, (3N,)."""
    return _w_dofs(system.node_dofs, system.w_offset, n_nodes)


def _w_dofs(node_dofs: int, w_offset: int, n_nodes: int) -> np.ndarray:
    """:func:`_w_space` for a layout of ``node_dofs`` unknowns per node with ``u_r`` at
    ``w_offset`` (``W'`` after it)."""
    base = node_dofs * np.arange(n_nodes)[:, None]
    return (base + np.array([0, w_offset, w_offset + 1])[None, :]).ravel()


def _span_nodes(z: np.ndarray) -> int:
    """The most node steps one contact patch of :data:`PATCH_SPAN` can reach: a patch starting
    in element ``a`` ends before the first node at or past ``z[a + 1] + PATCH_SPAN``, and
    loads the nodes ``a`` up to that one."""
    last = np.minimum(np.searchsorted(z, z[1:] + PATCH_SPAN), z.size - 1)
    return int((last - np.arange(z.size - 1)).max())


def _w_band(inverse: np.ndarray, bandwidth: int, free: np.ndarray, w_dofs: np.ndarray,
            width: int, correction=None) -> np.ndarray:
    """The W-space band of the flexibility of one or several orders from the band of their
    inverse on the free dofs (:func:`~batcert.physics.banded.inverse_band`, half-bandwidth
    ``bandwidth`` below): ``out[o, i, d] = K^-1[f_i, f_(i+d)]`` for ``d = 0..width``, zero where
    an unknown is held (``u_r`` of a closed end) or past the end. ``correction(fi, fj)`` (free
    positions, same shape) is added where given (order 0's inertia relief)."""
    position = np.full(w_dofs.max() + 1, -1)
    position[free] = np.arange(free.size)
    rows = position[w_dofs]  # free position of each W-space unknown, -1 if held
    size = w_dofs.size
    i = np.arange(size)[:, None]
    j = i + np.arange(width + 1)[None, :]
    fi = np.broadcast_to(rows[:, None], j.shape)
    fj = rows[np.minimum(j, size - 1)]
    ok = (j < size) & (fi >= 0) & (fj >= 0)
    offset = np.where(ok, fj - fi, 0)  # W space and free dofs run in the same order
    if np.any(offset > inverse.shape[-1] - bandwidth - 1):
        raise ValueError("the band of the inverse does not cover the patch's unknowns")
    fi, fj = np.where(ok, fi, 0), np.where(ok, fj, 0)
    out = inverse[:, fi, bandwidth + offset]
    if correction is not None:
        out = out + correction(fi, fj)
    return np.where(ok, out, 0.0)


def _green_bands(assembler: Assembler, orders: list[int], n_nodes: int) -> np.ndarray:
    """Static flexibility between the W-space unknowns of each order (order 0 with inertia
    relief), the band that one contact patch reads: ``green[o, i, d] = G_o[i, i + d]`` for
    ``d = 0..width``, shape (orders, 3N, width + 1); see :mod:`batcert.physics.banded`."""
    import scipy.linalg  # ~0.15 s to import: only where a wall is computed

    span = _span_nodes(assembler.shell.z)

    def reach(node_dofs: int) -> int:  # a patch loads nodes a .. a + span
        return node_dofs * (span + 1) - 1

    green = np.zeros((len(orders), 3 * n_nodes, reach(3) + 1))
    higher = [i for i, n in enumerate(orders) if n]
    if higher:  # five unknowns per node, u_r at slot 3 (shell._layout)
        bands, free = assembler.stiffness_bands([orders[i] for i in higher])
        factor = np.stack([scipy.linalg.cholesky_banded(ab, lower=True, check_finite=False)
                           for ab in bands])
        green[higher] = _w_band(inverse_band(factor, reach(5)), bands.shape[1] - 1, free,
                                _w_dofs(5, 3, n_nodes), reach(3))
    if 0 in orders:  # inertia relief against the axial translation (see shell.static_solve)
        system = assembler.system(0, support=True)
        assert system.rigid is not None
        bandwidth = 2 * system.node_dofs - 1
        ab = lower_band(system.stiffness, bandwidth)
        factor = scipy.linalg.cholesky_banded(ab, lower=True, check_finite=False)
        r = system.rigid
        mr = system.mass @ r
        y = scipy.linalg.cho_solve_banded((factor, True), mr, check_finite=False)  # K^-1 M r
        c = float(mr @ y)
        green[orders.index(0)] = _w_band(
            inverse_band(factor[None], reach(system.node_dofs)), bandwidth, system.free,
            _w_space(system, n_nodes), reach(3),
            lambda fi, fj: c * r[fi] * r[fj] - r[fi] * y[fj] - y[fi] * r[fj])[0]
    return green


def compute_barrel_modes(bat: BatModel, max_frequency: float = MAX_FREQUENCY,
                         dynamic_orders: int = DYNAMIC_ORDERS,
                         static_orders: int = STATIC_ORDERS) -> BarrelModes | None:
    """The barrel's modes up to ``max_frequency`` [Hz] in orders ``0, 2..dynamic_orders`` and
    the static flexibility of orders ``0, 2..static_orders``; None for a solid bat."""
    shell = barrel_shell(bat)
    if shell is None:
        return None
    return shell_modes(shell, max_frequency, dynamic_orders, static_orders)


def shell_modes(shell: ShellOfRevolution, max_frequency: float, dynamic_orders: int,
                static_orders: int) -> BarrelModes:
    """:func:`compute_barrel_modes` of a wall given as its shell."""
    assembler = Assembler(shell)
    n_nodes = shell.z.size
    omega, orders, shapes = [], [], []
    for n in _orders(dynamic_orders):
        system = assembler.system(n)
        modes = harmonic_modes(shell, n, max_frequency, system)
        omega.append(modes.omega)
        orders.append(np.full(modes.omega.size, n))
        shapes.append(modes.vectors[_w_space(system, n_nodes)])
    green = _green_bands(assembler, _orders(static_orders), n_nodes)
    return BarrelModes(shell, tuple(_orders(static_orders)), green,
                       np.concatenate(omega), np.concatenate(orders),
                       np.concatenate(shapes, axis=1), float(max_frequency))


# The nominal wall's modes are computed at least to this [Hz]: 1.25 x the 12 kHz of the bat's
# mode summary (model.diagnostics), which also covers the engine's 10 kHz for barrels down to
# x0.44 of their nominal stiffness (the plausible range's x0.8 among them) without recomputing.
NOMINAL_CUT = 15000.0


def wall_of(bat: BatModel) -> BatModel:
    """``bat`` with what its barrel shell (:func:`barrel_shell`) does not read set to neutral
    values: its name, its beam's stiffness and rotary inertia, its point masses and the
    material's name, shear modulus and loss factor. Bats that differ only there share their
    wall; any other field, a new one included, is part of the key of
    :func:`cached_barrel_modes`."""
    none = np.zeros(0)
    m = bat.material
    return replace(bat, name="", rotary_inertia=none, bending_stiffness=none,
                   shear_stiffness=none, point_masses=(), extras={},
                   material=replace(m, name="", shear_modulus=0.0, loss_factor=0.0))


def cached_barrel_modes(bat: BatModel, max_frequency: float = MAX_FREQUENCY,
                        dynamic_orders: int = DYNAMIC_ORDERS,
                        static_orders: int = STATIC_ORDERS) -> BarrelModes | None:
    """:func:`compute_barrel_modes` of :func:`wall_of` ``(bat)``, kept by the active workspace
    (:mod:`batcert.workspace`; kind ``barrel-scaled``, and the nominal wall it is scaled from,
    kind ``barrel``, also in the disk store where one is attached, which returns the computed
    arrays exactly; about 4 MB for a 34 in bat: the static flexibility band of 24 orders).

    The wall is computed once at its nominal stiffness and relative density; a calibrated or
    varied barrel (``barrel_stiffness_scale``, ``barrel_mass_scale``) or a uniformly scaled
    density is that computation scaled (:meth:`BarrelModes.scaled`), which is exact. The
    nominal modes are computed up to the frequency that the scaled ones need.
    """
    if bat.construction != "hollow":
        return None
    return workspace.current().call("barrel-scaled", _scaled_wall, wall_of(bat),
                                    float(max_frequency), int(dynamic_orders), int(static_orders))


def _scaled_wall(bat: BatModel, max_frequency: float, dynamic_orders: int,
                 static_orders: int) -> BarrelModes | None:
    # a bat whose density is uniformly scaled (reconciled to another measured mass) has the
    # same wall with another mass: the nominal wall has the density relative to its largest
    # value (to 12 digits) times that value rounded to a 1/16 step of its base-2 logarithm (so
    # the computed wall is within 2.2 % of the bat's), and the rest of the scale joins
    # barrel_mass_scale
    density = np.asarray(bat.linear_density, dtype=float)
    top = float(density.max())
    rounded = 2.0 ** (round(math.log2(top) * 16) / 16)
    relative = np.round(density / top, 12) * rounded
    s_k, s_m = bat.barrel_stiffness_scale, bat.barrel_mass_scale * top / rounded
    needed = float(max_frequency) / np.sqrt(s_k / s_m)  # nominal modes up to this [Hz]
    # the nominal modes are computed to a cut that depends only on what this request needs
    # (NOMINAL_CUT, doubled as often as needed), and the cut is part of the key: the numbers
    # of a run never depend on what the process computed before
    level = max(0, math.ceil(math.log2(needed / NOMINAL_CUT) - 1e-12))
    cut = NOMINAL_CUT * 2.0 ** level
    nominal = barrel_shell(replace(bat, linear_density=relative, barrel_stiffness_scale=1.0,
                                   barrel_mass_scale=1.0))
    if nominal is None:
        return None
    base = workspace.current().call("barrel", _nominal_wall, nominal, cut, int(dynamic_orders),
                                    int(static_orders), save=_to_arrays,
                                    load=lambda a: _from_arrays(a, cut))
    shell = barrel_shell(bat)
    assert shell is not None
    return base.scaled(shell, s_k, s_m, float(max_frequency))


def _nominal_wall(shell: ShellOfRevolution, cut: float, dynamic_orders: int,
                  static_orders: int) -> BarrelModes:
    return _read_only(shell_modes(shell, cut, dynamic_orders, static_orders))


def _read_only(modes: BarrelModes) -> BarrelModes:
    # shared between callers; a read-only array's content hash is computed once
    for a in (modes.green, modes.omega, modes.mode_orders, modes.shapes):
        a.flags.writeable = False
    return modes


def _to_arrays(modes: BarrelModes) -> dict[str, np.ndarray]:
    s = modes.shell
    return {"z": s.z, "r": s.r, "thickness": s.thickness, "density": s.density,
            "youngs_modulus": s.youngs_modulus, "poisson_ratio": np.array(s.poisson_ratio),
            "ends": np.array(s.ends), "orders": np.array(modes.orders), "green": modes.green,
            "omega": modes.omega, "mode_orders": modes.mode_orders, "shapes": modes.shapes,
            "max_frequency": np.array(modes.max_frequency),
            "green_scale": np.array(modes.green_scale)}


def _from_arrays(a: dict | None, cut: float) -> BarrelModes | None:
    """A stored wall, or None if ``a`` is missing or does not hold one computed to ``cut``."""
    if a is None:
        return None
    try:
        ends = tuple(str(e) for e in a["ends"])
        if len(ends) != 2:
            return None
        shell = ShellOfRevolution(a["z"], a["r"], a["thickness"], a["density"],
                                  a["youngs_modulus"], float(a["poisson_ratio"]),
                                  (ends[0], ends[1]))
        modes = BarrelModes(shell, tuple(int(n) for n in a["orders"]), a["green"], a["omega"],
                            a["mode_orders"], a["shapes"], float(a["max_frequency"]),
                            float(a["green_scale"]))
        size = 3 * shell.z.size
        ok = (modes.green.ndim == 3 and modes.green.shape[:2] == (len(modes.orders), size)
              and modes.shapes.shape == (size, modes.omega.size)
              and modes.mode_orders.shape == modes.omega.shape
              and modes.max_frequency == cut)
    except (TypeError, KeyError, ValueError, IndexError):
        return None
    return _read_only(modes) if ok else None


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
    edges = np.asarray(bat.z_edges, dtype=float)
    s = np.clip(np.searchsorted(edges, z, side="right") - 1, 0, edges.size - 2)
    return np.minimum(half_length / (0.5 * bat.outer_diameter[s]), 0.5 * np.pi)


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
        static = np.einsum("npg,np->pg", c**2, self.flexibility)
        order_row = {n: i for i, n in enumerate(self.orders)}
        mode_c = c[[order_row[n] for n in self.mode_orders]]  # (m, p, g)
        modal = np.einsum("mpg,pm->pg", mode_c**2, (self.axial / self.omega) ** 2)
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


def hoop_frequency(bat: BatModel) -> float | None:
    """The barrel's hoop frequency [Hz]: its lowest n = 2 mode whose largest normal deflection
    lies in the full-diameter barrel, the mode an impact-hammer test on the barrel of the free
    bat measures; None for a solid bat.

    A wall that is thinner in the taper than in the barrel can have a lower n = 2 mode there
    (a 4 mm barrel over a 2.2 mm taper: 2.37 kHz in the taper, 2.77 kHz in the barrel); the
    trampoline and the lab's hoop frequency are the barrel's. Read from the cached modes
    (:func:`cached_barrel_modes`; order 2 has no rigid motion, so the free and the supported
    wall share these modes), or solved directly if the barrel's mode lies above them.
    """
    modes = cached_barrel_modes(bat)
    if modes is None:
        return None
    in_barrel = modes.shell.r >= 0.99 * modes.shell.r.max()
    radial = np.abs(modes.shapes[1::3])  # u_r at the nodes, (N, m)
    for j in np.flatnonzero(modes.mode_orders == 2):  # ascending within the order
        if in_barrel[int(np.argmax(radial[:, j]))]:
            return float(modes.omega[j] / (2 * np.pi))
    return _hoop_frequency_direct(bat)


def _hoop_frequency_direct(bat: BatModel) -> float | None:
    """:func:`hoop_frequency` from the lowest eight n = 2 modes, solved afresh."""
    import scipy.linalg

    shell = barrel_shell(bat)
    if shell is None:
        return None
    system = assemble(shell, 2)
    lam, vec = scipy.linalg.eigh(system.stiffness, system.mass, subset_by_index=(0, 7),
                                 check_finite=False)
    full = np.zeros((system.node_dofs * shell.z.size, lam.size))
    full[system.free] = vec
    deflection = np.abs(full[system.w_offset::system.node_dofs])  # radial, at the nodes
    in_barrel = shell.r >= 0.99 * shell.r.max()
    for j in range(lam.size):
        if in_barrel[int(np.argmax(deflection[:, j]))]:
            return float(np.sqrt(lam[j]) / (2 * np.pi))
    return float(np.sqrt(lam[0]) / (2 * np.pi))  # no barrel-dominated mode among the lowest


def compression_stiffness(bat: BatModel, position: float, platen_width: float) -> float:
    """Static stiffness of the barrel squeezed between two flat platens [N/m].

    Two equal and opposite line loads at ``theta = 0`` and ``pi``, each spread uniformly over
    ``platen_width`` [m] along the bat around ``position`` [m from knob]: the force on one
    platen divided by the platens' approach (the even orders 0, 2, 4 .. ``STATIC_ORDERS``;
    the beam's bending, order 1, cancels). Shell theory only: the local crushing under a
    narrow platen edge is not modelled.
    """
    import scipy.linalg

    shell = barrel_shell(bat)
    if shell is None:
        raise ValueError("a solid bat has no barrel to compress")
    half = 0.5 * platen_width
    if not (shell.z[0] <= position - half and position + half <= shell.z[-1]):
        raise ValueError("the platens do not lie on the hollow barrel")
    k_pts = 16
    zs = position + half * (np.arange(k_pts) + 0.5) / k_pts * 2 - half
    w = np.full(k_pts, 1.0 / k_pts)
    approach = 0.0
    for n in range(0, STATIC_ORDERS + 1, 2):
        system = assemble(shell, n, support=True)
        cols, h = normal_reader(shell, n, zs)
        f = np.zeros(system.node_dofs * shell.z.size)
        np.add.at(f, cols.ravel(), (h * w[:, None]).ravel())
        f_free = f[system.free][:, None]
        factor = scipy.linalg.cho_factor(system.stiffness, check_finite=False)
        x = static_solve(system, factor, f_free)
        approach += 2.0 * 2.0 * float(f_free[:, 0] @ x[:, 0])  # both loads; both platens
    return 1.0 / approach
