"""Readable at 80 columns (issue 40, item 13): with ``COLUMNS=80`` (and piped, as here) no line
of a command's terminal output is wider than 80 characters, except a line that is one word (a
long path): headlines, warnings and stacked table cells wrap with a hanging indent, a table
wider than the width is stacked, and ``--json`` is never wrapped."""

from __future__ import annotations

import json

import pytest

WIDTH = 80


@pytest.fixture(autouse=True)
def _eighty_columns(monkeypatch):
    monkeypatch.setenv("COLUMNS", str(WIDTH))


def too_wide(text: str, width: int = WIDTH) -> list[str]:
    """The lines of ``text`` wider than ``width`` that are not one unbreakable word."""
    return [line for line in text.splitlines()
            if len(line) > width and len(line.split()) > 1]


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
