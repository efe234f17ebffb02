"""`batcert compare`: exit codes, clean --json, the comparison JSON shape and written reports.

All runs use the rigid engine (closed forms, fast); tests/test_compare.py checks the numbers.
"""

from __future__ import annotations

import json
from pathlib import Path

from jsonout import result as result_of

REPO = Path(__file__).resolve().parents[2]
ASH = REPO / "bats" / "ash-34.yaml"
ALU = REPO / "bats" / "aluminium-34.yaml"
STUDY_PROTOCOLS = ["smith2001-bpf-cop", "smith2001-besr-sweet-spot", "smith2001-bpf-sweet-spot",
                   "proposed", "smith2001-besr-matched"]


def test_help_lists_exit_codes(batcert_cli):
    result = batcert_cli("compare", "--help")
    assert result.exit_code == 0
    text = " ".join(result.stdout.split())
    for needle in ("0 the comparison ran", "1 a protocol with a limit fails", "2 usage error",
                   "3 invalid input"):
        assert needle in text


def test_study_json_is_the_only_stdout(batcert_cli):
    result = batcert_cli("compare", ASH, ALU, "--study", "smith2001", "--engine", "rigid",
                         "--json", "--no-reports")
    assert result.exit_code == 0, result.stderr
    data = result_of(result.stdout, "compare")
    assert data["study"] == "smith2001" and data["engine"] == "rigid"
    assert data["reference"] == "Ash 34 in (Smith 2001)"
    assert [p["protocol"] for p in data["protocols"]] == STUDY_PROTOCOLS
    labels = [b["label"] for b in data["bats"]]
    for p in data["protocols"]:
        assert [c["name"] for c in p["conditions"]] == ["stationary-bat", "stationary-ball",
                                                        "pitched-and-swung"]
        for c in p["conditions"]:
            assert list(c["bats"]) == labels
            for b in c["bats"].values():
                assert {"value", "relative", "cop", "sweet_spot", "sweet_spot_minus_cop"} <= set(b)
        assert set(p["relative_spread"][labels[1]]) == {"mean", "std", "min", "max", "range"}
    assert {c["status"] for c in data["claims"]} <= {"supported", "not-supported",
                                                     "not-testable"}
    assert data["findings"]


def test_study_names_default_bats(batcert_cli):
    result = batcert_cli("compare", "--study", "smith2001", "--engine", "rigid", "--json",
                         "--no-reports", "-p", "ncaa-besr")
    assert result.exit_code == 0, result.stderr
    data = result_of(result.stdout, "compare")
    assert [Path(b["path"]).name for b in data["bats"]] == ["ash-34.yaml", "aluminium-34.yaml"]
    assert data["protocols"][-1]["protocol"] == "ncaa-besr"  # extra protocols after the study's


def test_reference_option(batcert_cli):
    result = batcert_cli("compare", ASH, ALU, "-p", "ncaa-besr", "--reference", "aluminium-34",
                         "--engine", "rigid", "--json", "--no-reports")
    data = result_of(result.stdout, "compare")
    assert data["reference"] == "Aluminium 34 in (Smith 2001)"
    cond = data["protocols"][0]["conditions"][0]["bats"]
    assert cond["Aluminium 34 in (Smith 2001)"]["relative"] == 0.0
    assert cond["Ash 34 in (Smith 2001)"]["relative"] > 0  # the heavier ash scores higher BESR


def test_failing_limit_exits_1(batcert_cli):
    # the aluminium bat's predicted BBCOR, about 0.57, fails 0.500 (ash passes at 0.490, the
    # value the ball lot is calibrated on)
    result = batcert_cli("compare", ASH, ALU, "-p", "ncaa-bbcor", "--no-reports")
    assert result.exit_code == 1
    assert "ncaa-bbcor" in result.stdout


def test_reports_written(batcert_cli, tmp_path):
    out = tmp_path / "reports"
    result = batcert_cli("compare", ASH, ALU, "--study", "smith2001", "--engine", "rigid",
                         "--out", out)
    assert result.exit_code == 0, result.stderr
    files = sorted(p.name for p in out.glob("[!.]*"))
    stem = "compare--smith2001--ash-34-aluminium-34"
    assert files == [f"{stem}.html", f"{stem}.json", f"{stem}.md"]
    md = (out / f"{stem}.md").read_text()
    for needle in ("What the model finds", "The study's claims against the model",
                   "centre of percussion and sweet spot", "mean of P across conditions"):
        assert needle in md
    html = (out / f"{stem}.html").read_text()
    assert html.count("<svg") >= 2 * len(STUDY_PROTOCOLS)  # metric and sweet spot (P unless 0)
    saved = json.loads((out / f"{stem}.json").read_text())
    assert saved["study"] == "smith2001"


def test_usage_errors_exit_2(batcert_cli):
    assert batcert_cli("compare", ASH, ALU, "--engine", "rigid").exit_code == 2  # no protocol
    assert batcert_cli("compare", ASH, "-p", "proposed", "--engine", "rigid").exit_code == 2
    assert batcert_cli("compare", ASH, ALU, "-p", "nosuch", "--engine", "rigid").exit_code == 2
    assert batcert_cli("compare", ASH, ALU, "--study", "nosuch").exit_code == 2
    assert batcert_cli("compare", ASH, ALU, "-p", "proposed", "-p", "proposed",
                       "--engine", "rigid").exit_code == 2
    result = batcert_cli("compare", ASH, ALU, "-p", "proposed", "--engine", "warp")
    assert result.exit_code == 2 and "'warp' is not one of 'rigid', 'flexible'" in result.stderr


def test_invalid_input_exits_3_and_writes_nothing(batcert_cli, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(ASH.read_text().replace("length: 860 mm", "length: 860"))
    out = tmp_path / "reports"
    result = batcert_cli("compare", ASH, bad, "-p", "proposed", "--engine", "rigid",
                         "--out", out)
    assert result.exit_code == 3
    assert "a unit is required" in result.stderr
    assert not out.exists()


def test_reference_given_as_an_identical_copy_is_the_same_bat(batcert_cli, tmp_path):
    # A shipped name resolves to the copy installed with the package, another path to the same
    # bat: a reference with the same content as a compared bat must not be added a second time.
    copy = tmp_path / "aluminium-copy.yaml"
    copy.write_bytes(Path(ALU).read_bytes())
    result = batcert_cli("compare", ASH, ALU, "-p", "ncaa-besr", "--reference", copy,
                         "--engine", "rigid", "--json", "--no-reports")
    data = result_of(result.stdout, "compare")
    assert data["reference"] == "Aluminium 34 in (Smith 2001)"
    assert len(data["bats"]) == 2


def test_study_figures_only_when_asked(batcert_cli):
    # issue 29: the study's figures (sweeps of every bat) are most of a study's time; without
    # --study-figures they are not computed and the claims that read them say why
    plain = result_of(batcert_cli("compare", "--study", "smith2001", "--engine", "rigid",
                                  "--json", "--no-reports").stdout, "compare")
    assert plain["figures"] == []
    by_figure = [c for c in plain["claims"] if "study figure" in c["evidence"]]
    assert len(by_figure) == 2
    assert all(c["status"] == "not-testable" and "--study-figures" in c["evidence"]
               for c in by_figure)
    drawn = result_of(batcert_cli("compare", "--study", "smith2001", "--engine", "rigid",
                                  "--study-figures", "--json", "--no-reports").stdout, "compare")
    assert [f["id"] for f in drawn["figures"]] == ["wall-thickness", "sweet-spot-swing-speed"]
    assert all("not computed" not in c["evidence"] for c in drawn["claims"])
