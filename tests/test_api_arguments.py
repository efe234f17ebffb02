"""The library checks its arguments as the command line does (batcert.arguments) and raises
one exception family, batcert.BatcertError, with the argument's name first in the message
(issue 40, item 3: each of these returned something, or raised AttributeError, KeyError,
TypeError or OSError, before)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import batcert
from batcert import arguments

LAB = Path(__file__).resolve().parents[1] / "examples" / "lab"
SESSION = str(LAB / "synthetic-exact.yaml")

REFUSED = [
    ("bat", lambda: batcert.run(None, "ncaa-bbcor", engine="rigid")),
    ("bat", lambda: batcert.run(3, "ncaa-bbcor", engine="rigid")),
    ("bat", lambda: batcert.run(["ash-34"], "ncaa-bbcor", engine="rigid")),
    ("bat", lambda: batcert.run("", "ncaa-bbcor", engine="rigid")),
    ("bat", lambda: batcert.run("ncaa-bbcor", "ash-34", engine="rigid")),  # swapped
    ("protocol", lambda: batcert.run("ash-34", 0.5, engine="rigid")),
    ("engine", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="fast")),
    ("engine", lambda: batcert.run("ash-34", "ncaa-bbcor", engine=None)),
    ("bats", lambda: batcert.compare("ash-34", ["ncaa-bbcor"], engine="rigid")),
    ("bats[1]", lambda: batcert.compare(["ash-34", None], ["ncaa-bbcor"], engine="rigid")),
    ("figures", lambda: batcert.compare(["ash-34", "r161"], ["ncaa-bbcor"], engine="rigid",
                                        figures="yes")),
    ("bats", lambda: batcert.league("ncaa", None, engine="rigid")),
    ("bats", lambda: batcert.league("ncaa", [], engine="rigid")),
    ("league_id", lambda: batcert.league(7, ["ash-34"], engine="rigid")),
    ("launch_angle", lambda: batcert.field("ash-34", launch_angle=math.nan, engine="rigid")),
    ("launch_angle", lambda: batcert.field("ash-34", launch_angle=80, engine="rigid")),
    ("backspin", lambda: batcert.field("ash-34", backspin=math.inf, engine="rigid")),
    ("sidespin", lambda: batcert.field("ash-34", sidespin="lots", engine="rigid")),
    ("temperature", lambda: batcert.field("ash-34", temperature=1000.0, engine="rigid")),
    ("temperature", lambda: batcert.field("ash-34", temperature="58C", engine="rigid")),
    ("temperature", lambda: batcert.field("ash-34", temperature="warm", engine="rigid")),
    ("elevation", lambda: batcert.field("ash-34", elevation=math.inf, engine="rigid")),
    ("elevation", lambda: batcert.field("ash-34", elevation="9 km", engine="rigid")),
    ("pitch_speed", lambda: batcert.field("ash-34", pitch_speed=-5, engine="rigid")),
    ("pitch_speed", lambda: batcert.field("ash-34", pitch_speed="85 kg", engine="rigid")),
    ("batters[0]", lambda: batcert.field("ash-34", batters=[None], engine="rigid")),
    ("workers", lambda: batcert.sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2"],
                                      engine="rigid", workers=0)),
    ("workers", lambda: batcert.sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2"],
                                      engine="rigid", workers=-1)),
    ("workers", lambda: batcert.sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2"],
                                      engine="rigid", workers=1.5)),
    ("workers", lambda: batcert.sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2"],
                                      engine="rigid", workers=True)),
    ("vary", lambda: batcert.sweep("ash-34", "ncaa-bbcor", [3], engine="rigid")),
    ("points", lambda: batcert.design("aluminium-34", "ncaa-bbcor", "wall", engine="rigid",
                                      points=2)),
    ("parameter", lambda: batcert.design("aluminium-34", "ncaa-bbcor", None, engine="rigid")),
    ("decision_rule", lambda: batcert.reduce(SESSION, "ncaa-bbcor", decision_rule="strict",
                                             engine="rigid")),
    ("session", lambda: batcert.reduce(None, "ncaa-bbcor", engine="rigid")),
    # run's Monte Carlo (run --uncertainty N --seed S --uncertainty-method M
    # --uncertainty-bound X), refused before anything runs
    ("uncertainty", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid", uncertainty=1)),
    ("uncertainty", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                        uncertainty=100.0)),
    ("uncertainty", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                        uncertainty=True)),
    ("seed", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid", uncertainty=10,
                                 seed=-1)),
    ("seed", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid", seed=7)),
    ("uncertainty_method", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                               uncertainty=10, uncertainty_method="fast")),
    ("uncertainty_method", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                               uncertainty_method="full")),
    ("uncertainty_bound", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                              uncertainty=10, uncertainty_bound=0)),
    ("uncertainty_bound", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                              uncertainty=10, uncertainty_bound=math.nan)),
    ("uncertainty_bound", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                              uncertainty=10, uncertainty_bound="1e-4")),
    ("uncertainty_bound", lambda: batcert.run("ash-34", "ncaa-bbcor", engine="rigid",
                                              uncertainty_bound=1e-3)),
]


@pytest.mark.parametrize("name, call", REFUSED, ids=[f"{n}-{i}" for i, (n, _) in
                                                       enumerate(REFUSED)])
def test_an_argument_that_cannot_mean_anything_is_refused_by_name(name, call):
    with pytest.raises(batcert.UsageProblem) as err:
        call()
    assert isinstance(err.value, batcert.BatcertError)
    assert str(err.value).startswith(f"{name}: "), str(err.value)


def test_every_error_family_member_is_a_batcert_error():
    from batcert.engines import EngineUnavailable
    from batcert.errors import ModelError, OutputError, SchedulerUnavailable
    for cls in (batcert.InputError, batcert.NotFound, batcert.UsageProblem, ModelError,
                OutputError, SchedulerUnavailable, EngineUnavailable):
        assert issubclass(cls, batcert.BatcertError), cls
    with pytest.raises(batcert.BatcertError):
        batcert.run("no-such-bat", "ncaa-bbcor", engine="rigid")
    with pytest.raises(batcert.NotFound):
        batcert.run("ash-34", "no-such-protocol", engine="rigid")


def test_loaded_bats_and_quantities_with_units_are_taken():
    # a loaded bat stands for its file (it raised "File name too long": its repr was read as a
    # path); quantities as strings with units, the ends of a range included
    ash = batcert.load_bat("ash-34")
    c = batcert.compare([ash, "r161"], ["ncaa-bbcor"], engine="rigid")
    assert [Path(b.path).name for b in c.bats] == ["ash-34.yaml", "r161.yaml"]
    a = batcert.field(ash, pitch_speed="85 mph", temperature="57C", elevation="5280 ft",
                      engine="rigid")
    b = batcert.field("ash-34", pitch_speed=85 * 0.44704, temperature=57 + 273.15,
                      elevation=5280 * 0.3048, engine="rigid")
    assert a.to_dict()["batters"] == b.to_dict()["batters"]


def test_run_with_uncertainty_is_the_command_lines(batcert_cli):
    # the library's Monte Carlo is the command line's: the same draws, the same results
    import json
    result = batcert.run("ash-34", "ncaa-bbcor", uncertainty=100, seed=5,
                         uncertainty_bound=2e-4)
    u = result.uncertainty
    assert (u.samples, u.seed, u.propagation.method, u.propagation.bound) == (
        100, 5, "surrogate", 2e-4)
    cli = batcert_cli("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", "100", "--seed",
                      "5", "--uncertainty-bound", "2e-4", "--json")
    assert json.loads(cli.stdout)["results"][0]["uncertainty"]["values"] == u.values
    # the result reads back from its document, the propagation's record with it
    from batcert.results.run import RunResult
    assert RunResult.from_dict(result.to_dict()).uncertainty.propagation == u.propagation


def test_the_command_line_refuses_what_the_library_refuses(batcert_cli):
    # one reader for both: the same words after click's "Invalid value for '--temperature'"
    result = batcert_cli("field", "ash-34", "--temperature", "58C", "--engine", "rigid")
    assert result.exit_code == 2
    assert "Invalid value for '--temperature': 58C is outside -43 to 57 C" in result.stderr
    result = batcert_cli("field", "ash-34", "--launch-angle", "nan", "--engine", "rigid")
    assert result.exit_code == 2 and "must be a finite number" in result.stderr


@settings(max_examples=60, deadline=None)
@given(st.one_of(st.none(), st.integers(), st.floats(), st.booleans(),
                 st.lists(st.text(max_size=3), max_size=2), st.dictionaries(st.text(), st.text())))
def test_no_non_name_is_taken_as_a_bat(value):
    with pytest.raises(arguments.ArgumentError, match="^bat: expected a shipped bat name"):
        arguments.name_or_path("bat", value, "bat")


@settings(max_examples=60, deadline=None)
@given(st.floats(allow_nan=True, allow_infinity=True))
def test_a_temperature_is_within_its_range_or_refused(kelvin):
    try:
        t = arguments.temperature(kelvin)
    except arguments.ArgumentError as exc:
        assert str(exc).startswith("temperature: ")
        assert not (-43 <= kelvin - 273.15 <= 57)
    else:
        assert -43 - 1e-9 <= t - 273.15 <= 57 + 1e-9
