"""Command-line conventions: python -m, --version/-V, -v/-q, list, shell completion."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from click.testing import CliRunner
from jsonout import results

from batcert import __version__
from batcert.cli import main


def test_python_dash_m_and_version():
    proc = subprocess.run([sys.executable, "-m", "batcert", "-V"], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0 and __version__ in proc.stdout


def test_version_long_and_short(batcert_cli):
    assert __version__ in batcert_cli("--version").stdout
    assert batcert_cli("-V").stdout == batcert_cli("--version").stdout


def test_verbose_logs_settings_and_timings_to_stderr(batcert_cli):
    result = batcert_cli("-v", "run", "ash-34", "-p", "proposed", "--engine", "rigid",
                         "--json")
    assert result.exit_code == 0
    json.loads(result.stdout)  # stdout stays pure JSON
    assert "engine rigid" in result.stderr and "inputs" in result.stderr


def test_quiet_prints_only_the_verdict(batcert_cli, tmp_path):
    loud = batcert_cli("run", "ash-34", "-p", "ncaa-besr", "--engine", "rigid", "--out", tmp_path / "a")
    quiet = batcert_cli("-q", "run", "ash-34", "-p", "ncaa-besr", "--engine", "rigid", "--out",
                        tmp_path / "b")
    assert quiet.exit_code == loud.exit_code == 0
    assert "PASS" in quiet.stdout and "wrote" not in quiet.stdout and "wrote" in loud.stdout
    assert len(quiet.stdout.splitlines()) < len(loud.stdout.splitlines())


def test_list_every_kind(batcert_cli):
    data = {k["kind"]: k["entries"] for k in results(batcert_cli("list", "--json").stdout, "list")}
    assert set(data) == {"bats", "balls", "protocols", "leagues", "studies", "batters"}
    names = {k: [i["name"] for i in v] for k, v in data.items()}
    assert "ash-34" in names["bats"] and "collegiate-baseball" in names["balls"]
    assert "ncaa-bbcor" in names["protocols"] and "ncaa" in names["leagues"]
    assert names["studies"] == ["smith2001"]  # a study's protocols are not studies
    assert names["batters"] == ["college", "fastpitch", "high-school", "pro", "slowpitch",
                                "youth-12u"]
    assert "ash-34" in batcert_cli("list", "bats").stdout
    assert "Professional (MLB)" in batcert_cli("list", "batters").stdout


def _complete(words: str) -> list[str]:
    env = {"_BATCERT_COMPLETE": "bash_complete", "COMP_WORDS": words,
           "COMP_CWORD": str(len(words.split()) - (0 if words.endswith(" ") else 1))}
    result = CliRunner().invoke(main, [], env=env, prog_name="batcert")
    return [ln.split(",", 1)[1] for ln in result.stdout.splitlines() if ln.startswith("plain,")]


def test_completion_offers_shipped_names():
    assert "ash-34" in _complete("batcert run as")
    assert "ncaa-bbcor" in _complete("batcert run ash-34 -p ncaa-b")
    assert _complete("batcert compare --study ") == ["smith2001"]
    assert "ncaa" in _complete("batcert league nc")
    assert _complete("batcert field ash-34 --batter p") == ["pro"]


def test_completion_scripts_exist_for_every_shell():
    for shell in ("bash", "zsh", "fish"):
        env = dict(os.environ, _BATCERT_COMPLETE=f"{shell}_source")
        result = CliRunner().invoke(main, [], env=env, prog_name="batcert")
        assert "_BATCERT_COMPLETE" in result.stdout, shell
