"""Replace a set of files in one directory whole or not at all, even across a crash.

A set of files cannot be renamed into place in one step, so each set is written as a small
transaction, under an exclusive lock on the directory (concurrent writers take turns):

1. every new file is *staged* as a hidden, fsynced temporary file next to its target, and each
   existing target gets a hidden hard link (its *backup*);
2. a *journal* naming the staged files, targets and backups is written (staged, fsynced and
   renamed into place): this is the commit point;
3. the staged files are renamed onto their targets; then the backups and the journal go.

A process killed before step 2 leaves only hidden files: the old set is whole. Killed after it,
the journal says how to finish: the next writer into the directory (:func:`recover`) renames the
staged files that are still there onto their targets, so it finds the whole new set. An error
inside a living process after the commit point (a rename refused) rolls back instead: the
journal is marked ``rollback`` and the backups are renamed back, which a crash can also interrupt
and :func:`recover` finish. Either way recovery then removes what a crash left behind: the
hidden staging, backup and probe files of batcert, never anything else.

A set of several files with one stem (a report's ``.md``, ``.html`` and ``.json``) is not
written this way where symbolic links can be made: :mod:`batcert.reports.linkset` switches it
in one step, so that readers never see old and new files side by side, even right after a
crash. The journal serves single files and the rest; there, readers between a crash and the
next write can see a mixed set. This module knows nothing of reports;
:mod:`batcert.reports.write` uses it.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import secrets
import shutil
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from batcert.reports.durable import fsync_dir, write_synced

__all__ = ["recover", "write_set"]

JOURNAL_PREFIX = ".batcert-set."
JOURNAL_SUFFIX = ".journal"
FORMAT = "batcert-fileset/1"
TAG = "batcert-"
# the hidden files batcert creates and a crash can leave: this module's staged files and
# backups (".<name>.batcert-<8 hex>.tmp|.bak") and journals, the output probe
# (".batcert-probe.<8>.tmp"), and the staged files and backups of batcert 0.2's writer
# (".<report name>.<8>.tmp|.bak"; only beside a report's or a figure's kind of name)
_LEFTOVER = re.compile(r"^\..+\.batcert-[0-9a-f]{8}\.(tmp|bak)$"
                       r"|^\.batcert-set\.[0-9a-f]{8}\.journal(\.tmp)?$"
                       r"|^\.batcert-probe\.[a-z0-9_]{8}\.tmp$"
                       r"|^\..+\.(md|html|json|yaml|png|svg|pdf)\.[a-z0-9_]{8}\.(tmp|bak)$")


@dataclass
class _Entry:
    target: str           # file name in the directory
    staged: str           # hidden staged file name
    backup: str | None    # hidden hard link to the old target, if there was one


def write_set(directory: Path, files: dict[str, bytes], modes: dict[str, int]) -> None:
    """Replace ``directory/<name>`` by ``files[name]`` for every name, as one set (module
    notes); ``modes`` gives each new file's permission bits. Finishes or undoes what an earlier
    crash left in ``directory`` first. Raises ``OSError`` with the set as it was before."""
    from batcert.reports import linkset
    directory = Path(directory)
    with _locked(directory):
        _recover_locked(directory)
        stem = linkset.stem_of(list(files))
        if stem is not None and linkset.usable(directory):
            linkset.write_linked(directory, stem, files, modes)  # one step, no journal
            return
        entries: list[_Entry] = []
        journal = Path(_reserve(directory, JOURNAL_PREFIX, JOURNAL_SUFFIX))
        try:
            for name, data in files.items():
                entries.append(_Entry(name, _stage(directory, name, data, modes[name]), None))
            for entry in entries:
                entry.backup = _backup(directory, entry.target)
            _write_journal(directory, journal, "commit", entries)
        except BaseException:
            _discard(directory, entries, journal)
            raise
        try:
            for entry in entries:
                os.replace(directory / entry.staged, directory / entry.target)
        except KeyboardInterrupt:
            _finish(directory, journal, entries)  # committed: a Ctrl-C still gets the new set
            raise
        except BaseException:
            with contextlib.suppress(BaseException):  # if this fails, the next writer finishes
                _write_journal(directory, journal, "rollback", entries)
                _roll_back(directory, entries)
                _remove(journal)
                fsync_dir(directory)
            raise
        _finish(directory, journal, entries)


def recover(directory: Path) -> None:
    """Finish or undo, under the directory's lock, any set a crashed writer left in
    ``directory``, and remove batcert's leftover hidden files there (module notes)."""
    directory = Path(directory)
    if directory.is_dir():
        with _locked(directory):
            _recover_locked(directory)


def _recover_locked(directory: Path) -> None:
    names = os.listdir(directory)
    journals = [n for n in names if n.startswith(JOURNAL_PREFIX) and n.endswith(JOURNAL_SUFFIX)]
    for name in sorted(journals):
        try:
            doc = json.loads((directory / name).read_text(encoding="utf-8"))
            if doc.get("format") != FORMAT:
                continue  # not ours to interpret: leave it alone
            entries = [_Entry(e["target"], e["staged"], e.get("backup"))
                       for e in doc["entries"]]
            state = doc["state"]
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            continue
        if not all(_plain(e.target) and _plain(e.staged) and (e.backup is None or _plain(e.backup))
                   for e in entries):
            continue
        if state == "commit":
            _finish(directory, directory / name, entries)
        elif state == "rollback":
            _roll_back(directory, entries)
            _remove(directory / name)
    for name in os.listdir(directory):
        if _LEFTOVER.match(name) and (directory / name).is_file():
            _remove(directory / name)
    from batcert.reports.linkset import clean
    clean(directory)
    fsync_dir(directory)


def _finish(directory: Path, journal: Path, entries: list[_Entry]) -> None:
    """Roll forward: every staged file still there goes onto its target; then the backups and
    the journal go. Safe to repeat."""
    for entry in entries:
        if (directory / entry.staged).exists():
            os.replace(directory / entry.staged, directory / entry.target)
    fsync_dir(directory)
    for entry in entries:
        if entry.backup:
            _remove(directory / entry.backup)
    _remove(journal)
    fsync_dir(directory)


def _roll_back(directory: Path, entries: list[_Entry]) -> None:
    """Put every old target back from its backup and remove the new files. Safe to repeat."""
    for entry in entries:
        target, staged = directory / entry.target, directory / entry.staged
        if entry.backup and (directory / entry.backup).exists():
            # renaming a hard link onto its twin does nothing (POSIX), hence the removal
            os.replace(directory / entry.backup, target)
            _remove(directory / entry.backup)
        elif not entry.backup and not staged.exists():
            _remove(target)  # a new file that was moved in
        _remove(staged)
    fsync_dir(directory)


def _discard(directory: Path, entries: list[_Entry], journal: Path) -> None:
    """Before the commit point: remove what was staged; the targets were never touched."""
    _remove(journal)
    for entry in entries:
        _remove(directory / entry.staged)
        if entry.backup:
            _remove(directory / entry.backup)


def _write_journal(directory: Path, journal: Path, state: str, entries: list[_Entry]) -> None:
    """Write the journal whole (staged beside it, then renamed over it) and make it durable."""
    doc = {"format": FORMAT, "state": state,
           "entries": [{"target": e.target, "staged": e.staged, "backup": e.backup}
                       for e in entries]}
    tmp = journal.with_name(journal.name + ".tmp")
    try:
        write_synced(tmp, (json.dumps(doc, indent=1) + "\n").encode(), os.O_CREAT)
        os.replace(tmp, journal)
    except BaseException:
        _remove(tmp)
        raise
    fsync_dir(directory)


def _stage(directory: Path, name: str, data: bytes, mode: int) -> str:
    """Write ``data`` to a fsynced hidden file next to ``name``; return its name."""
    tmp = Path(_reserve(directory, f".{name}.{TAG}", ".tmp"))
    try:
        write_synced(tmp, data)
        os.chmod(tmp, mode)
    except BaseException:
        _remove(tmp)
        raise
    return tmp.name


def _backup(directory: Path, name: str) -> str | None:
    """A hidden hard link to the existing target (a copy where links are refused), or None."""
    target = directory / name
    if not target.is_file():
        return None
    backup = Path(_reserve(directory, f".{name}.{TAG}", ".bak"))
    try:
        backup.unlink()
        try:
            os.link(target, backup)
        except OSError:
            shutil.copy2(target, backup)
    except BaseException:
        _remove(backup)
        raise
    return backup.name


def _reserve(directory: Path, prefix: str, suffix: str) -> str:
    """A fresh file name ``prefix<8 random characters>suffix`` in ``directory``, created."""
    for _ in range(100):
        name = f"{prefix}{secrets.token_hex(4)}{suffix}"
        try:
            fd = os.open(directory / name, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        except FileExistsError:
            continue
        os.close(fd)
        return str(directory / name)
    raise FileExistsError(f"no free temporary name in {directory}")


def _plain(name: object) -> bool:
    return isinstance(name, str) and bool(name) and "/" not in name and "\0" not in name \
        and name not in (".", "..")


def _remove(path: Path) -> None:
    with contextlib.suppress(FileNotFoundError, IsADirectoryError):
        os.unlink(path)


@contextlib.contextmanager
def _locked(directory: Path) -> Iterator[None]:
    """An exclusive advisory lock on the directory itself (released if the process dies);
    where directories cannot be locked, writers are not serialised."""
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        yield
        return
    try:
        try:
            import fcntl
            fcntl.flock(fd, fcntl.LOCK_EX)
        except (ImportError, OSError):
            pass
        yield
    finally:
        os.close(fd)
