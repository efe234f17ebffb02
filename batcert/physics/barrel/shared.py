"""One nominal wall for many bats whose walls differ only by a uniform scale of their density
(a Monte Carlo's drawn masses, :mod:`batcert.engines.flexible_family`): found once, not looked
up per bat."""

from __future__ import annotations

from dataclasses import fields, is_dataclass

import numpy as np

from batcert.physics.barrel.wall import (
    DYNAMIC_ORDERS,
    MAX_FREQUENCY,
    STATIC_ORDERS,
    BarrelModes,
    nominal_of,
    wall_of,
)
from batcert.physics.batmodel import BatModel


def shared_wall(bats: list[BatModel], max_frequency: float = MAX_FREQUENCY,
                dynamic_orders: int = DYNAMIC_ORDERS, static_orders: int = STATIC_ORDERS
                ) -> tuple[BarrelModes, float, np.ndarray] | None:
    """One nominal wall for several bats whose walls differ only by a uniform scale of their
    density (a Monte Carlo's drawn masses): the nominal (:func:`cached_barrel_modes`' for the
    first bat), its stiffness scale and each bat's mass scale, (bats,). Each bat's barrel is
    ``nominal.scaled(shell, stiffness, mass[i], max_frequency)``, what
    :func:`cached_barrel_modes` gives to rounding, without a lookup per bat. None when some
    bat's wall differs otherwise, when the nominal's modes do not reach a bat's cut, or for
    solid bats."""
    found = nominal_of(bats[0], max_frequency, dynamic_orders, static_orders)
    if found is None:
        return None
    base, s_k, s_m = found
    first = wall_of(bats[0])
    masses = np.empty(len(bats))
    for i, bat in enumerate(bats):
        ratio = _density_ratio(first, wall_of(bat))
        if ratio is None:
            return None
        masses[i] = s_m * ratio
    if np.any(float(max_frequency) / np.sqrt(s_k / masses) > base.max_frequency):
        return None
    return base, s_k, masses


def _density_ratio(a: BatModel, b: BatModel) -> float | None:
    """``b``'s density over ``a``'s when it is the same profile (to 1e-12) and every other
    field is equal, else None."""
    da, db = np.asarray(a.linear_density, float), np.asarray(b.linear_density, float)
    if da.shape != db.shape or da.size == 0:
        return None
    ratio = float(db.max() / da.max())
    if not np.allclose(db, ratio * da, rtol=1e-12, atol=0.0):
        return None
    return ratio if all(f.name == "linear_density"
                        or _same(getattr(a, f.name), getattr(b, f.name)) for f in fields(a)) else None


def _same(x, y) -> bool:
    """``x`` and ``y`` hold equal values: arrays element by element, dataclasses (a layup) and
    sequences member by member."""
    if x is y:
        return True
    if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
        return bool(np.array_equal(x, y))
    if is_dataclass(x) and type(x) is type(y):
        return all(_same(getattr(x, f.name), getattr(y, f.name)) for f in fields(x))
    if isinstance(x, (tuple, list)) and isinstance(y, (tuple, list)):
        return len(x) == len(y) and all(_same(p, q) for p, q in zip(x, y, strict=True))
    try:
        return bool(x == y)
    except ValueError:  # something else that holds arrays: not known to be equal
        return False
