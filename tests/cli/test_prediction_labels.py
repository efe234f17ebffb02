"""A model prediction is not a certificate (issue 24): `run` says "predicted" on its verdict in
the terminal, the reports and the JSON, with the model's known offset for the metric from
docs/validation.md; only `reduce`, from measured hits, issues a certificate."""

from __future__ import annotations

import json
from pathlib import Path

from terminal_lines import items

from batcert.methods.metrics import METRICS

LAB = Path(__file__).resolve().parents[2] / "examples" / "lab"


def test_run_says_predicted_and_states_the_models_offset(batcert_cli):
    res = batcert_cli("run", "aluminium-34", "-p", "ncaa-bbcor", "--no-reports")
    first, second, third = items(res.stdout)[:3]  # (each may wrap at the width)
    assert first.startswith("predicted FAIL  Aluminium 34 in")  # the model's verdict, said so
    assert second.lstrip().startswith("predicted BBCOR") and "[model: engine flexible" in second
    assert third.strip() == f"known offset of the model: {METRICS['bbcor'].model_offset}"


def test_the_json_names_its_statement_and_offset(batcert_cli):
    data = json.loads(batcert_cli("run", "ash-34", "-p", "ncaa-besr", "--json").stdout)
    data = data["results"][0]
    assert data["statement"] == "predicted"
    assert data["model_offset"] == METRICS["besr"].model_offset != ""
    # a metric no published level anchors carries no offset
    data = json.loads(batcert_cli("run", "ash-34", "-p", "proposed", "--json").stdout)
    data = data["results"][0]
    assert data["statement"] == "predicted" and data["model_offset"] == ""


def test_a_lab_certificate_stays_a_measured_verdict(batcert_cli):
    res = batcert_cli("reduce", LAB / "synthetic-exact.yaml", "-p", "ncaa-bbcor",
                      "--no-reports")
    assert res.stdout.splitlines()[0].startswith("PASS  Lab certificate:")
    assert "predicted" not in res.stdout.splitlines()[0]


def test_a_league_performance_rule_is_a_prediction_and_a_dimension_rule_is_not(batcert_cli,
                                                                                tmp_path):
    res = batcert_cli("league", "ncaa", "bbcor-alloy-34", "--out", tmp_path)
    first = res.stdout.splitlines()[0]
    assert first.startswith("predicted FAIL"), first  # the model's BBCOR decides
    lines = [ln.split() for ln in res.stdout.splitlines() if ln.strip().startswith("verdict")]
    assert ["verdict", "PASS"] in lines and ["verdict", "predicted", "FAIL"] in lines
    [md] = tmp_path.glob("league--*.md")
    assert "predicted FAIL" in md.read_text(encoding="utf-8")
    assert "model's prediction from the bat file" in md.read_text(encoding="utf-8")
    wood = batcert_cli("league", "mlb", "ash-34", "--engine", "rigid", "--no-reports")
    assert wood.stdout.startswith("PASS")  # no performance rule: the file's numbers decide


def test_a_comparison_limit_verdict_is_a_prediction(batcert_cli, tmp_path):
    batcert_cli("compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "--out", tmp_path)
    [md] = tmp_path.glob("compare--*.md")
    text = md.read_text(encoding="utf-8")
    assert "predicted FAIL" in text and " FAIL" not in text.replace("predicted FAIL", "")
    assert "predicted PASS" in text and " PASS" not in text.replace("predicted PASS", "")
