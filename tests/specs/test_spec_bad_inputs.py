"""Bad input: one fixture per error message (tests/fixtures/bad/).

Each fixture must make both ``batcert validate`` and ``batcert run`` (``batcert field`` for a
batter file) exit with code 3, name the
file, line and field of every problem (``file:line: field: message``), and write nothing to the
``--out`` directory.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import pytest

BAD = Path(__file__).resolve().parents[1] / "fixtures" / "bad"


@dataclass(frozen=True)
class Expect:
    line: int
    field: str  # "" for problems of the whole file
    message: str  # a fragment of the message


CASES: dict[str, list[Expect]] = {
    # --- bat files
    "bat-misspelt-key.yaml": [
        Expect(4, "lenght", "unknown field; did you mean 'length'?"),
        Expect(2, "length", "required field is missing"),  # the misspelt key leaves it missing
    ],
    "bat-negative-mass.yaml": [Expect(10, "measured.mass", "must be at least 0.1 kg, got -906 g")],
    "bat-bad-indentation.yaml": [Expect(7, "", "malformed YAML: mapping values are not allowed")],
    "bat-unclosed-bracket.yaml": [
        Expect(7, "", "malformed YAML: expected ',' or ']', but got '[' (while parsing a flow "
                      "sequence started on line 6)"),
    ],
    "bat-moi-below-mrbar2.yaml": [
        Expect(15, "measured.moi", "MOI 0.1500 kg m^2 about the pivot is below M rbar^2 = 0.1667"),
    ],
    "bat-density-weight.yaml": [
        Expect(11, "measured", "cannot reconcile: matching the measured mass properties needs the "
                               "density scaled by 2.17 to 2.17 along the bat (allowed 0.5-2.0)"),
    ],
    "bat-point-masses-refused.yaml": [
        Expect(24, "measured", "cannot reconcile with point masses: it would need a negative knob "
                               "mass (-12 g) and a negative end-cap mass (-28 g); try `reconcile: "
                               "density-profile`"),
    ],
    "bat-layup-coupled.yaml": [
        Expect(7, "layup[0].walls[0].plies", "this wall couples stretching or bending with shear "
                                             "or twist"),
    ],
    "bat-layup-problems.yaml": [
        Expect(11, "layup[0].walls[0].plies[0]", "unknown ply material 't700-epoxi'"),
        Expect(12, "layup[0].walls[0].plies[1]", "a ply angle is written like '0 deg'"),
        Expect(13, "layup[0].walls[0].plies[2]", "a ply's thickness must be 0.01-20 mm"),
    ],
    "bat-layup-on-solid.yaml": [Expect(6, "layup", "only a hollow bat has a wall to lay up")],
    # issue 40, item 14b: 34 cm for 34 in was reported at the profile and the wall
    "bat-length-in-cm.yaml": [
        Expect(5, "length", "13.39 in is shorter than any bat (20 in) and than the profile and "
                            "the wall, which reach 34.00 in from the knob: is the length's unit "
                            "right?"),
    ],
    "bat-profile-beyond-tip.yaml": [
        Expect(5, "profile", "stations must lie between the knob (0) and the tip (the length, "
                             "33.00 in, line 4)"),
        Expect(10, "wall", "stations must lie between the knob (0) and the tip (the length, "
                           "33.00 in, line 4)"),
    ],
    "bat-layup-overlap.yaml": [Expect(10, "layup[1].span", "overlaps span 0")],
    # issue 40 item 6c: a span that holds no slice's centre was an IndexError in the model
    "bat-layup-span-narrower-than-a-slice.yaml": [
        Expect(10, "layup[1].span", "the span (0.254 mm, 50.80 to 50.83 cm from the knob) holds "
                                    "no slice's centre: the model slices the bat every 9.9 mm"),
    ],
    "protocol-break-in-without-compression.yaml": [
        Expect(14, "break_in", "the break-in reads the barrel's compression: add "
                               "`barrel_compression`"),
    ],
    "bat-bare-number.yaml": [
        Expect(4, "length", "a unit is required (e.g. '34 in'), got the bare number 34"),
    ],
    "bat-wrong-dimension.yaml": [Expect(4, "length", "'34 kg' is not a length")],
    "bat-dimensionless-length.yaml": [Expect(4, "length", "'34 dimensionless' is not a length")],
    "bat-unknown-unit.yaml": [
        Expect(4, "length", "cannot read '34 inchez': unknown unit 'inchez'"),
    ],
    "bat-frequency-in-rad-per-s.yaml": [
        Expect(13, "measured.first_bending_frequency", "'1100 rad/s' is an angular speed; give a "
                                                       "frequency"),
    ],
    "bat-unknown-material.yaml": [
        Expect(8, "material", "unknown material 'ashe' (library: ash, maple, birch, ash-bat, "
                              "aluminium-7050); did you mean 'ash'?"),
    ],
    "bat-missing-field.yaml": [Expect(2, "material", "required field is missing")],
    "bat-duplicate-key.yaml": [Expect(8, "length", "duplicate key (first given on line 4)")],
    "bat-hollow-without-wall.yaml": [Expect(3, "wall", "hollow bats need a wall thickness")],
    "bat-solid-with-wall.yaml": [Expect(8, "wall", "a solid bat has no wall")],
    "bat-wall-too-thick.yaml": [
        Expect(10, "wall", "the wall (14.0 mm) fills the section at 0.5 cm from the knob (outer "
                           "diameter 25.4 mm)"),
    ],
    "bat-hoop-on-solid.yaml": [
        Expect(11, "measured.hoop_frequency", "only a hollow bat has a barrel to measure"),
    ],
    "bat-hoop-absurd.yaml": [
        Expect(16, "measured.hoop_frequency", "matching 600 Hz needs the wall's stiffness x 0.10 "
                                              "(model hoop frequency 1901 Hz); allowed x0.25-x4.0"),
    ],
    "bat-compression-off-barrel.yaml": [
        Expect(19, "measured.barrel_compression.position", "the platens (32.5-34.5 in from the "
               "tip) do not lie on the hollow wall (the hollow wall runs 0.0-33.9 in from the "
               "tip)"),
    ],
    "bat-profile-not-increasing.yaml": [
        Expect(8, "profile[2]", "must increase; 10 in follows 12 in"),
    ],
    "bat-cg-and-balance-point.yaml": [
        Expect(14, "measured.cg", "give either balance_point (from the knob) or cg (from the "
                                  "pivot), not both"),
    ],
    "bat-three-errors.yaml": [
        Expect(4, "length", "a unit is required"),
        Expect(8, "material", "did you mean 'ash'?"),
        Expect(9, "knob_mas", "unknown field; did you mean 'knob_mass'?"),
    ],
    "empty.yaml": [Expect(1, "", "the file is empty; expected a mapping of fields")],
    "top-level-list.yaml": [Expect(1, "", "the top level must be a mapping of fields")],
    # --- protocol files
    "protocol-both-speeds.yaml": [
        Expect(8, "conditions[0]", "give either explicit speeds (pitch_speed with "
                                   "bat_angular_speed or bat_speed) or a matched relative_speed, "
                                   "not both"),
    ],
    "protocol-moi-scaling-misplaced.yaml": [
        Expect(10, "conditions[0].bat_speed_from_moi", "scales the bat speed, which is zero here"),
        Expect(16, "conditions[1].bat_speed_from_moi", "only with bat_speed or bat_angular_speed"),
        Expect(25, "conditions[2].bat_speed_from_moi.exponent", "must be at most 1"),
    ],
    "protocol-missing-speeds.yaml": [Expect(8, "conditions[0]", "give the speeds")],
    "protocol-bat-speed-without-position.yaml": [
        Expect(10, "conditions[0].bat_speed_from_tip", "bat_speed needs bat_speed_from_tip"),
    ],
    "protocol-angular-speed-in-hz.yaml": [
        Expect(10, "conditions[0].bat_angular_speed", "'8 Hz' is ambiguous as an angular speed"),
    ],
    "protocol-fixed-without-from-tip.yaml": [
        Expect(12, "impact_location.from_tip", "the fixed-from-tip rule needs from_tip"),
    ],
    "protocol-unknown-metric.yaml": [
        Expect(13, "metric", "must be one of exit-speed, besr, bpf, bbcor, collision-efficiency; "
                             "got 'bbcorr'; did you mean 'bbcor'?"),
    ],
    "protocol-fractional-sweep-points.yaml": [
        Expect(13, "impact_location.sweep_points", "expected a whole number, got 70.5"),
    ],
    "protocol-unknown-ball.yaml": [
        Expect(6, "ball", "unknown ball 'colegiate-baseball' (shipped: collegiate-baseball, "
                          "nathan-2000, softball-11in-44-375, softball-fastpitch-47-375, "
                          "softball-ncaa-47-350, softball-slowpitch-44-375, "
                          "softball-slowpitch-52-300, softball-test-52-275); did you mean "
                          "'collegiate-baseball'?"),
    ],
    "protocol-limit-without-unit.yaml": [
        Expect(16, "limit.max", "the exit-speed limit is a speed: give its unit, e.g. '97 mph', "
                                "got 97"),
    ],
    "protocol-limit-with-unit.yaml": [
        Expect(15, "limit.max", "bbcor is dimensionless: give a plain number, got '0.5 m/s'"),
    ],
    # --- ball files
    "ball-cor-out-of-range.yaml": [Expect(7, "cor[1]", "COR must be a number in (0, 1], got 1.2")],
    # issue 40 item 6d: a ZeroDivisionError in the fit's coordinates
    "ball-relaxed-fraction-1-held.yaml": [
        Expect(12, "contact.relaxed_fraction", "relaxed_fraction held at 1: the fit needs it "
                                               "strictly between 0 and 1"),
    ],
    "ball-speeds-not-increasing.yaml": [
        Expect(7, "cor[1]", "impact speeds must increase; 10 m/s follows 50 m/s"),
    ],
    # --- batter files (batcert field)
    "batter-misspelt-key.yaml": [
        Expect(3, "descripton", "unknown field; did you mean 'description'?"),
    ],
    "batter-missing-bat-speed.yaml": [Expect(8, "swing.bat_speed", "required field is missing")],
    "batter-exponent-above-1.yaml": [
        Expect(11, "swing.exponent", "must be at most 1, got 1.25"),
    ],
    "batter-bat-speed-without-unit.yaml": [
        Expect(8, "swing.bat_speed", "a unit is required (e.g. '70 mph'), got the bare number 65"),
    ],
    "batter-station-near-axis.yaml": [
        Expect(9, "swing.speed_from_tip", "the station where the bat speed is measured must lie "
                                          "more than 5 cm from the swing axis"),
    ],
    "batter-unknown-ball.yaml": [
        Expect(4, "ball", "unknown ball 'colegiate-baseball' (shipped: collegiate-baseball, "
                          "nathan-2000, softball-11in-44-375, softball-fastpitch-47-375, "
                          "softball-ncaa-47-350, softball-slowpitch-44-375, "
                          "softball-slowpitch-52-300, softball-test-52-275); did you mean "
                          "'collegiate-baseball'?"),
    ],
}


def test_every_fixture_has_a_case():
    assert sorted(p.name for p in BAD.glob("*.yaml")) == sorted(CASES)


def _run_args(name: str, path: Path, tmp_path: Path) -> list[str]:
    """`batcert run` arguments that load the bad file: as the bat, the protocol or the ball
    (`batcert field` arguments for a batter file)."""
    if name.startswith("batter-"):
        return ["field", "ash-34", "--batter", str(path)]
    if name.startswith("protocol-"):
        return ["run", "ash-34", "--protocol", str(path)]
    if name.startswith("ball-"):
        protocol = tmp_path / "uses-bad-ball.yaml"
        protocol.write_text(
            "id: uses-bad-ball\ntitle: t\nreference: t\nversion: '1'\n"
            f"ball: {path}\n"
            "conditions:\n  - name: c\n    pitch_speed: 31 m/s\n    bat_angular_speed: 0 rad/s\n"
            "impact_location:\n  rule: cop\nmetric: bbcor\n", encoding="utf-8")
        return ["run", "ash-34", "--protocol", str(protocol)]
    return ["run", str(path), "--protocol", "ncaa-bbcor"]


def _check_messages(stderr: str, path: Path, expected: list[Expect]) -> None:
    heads = [ln for ln in stderr.splitlines() if ln.startswith(f"{path}:")]
    assert len(heads) == len(expected), stderr
    for e in expected:
        head = f"{path}:{e.line}: {e.field + ': ' if e.field else ''}"
        assert any(h.startswith(head) and e.message in h for h in heads), (head, e.message, stderr)
    n = len(expected)
    assert f"{n} problem{'s' if n > 1 else ''} in {path}" in stderr


@pytest.mark.parametrize("name", sorted(CASES))
def test_validate_reports_file_line_field(name, batcert_cli):
    path = BAD / name
    result = batcert_cli("validate", path)
    assert result.exit_code == 3, result.output
    assert result.stdout == ""
    _check_messages(result.stderr, path, CASES[name])


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("fmt_args", [[], ["--json"]], ids=["table", "json"])
def test_run_exits_3_and_writes_nothing(name, fmt_args, batcert_cli, tmp_path):
    path = BAD / name
    out = tmp_path / "reports"
    result = batcert_cli(*_run_args(name, path, tmp_path), "--engine", "rigid", "--out", out,
                         *fmt_args)
    assert result.exit_code == 3, result.output
    assert result.stdout == ""  # nothing on stdout, not even with --json
    _check_messages(result.stderr, path, CASES[name])
    assert not out.exists()


def test_rendered_problem_shows_line_and_caret(batcert_cli):
    """The offending line is quoted under the message, with a caret under the value."""
    path = BAD / "bat-bare-number.yaml"
    err = batcert_cli("validate", path).stderr.splitlines()
    i = next(i for i, ln in enumerate(err) if ln.startswith(f"{path}:4:"))
    assert err[i + 1] == "    4 | length: 34"
    assert err[i + 2] == "      |         ^"


def test_validate_reports_every_file(batcert_cli):
    """Several files: every problem of every file, one summary per file, exit 3."""
    a, b = BAD / "bat-bare-number.yaml", BAD / "protocol-unknown-metric.yaml"
    good = BAD.parent / "good" / "ball.yaml"
    result = batcert_cli("validate", a, good, b)
    assert result.exit_code == 3
    assert f"ok  {good} (ball)" in result.stdout
    assert f"{a}:4: length:" in result.stderr and f"{b}:13: metric:" in result.stderr


def test_unknown_protocol_name_is_a_usage_error(batcert_cli, tmp_path):
    out = tmp_path / "reports"
    result = batcert_cli("run", "ash-34", "--protocol", "ncaa-bbcr", "--engine", "rigid",
                         "--out", out)
    assert result.exit_code == 2
    assert "unknown protocol 'ncaa-bbcr'" in result.stderr
    assert "did you mean 'ncaa-bbcor'?" in result.stderr
    assert not out.exists()


def test_missing_bat_file_is_a_usage_error(batcert_cli, tmp_path):
    result = batcert_cli("run", tmp_path / "nope.yaml", "--protocol", "proposed",
                         "--engine", "rigid", "--out", tmp_path / "reports")
    assert result.exit_code == 2
    assert re.search(r"bat file not found: .*nope\.yaml", result.stderr)


def test_bad_bat_stops_before_any_protocol_runs(batcert_cli, tmp_path):
    """With a good protocol first and a bad one second, nothing runs and nothing is written."""
    out = tmp_path / "reports"
    bad = BAD / "protocol-unknown-metric.yaml"
    result = batcert_cli("run", "ash-34", "-p", "proposed", "-p", bad, "--engine", "rigid",
                         "--out", out)
    assert result.exit_code == 3
    assert f"{bad}:13: metric:" in result.stderr
    assert not out.exists()
