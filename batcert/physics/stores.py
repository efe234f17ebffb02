"""Where computations that are costly to repeat may be kept between processes.

The physics reads and writes no files. A front end (the command line) installs a store here,
an object with ``load(key) -> dict of numpy arrays | None`` and ``save(key, arrays)``
(:class:`batcert.cache.ArrayStore`); without one, results are kept in the process only. A
stored result is valid only for the code that computed it: :data:`CODE` names, per kind, the
modules whose source (or, for a library, release) the store must fold into its keys.
"""

from __future__ import annotations

import hashlib
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any, Protocol, TypeVar

T = TypeVar("T")
K = TypeVar("K", bound=Hashable)
V = TypeVar("V")


class Store(Protocol):
    def load(self, key: str) -> dict[str, Any] | None: ...

    def save(self, key: str, arrays: dict[str, Any]) -> None: ...


CODE = {
    # batcert.physics.modes.cached_modes: a bat's beam modes
    "modes": ("batcert.physics.modes", "batcert.physics.beam", "batcert.physics.batmodel",
              "numpy"),
    # batcert.physics.barrel.cached_barrel_modes: a hollow bat's nominal wall
    "barrel": ("batcert.physics.barrel", "batcert.physics.shell", "batcert.physics.banded",
               "numpy", "scipy"),
    # batcert.physics.balls.impact1d.wall_table: a ball's COR and compression at a wall
    "ball-wall": ("batcert.physics.balls.impact1d", "batcert.physics.balls.viscoelastic",
                  "batcert.physics.balls.hysteresis", "batcert.physics.etd", "numpy"),
    # batcert.physics.balls.fit.cached_fit: a viscoelastic ball's parameters from its tests
    "ball-fit": ("batcert.physics.balls.fit", "batcert.physics.balls.impact1d",
                 "batcert.physics.balls.viscoelastic", "batcert.physics.balls.footprint",
                 "batcert.physics.etd",
                 "numpy", "scipy"),
}

_STORES: dict[str, Store] = {}
# the in-process memos (a bat's patch readings, a barrel's patch flexibilities) keep batches of
# at most this many impacts: those recur (a barrel's variants, the runner's repeated points);
# the passes of a large random batch do not, and would each hold about a megabyte
MEMO_ROWS = 2048


class Memo(OrderedDict[K, V]):
    """An in-process memo that keeps its ``size`` most recently used entries (the one LRU
    dict of the physics' memos: modes, barrel walls, patch readings, beam flexibilities, step
    exponentials)."""

    def __init__(self, size: int) -> None:
        super().__init__()
        self.size = size

    def look(self, key: K) -> V | None:
        """The entry under ``key``, now the most recently used, or None."""
        hit = self.get(key)
        if hit is not None:
            self.move_to_end(key)
        return hit

    def keep(self, key: K, value: V) -> V:
        """Keep ``value`` under ``key`` as the most recently used entry, dropping the least
        recently used beyond ``size``; return ``value``."""
        self[key] = value
        self.move_to_end(key)
        while len(self) > self.size:
            self.popitem(last=False)
        return value

    def batch(self: Memo[tuple, Any], owner: object, key: tuple, arrays: tuple,
              compute: Callable[[], T]) -> T:
        """``compute()`` for a batch of impacts, memoised on ``owner`` (the modes or the wall
        it reads, by identity: an entry is used only while it is that very object), ``key`` and
        a digest of ``arrays`` (each with one row per impact). A batch of more than
        :data:`MEMO_ROWS` impacts is neither hashed, looked up nor kept."""
        if arrays[0].shape[0] > MEMO_ROWS:
            return compute()
        digest = hashlib.sha1()
        for a in arrays:
            digest.update(a.tobytes())
        full = (id(owner), *key, digest.digest())
        hit = self.look(full)
        if hit is not None and hit[0] is owner:
            return hit[1]
        value = compute()
        self.keep(full, (owner, value))
        return value


def use(kind: str, store: Store | None) -> None:
    """Keep results of ``kind`` in ``store`` (None: in the process only)."""
    if store is None:
        _STORES.pop(kind, None)
    else:
        _STORES[kind] = store


def get(kind: str) -> Store | None:
    """The store installed for ``kind``, or None."""
    return _STORES.get(kind)


def kept(kind: str, key: tuple, compute: Callable[[], T | None],
         to_arrays: Callable[[T], dict[str, Any]],
         from_arrays: Callable[[dict[str, Any] | None], T | None]) -> T | None:
    """``compute()``, or what the store installed for ``kind`` holds under ``key``.

    ``from_arrays`` rebuilds the result from a stored entry (None for a missing one) or returns
    None when the entry does not fit; then the result is computed and, unless None, stored
    (``to_arrays``) under ``key`` (hashed; the store adds its code's fingerprint).
    """
    store = _STORES.get(kind)
    if store is None:
        return compute()
    name = hashlib.sha256(repr(key).encode()).hexdigest()
    value = from_arrays(store.load(name))
    if value is None:
        value = compute()
        if value is not None:
            store.save(name, to_arrays(value))
    return value
