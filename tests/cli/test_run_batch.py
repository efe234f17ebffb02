"""`run` takes several bats (a lab certifies a batch): every bat is loaded before anything runs,
each gets its own report set, and bats that share a name are told apart by their files."""

from __future__ import annotations

import shutil
from pathlib import Path

from jsonout import results

REPO = Path(__file__).resolve().parents[2]
BBCOR = ("-p", "ncaa-bbcor")  # aluminium-34's predicted BBCOR, about 0.57, fails 0.500


def _copies(tmp_path: Path, *names: str) -> list[Path]:
    out = []
    for n in names:
        shutil.copy(REPO / "bats" / "aluminium-34.yaml", tmp_path / n)
        out.append(tmp_path / n)
    return out


def test_a_batch_gives_one_result_and_one_report_set_per_bat_and_protocol(batcert_cli,
                                                                          tmp_path):
    res = batcert_cli("run", "ash-34", "aluminium-34", *BBCOR, "-p", "proposed", "--json",
                      "--out", tmp_path / "out")
    assert res.exit_code == 1, res.stderr  # the aluminium bat fails BBCOR by the model
    docs = results(res.stdout, "run")
    assert [(d["bat"][:3], d["protocol"]) for d in docs] == [
        ("Ash", "ncaa-bbcor"), ("Ash", "proposed"), ("Alu", "ncaa-bbcor"), ("Alu", "proposed")]
    assert len(list((tmp_path / "out").glob("*.html"))) == 4


def test_bats_sharing_a_name_are_told_apart_by_their_file(batcert_cli, tmp_path):
    a, b = _copies(tmp_path, "serial-001.yaml", "serial-002.yaml")
    res = batcert_cli("run", a, b, *BBCOR, "--out", tmp_path / "out")
    assert res.exit_code == 1
    names = sorted(p.name for p in (tmp_path / "out").glob("*.md"))
    assert names == ["aluminium-34-in-smith-2001--serial-001--ncaa-bbcor.md",
                     "aluminium-34-in-smith-2001--serial-002--ncaa-bbcor.md"]
    assert "2 bats, 2 runs: 0 predicted pass, 2 predicted fail" in res.stdout


def test_the_same_bat_twice_is_a_usage_error(batcert_cli, tmp_path):
    [a] = _copies(tmp_path, "a.yaml")
    res = batcert_cli("run", a, tmp_path / "." / "a.yaml", *BBCOR, "--out", tmp_path / "out")
    assert res.exit_code == 2 and "given twice" in res.stderr
    assert not (tmp_path / "out").exists()


def test_one_invalid_bat_stops_the_batch_before_anything_runs(batcert_cli, tmp_path):
    [good, bad] = _copies(tmp_path, "good.yaml", "bad.yaml")
    bad.write_text(bad.read_text(encoding="utf-8").replace("length: 860 mm", "length: -1 mm"),
                   encoding="utf-8")
    res = batcert_cli("run", good, bad, *BBCOR, "--out", tmp_path / "out")
    assert res.exit_code == 3 and "bad.yaml" in res.stderr
    assert not (tmp_path / "out").exists()
