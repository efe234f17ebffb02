"""Shipped names (issue 24): they compare case-insensitively, and a mistyped one is answered
with the name it most likely meant ('alu-34' suggested 'ash-34', by spelling alone)."""

from __future__ import annotations

import pytest

from batcert.specs.resolve import NotFound, resolve, shipped_names


def test_names_compare_case_insensitively():
    assert resolve("bat", "ASH-34") == resolve("bat", "ash-34") == shipped_names("bat")["ash-34"]
    assert resolve("protocol", "NCAA-BBCOR") == shipped_names("protocol")["ncaa-bbcor"]


@pytest.mark.parametrize("typed, meant", [
    ("alu-34", "aluminium-34"),  # what was typed before the dash starts the name
    ("aluminum-34", "aluminium-34"),
    ("ash34", "ash-34"),
    ("bbcor-alloy", "bbcor-alloy-34"),
    ("r-161", "r161"),
])
def test_a_mistyped_name_suggests_the_one_meant(typed, meant):
    with pytest.raises(NotFound, match=f"did you mean '{meant}'"):
        resolve("bat", typed)


def test_nothing_close_suggests_nothing():
    with pytest.raises(NotFound) as exc:
        resolve("bat", "zzzz")
    assert "did you mean" not in str(exc.value)
