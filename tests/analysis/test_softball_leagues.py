"""The shipped softball leagues on the shipped fast-pitch bat (33 in, 23 oz, 2 1/4 in): the size
rules follow from the bat file by arithmetic; the performance rule runs its protocol; the rules
the files mark not modelled stay so (batcert.analysis.league). Rigid engine: the numbers of the
performance rules are not what is tested here."""

from __future__ import annotations

import pytest

from batcert.analysis.league import EVALUATIONS
from batcert.commands.league import run_league

OZ = 0.028349523125


@pytest.mark.parametrize("league, modelled, not_modelled", [
    ("usa-softball", {"length", "weight", "barrel", "bbs"}, {"approved-list"}),
    ("usssa-slowpitch", {"length", "barrel", "bpf"}, {"weight", "compression"}),
    ("ncaa-softball", {"length", "weight", "barrel", "bbs"}, {"compression", "approved-list"}),
    ("usssa-fastpitch", {"length", "weight", "barrel", "bpf"}, set()),
    ("nsa", {"length", "weight", "barrel", "bpf"}, set()),
    ("little-league-softball", {"barrel", "bpf"}, {"length-by-division"}),
    ("wbsc", {"length", "weight", "barrel", "performance"}, set()),
    ("usa-softball-slowpitch", {"length", "weight", "barrel", "bbs"}, {"approved-list"}),
    ("nfhs-softball", {"length", "weight", "barrel", "bbs"}, {"non-approved-list"}),
    ("isa", {"length", "weight", "barrel", "bpf"}, set()),
])
def test_every_rule_a_model_can_evaluate_is_evaluated(league, modelled, not_modelled):
    result = run_league(league, ["fastpitch-alloy-33"], engine="rigid")
    rules = {r.rule: r for r in result.bats[0].rules}
    assert set(rules) == modelled | not_modelled
    assert {k for k, r in rules.items() if r.verdict == "not-modelled"} == not_modelled
    for name in modelled & {"length", "weight", "barrel"}:
        assert rules[name].verdict == "pass", name
    if "weight" in modelled:
        assert rules["weight"].value == pytest.approx(23 * OZ, rel=1e-9)
        assert rules["weight"].margin == pytest.approx(15 * OZ, rel=1e-9)
    assert rules["barrel"].margin == 0.0  # at the 2 1/4 in limit exactly


@pytest.mark.parametrize("league, protocol", [
    ("usa-softball", "usa-softball-2004"), ("usa-softball-slowpitch", "usa-softball-2013-slowpitch"),
    ("ncaa-softball", "ncaa-softball-bbs"), ("wbsc", "wbsc-bbs"), ("nfhs-softball",
                                                                   "usa-softball-2004"),
    ("nsa", "softball-bpf"), ("isa", "softball-bpf"), ("usssa-slowpitch", "softball-bpf"),
    ("usssa-fastpitch", "softball-bpf"),
    ("little-league-softball", "softball-bpf"),
])
def test_each_performance_rule_runs_its_body_s_protocol(league, protocol):
    """Which protocol judges each body's performance rule (the league files' sources say why)."""
    from batcert.commands.inputs import load_league_any
    rules = [r for r in load_league_any(league).rules if r.kind == "performance"]
    assert [r.protocol for r in rules] == [protocol]


def test_a_bat_over_the_weight_limit_fails():
    class Facts:  # the one fact the rule reads
        mass = 39 * OZ

    class Rule:
        id, kind, limit = "weight", "max-mass", 38 * OZ

    got = EVALUATIONS["max-mass"](Rule(), Facts(), None)
    assert got.verdict == "fail" and got.margin == pytest.approx(-OZ, rel=1e-9)
