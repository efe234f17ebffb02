"""Test helper: an in-memory store for batcert.physics.stores (what the command line keeps in
its cache directory), counting its loads and saves."""

from __future__ import annotations

import numpy as np


class DictStore:
    def __init__(self):
        self.entries, self.loads, self.saves = {}, 0, 0

    def load(self, key):
        self.loads += 1
        return self.entries.get(key)

    def save(self, key, arrays):
        self.saves += 1
        self.entries[key] = {k: np.array(v) for k, v in arrays.items()}
