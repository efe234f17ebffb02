"""``batcert run BAT -p PROTOCOL --uncertainty N [--seed S]``: usage errors, and the Monte Carlo's
JSON and Markdown on the shipped ash bat under ncaa-bbcor (40 draws: each run costs about a
second, so the runs are few and shared)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from batcert.cli import main

REPO = Path(__file__).resolve().parents[2]
ASH = REPO / "bats" / "ash-34.yaml"
BALL = REPO / "protocols" / "balls" / "collegiate-baseball.yaml"
BBCOR = REPO / "protocols" / "ncaa-bbcor.yaml"
N = 40
SURFACE_N = 100  # more draws than the response surface's engine runs (at most 69 here)
DEFAULT_SEED = 20011  # documented default of --seed (run --help, docs/uncertainty.md)


def invoke(*args: str | Path):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False)


def test_seed_needs_uncertainty():
    result = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--seed", "5", "--json")
    assert result.exit_code == 2
    assert "--seed needs --uncertainty N" in result.stderr
    assert result.stdout == ""


def test_one_draw_is_refused():
    result = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", "1", "--json")
    assert result.exit_code == 2
    assert "'--uncertainty'" in result.stderr and "2<=x" in result.stderr


def test_files_that_state_no_uncertainty_are_a_usage_error(tmp_path):
    """A bat and a ball without +/- (the shipped bat and batcert 0.2's ball of Nathan's law with
    their +/- removed: a fitted viscoelastic ball needs its tests' uncertainties), under a copy
    of ncaa-bbcor that names that ball."""
    bat = tmp_path / "plain-bat.yaml"
    bat.write_text(re.sub(r" \+/- [^#\n]*\(uniform\)", "", ASH.read_text(encoding="utf-8")))
    ball = tmp_path / "plain-ball.yaml"
    nathan = Path(__file__).resolve().parents[1] / "fixtures" / "good" / "ball-nathan-law.yaml"
    ball.write_text(re.sub(r" \+/- [^\]\n]*\(uniform\)", "", nathan.read_text(encoding="utf-8")))
    for path in (bat, ball):  # only comments still say +/-
        assert not any("+/-" in line.split("#")[0] for line in path.read_text().splitlines())
    text = BBCOR.read_text(encoding="utf-8")
    assert text.count("ball: collegiate-baseball\n") == 1
    protocol = tmp_path / "bbcor-plain-ball.yaml"
    protocol.write_text(text.replace("ball: collegiate-baseball\n", "ball: plain-ball.yaml\n"))
    result = invoke("run", bat, "-p", protocol, "--uncertainty", "10", "--json")
    assert result.exit_code == 2
    message = " ".join(result.stderr.split())
    assert f"neither {bat} nor the ball file states an uncertainty" in message
    assert "mass: 863 g +/- 1 g" in message  # says how to state one
    assert result.stdout == ""  # no JSON of the nominal run either


def test_an_impossible_draw_is_invalid_input_at_its_line(tmp_path):
    """906 g +/- 900 g (normal): a draw at or below 0 kg comes in 16 % of draws
    (Phi(-906/900)), so 200 draws miss it with probability 0.84^200 ~ 1e-15. The draws are
    checked before anything runs, so many cost nothing."""
    text = ASH.read_text(encoding="utf-8")
    old = "  mass: 906 g +/- 0.5 g (uniform)\n"
    assert text.count(old) == 1
    bat = tmp_path / "wide-mass.yaml"
    bat.write_text(text.replace(old, "  mass: 906 g +/- 900 g\n"))
    line = text.splitlines().index(old.rstrip("\n")) + 1
    result = invoke("run", bat, "-p", "ncaa-bbcor", "--uncertainty", "200", "--json")
    assert result.exit_code == 3
    assert f"{bat}:{line}: measured.mass: the stated uncertainty draws" in result.stderr
    assert result.stdout == ""


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The default seed (with JSON and Markdown reports), the same seed given explicitly, and
    another seed."""
    out = tmp_path_factory.mktemp("reports")
    default = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", N, "--json", "--out",
                     out, "--format", "json,md")
    same = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", N, "--json", "--seed",
                  DEFAULT_SEED)
    other = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", N, "--json", "--seed",
                   7)
    return default, same, other, out


def test_json_gives_the_distribution(runs):
    result = runs[0]
    run = json.loads(result.stdout)["results"][0]
    # the exit code and verdict stay the nominal ones, whatever the pass probability
    assert result.exit_code == {"pass": 0, "fail": 1}[run["verdict"]]
    u = run["uncertainty"]
    assert u["samples"] == N and u["seed"] == DEFAULT_SEED
    values = np.array(u["values"])
    assert values.shape == (N,) and np.all(np.isfinite(values))
    assert values.std() > 0  # the draws move the result (the COR band alone does: +/- 0.032)
    assert 0 <= u["pass_probability"] <= 1
    # the share of draws within the limit (BBCOR <= 0.500 + tolerance), as decide() counts
    assert u["pass_probability"] == np.mean(values <= run["limit"] + run["tolerance"])
    assert u["interval_low"] <= u["median"] <= u["interval_high"]
    assert u["median"] == pytest.approx(np.median(values), rel=1e-12)
    assert (u["minimum"], u["maximum"]) == (values.min(), values.max())
    assert u["mean"] == pytest.approx(values.mean(), rel=1e-12)
    assert u["nominal_value"] == run["value"]
    assert [(i["file"], i["field"]) for i in u["inputs"]] == [
        ("bat", "measured.mass"), ("bat", "measured.cg"), ("bat", "measured.moi"),
        ("ball", "mass"), ("ball", "cor")]
    assert all(i["distribution"] == "uniform" for i in u["inputs"])
    assert u["inputs"][0]["nominal"] == [0.906]
    # 40 draws cost fewer engine runs than the response surface would (69 for five inputs):
    # every draw is solved, and the document says why
    p = u["propagation"]
    assert (p["method"], p["requested"], p["engine_draws"]) == ("full", "surrogate", N)
    assert p["reason"] == "40 draws are not more than the 69 engine runs the surface may take"


def test_same_seed_same_draws_other_seed_other_draws(runs):
    default, same, other, _ = runs
    values = [json.loads(r.stdout)["results"][0]["uncertainty"] for r in (default, same, other)]
    assert values[1]["seed"] == DEFAULT_SEED and values[2]["seed"] == 7
    assert values[1]["values"] == values[0]["values"]  # same draws, same computation: exact
    assert not np.any(np.isclose(values[2]["values"], values[0]["values"], rtol=0, atol=1e-12))


def test_markdown_report_has_the_monte_carlo_section(runs):
    _, _, _, out = runs
    [md] = out.glob("*.md")
    text = md.read_text(encoding="utf-8")
    assert "## Predicted uncertainty (Monte Carlo)" in text
    assert "measured.mass" in text and "cor" in text
    [js] = out.glob("*.json")  # the written JSON carries the same draws as stdout
    written = json.loads(js.read_text(encoding="utf-8"))
    run = written["results"][0] if "results" in written else written
    assert run["uncertainty"]["values"] == json.loads(runs[0].stdout)["results"][0][
        "uncertainty"]["values"]


@pytest.mark.parametrize("option, value, message", [
    ("--uncertainty-method", "fast", "Invalid value for '--uncertainty-method': 'fast' is not one of"),
    ("--uncertainty-bound", "0", "Invalid value for '--uncertainty-bound': must be above 0, got 0.0"),
    ("--uncertainty-bound", "-1e-4", "must be above 0, got -0.0001"),
    ("--uncertainty-bound", "nan", "must be a finite number, got nan"),
    ("--uncertainty-bound", "small", "expected a number, got str 'small'"),
])
def test_bad_method_or_bound_is_a_usage_error(option, value, message):
    result = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", N, option, value,
                    "--json")
    assert result.exit_code == 2
    assert message in " ".join(result.stderr.split())
    assert result.stdout == ""


@pytest.mark.parametrize("option, value", [("--uncertainty-method", "full"),
                                           ("--uncertainty-bound", "1e-3")])
def test_method_and_bound_need_uncertainty(option, value):
    result = invoke("run", "ash-34", "-p", "ncaa-bbcor", option, value, "--json")
    assert result.exit_code == 2
    assert f"{option} needs --uncertainty N" in result.stderr


@pytest.fixture(scope="module")
def surface_runs(tmp_path_factory):
    """SURFACE_N draws by the response surface (the default; Markdown report and the terminal
    view) and by full draws (JSON)."""
    out = tmp_path_factory.mktemp("surface")
    surface = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", SURFACE_N, "--out",
                     out, "--format", "json,md")
    full = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", SURFACE_N,
                  "--uncertainty-method", "full", "--json")
    return surface, full, out


def test_the_report_states_the_surface_and_its_check(surface_runs):
    surface, full, out = surface_runs
    [js] = out.glob("*.json")
    written = json.loads(js.read_text(encoding="utf-8"))
    u = (written["results"][0] if "results" in written else written)["uncertainty"]
    p = u["propagation"]
    assert (p["method"], p["requested"], p["reason"], p["bound"]) == (
        "surrogate", "surrogate", "", 1e-4)
    assert p["checked_draws"] == 8 and p["engine_draws"] == p["design_points"] + 8 < SURFACE_N
    assert 0 < p["largest_difference"] <= 1e-4
    f = json.loads(full.stdout)["results"][0]["uncertainty"]
    assert (f["propagation"]["method"], f["propagation"]["requested"]) == ("full", "full")
    assert f["propagation"]["largest_difference"] is None
    # the same draws: the surface's results are the engine's to within the bound (measured
    # 3e-6 on ash-34)
    np.testing.assert_allclose(u["values"], f["values"], rtol=0, atol=1e-4)
    [md] = out.glob("*.md")
    text = " ".join(md.read_text(encoding="utf-8").split())
    assert "| Propagation | response surface |" in text
    assert "| Surrogate check |" in text and "bound 0.00010" in text
    assert "engine runs in all" in text
    terminal = " ".join(surface.stdout.split())  # the terminal's sentence says it too
    assert (f"fitted on {p['design_points']} engine runs; the engine's own results for 8 of "
            "the draws differ from it by at most") in terminal


def test_a_surface_beyond_its_bound_is_replaced_by_every_draw_and_the_terminal_says_so():
    # 1e-12 is below what the surface misses by on the flexible engine (its scatter from draw
    # to draw alone is about 1e-6): every draw is solved, and the terminal's sentence says why
    result = invoke("run", "ash-34", "-p", "ncaa-bbcor", "--uncertainty", SURFACE_N,
                    "--uncertainty-bound", "1e-12", "--no-reports")
    assert result.exit_code in (0, 1)
    text = " ".join(result.stdout.split())
    assert "Every draw solved by the engine (" in text
    assert ("engine runs), not by the response surface: the response surface missed the engine "
            "by ") in text
    assert "on 8 checked draws, more than the bound 1e-12." in text
