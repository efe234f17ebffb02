"""The one owner of what batcert keeps so as not to compute it twice: a :class:`Workspace`.

The physics asks the active workspace (:func:`current`) for a result by its *kind* and by the
function and arguments that compute it::

    modes = workspace.current().call("modes", compute_modes, bat, "free", pivot, 24, 1)

The key is a content hash (:func:`content_key`) of the kind, the function's qualified name and
every argument: arrays by dtype, shape and bytes, dataclasses by every field, recursively. It is
never a hand-made list of the fields someone thought mattered, and never an object's identity:
two computations that differ in any input never share a result, and equal inputs always do.
The function receives exactly the arguments that were hashed, so nothing it reads can be left
out of its key.

A workspace keeps each kind's most recently used entries in the process (:data:`KINDS` says how
many and why the kind is kept at all). Where a disk store is attached (:meth:`Workspace.attach`,
the library and the command line attach :class:`batcert.cache.ArrayStore`), the kinds marked
``on_disk`` are also kept in files that every process of the machine shares (a sweep's workers
among them); a store folds the fingerprint of the physics' source into its file names, so a
changed computation never reads what an older one stored.

Which workspace is active is a context variable: the process has one default workspace, and
:func:`active` makes another one current for a block (a test that wants a cold start, a library
user who wants two isolated sessions). Nothing here changes a number: a result computed through
the workspace is bit-for-bit the function's result.
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import hashlib
import weakref
from collections import OrderedDict
from collections.abc import Callable, Iterator
from typing import Any, NamedTuple, Protocol, TypeVar

import numpy as np

T = TypeVar("T")


class Store(Protocol):
    """A disk store: named sets of numpy arrays (:class:`batcert.cache.ArrayStore`)."""

    def load(self, key: str) -> dict[str, Any] | None: ...

    def save(self, key: str, arrays: dict[str, Any]) -> None: ...

    def damaged(self, key: str, why: object) -> None:
        """The entry of ``key`` loaded but does not make a result: say so, drop it."""


class Kind(NamedTuple):
    """One kind of kept result: how many the process keeps, whether (and in which folder of
    the cache directory) it is also kept on disk, and what it is."""

    size: int
    folder: str | None
    what: str


KINDS: dict[str, Kind] = {
    "modes": Kind(64, "modes", "a bat's beam modes (batcert.physics.modes.cached_modes)"),
    "barrel": Kind(8, "barrels", "a hollow bat's nominal wall: shell modes and static "
                   "flexibility, about 4 MB for a 34 in bat (batcert.physics.barrel)"),
    "barrel-compression": Kind(32, "compressions", "a hollow barrel's stiffness between two "
                               "platens (a protocol's compression test; a static shell solve)"),
    "barrel-scaled": Kind(16, None, "a bat's own wall, scaled from its nominal one: the engine "
                          "asks for it once per batch"),
    "patch-flexibility": Kind(64, None, "a barrel's flexibility under a batch of patches: a "
                              "scaled wall shares its nominal one, the runner repeats points"),
    "patch-factors": Kind(64, None, "circumferential factors of a batch of patch sizes"),
    "residual-flexibility": Kind(32, None, "a beam's static flexibility behind the residual "
                                 "compliance of its truncated modes"),
    "beam-response": Kind(256, None, "a beam's modal readings at a batch of impact points"),
    "step-exponentials": Kind(128, None, "the exponentials of one block's modal eigenvalues "
                              "for the time step (a bat's modes recur in every batch)"),
    "ball-wall": Kind(64, "ball-walls", "a viscoelastic ball's COR and compression against "
                      "a rigid wall, tabulated in speed"),
    "ball-fit": Kind(16, "ball-fits", "a viscoelastic ball's parameters fitted to its tests"),
    "footprint": Kind(256, None, "a ball's contact footprint at one compression"),
    "ball-lot": Kind(8, "ball-lots", "a ball lot's calibration on its reference bat: a few "
                     "protocol runs of the reference bat (batcert.runner.lot)"),
}

# batches of more than this many impacts are neither hashed nor kept: those recur (a barrel's
# variants, the runner's repeated points) and a large random batch's passes do not, and would
# each hold about a megabyte
BATCH_ROWS = 2048


def content_key(*parts: Any) -> str:
    """A SHA-256 hex digest of ``parts``: numbers, strings, None, tuples and lists, dicts,
    numpy arrays (dtype, shape, bytes), dataclasses (class name and every field), recursively.
    TypeError for anything else (an object without a content cannot be a key)."""
    h = hashlib.sha256()
    for part in parts:
        _feed(h, part)
    return h.hexdigest()


def _feed(h: Any, x: Any) -> None:
    if x is None or isinstance(x, (bool, int, float, complex, str, bytes)):
        h.update(f"{type(x).__name__}:{x!r};".encode())
    elif isinstance(x, np.ndarray):
        h.update(f"array:{x.dtype.str}:{x.shape};".encode())
        h.update(_array_digest(x))
    elif isinstance(x, np.generic):
        _feed(h, x.item())
    elif isinstance(x, (tuple, list)):
        h.update(f"{type(x).__name__}[{len(x)}](".encode())
        for item in x:
            _feed(h, item)
        h.update(b")")
    elif isinstance(x, dict):
        h.update(f"dict[{len(x)}](".encode())
        for k in sorted(x, key=repr):
            _feed(h, k)
            _feed(h, x[k])
        h.update(b")")
    elif dataclasses.is_dataclass(x) and not isinstance(x, type):
        h.update(f"{type(x).__module__}.{type(x).__qualname__}(".encode())
        for f in dataclasses.fields(x):
            h.update(f.name.encode() + b"=")
            _feed(h, getattr(x, f.name))
        h.update(b")")
    elif callable(x) and hasattr(x, "__qualname__") and "<" not in x.__qualname__:
        # a module-level function or method by name (its code is the store's fingerprint);
        # a lambda or a closure has no name that says what it computes and cannot be a key
        h.update(f"function:{x.__module__}.{x.__qualname__};".encode())
    else:
        raise TypeError(f"no content key for a {type(x).__name__}")


# the digests of read-only arrays, by identity while the array lives: a shared wall's 4 MB
# flexibility is hashed once, not at every batch that reads it. A writeable array is hashed
# every time (it may change); a read-only one cannot change through any name that batcert
# holds (the workspace marks every array it hands out read-only).
_DIGESTS: dict[int, tuple[weakref.ref, bytes]] = {}


def _array_digest(a: np.ndarray) -> bytes:
    if a.flags.writeable or a.size < 4096:
        return hashlib.sha256(np.ascontiguousarray(a).tobytes()).digest()
    hit = _DIGESTS.get(id(a))
    if hit is not None and hit[0]() is a:
        return hit[1]
    digest = hashlib.sha256(np.ascontiguousarray(a).tobytes()).digest()
    key = id(a)

    def forget(_: weakref.ref) -> None:  # the array is gone: its id may be another's next
        _DIGESTS.pop(key, None)

    _DIGESTS[key] = (weakref.ref(a, forget), digest)
    return digest


class Workspace:
    """The results kept by one session: per kind (:data:`KINDS`) an in-process store of the
    most recently used entries, and an optional disk store (:meth:`attach`)."""

    def __init__(self) -> None:
        self._memos: dict[str, OrderedDict[str, Any]] = {k: OrderedDict() for k in KINDS}
        self._stores: dict[str, Store] = {}

    def attach(self, make: Callable[[str], Store] | None) -> None:
        """Keep the ``on_disk`` kinds also in ``make(folder)`` (None: in the process only)."""
        self._stores = {} if make is None else {
            kind: make(spec.folder) for kind, spec in KINDS.items() if spec.folder is not None}

    @property
    def attached(self) -> bool:
        """Whether a disk store is attached."""
        return bool(self._stores)

    def clear(self, kind: str | None = None) -> None:
        """Forget the in-process entries of ``kind`` (None: of every kind); disk stays."""
        for k in ([kind] if kind is not None else list(self._memos)):
            self._memos[k].clear()

    def count(self, kind: str) -> int:
        """How many entries of ``kind`` the process keeps now."""
        return len(self._memos[kind])

    def entries(self, kind: str) -> list[Any]:
        """The entries of ``kind`` the process keeps now, least recently used first."""
        return list(self._memos[kind].values())

    def call(self, kind: str, fn: Callable[..., T], *args: Any, rows: int = 0,
             save: Callable[[T], dict[str, Any]] | None = None,
             load: Callable[[dict[str, Any]], T | None] | None = None) -> T:
        """``fn(*args)``, or the kept result of the same function on equal arguments.

        ``rows``: the number of impacts of a batch; a batch of more than :data:`BATCH_ROWS` is
        computed and not kept. ``save``/``load`` turn the result into arrays and back (``load``
        returns None for an entry that does not hold a consistent result) for a kind kept on
        disk; without them a kind is kept in the process only."""
        if rows > BATCH_ROWS:
            return fn(*args)
        memo = self._memos[kind]
        key = content_key(kind, fn, args)
        if key in memo:
            memo.move_to_end(key)
            return memo[key]
        store = self._stores.get(kind) if save is not None and load is not None else None
        value = None
        if store is not None and load is not None:
            arrays = store.load(key)
            value = _loaded(load, arrays)
            if arrays is not None and value is None:
                store.damaged(key, "its arrays do not make a result")
        if value is None:
            value = fn(*args)
            if store is not None and value is not None and save is not None:
                store.save(key, save(value))
        memo[key] = value
        while len(memo) > KINDS[kind].size:
            memo.popitem(last=False)
        return value


def _loaded(load: Callable[[dict[str, Any]], T | None], arrays: dict[str, Any] | None) -> T | None:
    """``load(arrays)``, None where the arrays do not make a result (a missing array, a wrong
    shape: any error of ``load`` on them is a miss, never a traceback)."""
    if arrays is None:
        return None
    try:
        return load(arrays)
    except Exception:  # noqa: BLE001 - a stored entry that does not load is only a miss
        return None


_CURRENT: contextvars.ContextVar[Workspace] = contextvars.ContextVar("batcert_workspace")
_DEFAULT = Workspace()


def current() -> Workspace:
    """The active workspace: the one :func:`active` set, else the process's default one."""
    return _CURRENT.get(_DEFAULT)


@contextlib.contextmanager
def active(ws: Workspace) -> Iterator[Workspace]:
    """Make ``ws`` the active workspace inside the block."""
    token = _CURRENT.set(ws)
    try:
        yield ws
    finally:
        _CURRENT.reset(token)
