"""What batcert's cache directory holds and what may be deleted in it: the names batcert writes,
its ``CACHEDIR.TAG``, the least-recently-used trim of a kind's folder, and what ``batcert
cache`` shows (:func:`survey`) and clears (:func:`clear`).

The bound: each kind's folder (``barrels``, ``modes``, ...) holds at most :data:`KIND_LIMIT`
bytes of entries; a write past it removes the least recently used. Compiled report templates
(``templates``) are a few kB each and are not trimmed.

Deleting is for batcert's own names only (:data:`OWN_NAMES`), regular files only (a link is
never followed nor removed), and :func:`clear` empties only a top folder that holds batcert's
tag: a folder that is not batcert's is left as it is.
"""

from __future__ import annotations

import contextlib
import os
import re
import stat
import time
from dataclasses import dataclass, field
from pathlib import Path

TAG_NAME = "CACHEDIR.TAG"
TAG = "Signature: 8a477f597d28d172789f06886806bc55\n# a cache directory tag, written by batcert\n"
# the files batcert writes in a kind's folder: entries, their temporary files, Jinja's templates
ENTRY_NAME = re.compile(r"[0-9a-f]{32}\.arrays")
TEMP_NAME = re.compile(r"\.batcert-[A-Za-z0-9_]+\.tmp")
TEMPLATE_NAME = re.compile(r"__jinja2_[0-9a-f]+\.cache")
OWN_NAMES = (ENTRY_NAME, TEMP_NAME, TEMPLATE_NAME)
STALE_TEMP = 24 * 3600.0  # [s] a temporary file older than this was left by a killed writer
# the most bytes of entries one kind's folder keeps (least recently used out first): a 34 in
# hollow bat's barrel is about 4 MB, so a wall sweep of 60 walls fits
KIND_LIMIT = 256 * 2**20


def cache_root() -> Path:
    """The cache directory's top folder (not made, not checked)."""
    return Path(os.environ.get("BATCERT_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
        "batcert"))


def own(name: str) -> bool:
    """Whether a file name is one batcert writes in a kind's folder."""
    return any(p.fullmatch(name) for p in OWN_NAMES)


def is_batcerts(root: Path) -> bool:
    """Whether ``root`` holds batcert's ``CACHEDIR.TAG`` (a regular file, not a link)."""
    tag = root / TAG_NAME
    with contextlib.suppress(OSError):
        return stat.S_ISREG(os.lstat(tag).st_mode) and "batcert" in tag.read_text(errors="replace")
    return False


def remove(path: str) -> bool:
    with contextlib.suppress(OSError):
        os.unlink(path)
        return True
    return False


def _files(where: Path) -> list[tuple[str, float, int, str]]:
    """(name, mtime, size, path) of every regular file in ``where`` (links left out)."""
    out = []
    with contextlib.suppress(OSError), os.scandir(where) as it:
        for p in list(it):
            with contextlib.suppress(OSError):
                st = p.stat(follow_symlinks=False)
                if stat.S_ISREG(st.st_mode):
                    out.append((p.name, st.st_mtime, st.st_size, p.path))
    return out


def trim(where: Path, limit: int, names: tuple[re.Pattern, ...] = (ENTRY_NAME,)) -> tuple[int, int]:
    """Least recently used files of ``names`` out of ``where`` until they hold at most
    ``limit`` bytes; a writer's temporary file older than :data:`STALE_TEMP` out. Only
    batcert's own names, only regular files (a link is never followed nor removed). Returns
    the files removed and their bytes."""
    entries, now, removed, freed = [], time.time(), 0, 0
    for name, mtime, size, path in _files(where):
        if any(p.fullmatch(name) for p in names):
            entries.append((mtime, size, path))
        elif TEMP_NAME.fullmatch(name) and now - mtime > STALE_TEMP and remove(path):
            removed, freed = removed + 1, freed + size
    total = sum(size for _, size, _ in entries)
    for _, size, path in sorted(entries):
        if total <= limit:
            break
        if remove(path):
            total, removed, freed = total - size, removed + 1, freed + size
    return removed, freed


@dataclass
class KindUsage:
    """One kind's folder: batcert's entries in it, and other files (not batcert's, kept)."""

    kind: str
    entries: int = 0
    bytes: int = 0
    other_files: int = 0
    limit: int | None = KIND_LIMIT  # None: not trimmed (templates)


@dataclass
class CacheSurvey:
    """What ``batcert cache`` shows: the folder, whether it is batcert's, each kind."""

    root: str
    exists: bool
    batcerts: bool  # it holds batcert's tag (what clear needs)
    kinds: list[KindUsage] = field(default_factory=list)
    kind_limit: int = KIND_LIMIT

    @property
    def bytes(self) -> int:
        return sum(k.bytes for k in self.kinds)

    @property
    def entries(self) -> int:
        return sum(k.entries for k in self.kinds)


def _kind_folders(root: Path) -> list[Path]:
    """The kinds' folders in ``root``: folders, not links, sorted by name."""
    with contextlib.suppress(OSError), os.scandir(root) as it:
        return sorted(Path(e.path) for e in it if e.is_dir(follow_symlinks=False))
    return []


def survey(root: Path | None = None) -> CacheSurvey:
    """The cache directory as it is (nothing made, nothing changed)."""
    root = cache_root() if root is None else root
    out = CacheSurvey(str(root), root.is_dir(), is_batcerts(root))
    for folder in _kind_folders(root):
        usage = KindUsage(folder.name, limit=None if folder.name == "templates" else KIND_LIMIT)
        for name, _, size, _ in _files(folder):
            if own(name) and not TEMP_NAME.fullmatch(name):
                usage.entries, usage.bytes = usage.entries + 1, usage.bytes + size
            elif not own(name):
                usage.other_files += 1
        out.kinds.append(usage)
    return out


def clear(root: Path | None = None) -> tuple[int, int]:
    """Remove every entry batcert wrote in the cache directory (entries, compiled templates,
    a killed writer's stale temporary files), in a top folder that holds batcert's tag only;
    nothing else. Returns the files removed and their bytes; ValueError when the folder is
    not batcert's."""
    root = cache_root() if root is None else root
    if not root.is_dir():
        return 0, 0
    if not is_batcerts(root):
        raise ValueError(f"{root} holds no CACHEDIR.TAG written by batcert: it is not "
                         "batcert's cache, and nothing in it was deleted")
    removed = freed = 0
    for folder in _kind_folders(root):
        n, size = trim(folder, 0, (ENTRY_NAME, TEMPLATE_NAME))
        removed, freed = removed + n, freed + size
    return removed, freed
