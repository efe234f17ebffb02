"""`batcert league`: per-bat rule tables, exit codes, clean --json and written reports."""

from __future__ import annotations

import json
from pathlib import Path

from jsonout import result as result_of

REPO = Path(__file__).resolve().parents[2]
ASH = REPO / "bats" / "ash-34.yaml"
ALU = REPO / "bats" / "aluminium-34.yaml"
R161 = REPO / "bats" / "r161.yaml"


def test_help_lists_exit_codes(batcert_cli):
    result = batcert_cli("league", "--help")
    assert result.exit_code == 0
    text = " ".join(result.stdout.split())
    for needle in ("0 every bat passes every rule", "1 a rule fails, or a rule is not modelled",
                   "2 usage error", "3 invalid input"):
        assert needle in text


def test_mlb_json_shape(batcert_cli):
    result = batcert_cli("league", "mlb", ASH, ALU, "--engine", "rigid", "--json",
                         "--no-reports")
    assert result.exit_code == 1  # aluminium fails MLB's one-piece solid wood rule
    data = result_of(result.stdout, "league")
    assert data["league"] == "mlb"
    assert [b["verdict"] for b in data["bats"]] == ["pass", "fail"]
    for bat in data["bats"]:
        assert [r["rule"] for r in bat["rules"]] == ["length", "diameter", "solid", "wood"]
        for r in bat["rules"]:
            assert {"rule", "value", "limit", "verdict"} <= set(r)
    ash = {r["rule"]: r for r in data["bats"][0]["rules"]}
    assert ash["length"]["value"] == 0.86 and ash["length"]["limit"] == 42 * 0.0254


def test_rigid_engine_warning_is_the_engines_own(batcert_cli):
    """The league's rigid-engine warning is the engine's (one text for league, sweep and
    design), once per bat."""
    from batcert.engines.rigid import RigidEngine
    result = batcert_cli("league", "ncaa", ALU, "--engine", "rigid", "--json", "--no-reports")
    data = result_of(result.stdout, "league")
    (bat,) = data["bats"]
    assert bat["warnings"].count(RigidEngine.construction_warning) == 1


def test_passing_bats_exit_0(batcert_cli):
    # MLB needs no protocol run, so the default engine is not used
    result = batcert_cli("league", "mlb", ASH, R161, "--no-reports")
    assert result.exit_code == 0, result.stderr
    assert "PASS" in result.stdout


def test_not_modelled_exits_1_unless_allowed(batcert_cli):
    args = ("league", "usa-baseball", ASH, ALU, "--engine", "rigid", "--no-reports")
    result = batcert_cli(*args)
    assert result.exit_code == 1
    assert "NOT MODELLED" in result.stdout and "INCOMPLETE" in result.stdout
    assert batcert_cli(*args, "--allow-not-modelled").exit_code == 0


def test_reports_written(batcert_cli, tmp_path):
    out = tmp_path / "r"
    result = batcert_cli("league", "ncaa", ASH, ALU, R161, "--engine", "rigid", "--out", out)
    assert result.exit_code == 1
    stem = "league--ncaa--ash-34-aluminium-34-r161"
    assert sorted(p.name for p in out.glob("[!.]*")) == [f"{stem}.html", f"{stem}.json",
                                                     f"{stem}.md"]
    md = (out / f"{stem}.md").read_text()
    assert "NOT MODELLED" in md and "not applicable" in md and "FAIL" in md
    saved = json.loads((out / f"{stem}.json").read_text())
    assert len(saved["bats"]) == 3


def test_usage_and_input_errors(batcert_cli, tmp_path):
    assert batcert_cli("league", "nosuch", ASH).exit_code == 2
    assert batcert_cli("league", "mlb").exit_code == 2  # no bat
    assert batcert_cli("league", "ncaa", ALU, "--engine", "warp",
                       "--no-reports").exit_code == 2
    bad = tmp_path / "league.yaml"
    bad.write_text('id: x\ntitle: X\nreference: r\nversion: "1"\nrules:\n'
                   "  - id: l\n    kind: max-length\n    limit: 36\n    source: s\n"
                   "    confidence: M\n")
    result = batcert_cli("league", bad, ASH, "--out", tmp_path / "out")
    assert result.exit_code == 3 and "a unit is required" in result.stderr
    assert not (tmp_path / "out").exists()
