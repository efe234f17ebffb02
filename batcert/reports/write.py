"""Render reports in memory, then write them atomically: a reader never sees half a report.

All requested formats are rendered before anything touches the disk, so a rendering error writes
nothing. Each file is then staged as a temporary file in the target directory (flushed and
fsynced) and only when every file is staged are they moved onto their targets with
``os.replace``. On any error the temporary files are removed and existing reports stay as they
were.
"""

from __future__ import annotations

import os
import re
import tempfile
import unicodedata
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from batcert.results import RunResult


def _markdown(result: RunResult) -> str:
    from batcert.reports.markdown import render_markdown

    return render_markdown(result)


def _html(result: RunResult) -> str:
    from batcert.reports.html import render_html

    return render_html(result)


def _json(result: RunResult) -> str:
    return result.to_json() + "\n"


# format -> (file suffix, renderer); renderers are imported lazily to keep start-up fast
FORMATS: dict[str, tuple[str, Callable[[RunResult], str]]] = {
    "md": (".md", _markdown),
    "html": (".html", _html),
    "json": (".json", _json),
}


def render(result: RunResult, fmt: str) -> str:
    """One report as text: ``fmt`` is ``"md"``, ``"html"`` or ``"json"``."""
    if fmt not in FORMATS:
        raise ValueError(f"unknown report format {fmt!r} (choose from {', '.join(FORMATS)})")
    return FORMATS[fmt][1](result)


def slugify(text: str, fallback: str = "report") -> str:
    """``"Ash 34 in (R161)"`` -> ``"ash-34-in-r161"``: ASCII, lower case, safe in file names."""
    ascii_text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    slug = re.sub(r"[^a-z0-9]+", "-", ascii_text.lower()).strip("-")
    return slug or fallback


def default_stem(result: RunResult) -> str:
    """``<bat-slug>--<protocol-id>``, e.g. ``ash-34-in--proposed``."""
    return f"{slugify(result.bat, 'bat')}--{slugify(result.protocol, 'protocol')}"


def write_reports(
    result: RunResult,
    out_dir: Path,
    formats: Sequence[str] = ("md", "html", "json"),
    stem: str | None = None,
) -> list[Path]:
    """Render ``result`` in each format and write ``out_dir/<stem>.<ext>`` atomically.

    Returns the written paths in the order of ``formats`` (duplicates dropped). ``out_dir`` is
    created when missing. Raises ``ValueError`` for an unknown format or a stem that is not a
    plain file name; any rendering or writing error propagates after cleaning up, leaving no
    partial or temporary file and existing reports untouched.
    """
    wanted = list(dict.fromkeys(formats))
    unknown = [f for f in wanted if f not in FORMATS]
    if unknown:
        raise ValueError(f"unknown report format(s) {', '.join(map(repr, unknown))} "
                         f"(choose from {', '.join(FORMATS)})")
    stem = default_stem(result) if stem is None else stem
    if not stem or stem in (".", "..") or "/" in stem or "\\" in stem or "\0" in stem:
        raise ValueError(f"report stem {stem!r} must be a plain file name")

    out_dir = Path(out_dir)
    return write_texts({out_dir / f"{stem}{FORMATS[f][0]}": render(result, f) for f in wanted})


def write_texts(texts: dict[Path, str]) -> list[Path]:
    """Write already-rendered reports: every file is staged before the first one replaces its
    target, and each replacement is atomic. Parent directories are created."""
    for directory in {Path(p).parent for p in texts}:
        directory.mkdir(parents=True, exist_ok=True)
    _write_all({Path(p): t for p, t in texts.items()})
    return [Path(p) for p in texts]


def atomic_write_text(path: Path, text: str, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` so that readers see either the old file or the whole new one."""
    path = Path(path)
    _write_all({path: text}, encoding)
    return path


def _write_all(texts: dict[Path, str], encoding: str = "utf-8") -> None:
    staged: list[tuple[str, Path]] = []
    try:
        for target, text in texts.items():
            staged.append((_stage(target, text.encode(encoding)), target))
        for tmp, target in staged:
            os.replace(tmp, target)
    except BaseException:
        for tmp, _ in staged:
            _unlink_quietly(tmp)
        raise
    for directory in {target.parent for target in texts}:
        _fsync_dir(directory)


def _stage(target: Path, data: bytes) -> str:
    """Write ``data`` to a fsynced temporary file next to ``target``; return its path."""
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, _mode_for(target))
    except BaseException:
        _unlink_quietly(tmp)
        raise
    return tmp


def _mode_for(target: Path) -> int:
    """Keep an existing report's permissions; a new one gets the usual 0o666 minus the umask
    (mkstemp alone would leave it readable by the owner only)."""
    try:
        return target.stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


def _unlink_quietly(path: str) -> None:
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass


def _fsync_dir(directory: Path) -> None:
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
