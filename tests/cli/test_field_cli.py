"""`batcert field`: bats in play for batter profiles against a reference bat; exit codes, --json,
written reports and figures, the options that change the pitch and the air, and the swing law.

Rigid engine (closed forms, fast) but for one run of the default flexible engine."""

from __future__ import annotations

import json

import pytest
from jsonout import result as result_of

from batcert.results.field import FieldResult

RIGID = ("--engine", "rigid")
MPH = 0.44704  # [m/s]
SCENARIOS = ["nominal", "exponent-low", "exponent-high", "bat-speed-low", "bat-speed-high",
             "constant-swing", "plus-1mph-bat", "plus-1mph-pitch"]


def _field(batcert_cli, *args):
    """``batcert field ARGS --json`` (rigid, no reports): its one result, after exit 0."""
    res = batcert_cli("field", *args, *RIGID, "--json")
    assert res.exit_code == 0, res.stderr
    return result_of(res.stdout, "field")


def test_help_lists_exit_codes(batcert_cli):
    text = " ".join(batcert_cli("field", "--help").stdout.split())
    for needle in ("0 the prediction ran", "2 usage error", "3 invalid input"):
        assert needle in text


def test_json_shape_writes_no_files(batcert_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    data = _field(batcert_cli, "aluminium-34", "--batter", "pro")
    assert list(tmp_path.iterdir()) == []  # --json without --out writes nothing
    assert data["engine"] == "rigid" and data["reference"] == "Ash 34 in (Smith 2001)"
    [pro] = data["batters"]
    assert pro["batter"] == "pro" and pro["body"] == "baseball"
    assert [b["path"] for b in pro["bats"]] == ["shipped:bats/aluminium-34.yaml",
                                                "shipped:bats/ash-34.yaml"]
    for bat in pro["bats"]:
        assert [o["scenario"] for o in bat["outcomes"]] == SCENARIOS
        assert len(bat["along"]["from_tip"]) == len(bat["along"]["exit_speed"]) == 47


def test_the_reference_is_the_last_bat_with_no_gain(batcert_cli):
    data = _field(batcert_cli, "aluminium-34", "bbcor-alloy-34", "--batter", "college",
                  "--reference", "r161")
    bats = data["batters"][0]["bats"]
    assert [b["is_reference"] for b in bats] == [False, False, True]
    assert bats[-1]["path"] == "shipped:bats/r161.yaml"
    for o in bats[-1]["outcomes"]:
        assert o["gain_exit_speed"] == 0 and o["gain_distance"] == 0
    others = [o["gain_exit_speed"] for b in bats[:-1] for o in b["outcomes"]]
    assert all(g != 0 for g in others)


def test_reports_written(batcert_cli, tmp_path):
    out = tmp_path / "r"
    res = batcert_cli("field", "aluminium-34", "-b", "pro", "-b", "college", *RIGID,
                      "--out", out)
    assert res.exit_code == 0, res.stderr
    stem = "field--pro-college--aluminium-34-ash-34"
    assert sorted(p.name for p in out.glob("[!.]*")) == [f"{stem}.html", f"{stem}.json",
                                                     f"{stem}.md"]
    saved = json.loads((out / f"{stem}.json").read_text())
    assert saved["kind"] == "field"
    assert [b["batter"] for b in saved["batters"]] == ["pro", "college"]
    assert "Professional (MLB)" in (out / f"{stem}.md").read_text()


def test_batter_all_is_every_shipped_profile(batcert_cli):
    data = _field(batcert_cli, "ash-34", "--batter", "all", "--batter", "pro")
    assert sorted(b["batter"] for b in data["batters"]) == [
        "college", "fastpitch", "high-school", "pro", "slowpitch", "youth-12u"]
    assert any("softball" in w for w in data["warnings"])  # fastpitch and slowpitch fly


def test_pitch_replaces_every_profiles_pitch(batcert_cli):
    data = _field(batcert_cli, "ash-34", "-b", "pro", "-b", "fastpitch", "--pitch", "80mph")
    v = 35.7632  # 80 mph [m/s]
    for fb in data["batters"]:
        assert fb["pitch_speed"] == pytest.approx(v, rel=1e-12)
        for o in fb["bats"][0]["outcomes"]:
            step = MPH if o["scenario"] == "plus-1mph-pitch" else 0.0
            assert o["pitch_speed"] == pytest.approx(v + step, rel=1e-12), o["scenario"]


def test_nominal_swing_speed_follows_the_swing_law(batcert_cli):
    """v = v_ref (I / I_ref)^-n r / r_ref, r the station's distance from the swing axis."""
    [pro] = _field(batcert_cli, "ash-34", "aluminium-34", "--batter", "pro")["batters"]
    assert pro["bat_speed"] == pytest.approx(71.5 * MPH, rel=1e-12) and pro["exponent"] == 0.25
    station = pro["speed_from_tip"] + pro["axis_from_knob"]
    assert pro["speed_from_tip"] == pytest.approx(6 * 0.0254, rel=1e-12)
    for bat in pro["bats"]:
        expected = (pro["bat_speed"] * (bat["moi_axis"] / pro["reference_moi"]) ** -0.25
                    * (bat["length"] - station) / (pro["reference_length"] - station))
        nominal = bat["outcomes"][0]
        assert nominal["scenario"] == "nominal"
        assert nominal["swing_speed"] == pytest.approx(expected, rel=1e-9), bat["bat"]
        faster = bat["outcomes"][SCENARIOS.index("plus-1mph-bat")]
        assert faster["swing_speed"] - nominal["swing_speed"] == pytest.approx(MPH, rel=1e-9)


def test_json_round_trips_to_the_same_report():
    """A field result read back from its JSON renders as the one the command made."""
    from batcert.api import field
    from batcert.reports.write import render
    made = field("aluminium-34", ["pro", "slowpitch"], engine="rigid")
    assert isinstance(made, FieldResult) and made.batters[1].body == "softball"
    back = FieldResult.from_dict(json.loads(made.to_json()))
    assert back.to_dict() == made.to_dict()
    for fmt in ("md", "html"):
        assert render(back, fmt) == render(made, fmt)


def test_batcert_field_stays_the_api_after_a_run():
    import batcert
    from batcert import api
    assert batcert.field is api.field
    api.field("ash-34", "pro", engine="rigid")  # imports batcert.inplay.barrel and .evaluate
    assert callable(batcert.field)


def test_warm_air_carries_further_at_the_same_exit_speed(batcert_cli):
    def nominal(*args):
        return _field(batcert_cli, "ash-34", "-b", "pro", *args)["batters"][0]["bats"][0][
            "outcomes"][0]
    cold, warm = nominal("--temperature", "40F"), nominal("--temperature", "30C")
    assert warm["best_exit_speed"] == cold["best_exit_speed"]
    assert warm["distance"] > cold["distance"] + 3  # thinner air [m]


def test_elevation_in_feet_as_the_help_shows(batcert_cli):
    def carry(*args):
        return _field(batcert_cli, "ash-34", "-b", "pro", *args)["batters"][0]["bats"][0][
            "outcomes"][0]["distance"]
    assert carry("--elevation", "5280ft") > carry() + 5  # Denver's air [m]


def test_flexible_engine_default(batcert_cli):
    res = batcert_cli("field", "aluminium-34", "--batter", "college", "--json")
    assert res.exit_code == 0, res.stderr
    data = result_of(res.stdout, "field")
    assert data["engine"] == "flexible"
    [college] = data["batters"]
    assert college["batter"] == "college"
    for bat in college["bats"]:
        o = bat["outcomes"][0]
        assert 30 * MPH < o["best_exit_speed"] < 120 * MPH and 0 < o["collision_efficiency"] < 1


def test_unknown_batter_is_a_usage_error(batcert_cli, tmp_path):
    out = tmp_path / "out"
    res = batcert_cli("field", "ash-34", "--batter", "pr0", *RIGID, "--out", out)
    assert res.exit_code == 2
    assert "unknown batter 'pr0'" in res.stderr and "did you mean 'pro'?" in res.stderr
    assert not out.exists()


@pytest.mark.parametrize("args, message", [
    (("--temperature", "70X"), "cannot read '70X'"),
    (("--temperature", "500F"), "outside"),
    (("--temperature", "57.1C"), "outside -43 to 57 C"),
    (("--temperature", "-43.1C"), "outside -43 to 57 C"),
    (("--pitch", "80"), "a unit is required"),
    (("--engine", "warp"), "'warp' is not one of"),
    (("--reference", "ash-3"), "did you mean 'ash-34'?"),
    # issue 40 item 6e: NaN passed click's range and flew until a ValueError traceback
    # (read by batcert.arguments, as the library reads them)
    (("--launch-angle", "nan"), "launch-angle': must be a finite number, got nan"),
    (("--backspin", "nan"), "backspin': must be a finite number, got nan"),
    (("--sidespin", "NaN"), "sidespin': must be a finite number, got nan"),
])
def test_bad_values_are_usage_errors(batcert_cli, tmp_path, args, message):
    out = tmp_path / "out"
    res = batcert_cli("field", "ash-34", "--out", out, *args)
    assert res.exit_code == 2 and message in res.stderr
    assert not out.exists()


@pytest.mark.parametrize("end", ["57C", "-43C"])
def test_a_temperature_bound_accepts_its_own_end(batcert_cli, end):
    # issue 40: "57C" was refused as "outside -43 to 57 C" (the bound was 330 K, 56.85 C)
    res = batcert_cli("field", "ash-34", *RIGID, "--no-reports", "--temperature", end)
    assert res.exit_code == 0, res.stderr


def test_invalid_batter_file_exits_3(batcert_cli, tmp_path, repo_root):
    bad = tmp_path / "batter.yaml"
    text = (repo_root / "protocols" / "batters" / "pro.yaml").read_text()
    bad.write_text(text.replace("exponent: 0.25", "exponent: 1.25"))
    out = tmp_path / "out"
    res = batcert_cli("field", "ash-34", "--batter", bad, *RIGID, "--out", out)
    assert res.exit_code == 3 and f"{bad}:" in res.stderr and "swing.exponent" in res.stderr
    assert not out.exists()


def test_figures_written(batcert_cli, tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "figures"
    res = batcert_cli("field", "aluminium-34", "--batter", "pro", *RIGID, "--no-reports",
                      "--figures", out)
    assert res.exit_code == 0, res.stderr
    stem = "field--pro--aluminium-34-ash-34"
    assert sorted(p.name for p in out.glob("[!.]*")) == sorted(
        f"{stem}--pro-{f}.{x}" for f in ("exit-speed", "carry") for x in ("svg", "pdf", "png"))
    assert (out / f"{stem}--pro-carry.png").read_bytes().startswith(b"\x89PNG")
    assert "wrote 6 figure files" in res.stderr


def test_a_bat_or_profile_named_twice_runs_once(batcert_cli):
    doc = _field(batcert_cli, "aluminium-34", "aluminium-34", "-b", "pro", "-b",
                 "protocols/batters/pro.yaml")
    assert [b["batter"] for b in doc["batters"]] == ["pro"]
    assert [b["is_reference"] for b in doc["batters"][0]["bats"]] == [False, True]
