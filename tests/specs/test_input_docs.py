"""docs/inputs.md is generated from the schemas (scripts/gen_input_docs.py) and must be current."""

from __future__ import annotations

from repo_script import REPO, load


def _generator():
    return load("scripts/gen_input_docs.py")


def test_inputs_md_is_current():
    """If this fails, run `python scripts/gen_input_docs.py` and commit docs/inputs.md."""
    committed = (REPO / "docs" / "inputs.md").read_text(encoding="utf-8")
    assert committed == _generator().generate()


def test_every_field_is_documented():
    """Every field of every (nested) schema appears in a table row, with a meaning."""
    from batcert.specs.ball import BALL_SCHEMA
    from batcert.specs.bat import BAT_SCHEMA
    from batcert.specs.protocol import PROTOCOL_SCHEMA
    text = _generator().generate()

    def walk(schema):
        for f in schema.fields:
            assert f.doc.strip(), f"{schema.title}.{f.name} has no doc"
            assert f"| `{f.name}` | {f.doc} |" in text
            if f.kind.schema is not None:
                assert f.kind.schema.title in text
                walk(f.kind.schema)

    for schema in (BAT_SCHEMA, BALL_SCHEMA, PROTOCOL_SCHEMA):
        walk(schema)


def test_check_mode(tmp_path, monkeypatch):
    gen = _generator()
    monkeypatch.setattr(gen, "TARGET", tmp_path / "docs" / "inputs.md")
    monkeypatch.setattr(gen, "ROOT", tmp_path)
    assert gen.main(["--check"]) == 1  # missing: out of date
    assert gen.main([]) == 0
    assert gen.main(["--check"]) == 0
