"""batcert's cache directory: results that are costly to rebuild and cheap to keep, reused by
later runs. Everything in it is an optimisation: a directory that cannot be made, read or
written is passed over in silence, a damaged entry is recomputed, and deleting the directory is
always safe.

Where: ``$BATCERT_CACHE_DIR``, else ``$XDG_CACHE_HOME/batcert`` or ``~/.cache/batcert``, one
folder per kind (``templates``: compiled report templates; ``barrels``: hollow bats' barrel
shells, :mod:`batcert.physics.barrel`; ``modes``: bats' beam modes; ``ball-fits``: viscoelastic
balls fitted to their tests; ``ball-walls``: balls' rigid-wall tables,
:mod:`batcert.physics.balls`; ``compressions``: barrels' compression stiffness).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def cache_dir(kind: str) -> Path | None:
    """The folder of one kind of cache entry (made if missing), or None where that cannot be."""
    root = os.environ.get("BATCERT_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "batcert")
    path = Path(root) / kind
    try:
        path.mkdir(parents=True, exist_ok=True, mode=0o700)
    except OSError:
        return None
    return path if os.access(path, os.W_OK | os.X_OK) else None


# what a stored physics result depends on besides its inputs: every source file of the physics
# and of the workspace that keys it, and the releases of numpy and scipy (not a hand-kept list
# of modules per kind: a change anywhere in the physics retires every stored entry)
PHYSICS_CODE = ("batcert.physics", "batcert.workspace", "numpy", "scipy")


def code_fingerprint(modules) -> str | None:
    """A checksum of the code of ``modules`` (import names): a module's source; for a package
    of batcert every ``.py`` file in it (sorted by path); for another package its
    ``version.py`` (a library's release) else its ``__init__.py``; None if one cannot be found
    or read."""
    import hashlib
    import importlib.util

    h = hashlib.sha256()
    for name in modules:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            return None
        if spec is None or spec.origin is None:
            return None
        origin = Path(spec.origin)
        files = [origin]
        if spec.submodule_search_locations is not None:
            if name.split(".")[0] == "batcert":
                files = sorted(origin.parent.rglob("*.py"))
            elif origin.with_name("version.py").is_file():
                files = [origin.with_name("version.py")]
        try:
            for f in files:
                where = f.relative_to(origin.parent).as_posix()
                h.update(name.encode() + b"\0" + where.encode() + b"\0" + f.read_bytes())
        except OSError:
            return None
    return h.hexdigest()


class Fingerprint:
    """:func:`code_fingerprint` of ``modules``, read when first needed and then kept: the
    stores of one session share one (reading the physics' sources costs about 3 ms)."""

    def __init__(self, modules: tuple) -> None:
        self.modules = tuple(modules)
        self._value: str | None = None

    @property
    def value(self) -> str:
        """The checksum, or "" where the code cannot be read (then nothing is stored)."""
        if self._value is None:
            self._value = code_fingerprint(self.modules) or ""
        return self._value


_MAGIC = b"batcert arrays 1\n"
_ALIGN = 64  # each array's bytes start on a multiple of this


def disk_stores():
    """What :meth:`batcert.workspace.Workspace.attach` takes to keep the physics' results in
    the cache directory: one :class:`ArrayStore` per folder, sharing one fingerprint of the
    physics' code (read when a store first needs it)."""
    code = Fingerprint(PHYSICS_CODE)
    return lambda folder: ArrayStore(folder, code)


class ArrayStore:
    """Named sets of numpy arrays kept as files in :func:`cache_dir` ``(kind)``, least recently
    used first out once they hold more than ``limit`` bytes.

    An entry's file name folds the caller's key with :func:`code_fingerprint` of ``code``, so
    that a changed computation never reads what an older one stored (no code, no store).
    ``load`` returns None for a missing, unreadable or damaged entry; ``save`` writes through
    a temporary file and a rename (a reader never sees half an entry) and passes over any
    failure (a full disk, a read-only directory). An entry is a line naming the format, a line
    of JSON listing each array's name, dtype, shape and place, and the arrays' bytes: read
    with one ``readinto`` and no zip archive (``numpy.load`` of an ``.npz`` imports
    ``zipfile``, 10 ms of a run that loads a stored barrel).
    """

    SUFFIX = ".arrays"

    def __init__(self, kind: str, code: Fingerprint | tuple = (), limit: int = 256 * 2**20):
        self.kind, self.limit = kind, int(limit)
        self.code = code if isinstance(code, Fingerprint) else Fingerprint(tuple(code))

    def _path(self, key: str) -> Path | None:
        fingerprint = self.code.value
        if not fingerprint:
            return None
        where = cache_dir(self.kind)
        if where is None:
            return None
        import hashlib

        name = hashlib.sha256(f"{key}|{fingerprint}".encode()).hexdigest()[:32]
        return where / f"{name}{self.SUFFIX}"

    def load(self, key: str) -> dict | None:
        path = self._path(key)
        if path is None or not path.is_file():
            return None
        try:
            with open(path, "rb") as f:
                buf = bytearray(os.fstat(f.fileno()).st_size)
                if f.readinto(buf) != len(buf):
                    return None
            arrays = _unpack(buf)
            os.utime(path)  # recently used
        except Exception:  # noqa: BLE001 - a damaged entry of any kind is only a miss
            return None
        return arrays

    def save(self, key: str, arrays: dict) -> None:
        path = self._path(key)
        if path is None:
            return
        try:
            parts = _pack(arrays)
        except ValueError:  # arrays of Python objects are not kept
            return
        tmp = None
        try:
            fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".", suffix=".tmp")
            with os.fdopen(fd, "wb") as f:
                f.writelines(parts)
            os.replace(tmp, path)
            tmp = None
            self._trim(path.parent)
        except OSError:
            pass
        finally:
            if tmp is not None:
                try:
                    os.unlink(tmp)
                except OSError:
                    pass

    def _trim(self, where: Path) -> None:
        entries = []
        for p in where.iterdir():
            if p.name.startswith("."):  # another writer's temporary file
                continue
            try:
                st = p.stat()
            except OSError:
                continue
            entries.append((st.st_mtime, st.st_size, p))
        total = sum(size for _, size, _ in entries)
        for _, size, p in sorted(entries):
            if total <= self.limit:
                break
            try:
                p.unlink()
                total -= size
            except OSError:
                pass


def _pack(arrays: dict) -> list[bytes]:
    """An entry's bytes (:class:`ArrayStore`), in pieces; ValueError for object arrays."""
    import json

    import numpy as np

    items, offset = [], 0
    for name, value in arrays.items():
        a = np.asarray(value)
        a = a if a.flags.c_contiguous else a.copy(order="C")
        if a.dtype.hasobject:
            raise ValueError(f"{name}: an array of Python objects")
        items.append((name, a, offset))
        offset += a.nbytes + -a.nbytes % _ALIGN
    header = json.dumps([{"name": n, "dtype": a.dtype.str, "shape": a.shape, "offset": o}
                         for n, a, o in items]).encode() + b"\n"
    pad = -(len(_MAGIC) + len(header)) % _ALIGN
    parts = [_MAGIC, header, b" " * pad]
    for _, a, _ in items:
        parts += [a.tobytes(), bytes(-a.nbytes % _ALIGN)]
    return parts


def _unpack(buf: bytearray) -> dict:
    """The arrays of an entry read whole into ``buf`` (views into it, writable)."""
    import json

    import numpy as np

    if not buf.startswith(_MAGIC):
        raise ValueError("not an array entry")
    end = buf.index(b"\n", len(_MAGIC)) + 1
    start = end + (-end % _ALIGN)
    arrays = {}
    for item in json.loads(bytes(buf[len(_MAGIC):end])):
        dtype, shape = np.dtype(item["dtype"]), tuple(item["shape"])
        count = int(np.prod(shape, dtype=np.int64))
        at = start + int(item["offset"])
        if dtype.hasobject or at + count * dtype.itemsize > len(buf):
            raise ValueError("damaged entry")
        arrays[item["name"]] = np.frombuffer(buf, dtype, count, at).reshape(shape)
    return arrays
