"""A bat file's optional identification (maker, model, serial, lot) is shown on every report
of the bat (issue 24): a lab files a report by the bat it is about."""

from __future__ import annotations

import json
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
IDENT = """
identification:
  maker: Example Bats Co.
  model: EB-34
  serial: SN 000123
"""
SHOWN = "maker Example Bats Co., model EB-34, serial SN 000123"


def _bat(tmp_path: Path, extra: str = IDENT) -> Path:
    path = tmp_path / "bat.yaml"
    path.write_text((REPO / "bats" / "ash-34.yaml").read_text(encoding="utf-8") + extra,
                    encoding="utf-8")
    return path


def test_run_and_sweep_reports_show_it(batcert_cli, tmp_path):
    bat, out = _bat(tmp_path), tmp_path / "r"
    assert batcert_cli("run", bat, "-p", "ncaa-bbcor", "--engine", "rigid", "--out", out
                       ).exit_code == 0  # rigid wood: BBCOR about 0.48, a predicted pass
    assert batcert_cli("sweep", bat, "-p", "ncaa-bbcor", "--vary", "pitch_speed=40m/s:60m/s:3",
                       "--engine", "rigid", "--out", out).exit_code == 0
    reports = {p.name: p.read_text(encoding="utf-8") for p in out.glob("[!.]*")}
    assert len(reports) == 6
    for name, text in reports.items():
        if name.endswith(".json"):
            assert json.loads(text)["bat_identification"] == {
                "maker": "Example Bats Co.", "model": "EB-34", "serial": "SN 000123"}, name
        else:
            assert "Bat identification" in text and SHOWN in text.replace("&amp;", "&"), name


def test_without_it_nothing_is_shown(batcert_cli, tmp_path):
    res = batcert_cli("run", _bat(tmp_path, ""), "-p", "ncaa-bbcor", "--engine", "rigid",
                      "--json")
    assert json.loads(res.stdout)["results"][0]["bat_identification"] == {}


def test_an_unknown_identification_field_points_at_its_line(batcert_cli, tmp_path):
    bat = _bat(tmp_path, IDENT + "  colour: red\n")
    res = batcert_cli("validate", bat)
    assert res.exit_code == 3
    line = len(bat.read_text(encoding="utf-8").splitlines())
    assert f"{bat}:{line}: identification.colour: unknown field" in res.stderr
