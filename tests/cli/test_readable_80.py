"""Readable at 80 columns (issue 40, item 13): with ``COLUMNS=80`` (and piped, as here) no line
of a command's terminal output is wider than 80 characters, except a line that is one word (a
long path): headlines, warnings and stacked table cells wrap with a hanging indent, a table
wider than the width is stacked, and ``--json`` is never wrapped."""

from __future__ import annotations

import json

import pytest
from terminal_lines import too_wide

WIDTH = 80


@pytest.fixture(autouse=True)
def _eighty_columns(monkeypatch):
    monkeypatch.setenv("COLUMNS", str(WIDTH))


def _assert_fits(res) -> None:
    assert too_wide(res.stdout) == [], res.stdout
    assert too_wide(res.stderr) == [], res.stderr


RIGID = ("--engine", "rigid", "--no-reports")

# the README's short tour (the rigid engine where the physics does not matter to the layout)
TOUR = [
    ("protocols",),
    ("list", "bats"),
    ("list", "protocols"),
    ("list", "leagues"),
    ("inspect", "bats/ash-34.yaml"),
    ("inspect", "bats/bbcor-alloy-34.yaml"),
    ("inspect", "bats/double-wall-alloy-34.yaml"),
    pytest.param(("inspect", "collegiate-baseball"), marks=pytest.mark.slow),
    ("run", "bats/ash-34.yaml", "-p", "ncaa-bbcor", "-p", "proposed", *RIGID),
    ("run", "bats/composite-bbcor-34.yaml", "-p", "ncaa-bbcor", *RIGID),
    ("validate", "bats/ash-34.yaml", "protocols/ncaa-bbcor.yaml"),
    pytest.param(("compare", "bats/ash-34.yaml", "bats/aluminium-34.yaml", "--study", "smith2001",
                  *RIGID), marks=pytest.mark.slow),
    ("league", "ncaa", "bats/ash-34.yaml", "bats/aluminium-34.yaml", *RIGID),
    ("league", "usssa-slowpitch", "bats/slowpitch-composite-34.yaml", *RIGID),
    ("field", "bbcor-alloy-34", "--batter", "college", *RIGID),
    ("sweep", "ash-34", "-p", "ncaa-bbcor", "--vary", "pitch_speed=50m/s:60m/s:3", *RIGID),
    ("reduce", "examples/lab/synthetic-scatter.yaml", "-p", "ncaa-bbcor", "--no-reports"),
]


@pytest.mark.parametrize("command", TOUR, ids=lambda c: " ".join(c[:2]))
def test_the_short_tour_fits_80_columns(batcert_cli, repo_root, monkeypatch, command):
    monkeypatch.chdir(repo_root)
    res = batcert_cli(*command)
    assert res.exit_code in (0, 1), res.stderr
    _assert_fits(res)


def test_a_long_warning_wraps_with_a_hanging_indent(batcert_cli):
    # (a) the rigid engine's BPF warning runs to about 200 characters on one line
    res = batcert_cli("run", "ash-34", "-p", "proposed", *RIGID)
    lines = res.stderr.splitlines()
    assert too_wide(res.stderr) == []
    first = next(k for k, line in enumerate(lines) if "rigid engine: the bat neither" in line)
    assert lines[first].startswith("  warning: ")
    assert lines[first + 1].startswith(" " * len("  warning: ")) and lines[first + 1].strip()
    assert "use the flexible engine for a meaningful BPF" in " ".join(res.stderr.split())


def test_json_is_never_wrapped(batcert_cli):
    res = batcert_cli("run", "ash-34", "-p", "proposed", *RIGID, "--json")
    warnings = json.loads(res.stdout)["results"][0]["warnings"]
    long = [w for w in warnings if len(w) > WIDTH]
    assert long and all(json.dumps(w, ensure_ascii=False) in res.stdout for w in long)


def test_compare_stacks_its_table_at_80_columns(batcert_cli):
    # (c) the comparison's grid needs about 165 columns side by side: stacked, a condition per
    # block, every cell whole
    res = batcert_cli("compare", "ash-34", "aluminium-34", "-p", "ncaa-bbcor", "-p", "proposed",
                      *RIGID)
    _assert_fits(res)
    out = res.stdout.splitlines()
    assert "Condition: pitched-and-swung" in out
    assert any(line.startswith("  P: Aluminium 34 in (Smith 2001)  ") for line in out)
    # an empty cell (the bats' own metric has no mean of P) is left out, not shown blank
    assert all(line.split(")")[-1].strip() for line in out if line.startswith("  BPF: "))


# ---------------------------------------------------------------- (b) a sweep's warnings


@pytest.fixture(scope="module")
def deflection_sweep():
    """A small rigid sweep whose warnings are replaced by the kind a 15-point wall sweep gives:
    the same sentence with its numbers, per condition and per variant, as the sweep words
    them."""
    from dataclasses import replace

    from batcert.commands.sweep import plan_sweep, run_sweep
    from batcert.sweeps.sweep import variant_name
    plan = plan_sweep("ash-34", "proposed", ["relative_speed=50m/s:60m/s:3"], "rigid")
    result = run_sweep(plan)
    said = ("{c}: the barrel's wall deflects about {d} mm under the peak force, {r} times its "
            "thickness; the model's wall is linear elastic (docs/physics.md) (1 of 3 variants: "
            "{v})")
    warnings = [said.format(c=c.name, d=1.5 + i, r=0.5 + i / 10, v=variant_name(plan, i))
                for c in result.conditions for i in (0, 1)]
    warnings.append("stationary-bat: the located impact point lies on the search window's edge "
                    "(40.3 cm from the pivot); the true maximum is outside the window (all 3 "
                    "variants)")
    return replace(result, warnings=sorted(warnings))


def test_a_sweeps_alike_warnings_are_one_line(deflection_sweep):
    from batcert.reports.warning_groups import grouped_warnings
    assert len(deflection_sweep.warnings) == 3 * 2 + 1
    grouped = grouped_warnings(deflection_sweep)
    assert len(grouped) == 2
    assert any(g.startswith("relative_speed 50-55 m/s (2 of 3 variants): every condition: the "
                            "barrel's wall deflects about 1.5 to 2.5 mm under the peak force, "
                            "0.5 to 0.6 times its thickness; the model's wall") for g in grouped)
    assert any(g.startswith("all 3 variants: stationary-bat: the located impact point")
               for g in grouped)


def test_the_sweep_view_prints_grouped_warnings_and_keeps_them_all(deflection_sweep, capsys):
    from batcert.console import views
    views.sweep_summary(deflection_sweep, [])
    err = capsys.readouterr().err
    assert too_wide(err) == []
    assert err.count("warning:") == 2 and "every condition" in err
    assert len(deflection_sweep.warnings) == 7  # the result (its JSON, its reports): every one


# ---------------------------------------------------------------- (d) a league of ten bats


def _summary(stdout: str) -> list[str]:
    lines = stdout.splitlines()
    return lines[:lines.index("")]  # the summary, then a blank line, then the detail


def test_a_league_of_several_bats_opens_with_a_summary(batcert_cli):
    bats = ("aluminium-34", "ash-34", "r161")
    res = batcert_cli("league", "ncaa", *bats, *RIGID)
    _assert_fits(res)
    head = _summary(res.stdout)
    # aluminium-34 fails the drop rule, a number of its file: a plain FAIL (issue 40, item 11)
    assert head[0].startswith("FAIL  ncaa") and "Of 3 bats" in " ".join(head)
    rows = {line.split()[0]: line for line in head[1:] if line.startswith("  ")}
    assert rows["aluminium-34"].split()[1:] == ["FAIL", "drop-non-wood"]
    assert rows["ash-34"].split()[1] == "PASS"
    assert sum(line.startswith("rule: ") for line in res.stdout.splitlines()) > 10  # detail
    quiet = batcert_cli("-q", "league", "ncaa", *bats, *RIGID)  # the summary alone, and the
    offset = quiet.stdout.index("known offset of the model")  # model's offset for its verdicts
    assert quiet.stdout[:offset].splitlines() == head


@pytest.mark.slow
def test_a_league_of_ten_bats_sums_up_on_one_screen(batcert_cli, repo_root):
    bats = sorted((repo_root / "bats").glob("*.yaml"))
    assert len(bats) == 10
    res = batcert_cli("league", "ncaa", *bats, *RIGID)
    _assert_fits(res)
    head = _summary(res.stdout)
    assert len(head) <= 24 - 1 and "Of 10 bats" in " ".join(head)  # one 80x24 screen
    assert len([line for line in head if line.startswith("  ")]) >= 10


# ---------------------------------------------------------------- (g) a speed limit's unit


def test_protocols_show_a_speed_limit_with_its_unit(batcert_cli):
    # the batted-ball speed protocols' limit read "43.8099", a number of m/s without its unit
    res = batcert_cli("protocols")
    limits = [line.split(None, 1)[1] for line in res.stdout.splitlines()
              if line.strip().startswith("limit ")]
    assert "43.81 m/s (98.0 mph)" in limits and "43.8099" not in res.stdout
    assert "0.5000" in limits  # BBCOR's, dimensionless, as run shows it
