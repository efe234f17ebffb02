"""Shipped inputs' texts (descriptions, notes) speak to their readers about the bat, the test and
the model, not about batcert's development: no issue numbers, no earlier versions' figures
(those belong in CHANGELOG.md and docs/validation.md)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SHIPPED = sorted([*REPO.glob("bats/*.yaml"), *REPO.glob("protocols/**/*.yaml")])
HISTORY = re.compile(r"\bissue \d+|\bbatcert \d+\.\d+|\bthis session\b|\bwas fixed\b", re.I)


@pytest.mark.parametrize("path", SHIPPED, ids=[p.name for p in SHIPPED])
def test_a_shipped_input_tells_no_development_history(path):
    hits = [f"{i}: {line.strip()}" for i, line in
            enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if HISTORY.search(line)]
    assert hits == []
