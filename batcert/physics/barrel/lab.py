"""What a lab measures of a hollow bat's barrel (:mod:`batcert.physics.barrel`): its hoop
frequency (an impact-hammer test on the free bat) and its static compression stiffness between
two platens.
"""

from __future__ import annotations

import numpy as np

from batcert import workspace
from batcert.physics.banded import lower_band
from batcert.physics.barrel.wall import (
    STATIC_ORDERS,
    barrel_shell,
    cached_barrel_modes,
    wall_of,
)
from batcert.physics.batmodel import BatModel
from batcert.physics.shell import (
    Assembler,
    assemble,
    normal_reader,
    static_solve,
)


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

    Kept by the active workspace (kind ``barrel-compression``, also on disk where a store is
    attached), keyed by :func:`wall_of` ``(bat)``: a run of a hollow bat under a protocol
    with a compression test, and every draw of a Monte Carlo, would otherwise solve the
    shell again (and import :mod:`scipy.linalg`, about 0.12 s).
    """
    return workspace.current().call(
        "barrel-compression", _compression_stiffness, wall_of(bat), float(position),
        float(platen_width), save=lambda k: {"stiffness": np.array(k)},
        load=_stored_stiffness)


def _stored_stiffness(arrays: dict) -> float | None:
    """A kept compression stiffness, None unless it is one finite positive number."""
    k = float(np.asarray(arrays["stiffness"]).reshape(()))
    return k if np.isfinite(k) and k > 0 else None


def _compression_stiffness(bat: BatModel, position: float, platen_width: float) -> float:
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
    assembler = Assembler(shell)

    def load(n: int, free: np.ndarray) -> np.ndarray:  # the platen's unit load, free dofs
        cols, h = normal_reader(shell, n, zs)
        f = np.zeros(shell.node_dofs(n) * shell.z.size)
        np.add.at(f, cols.ravel(), (h * w[:, None]).ravel())
        return f[free]

    # the even orders n >= 2 (banded: each node couples only to its neighbours); they share
    # their layout and free dofs, so one load serves them all
    orders = list(range(2, STATIC_ORDERS + 1, 2))
    bands, free = assembler.stiffness_bands(orders)
    f = load(2, free)
    approach = 0.0
    for ab in bands:
        factor = scipy.linalg.cholesky_banded(ab, lower=True, check_finite=False)
        x = scipy.linalg.cho_solve_banded((factor, True), f, check_finite=False)
        approach += 4.0 * float(f @ x)  # both loads; both platens
    system = assembler.system(0, support=True)  # order 0, with inertia relief
    f0 = load(0, system.free)
    factor = scipy.linalg.cholesky_banded(lower_band(system.stiffness, 2 * system.node_dofs - 1),
                                          lower=True, check_finite=False)
    x0 = static_solve(system, lambda b: scipy.linalg.cho_solve_banded(
        (factor, True), b, check_finite=False), f0[:, None])
    approach += 4.0 * float(f0 @ x0[:, 0])
    return 1.0 / approach

