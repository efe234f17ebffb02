"""Inside a batcert source checkout, a shipped name whose checkout copy differs from the
installed one resolves to the checkout's copy and says so; an identical copy changes nothing."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from batcert.specs import resolve as resolving

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def checkout(tmp_path, monkeypatch):
    """A second checkout (not the one batcert runs from) as the working directory."""
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "batcert"\n', encoding="utf-8")
    (tmp_path / "bats").mkdir()
    monkeypatch.chdir(tmp_path)
    notes: list[str] = []
    resolving.set_notifier(notes.append)
    yield tmp_path, notes
    resolving.set_notifier(None)


def test_a_differing_checkout_copy_is_used_and_named(checkout):
    root, notes = checkout
    mine = root / "bats" / "ash-34.yaml"
    mine.write_text((REPO / "bats" / "ash-34.yaml").read_text(encoding="utf-8") + "# edited\n",
                    encoding="utf-8")
    assert resolving.resolve("bat", "ash-34") == root / "bats" / "ash-34.yaml"
    assert len(notes) == 1 and "this checkout's bats/ash-34.yaml" in notes[0]


def test_an_identical_checkout_copy_changes_nothing(checkout):
    root, notes = checkout
    shutil.copy(REPO / "bats" / "ash-34.yaml", root / "bats" / "ash-34.yaml")
    assert resolving.resolve("bat", "ash-34").parent != root / "bats"
    assert notes == []


def test_outside_a_checkout_the_installed_copy_is_used(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert resolving.resolve("bat", "ash-34").name == "ash-34.yaml"
    assert resolving._checkout_of_cwd() is None
