r"""A hollow bat's wall as a thin shell of revolution (:func:`barrel_shell`), and its modes and
static flexibility (:func:`compute_barrel_modes`, kept by the workspace:
:func:`cached_barrel_modes`); the model is in :mod:`batcert.physics.barrel`'s notes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from batcert import workspace
from batcert.physics.banded import inverse_band, lower_band
from batcert.physics.batmodel import BatModel
from batcert.physics.shell import (
    Assembler,
    HarmonicSystem,
    ShellOfRevolution,
    harmonic_modes,
)
from batcert.physics.shell_element import isotropic_law

DYNAMIC_ORDERS = 6  # highest order whose modes join the engine (0, 2..6)
# highest order summed into the quasi-static residual: the orders above it hold under 3e-6 of
# the barrel's compliance under a ball's patch, even for a 1 m/s impact's 9 mm patch (measured
# against 40 orders on aluminium-34; 1e-7 at game speeds)
STATIC_ORDERS = 24
# modes above this [Hz] respond quasi-statically (the engine default): 12 kHz since the ball with
# two relaxation times (issue 39), whose fast branch excites the shell higher: at 10 kHz a
# 1.8 mm wall's exit speed was 5.1e-4 from the converged engine, at 12 kHz 1.6e-4
MAX_FREQUENCY = 12_000.0
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
    wall = 0.5 * (outer[sl] - inner[sl])
    return ShellOfRevolution(z, r, wall, density, young, bat.material.poisson_ratio,
                             ("closed", bat.barrel_end), _layup_law(bat, sl, wall))


def _layup_law(bat: BatModel, sl: slice, wall: np.ndarray) -> np.ndarray | None:
    """The shell's law per element where some of its slices are laminated or multi-wall
    (``bat.layup``, after ``bat.wall_damage``), else None (the material's isotropic wall);
    times ``barrel_stiffness_scale``."""
    if bat.layup is None:
        return None
    index = np.asarray(bat.layup.index)[sl]
    if not np.any(index >= 0):
        return None
    law = isotropic_law(np.full(wall.size, bat.material.youngs_modulus), wall,
                        bat.material.poisson_ratio)
    for k in np.unique(index[index >= 0]):
        law[index == k] = bat.layup.stacks[int(k)].law(bat.wall_damage)
    return law * bat.barrel_stiffness_scale


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
    if higher:  # five unknowns per node, u_r at slot 3 (shell_element._layout)
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
# mode summary (model.diagnostics), which also covers the engine's 12 kHz for barrels down to
# x0.64 of their nominal stiffness (the plausible range's x0.8 among them) without recomputing.
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
    found = nominal_of(bat, max_frequency, dynamic_orders, static_orders)
    if found is None:
        return None
    base, s_k, s_m = found
    shell = barrel_shell(bat)
    assert shell is not None
    return base.scaled(shell, s_k, s_m, float(max_frequency))


def nominal_of(bat: BatModel, max_frequency: float, dynamic_orders: int, static_orders: int
                ) -> tuple[BarrelModes, float, float] | None:
    """The nominal wall (kept by the workspace, kind ``barrel``) that ``bat``'s is scaled from,
    and the stiffness and mass scales; None for a solid bat."""
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
    return base, float(s_k), float(s_m)


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
            "ends": np.array(s.ends), "law": np.zeros(0) if s.law is None else s.law,
            "orders": np.array(modes.orders), "green": modes.green,
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
        law = a["law"]
        shell = ShellOfRevolution(a["z"], a["r"], a["thickness"], a["density"],
                                  a["youngs_modulus"], float(a["poisson_ratio"]),
                                  (ends[0], ends[1]), None if law.size == 0 else law)
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
