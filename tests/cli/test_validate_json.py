"""`batcert validate --json` (issue 24): each file with its kind and every problem, as data."""

from __future__ import annotations

from pathlib import Path

from jsonout import results

REPO = Path(__file__).resolve().parents[2]

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"


def test_validate_json_lists_every_problem_of_every_file(batcert_cli, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text((FIXTURES / "bad" / "bat-three-errors.yaml").read_text(encoding="utf-8"))
    res = batcert_cli("validate", "ash-34", bad, "no-such-thing", "--json")
    assert res.exit_code == 3
    files = results(res.stdout, "validate")  # stdout is the JSON alone
    assert [f["file"] for f in files] == ["ash-34", str(bad), "no-such-thing"]
    assert files[0] == {"file": "ash-34", "kind": "bat", "ok": True, "problems": []}
    assert files[1]["ok"] is False and len(files[1]["problems"]) == 3
    assert all(p["file"] == str(bad) and p["line"] and p["message"]
               for p in files[1]["problems"])
    assert files[2]["ok"] is False and files[2]["problems"][0]["line"] is None
    assert res.stderr == ""


def test_validate_json_all_good_exits_0(batcert_cli):
    res = batcert_cli("validate", "ash-34", "ncaa-bbcor", "--json")
    assert res.exit_code == 0
    assert [f["kind"] for f in results(res.stdout, "validate")] == ["bat", "protocol"]


def test_a_protocol_with_four_problems_shows_them_in_one_round(batcert_cli, tmp_path):
    """A unit error, an unreadable speed, a misspelt metric and an unknown ball: all four at
    once, in line order (the unknown ball came only once the others were fixed)."""
    text = (REPO / "protocols" / "ncaa-bbcor.yaml").read_text(encoding="utf-8")
    for old, new in [("pivot: 6 in", "pivot: 6 kg"), ("ball: collegiate-baseball", "ball: nope"),
                     ("    pitch_speed: 136 mph", "    pitch_speed: fast"),
                     ("metric: bbcor\n", "metric: bbcorr\n")]:
        assert old in text
        text = text.replace(old, new)
    (tmp_path / "p.yaml").write_text(text, encoding="utf-8")
    res = batcert_cli("validate", tmp_path / "p.yaml", "--json")
    [entry] = results(res.stdout, "validate")
    fields = [p["field"] for p in entry["problems"]]
    assert fields == ["pivot", "ball", "conditions[0].pitch_speed", "metric"]


def test_a_hits_csv_is_validated_as_reduce_reads_it(batcert_cli, tmp_path):
    """Issue 40, item 14a: a hits CSV was parsed as YAML ('the top level must be a mapping');
    it is a hits file, checked as `batcert reduce HITS.csv --bat BAT` reads it, every problem
    at its line and column."""
    good = REPO / "examples" / "lab" / "synthetic-scatter.csv"
    bad = tmp_path / "hits.csv"
    bad.write_text("hit,ball,inbound_speed [m/s],rebound_speed [m/s],"
                   "impact_location [in from tip],valid\n"
                   "1,B1,60,abc,4.5,yes\n"
                   "2,B1,0.1,10,4.5,maybe\n", encoding="utf-8")
    res = batcert_cli("validate", good, bad, "--json")
    assert res.exit_code == 3
    files = results(res.stdout, "validate")
    assert files[0] == {"file": str(good), "kind": "hits", "ok": True, "problems": []}
    assert [(p["line"], p["column"], p["field"]) for p in files[1]["problems"]] == [
        (2, 9, "rebound_speed"), (3, 6, "inbound_speed"), (3, 17, "valid")]
    assert batcert_cli("validate", good).stdout == f"ok  {good} (hits)\n"


def test_a_csv_that_is_not_hits_says_so(batcert_cli):
    res = batcert_cli("validate", REPO / "bats" / "r161-profile.csv", "--json")
    assert res.exit_code == 3
    ((problem,),) = [f["problems"] for f in results(res.stdout, "validate")]
    assert problem["line"] == 6 and problem["message"].startswith("not a hits CSV")
