"""The youth league files (Little League Intermediate/Junior and Senior, Babe Ruth 16-18, PONY)
on the shipped BBCOR alloy bat
(34 in, 2 5/8 in): the size rules follow from the bat file; the either-or performance rule is
not modelled, the BBCOR-only one runs ncaa-bbcor (rigid engine: the number is not what is
tested)."""

from __future__ import annotations

import pytest

from batcert.commands.league import run_league


@pytest.mark.parametrize("league, verdicts", [
    ("little-league-intermediate", {"length": "pass", "diameter": "pass",
                                    "performance": "not-modelled"}),
    ("little-league-senior", {"diameter": "pass", "bbcor": None}),
    ("babe-ruth-16-18", {"length": "pass", "diameter": "pass", "drop": "pass", "bbcor": None}),
    ("pony", {"diameter": "pass", "performance": "not-modelled"}),
])
def test_every_rule_is_evaluated_or_said_not_to_be(league, verdicts):
    result = run_league(league, ["bbcor-alloy-34"], engine="rigid")
    rules = {r.rule: r for r in result.bats[0].rules}
    assert set(rules) == set(verdicts)
    for name, verdict in verdicts.items():
        if verdict is not None:
            assert rules[name].verdict == verdict, name
    if "bbcor" in rules:
        assert rules["bbcor"].protocol == "ncaa-bbcor" and rules["bbcor"].verdict in ("pass",
                                                                                      "fail")
    assert rules["diameter"].margin == 0.0  # the bat's 2 5/8 in barrel, at the limit
