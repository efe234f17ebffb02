"""Test helper: an in-memory disk store for a workspace (what the command line keeps in its
cache directory, batcert.cache.ArrayStore), counting its loads and saves."""

from __future__ import annotations

from contextlib import contextmanager

import numpy as np

from batcert import workspace


class DictStore:
    def __init__(self):
        self.entries, self.loads, self.saves, self.bad = {}, 0, 0, []

    def load(self, key):
        self.loads += 1
        return self.entries.get(key)

    def damaged(self, key, why):
        self.bad.append(key)
        self.entries.pop(key, None)

    def save(self, key, arrays):
        self.saves += 1
        self.entries[key] = {k: np.array(v) for k, v in arrays.items()}


@contextmanager
def installed(kind: str):
    """A fresh workspace, active inside the block, whose disk store for ``kind`` is a fresh
    :class:`DictStore` (the other kinds' stores are thrown away)."""
    s = DictStore()
    ws = workspace.Workspace()
    folder = workspace.KINDS[kind].folder
    ws.attach(lambda f: s if f == folder else DictStore())
    with workspace.active(ws):
        yield s


def forget(kind: str) -> None:
    """Empty the active workspace's in-process entries of ``kind`` (its disk store stays)."""
    workspace.current().clear(kind)
