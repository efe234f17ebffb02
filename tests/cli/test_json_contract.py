"""One JSON contract: every command's --json prints the same envelope (schema, command,
batcert_version, results as a list), and every result document starts with schema and kind
(docs/results-json.md)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from jsonout import results

from batcert import __version__

REPO = Path(__file__).resolve().parents[2]
SESSION = REPO / "examples" / "lab" / "synthetic-exact.yaml"
RIGID = ("--engine", "rigid")

COMMANDS = {
    "run": (["run", "ash-34", "-p", "ncaa-bbcor", "-p", "proposed", *RIGID], "run", 2),
    "compare": (["compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", *RIGID], "comparison", 1),
    "league": (["league", "mlb", "ash-34", *RIGID], "league", 1),
    "field": (["field", "aluminium-34", "--batter", "pro", *RIGID], "field", 1),
    "sweep": (["sweep", "ash-34", "-p", "ncaa-bbcor", "--vary", "pitch_speed=50m/s:60m/s:2",
               *RIGID], "sweep", 1),
    "design": (["design", "ash-34", "-p", "ncaa-bbcor", "--solve", "pitch_speed", "--range",
                "40m/s:75m/s", "--points", "3", *RIGID], "design", 1),
    "reduce": (["reduce", SESSION, "-p", "ncaa-bbcor", *RIGID], "lab", 1),
    "inspect": (["inspect", "ash-34"], None, 1),
    "validate": (["validate", "ash-34", "ncaa-bbcor"], None, 2),
    "protocols": (["protocols"], None, 10),
    "list": (["list"], None, 6),  # bats, balls, protocols, leagues, studies, batters
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_command_prints_the_one_envelope(batcert_cli, command):
    argv, kind, n = COMMANDS[command]
    res = batcert_cli(*argv, "--json")
    assert res.exit_code in (0, 1), res.stderr
    data = json.loads(res.stdout)
    assert data["batcert_version"] == __version__
    docs = results(res.stdout, command)  # checks schema, command and the key order
    assert isinstance(docs, list) and len(docs) == n
    if kind is not None:
        for doc in docs:
            assert list(doc)[:2] == ["schema", "kind"]
            assert doc["schema"] == "batcert/1" and doc["kind"] == kind


def test_a_written_json_report_is_a_document_of_the_contract(batcert_cli, tmp_path):
    res = batcert_cli("league", "mlb", "ash-34", *RIGID, "--format", "json", "--out", tmp_path)
    assert res.exit_code == 0, res.stderr
    [path] = tmp_path.glob("league--*.json")
    doc = json.loads(path.read_text(encoding="utf-8"))
    assert (doc["schema"], doc["kind"]) == ("batcert/1", "league")
