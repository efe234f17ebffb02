"""The youth league files (Little League Intermediate/Junior and Senior, Babe Ruth 16-18, PONY)
on the shipped BBCOR alloy bat
(34 in, 2 5/8 in): the size rules follow from the bat file; the either-or performance rule is
not modelled, the BBCOR-only one runs ncaa-bbcor (rigid engine: the number is not what is
tested)."""

from __future__ import annotations

import pytest

from batcert.commands.league import run_league


def _checked_rules(league: str, bat: str, verdicts: dict) -> dict:
    """The league's rule results for ``bat`` (rigid engine), each rule of ``verdicts`` present
    with its verdict (None: any)."""
    result = run_league(league, [bat], engine="rigid")
    rules = {r.rule: r for r in result.bats[0].rules}
    assert set(rules) == set(verdicts)
    for name, verdict in verdicts.items():
        if verdict is not None:
            assert rules[name].verdict == verdict, name
    return rules


@pytest.mark.parametrize("league, verdicts", [
    ("little-league-intermediate", {"length": "pass", "diameter": "pass",
                                    "performance": "not-modelled"}),
    ("little-league-senior", {"diameter": "pass", "bbcor": None}),
    ("babe-ruth-16-18", {"length": "pass", "diameter": "pass", "drop": "pass", "bbcor": None}),
    ("pony", {"diameter": "pass", "performance": "not-modelled"}),
    ("babe-ruth-13-15", {"length": "pass", "diameter": "pass", "performance": "not-modelled"}),
    ("dixie-boys", {"diameter": "pass", "performance": "not-modelled"}),
])
def test_every_rule_is_evaluated_or_said_not_to_be(league, verdicts):
    rules = _checked_rules(league, "bbcor-alloy-34", verdicts)
    if "bbcor" in rules:
        assert rules["bbcor"].protocol == "ncaa-bbcor" and rules["bbcor"].verdict in ("pass",
                                                                                      "fail")
    assert rules["diameter"].margin == 0.0  # the bat's 2 5/8 in barrel, at the limit


IN, OZ = 0.0254, 0.028349523125


@pytest.mark.parametrize("league, verdicts", [
    # youth-alloy-30: 30 in, 20 oz (drop 10), 2 5/8 in barrel
    ("usssa", {"barrel": "pass", "bpf": None}),
    ("usssa-13u", {"barrel": "pass", "drop": "fail", "bpf": None}),
    ("usssa-14u", {"barrel": "pass", "drop": "fail", "bpf": None}),
    ("cal-ripken", {"length": "pass", "diameter": "pass", "usabat": "not-modelled"}),
    ("dixie-youth", {"length": "pass", "diameter": "pass", "performance": "not-modelled"}),
    ("little-league", {"length": "pass", "diameter": "pass", "handle-wood": "not-applicable",
                       "handle-wood-short": "not-applicable", "usabat": "not-modelled"}),
])
def test_the_youth_bat_under_the_youth_leagues(league, verdicts):
    """The drop rules by USSSA division (13U: at most 8, 14U: at most 5; USSSA statement as
    quoted, REFERENCE-DATA.md H) on a drop-10 bat: margins by arithmetic on the bat file."""
    rules = _checked_rules(league, "youth-alloy-30", verdicts)
    if "drop" in rules:
        limit = {"usssa-13u": 8, "usssa-14u": 5}[league]
        drop = 30 - 20  # the bat's length in inches minus its weight in ounces
        assert rules["drop"].value == pytest.approx(drop, rel=1e-9)
        assert rules["drop"].margin == pytest.approx(limit - drop, rel=1e-9)
