"""A set of files switched in one step: readers see the whole old set or the whole new one, even
right after a crash.

The journal of :mod:`batcert.reports.fileset` makes a crashed write whole again, but only when
the next writer comes: in between, a reader could see old and new files side by side. Here the
files of a set (``<stem>.md``, ``<stem>.html``, ``<stem>.json``) are kept in a folder of their
own under ``.batcert-sets/`` and each name in the directory is a relative symbolic link through
one link per stem::

    r.md   -> .batcert-sets/r.current/r.md
    r.html -> .batcert-sets/r.current/r.html
    .batcert-sets/r.current -> r.3f9a1c2e.set     (the one link a write replaces)
    .batcert-sets/r.3f9a1c2e.set/{r.md, r.html, r.json}

A write puts the new files in a fresh ``<stem>.<8 hex>.set`` folder (fsynced), makes sure every
name is a link through ``<stem>.current`` (a name that is still a regular file is first moved
into a folder of the old set, so that nothing a reader sees changes), and then renames a new
``<stem>.current`` link over the old one: that rename is the switch, one step. The old folder
goes afterwards; a crash's leftovers (unused set folders, temporary links) go at the next write
into the directory. A name the set keeps but does not rewrite (``--format md`` after a full
set) is carried into the new folder as it was.

Where symbolic links cannot be made (some Windows accounts, some file systems), or the names
do not share a stem, :mod:`batcert.reports.fileset` writes the set by its journal instead.
"""

from __future__ import annotations

import contextlib
import os
import re
import secrets
import shutil
from pathlib import Path

from batcert.reports.durable import fsync_dir, write_synced

__all__ = ["SETS", "clean", "usable", "write_linked"]

SETS = ".batcert-sets"  # the folder that holds the sets, in the reports' directory
_SET_DIR = re.compile(r"^(?P<stem>.+)\.[0-9a-f]{8}\.set$")
_TEMP_LINK = re.compile(r"^.+\.current\.[0-9a-f]{8}\.tmp$")
_PROBE = re.compile(r"^\.batcert-link-probe\.[0-9a-f]{8}\.tmp$")


def stem_of(names: list[str]) -> str | None:
    """The stem every name shares (``r`` of ``r.md``, ``r.html``), or None."""
    stems = {Path(n).stem for n in names}
    if len(stems) != 1 or len(names) < 2:
        return None
    stem = stems.pop()
    return stem if stem and not stem.startswith(".") else None


def usable(directory: Path) -> bool:
    """Whether symbolic links can be made in ``directory`` (probed once per write) and its
    sets' folder is a folder of its own (not a link to elsewhere, not a file)."""
    sets = directory / SETS
    if sets.is_symlink() or (sets.exists() and not sets.is_dir()):
        return False
    probe = directory / f".batcert-link-probe.{secrets.token_hex(4)}.tmp"
    try:
        os.symlink("nowhere", probe)
    except (OSError, NotImplementedError):
        return False
    with contextlib.suppress(OSError):
        os.unlink(probe)
    return True


def write_linked(directory: Path, stem: str, files: dict[str, bytes],
                 modes: dict[str, int]) -> None:
    """Switch the set ``stem`` of ``directory`` to ``files`` in one step (module notes). The
    caller holds the directory's lock. Raises ``OSError`` with the old set still in place."""
    sets = directory / SETS
    sets.mkdir(exist_ok=True)
    try:
        _switch(directory, sets, stem, files, modes)
    except BaseException:
        with contextlib.suppress(OSError):
            sets.rmdir()  # only if empty: a first write that failed leaves no folder behind
        raise


def _switch(directory: Path, sets: Path, stem: str, files: dict[str, bytes],
            modes: dict[str, int]) -> None:
    current = sets / f"{stem}.current"
    old = _adopt(directory, sets, stem, current, list(files))
    new = sets / f"{stem}.{secrets.token_hex(4)}.set"
    new.mkdir()
    try:
        for name, data in files.items():
            _write(new / name, data, modes[name])
        if old is not None:
            for kept in os.listdir(old):
                if kept not in files:
                    _carry(old / kept, new / kept)
        fsync_dir(new)
        for name in files:
            _link_name(directory, stem, name)
        fsync_dir(directory)
        _replace_link(sets, current, new.name)  # the switch
    except BaseException:
        shutil.rmtree(new, ignore_errors=True)
        raise
    if old is not None and old != new:
        shutil.rmtree(old, ignore_errors=True)


def _adopt(directory: Path, sets: Path, stem: str, current: Path,
           names: list[str]) -> Path | None:
    """The folder of the set now shown (None: there is none). A name being written that is
    still a regular file (a set written before links, or by the journal) is moved first into
    a folder of its own set, each name then linked to it: what a reader sees does not change."""
    shown = _target(current)
    plain = [n for n in names if (directory / n).is_file() and not (directory / n).is_symlink()]
    if not plain:
        return shown
    folder = sets / f"{stem}.{secrets.token_hex(4)}.set"
    folder.mkdir()
    try:
        if shown is not None:
            for kept in os.listdir(shown):
                if kept not in plain:
                    _carry(shown / kept, folder / kept)
        for name in plain:
            _carry(directory / name, folder / name)
        fsync_dir(folder)
        _replace_link(sets, current, folder.name)
    except BaseException:
        shutil.rmtree(folder, ignore_errors=True)
        raise
    for name in plain:
        _link_name(directory, stem, name)
    fsync_dir(directory)
    if shown is not None:
        shutil.rmtree(shown, ignore_errors=True)
    return folder


def _target(current: Path) -> Path | None:
    """The set folder ``current`` points at, if it is one of ours and there."""
    try:
        name = os.readlink(current)
    except OSError:
        return None
    folder = current.parent / name
    return folder if _SET_DIR.match(name) and folder.is_dir() else None


def _link_name(directory: Path, stem: str, name: str) -> None:
    """Make ``directory/name`` the link through the stem's current set (replacing a regular
    file or another link in one rename)."""
    want = f"{SETS}/{stem}.current/{name}"
    path = directory / name
    with contextlib.suppress(OSError):
        if os.readlink(path) == want:
            return
    _put_link(want, path, directory / f".{name}.batcert-{secrets.token_hex(4)}.tmp")


def _replace_link(sets: Path, current: Path, target: str) -> None:
    _put_link(target, current, sets / f"{current.name}.{secrets.token_hex(4)}.tmp")
    fsync_dir(sets)


def _put_link(target: str, path: Path, tmp: Path) -> None:
    """``path`` a link to ``target`` in one rename (made as ``tmp`` first, removed on failure)."""
    os.symlink(target, tmp)
    try:
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _write(path: Path, data: bytes, mode: int) -> None:
    """A new file of a new set folder, durable, with the set's permission bits."""
    write_synced(path, data, os.O_CREAT | os.O_EXCL)
    os.chmod(path, mode)


def _carry(source: Path, target: Path) -> None:
    """``source`` into a new set folder as it is: a hard link, else a copy."""
    try:
        os.link(source, target)
    except OSError:
        shutil.copy2(source, target)


def clean(directory: Path) -> None:
    """Remove what a crashed write left in ``directory``: links of ours whose set was never
    switched in (and a link probe), then in its sets' folder the set folders no stem shows and
    temporary links."""
    for entry in directory.iterdir():
        if entry.is_symlink() and not entry.exists():
            with contextlib.suppress(OSError):
                if os.readlink(entry).startswith(f"{SETS}/") or _PROBE.match(entry.name):
                    entry.unlink()
    sets = directory / SETS
    if not sets.is_dir() or sets.is_symlink():
        return
    shown = {t.name for c in sets.iterdir() if c.name.endswith(".current")
             for t in [_target(c)] if t is not None}
    for entry in sets.iterdir():
        if _TEMP_LINK.match(entry.name) and entry.is_symlink():
            entry.unlink()
        elif _SET_DIR.match(entry.name) and entry.name not in shown and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
