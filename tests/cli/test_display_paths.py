"""Reports name shipped files `shipped:...` wherever batcert is installed, and a user's files
relative to the working directory, never by an absolute path into the installation."""

from __future__ import annotations

import shutil
from pathlib import Path

from jsonout import result

REPO = Path(__file__).resolve().parents[2]


def test_a_shipped_league_and_an_absolute_user_path_inside_the_working_directory(
        batcert_cli, tmp_path, monkeypatch):
    (tmp_path / "bats").mkdir()
    shutil.copy(REPO / "bats" / "ash-34.yaml", tmp_path / "bats" / "mine.yaml")
    monkeypatch.chdir(tmp_path)
    res = batcert_cli("league", "mlb", tmp_path / "bats" / "mine.yaml", "--engine", "rigid",
                      "--json")
    doc = result(res.stdout, "league")
    assert doc["path"] == "shipped:protocols/leagues/mlb.yaml"  # was the installed file's path
    assert doc["bats"][0]["path"] == "bats/mine.yaml"  # was /tmp/.../bats/mine.yaml


def test_a_user_file_outside_the_working_directory_keeps_the_path_given(batcert_cli, tmp_path,
                                                                       monkeypatch):
    shutil.copy(REPO / "bats" / "ash-34.yaml", tmp_path / "mine.yaml")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    for given in (str(tmp_path / "mine.yaml"), "../mine.yaml"):
        res = batcert_cli("run", given, "-p", "ncaa-bbcor", "--engine", "rigid", "--json")
        [bat] = [i for i in result(res.stdout, "run")["inputs"] if i["role"] == "bat"]
        assert bat["path"] == given
