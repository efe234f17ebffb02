"""The README's lists of shipped things match what ships (issue 40, item 14f): every shipped
input of every kind is named in its bullet of "Shipped inputs", and nothing else; every
document in docs/ is in "Documentation", and nothing else."""

from __future__ import annotations

import re
from pathlib import Path

from batcert.specs.resolve import KINDS, shipped_names

REPO = Path(__file__).resolve().parents[1]
README = (REPO / "README.md").read_text(encoding="utf-8")
FOLDERS = {"bats/": "bat", "protocols/": "protocol", "protocols/balls/": "ball",
           "protocols/leagues/": "league", "protocols/studies/": "study",
           "protocols/batters/": "batter"}
NAME = re.compile(r"[a-z0-9][a-z0-9-]*")


def _section(start: str) -> str:
    """README text from the line starting with ``start`` to the next blank line before a
    heading or a paragraph that is no bullet."""
    at = README.index(start)
    end = README.find("\n## ", at)
    return README[at:end if end >= 0 else len(README)]


def _bullets(text: str) -> list[str]:
    """The bullets of a section, each with its continuation lines."""
    out: list[str] = []
    for line in text.splitlines():
        if line.startswith("- "):
            out.append(line[2:])
        elif line.startswith("  ") and out:
            out[-1] += " " + line.strip()
    return out


def test_every_shipped_input_is_listed_by_its_name():
    listed: dict[str, set[str]] = {}
    for bullet in _bullets(_section("Shipped inputs")):
        folder, *rest = re.findall(r"`([^`]+)`", bullet)
        assert folder in FOLDERS, f"a bullet of Shipped inputs starts with {folder!r}"
        listed[FOLDERS[folder]] = {t for t in rest if NAME.fullmatch(t)}
    assert sorted(listed) == sorted(KINDS)
    for kind in KINDS:
        assert listed[kind] == set(shipped_names(kind)), kind


def test_every_document_is_listed():
    listed = set(re.findall(r"`docs/([a-z0-9-]+\.md)`", _section("## Documentation")))
    assert listed == {p.name for p in (REPO / "docs").glob("*.md")}


def test_the_tour_names_only_shipped_inputs():
    """Each shipped name in the tour's commands (a word that is a shipped input's name, or a
    bats/ or protocols/ path) exists."""
    tour = _section("## A short tour")
    for path in re.findall(r"\b((?:bats|protocols|examples)/[\w./-]+\.(?:yaml|csv))", tour):
        assert (REPO / path).is_file(), path
    known = {n for kind in KINDS for n in shipped_names(kind)}
    for line in tour.splitlines():
        command = line.split("#")[0].split()
        for flag, value in zip(command, command[1:], strict=False):
            if flag in ("-p", "--protocol", "--study", "--batter") and value != "all":
                assert value in known, line
