"""Shared test helpers: an edited copy of an input file, and the line a text stands on."""

from __future__ import annotations

from pathlib import Path


def edited(tmp_path: Path, source: Path, *changes: tuple[str, str], name: str = "") -> Path:
    """``source`` with each (old, new) replaced once, written to tmp_path."""
    text = source.read_text(encoding="utf-8")
    for old, new in changes:
        assert text.count(old) == 1, f"{old!r} is not once in {source.name}"
        text = text.replace(old, new)
    path = tmp_path / (name or source.name)
    path.write_text(text, encoding="utf-8")
    return path


def line_of(path: Path, start: str) -> int:
    """1-based number of the only line of ``path`` that starts with ``start``."""
    hits = [i for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
            if line.startswith(start)]
    assert len(hits) == 1, (start, hits)
    return hits[0]
