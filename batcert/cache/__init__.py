"""batcert's cache directory: results that are costly to rebuild and cheap to keep, reused by
later runs. Everything in it is an optimisation: a directory that cannot be made, read or
written is passed over, a damaged entry is recomputed and replaced, and deleting the directory
is always safe.

Where: ``$BATCERT_CACHE_DIR``, else ``$XDG_CACHE_HOME/batcert`` or ``~/.cache/batcert``, one
folder per kind (``templates``: compiled report templates; ``barrels``: hollow bats' barrel
shells, :mod:`batcert.physics.barrel`; ``modes``: bats' beam modes; ``ball-fits``: viscoelastic
balls fitted to their tests; ``ball-walls``: balls' rigid-wall tables,
:mod:`batcert.physics.balls`; ``compressions``: barrels' compression stiffness).

How large it grows: each kind's folder holds at most :data:`KIND_LIMIT` bytes of entries (256
MiB), the least recently used going first; ``batcert cache`` shows the folders, their sizes and
that bound, and ``batcert cache clear`` empties them (:mod:`batcert.cache.folder`).

What the cache may touch. The top folder is batcert's only when it holds batcert's
``CACHEDIR.TAG`` (the tag backup tools honour), written when batcert makes the folder or adopts
an empty one or one of only its entries. A folder holding anything else, or a kind's folder
that is a link, is not used: caching is off for it, with one :class:`CacheWarning`. In its
folders the cache reads and deletes only its own names, never following a link.

What it trusts. Every entry carries a SHA-256 checksum of its header and arrays; a mismatch (a
bad disk block, an edited file) is a miss, said once (:class:`CacheWarning`), recomputed and
replaced, never a result.
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path

from batcert.cache.folder import (
    KIND_LIMIT,
    TAG,
    TAG_NAME,
    cache_root,
    is_batcerts,
    own,
    remove,
    trim,
)


class CacheWarning(UserWarning):
    """Something about the cache directory that a user should know and that changes no result:
    a damaged entry (recomputed and replaced), a folder the cache will not use."""


_SAID: set[str] = set()  # each notice once per process


def notice(message: str) -> None:
    """One :class:`CacheWarning`, once per process (the command line prints it as one
    ``warning:`` line; a library user sees a Python warning)."""
    if message not in _SAID:
        _SAID.add(message)
        warnings.warn(message, CacheWarning, stacklevel=3)


@contextlib.contextmanager
def warnings_as_lines(say: Callable[[str], None]) -> Iterator[None]:
    """Inside the block every :class:`CacheWarning` is ``say(message)`` (one line: the
    command line's ``warning:``), not Python's warning format with its source line."""
    with warnings.catch_warnings():
        warnings.simplefilter("always", CacheWarning)
        shown = warnings.showwarning

        def show(message, category, filename, lineno, file=None, line=None):
            if issubclass(category, CacheWarning):
                say(str(message))
            else:
                shown(message, category, filename, lineno, file, line)

        warnings.showwarning = show
        yield


def _only_ours(root: Path) -> bool:
    """Whether ``root`` holds nothing but folders of batcert's own entries (no link followed)."""
    try:
        with os.scandir(root) as children:
            for child in children:
                if child.name == TAG_NAME:
                    continue
                if child.is_symlink() or not child.is_dir(follow_symlinks=False):
                    return False
                with os.scandir(child.path) as entries:
                    if any(e.is_symlink() or not own(e.name) for e in entries):
                        return False
    except OSError:
        return False
    return True


def _claim(root: Path) -> bool:
    """Make ``root`` batcert's (create it and its tag), or say why it is not; True when the
    cache may use it."""
    tag = root / TAG_NAME
    try:
        if str(root) in _CLAIMED and tag.is_file():
            return True
        if is_batcerts(root):
            _CLAIMED.add(str(root))
            return True
        root.mkdir(parents=True, exist_ok=True, mode=0o700)
        if not _only_ours(root):
            notice(f"cache directory {root} holds files batcert did not write: caching is off "
                   "(point BATCERT_CACHE_DIR at a new or empty folder)")
            return False
        tag.write_text(TAG)
    except OSError:
        return False
    _CLAIMED.add(str(root))
    return True


_CLAIMED: set[str] = set()  # top folders found or made batcert's in this process


def cache_dir(kind: str) -> Path | None:
    """The folder of one kind of cache entry (made if missing), or None where that cannot be or
    must not be (a top folder that is not batcert's, a kind's folder that is a link)."""
    root = cache_root()
    if not _claim(root):
        return None
    path = root / kind
    try:
        path.mkdir(exist_ok=True, mode=0o700)
        st = os.lstat(path)
    except OSError:
        return None
    if stat.S_ISLNK(st.st_mode) or not stat.S_ISDIR(st.st_mode):
        notice(f"cache folder {path} is a link or not a folder: caching of {kind} is off")
        return None
    return path if os.access(path, os.W_OK | os.X_OK) else None


# what a stored result depends on besides its inputs: the sources of the physics, the workspace
# and what computes a kept result above the physics (a ball lot's calibration runs a protocol),
# and numpy's and scipy's releases (a change anywhere retires every entry)
PHYSICS_CODE = ("batcert.physics", "batcert.workspace", "numpy", "scipy", "batcert.engines",
                "batcert.runner", "batcert.model", "batcert.methods", "batcert.specs", "batcert.units")


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


_MAGIC = b"batcert arrays 2 "  # then the SHA-256 of the rest, in hex, and a newline
_ALIGN = 64  # each array's bytes start on a multiple of this


def disk_stores():
    """What :meth:`batcert.workspace.Workspace.attach` takes to keep the physics' results in
    the cache directory: one :class:`ArrayStore` per folder, sharing one fingerprint of the
    physics' code (read when a store first needs it)."""
    code = Fingerprint(PHYSICS_CODE)
    return lambda folder: ArrayStore(folder, code)


class ArrayStore:
    """Named sets of numpy arrays kept as files in :func:`cache_dir` ``(kind)``, least recently
    used first out once they hold more than ``limit`` bytes (:data:`KIND_LIMIT` by default).

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

    def __init__(self, kind: str, code: Fingerprint | tuple = (), limit: int = KIND_LIMIT):
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

        # the entry format is part of the name: an older format's entries are never read
        name = hashlib.sha256(f"{key}|{fingerprint}|{_MAGIC!r}".encode()).hexdigest()[:32]
        return where / f"{name}{self.SUFFIX}"

    def load(self, key: str) -> dict | None:
        path = self._path(key)
        if path is None:
            return None
        try:
            fd = os.open(path, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
        except OSError:  # missing, unreadable, or a link
            return None
        try:
            with os.fdopen(fd, "rb") as f:
                st = os.fstat(f.fileno())
                if not stat.S_ISREG(st.st_mode):
                    return None
                buf = bytearray(st.st_size)
                if f.readinto(buf) != len(buf):
                    raise ValueError("shorter than its size")
            arrays = _unpack(buf)
            os.utime(path)  # recently used
        except Exception as exc:  # noqa: BLE001 - a damaged entry of any kind is only a miss
            damaged(path, exc)
            return None
        return arrays

    def damaged(self, key: str, why: object) -> None:
        """The entry of ``key`` read intact but its arrays do not make a result (the caller's
        check): said once, and removed (the caller recomputes and replaces it)."""
        path = self._path(key)
        if path is not None:
            damaged(path, why)
            _remove(str(path))

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
            fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".batcert-", suffix=".tmp")
            with os.fdopen(fd, "wb") as f:
                f.writelines(parts)
            os.replace(tmp, path)
            tmp = None
            self._trim(path.parent)
        except OSError:
            pass
        finally:
            if tmp is not None:
                _remove(tmp)

    def _trim(self, where: Path) -> None:
        """Least recently used entries out until the folder holds at most ``limit`` bytes of
        them (:func:`batcert.cache.folder.trim`: only batcert's own names, never a link)."""
        trim(where, self.limit)


_remove = remove


def damaged(path: Path | str, why: object) -> None:
    """Say that a cache entry is damaged and is not used (it is recomputed and replaced)."""
    notice(f"cache entry {path} is damaged ({why}); recomputed and replaced")


def _pack(arrays: dict) -> list[bytes]:
    """An entry's bytes (:class:`ArrayStore`), in pieces; ValueError for object arrays.

    A first line names the format and carries the SHA-256 of everything after it; then a line of
    JSON listing each array's name, dtype, shape and offset; then each array's bytes, starting on
    a multiple of :data:`_ALIGN` from the start of the file."""
    import hashlib
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
    first = len(_MAGIC) + 64 + 1
    pad = -(first + len(header)) % _ALIGN
    body = [header, b" " * pad]
    for _, a, _ in items:
        body += [a.tobytes(), bytes(-a.nbytes % _ALIGN)]
    h = hashlib.sha256()
    for piece in body:
        h.update(piece)
    return [_MAGIC, h.hexdigest().encode(), b"\n", *body]


def _unpack(buf: bytearray) -> dict:
    """The arrays of an entry read whole into ``buf`` (views into it, writable); ValueError
    for anything but an intact entry of this format (its checksum checked first)."""
    import hashlib
    import json

    import numpy as np

    first = len(_MAGIC) + 64 + 1
    if not buf.startswith(_MAGIC) or len(buf) < first or buf[first - 1:first] != b"\n":
        raise ValueError("not a batcert array entry of this format")
    want = bytes(buf[len(_MAGIC):first - 1]).decode("ascii", "replace")
    if hashlib.sha256(memoryview(buf)[first:]).hexdigest() != want:
        raise ValueError("checksum mismatch")
    end = buf.index(b"\n", first) + 1
    start = end + (-end % _ALIGN)
    arrays = {}
    for item in json.loads(bytes(buf[first:end])):
        dtype, shape = np.dtype(item["dtype"]), tuple(item["shape"])
        count = int(np.prod(shape, dtype=np.int64))
        at = start + int(item["offset"])
        if dtype.hasobject or at + count * dtype.itemsize > len(buf):
            raise ValueError("arrays beyond the end of the entry")
        arrays[item["name"]] = np.frombuffer(buf, dtype, count, at).reshape(shape)
    return arrays
