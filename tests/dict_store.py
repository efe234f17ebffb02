"""Test helper: an in-memory store for batcert.physics.stores (what the command line keeps in
its cache directory), counting its loads and saves."""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np

from batcert.physics import stores


class DictStore:
    def __init__(self):
        self.entries, self.loads, self.saves = {}, 0, 0

    def load(self, key):
        self.loads += 1
        return self.entries.get(key)

    def save(self, key, arrays):
        self.saves += 1
        self.entries[key] = {k: np.array(v) for k, v in arrays.items()}


@contextmanager
def installed(kind: str, clear):
    """A fresh :class:`DictStore` installed for ``kind``, the in-process cache emptied
    (``clear``) before and after, the previous store put back."""
    s = DictStore()
    previous = stores.get(kind)
    stores.use(kind, s)
    clear()
    try:
        yield s
    finally:
        stores.use(kind, previous)
        clear()
