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
