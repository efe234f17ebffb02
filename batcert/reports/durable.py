"""Writes that survive a crash, shared by the report writers (:mod:`batcert.reports.fileset`,
:mod:`batcert.reports.linkset`): a file's content flushed to the disk, and a directory's
renames made durable."""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["fsync_dir", "write_synced"]


def write_synced(path: Path, data: bytes, flags: int = 0) -> None:
    """``data`` as the whole content of ``path`` (``flags``: os.O_CREAT where it may not exist
    yet), flushed and fsynced; never through a link."""
    fd = os.open(path, os.O_WRONLY | os.O_TRUNC | os.O_NOFOLLOW | flags, 0o600)
    with os.fdopen(fd, "wb") as fh:
        fh.write(data)
        fh.flush()
        os.fsync(fh.fileno())


def fsync_dir(directory: Path) -> None:
    """Make the renames durable (POSIX); silently skipped where directories cannot be opened."""
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
