"""The model's known offset and "predicted" wherever a model verdict or prediction appears
(issue 40, item 11): `league` and `field` showed no offset, `run -q` hid it, and a league bat
that failed a geometric rule was a "predicted FAIL" though no model decided it."""

from __future__ import annotations

import json

from batcert.inplay.evaluate import MODEL_OFFSET
from batcert.methods.metrics import METRICS


def flat(text: str) -> str:
    """``text`` with its wrapping undone (terminal output wraps at the width)."""
    return " ".join(text.split())


def test_run_quiet_keeps_the_offset(batcert_cli):
    res = batcert_cli("run", "ash-34", "-p", "ncaa-bbcor", "-q", "--engine", "rigid",
                      "--no-reports")
    assert res.stdout.startswith("predicted PASS")
    assert flat(f"known offset of the model: {METRICS['bbcor'].model_offset}") in flat(res.stdout)


def test_league_shows_the_offset_and_a_geometric_fail_is_plain(batcert_cli, tmp_path):
    res = batcert_cli("league", "ncaa", "aluminium-34", "--out", tmp_path)
    lines = res.stdout.splitlines()
    # aluminium-34 fails the drop rule (-3.42, a number of the bat file) and the BBCOR rule
    # (the model's): the drop decides, so the bat's FAIL is plain; the BBCOR rule says predicted
    assert lines[0].startswith("FAIL  Aluminium 34 in")
    assert any(line.strip() == "verdict  predicted FAIL" for line in lines)
    assert flat(f"known offset of the model (BBCOR: {METRICS['bbcor'].model_offset})") \
        in flat(res.stdout)
    md = next(tmp_path.glob("*.md")).read_text()
    assert f"Known offset of the model (BBCOR: {METRICS['bbcor'].model_offset})" in md.replace("\\", "")


def test_league_fail_by_the_model_alone_is_predicted(batcert_cli):
    # bbcor-alloy-34 meets every geometric rule of the NCAA and fails only the BBCOR rule
    res = batcert_cli("league", "ncaa", "bbcor-alloy-34", "--engine", "flexible",
                      "--no-reports")
    assert res.stdout.splitlines()[0].startswith("predicted FAIL  BBCOR-era alloy")


def test_field_states_its_offset(batcert_cli):
    res = batcert_cli("field", "ash-34", "--engine", "rigid", "--no-reports")
    assert flat(f"Known offset of the model: {MODEL_OFFSET}.") in flat(res.stdout)
    data = json.loads(batcert_cli("field", "ash-34", "--engine", "rigid", "--json").stdout)
    assert data["results"][0]["model_offset"] == MODEL_OFFSET
