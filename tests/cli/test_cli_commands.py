"""The command line (batcert.cli): help, protocols, inspect, run, exit codes and clean --json."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from jsonout import result as result_of
from jsonout import results

REPO = Path(__file__).resolve().parents[2]
ASH = REPO / "bats" / "ash-34.yaml"
ALUMINIUM = REPO / "bats" / "aluminium-34.yaml"
SHIPPED = ["astm-bpf", "ncaa-bbcor", "ncaa-besr", "ncaa-softball-bbs", "proposed", "softball-bpf",
           "stationary-ball", "usa-softball-2004", "usa-softball-2013-slowpitch", "wbsc-bbs"]
CONDITION_KEYS = {"name", "pitch_speed", "bat_angular_speed", "impact_location", "exit_speed",
                  "bat_angular_speed_after", "cor", "bpf", "besr", "bbcor",
                  "collision_efficiency", "sweep"}


@pytest.mark.parametrize("args", [["--help"], ["run", "--help"]])
def test_help_lists_exit_codes(batcert_cli, args):
    result = batcert_cli(*args)
    assert result.exit_code == 0
    text = " ".join(result.stdout.split())
    for line in ("0 every verdict passes", "1 at least one verdict fails", "2 usage error",
                 "3 invalid input"):
        assert line in text


@pytest.mark.parametrize("args", [["validate", "--help"], ["inspect", "--help"],
                                  ["protocols", "--help"]])
def test_checking_commands_list_their_own_exit_codes(batcert_cli, args):
    text = " ".join(batcert_cli(*args).stdout.split())
    for line in ("0 the input is valid", "2 usage error", "3 invalid input"):
        assert line in text
    assert "verdict" not in text  # these commands give no verdict


def test_version(batcert_cli):
    from batcert import __version__
    result = batcert_cli("--version")
    assert result.exit_code == 0 and __version__ in result.stdout


def test_protocols_lists_shipped(batcert_cli):
    result = batcert_cli("protocols")
    assert result.exit_code == 0
    for pid in SHIPPED:
        assert pid in result.stdout
    data = results(batcert_cli("protocols", "--json").stdout, "protocols")
    assert sorted(p["id"] for p in data) == SHIPPED
    limits = {p["id"]: p["limit"] for p in data}
    assert limits == {"astm-bpf": 1.15, "ncaa-bbcor": 0.5, "ncaa-besr": 0.728, "proposed": None,
                      "softball-bpf": 1.2, "stationary-ball": None,
                      "usa-softball-2004": pytest.approx(98 * 0.44704, rel=1e-12),
                      "usa-softball-2013-slowpitch": pytest.approx(98 * 0.44704, rel=1e-12),
                      "ncaa-softball-bbs": pytest.approx(98 * 0.44704, rel=1e-12),
                      "wbsc-bbs": pytest.approx(100 * 0.44704, rel=1e-12)}


def test_inspect_ash_json(batcert_cli):
    """Smith 2001 ash bat, reconciled exactly to the measured values about its 150 mm pivot; COP
    from Eq. 4, q = I / (M rbar)."""
    result = batcert_cli("inspect", ASH, "--json")
    assert result.exit_code == 0, result.stderr
    info = result_of(result.stdout, "inspect")
    rel = 5e-6  # reconciliation is exact; inspect prints 6 significant digits (half a unit)
    assert info["pivot"] == pytest.approx(0.150, rel=rel)
    assert info["mass"] == pytest.approx(0.906, rel=rel)
    assert info["cg"] == pytest.approx(0.429, rel=rel)
    assert info["moi_pivot"] == pytest.approx(0.209, rel=rel)
    assert info["cop"] == pytest.approx(info["moi_pivot"] / (info["mass"] * info["cg"]), rel=rel)
    assert info["cg"] == 0.429 and info["balance_point"] == 0.579  # no binary noise printed
    assert info["balance_point"] == pytest.approx(0.579, rel=rel)
    assert info["moi_cg"] == pytest.approx(0.209 - 0.906 * 0.429**2, rel=rel)
    assert info["reconciliation"]["method"] == "density-profile"
    assert info["geometry"]["mass"] != pytest.approx(0.906, rel=1e-4)  # geometry alone differs


def test_inspect_by_shipped_name_and_pivot(batcert_cli):
    info = result_of(batcert_cli("inspect", "ash-34", "--json", "--pivot", "6 in").stdout,
                     "inspect")
    p = 6 * 0.0254
    assert info["pivot"] == pytest.approx(p)
    rel = 5e-6  # inspect prints 6 significant digits
    assert info["cg"] == pytest.approx(0.579 - p, rel=rel)
    assert info["moi_pivot"] == pytest.approx(0.209 - 0.906 * 0.429**2 + 0.906 * (0.579 - p) ** 2,
                                              rel=rel)


def test_inspect_bad_pivot_is_usage_error(batcert_cli):
    result = batcert_cli("inspect", "ash-34", "--pivot", "6 kg")
    assert result.exit_code == 2 and "not a length" in result.stderr


def test_inspect_ball(batcert_cli):
    result = batcert_cli("inspect", REPO / "protocols" / "balls" / "nathan-2000.yaml", "--json")
    assert result.exit_code == 0, result.stderr
    info = result_of(result.stdout, "inspect")
    assert info["mass"] == 0.145 and info["radius"] == pytest.approx(0.0366)
    # the law's rigid-wall COR is e0 at every speed (energy ratio (1+alpha)/(1+beta) = e0^2)
    assert info["cor"] == pytest.approx([0.53] * len(info["speeds"]), rel=1e-9)
    # Nathan 2000: 99 %-impulse collision time 0.7 ms at 45 m/s (REFERENCE-DATA, H); 15 % as in
    # the validation tests (the paper's times are read off a figure)
    i = info["speeds"].index(45.0)
    assert info["collision_time"][i] == pytest.approx(0.7e-3, rel=0.15)
    assert set(info) >= {"contact_time", "max_compression", "peak_force"}


def test_inspect_table(batcert_cli):
    result = batcert_cli("inspect", ASH)
    assert result.exit_code == 0
    assert "0.906 kg" in result.stdout and "COP (from pivot)" in result.stdout


def _run(batcert_cli, *args):
    return batcert_cli("run", ASH, "--engine", "rigid", *args)


def test_run_json_contract(batcert_cli, tmp_path):
    result = _run(batcert_cli, "-p", "ncaa-besr", "--json", "--out", tmp_path / "r")
    assert result.exit_code == 0, result.stderr
    (data,) = json.loads(result.stdout)["results"]  # stdout is only JSON
    assert {"protocol", "metric", "value", "limit", "verdict", "conditions"} <= set(data)
    assert data["protocol"] == "ncaa-besr" and data["metric"] == "besr"
    assert data["limit"] == 0.728 and data["verdict"] == "pass"
    assert data["engine"] == "rigid"
    for c in data["conditions"]:
        assert CONDITION_KEYS <= set(c)
        assert c["pitch_speed"] < 0  # stored negative: toward the bat
        sweep = c["sweep"]
        assert len(sweep["impact_location"]) == len(sweep["exit_speed"]) > 2


def test_run_json_is_a_list_however_many_protocols(batcert_cli, tmp_path):
    result = _run(batcert_cli, "-p", "ncaa-besr", "-p", "proposed", "--json", "--no-reports")
    assert result.exit_code == 0
    data = json.loads(result.stdout)["results"]
    assert [d["protocol"] for d in data] == ["ncaa-besr", "proposed"]
    assert data[1]["verdict"] is None and data[1]["limit"] is None


def _failing(batcert_cli, *args):
    """The study's aluminium bat on the flexible engine: predicted BBCOR about 0.56, which fails
    the 0.500 limit (the ball lot is calibrated on ash-34 at 0.490)."""
    return batcert_cli("run", ALUMINIUM, *args)


@pytest.mark.parametrize("protocol, code, verdict", [
    ("ncaa-bbcor", 1, "fail"),  # predicted BBCOR about 0.56 > 0.500
    ("astm-bpf", 0, "pass"),  # BPF about 1.1 <= 1.15 (USSSA's limit)
    ("proposed", 0, None),  # no limit: exit 0
])
def test_exit_code_follows_verdict(batcert_cli, protocol, code, verdict):
    result = _failing(batcert_cli, "-p", protocol, "--json", "--no-reports")
    assert result.exit_code == code
    assert json.loads(result.stdout)["results"][0]["verdict"] == verdict


def test_one_failing_protocol_fails_the_run(batcert_cli):
    result = _failing(batcert_cli, "-p", "astm-bpf", "-p", "ncaa-bbcor", "--no-reports")
    assert result.exit_code == 1
    assert "PASS" in result.stdout and "FAIL" in result.stdout


def test_run_writes_reports(batcert_cli, tmp_path):
    out = tmp_path / "reports"
    result = _run(batcert_cli, "-p", "ncaa-besr", "--out", out)
    assert result.exit_code == 0, result.stderr
    written = sorted(p.name for p in out.glob("[!.]*"))
    assert [Path(n).suffix for n in written] == [".html", ".json", ".md"]
    stem = Path(written[0]).stem
    assert all(Path(n).stem == stem for n in written)
    saved = json.loads((out / f"{stem}.json").read_text())
    assert saved["protocol"] == "ncaa-besr" and saved["verdict"] == "pass"
    for name in written:
        assert f"wrote {out / name}" in result.stdout


def test_run_json_with_reports_keeps_stdout_clean(batcert_cli, tmp_path):
    out = tmp_path / "reports"
    result = _run(batcert_cli, "-p", "proposed", "--json", "--out", out, "--format", "json")
    assert result.exit_code == 0
    (printed,) = json.loads(result.stdout)["results"]
    (saved,) = [json.loads(p.read_text()) for p in out.glob("[!.]*")]
    assert printed == saved


def test_json_without_out_writes_no_files(batcert_cli, tmp_path, monkeypatch):
    # --json prints the results and writes report files only where --out says (so a script
    # that only wants the JSON leaves nothing behind in its working directory)
    monkeypatch.chdir(tmp_path)
    result = batcert_cli("run", ASH, "-p", "proposed", "--json")
    assert result.exit_code == 0 and json.loads(result.stdout)["results"][0]["protocol"] == "proposed"
    assert list(tmp_path.iterdir()) == []
    monkeypatch.chdir(REPO)


def test_no_reports_writes_nothing(batcert_cli, tmp_path):
    out = tmp_path / "reports"
    assert _run(batcert_cli, "-p", "proposed", "--no-reports", "--out", out).exit_code == 0
    assert not out.exists()


def test_bad_format_is_usage_error(batcert_cli, tmp_path):
    out = tmp_path / "reports"
    result = _run(batcert_cli, "-p", "proposed", "--format", "pdf", "--out", out)
    assert result.exit_code == 2 and "choose from md, html, json" in result.stderr
    assert not out.exists()


def test_unknown_option_is_usage_error(batcert_cli):
    assert batcert_cli("run", ASH, "--protocl", "proposed").exit_code == 2


def test_protocol_error_exits_3(batcert_cli, tmp_path):
    """A protocol that cannot apply to this bat (window beyond the pivot) is invalid input."""
    proto = tmp_path / "long-window.yaml"
    proto.write_text((REPO / "protocols" / "ncaa-besr.yaml").read_text().replace(
        "window: [2 in, 12 in]", "window: [2 in, 30 in]"))
    out = tmp_path / "reports"
    result = _run(batcert_cli, "-p", proto, "--out", out)
    assert result.exit_code == 3
    assert "long-window.yaml:23: impact_location.window: the search window reaches 76.2 cm " \
        "from the tip: it must end at least 1 cm short of the pivot" in result.stderr
    assert not out.exists()


def test_installed_entry_point_json_is_clean(tmp_path):
    """The real console script, in a fresh process: stdout parses as JSON, nothing else on it."""
    exe = Path(sys.executable).with_name("batcert")
    cmd = [str(exe)] if exe.exists() else [sys.executable, "-m", "batcert.cli"]
    env = dict(os.environ, COLUMNS="60")
    proc = subprocess.run([*cmd, "run", str(ALUMINIUM), "-p", "ncaa-bbcor", "--json", "--out",
                           str(tmp_path / "r"), "--format", "json"],
                          capture_output=True, text=True, env=env, timeout=300)
    assert proc.returncode == 1, proc.stderr  # predicted BBCOR about 0.56 fails the 0.500 limit
    assert json.loads(proc.stdout)["results"][0]["verdict"] == "fail"


def test_inspect_protocol_file_is_usage_error(batcert_cli):
    result = batcert_cli("inspect", REPO / "protocols" / "proposed.yaml")
    assert result.exit_code == 2
    assert "is a protocol file; inspect takes a bat or a ball" in result.stderr


def test_inspect_invalid_bat_exits_3(batcert_cli):
    bad = REPO / "tests" / "fixtures" / "bad" / "bat-unknown-material.yaml"
    result = batcert_cli("inspect", bad, "--json")
    assert result.exit_code == 3 and result.stdout == ""
    assert f"{bad}:8: material:" in result.stderr


@pytest.mark.parametrize("where", ["/dev/null", "under-file", "long-name"])
def test_bad_output_location_exits_4_before_running(batcert_cli, tmp_path, monkeypatch, where):
    # one line, its own exit code, and the engine is never started
    import batcert.commands.run as run_module

    def never(*args, **kwargs):
        raise AssertionError("the engine ran")
    monkeypatch.setattr(run_module, "run_protocols", never)
    regular = tmp_path / "a-file"
    regular.write_text("x")
    out = {"/dev/null": Path("/dev/null"), "under-file": regular / "reports",
           "long-name": tmp_path / ("r" * 300)}[where]
    result = batcert_cli("run", ASH, "-p", "proposed", "--out", out)
    assert result.exit_code == 4
    assert result.stderr.startswith("error: cannot write reports to")
    assert len(result.stderr.strip().splitlines()) == 1 and "Traceback" not in result.stderr


def test_write_failure_after_running_still_shows_the_verdict(batcert_cli, tmp_path, monkeypatch):
    import batcert.reports.fileset as fileset
    import batcert.reports.linkset as linkset

    def full(*args):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(fileset, "_stage", full)  # a set written by the journal
    monkeypatch.setattr(linkset, "_write", full)  # a set switched by its link
    result = batcert_cli("run", ALUMINIUM, "-p", "ncaa-bbcor", "--out", tmp_path / "reports")
    assert result.exit_code == 4
    assert "FAIL" in result.stdout and "BBCOR" in result.stdout  # the verdict is not lost
    assert "No space left on device" in result.stderr
    assert not any((tmp_path / "reports").glob("*"))


def test_interrupt_exits_130_without_leftovers(batcert_cli, tmp_path, monkeypatch):
    import batcert.commands.run as run_module

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt
    monkeypatch.setattr(run_module, "run_protocols", interrupted)
    result = batcert_cli("run", ASH, "-p", "proposed", "--out", tmp_path / "reports")
    assert result.exit_code == 130 and "interrupted" in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_inspect_takes_a_shipped_ball_by_name(batcert_cli):
    res = batcert_cli("inspect", "collegiate-baseball")
    assert res.exit_code == 0, res.stderr
    for shown in ("viscoelastic", "against a rigid flat wall", "rigid cylinder", "CALIBRATED"):
        assert shown in res.stdout, shown
    res = batcert_cli("inspect", "no-such-thing")
    assert res.exit_code == 2 and "neither a file nor a shipped bat or ball" in res.stderr
