"""The docs' tables that restate a registry are generated from it (scripts/gen_doc_tables.py)
and must be current: a new sweep parameter is one registry entry, and its row follows."""

from __future__ import annotations

import pytest
from repo_script import REPO, load


def _generator():
    return load("scripts/gen_doc_tables.py")


def test_the_generated_tables_are_current():
    """If this fails, run `python scripts/gen_doc_tables.py` and commit the docs."""
    gen = _generator()
    for name, (doc, _) in gen.TABLES.items():
        text = (REPO / doc).read_text(encoding="utf-8")
        assert gen.generate(name, text) == text, f"{doc}: table {name} is out of date"


def test_every_sweep_parameter_has_its_row():
    from batcert.sweeps.variants import PARAMETERS
    text = (REPO / "docs" / "sweeps.md").read_text(encoding="utf-8")
    for p in PARAMETERS.values():
        assert f"| `{p.name}` | " in text


def test_a_new_registry_entry_makes_the_table_stale(monkeypatch):
    from dataclasses import replace

    from batcert.sweeps import variants
    gen = _generator()
    text = (REPO / "docs" / "sweeps.md").read_text(encoding="utf-8")
    extra = replace(variants.PARAMETERS["density"], name="made_up", doc="A test's parameter.")
    monkeypatch.setitem(variants.PARAMETERS, "made_up", extra)
    new = gen.generate("sweep-parameters", text)
    assert new != text and "| `made_up` | density | geometry | A test's parameter. |" in new


def test_a_document_without_its_region_is_refused():
    gen = _generator()
    with pytest.raises(ValueError, match="no region"):
        gen.generate("sweep-parameters", "# no table here\n")
