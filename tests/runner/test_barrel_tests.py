"""The protocol's barrel tests (batcert.runner.barrel_tests): the barrel compression test and the
emulated accelerated break-in (ABI), on the shipped composite, hybrid, double-wall and alloy
bats under ncaa-bbcor (its break-in and compression blocks: docs/physics.md).

What is checked is what the procedure and the model must do, not a published number: the
compression is linear in the approach; the break-in rolls pass by pass and stops at the first
reading at least ``target_drop`` below the initial (so the one before is above it); it applies
to a composite barrel only; the run is made before and after it; a measured history is judged
by the same rules. The published statements (composite barrels gain with break-in, double walls
outperform single walls) are measured in docs/validation.md; the signs are checked here.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import get_engine
from batcert.runner import barrel_tests as abi
from batcert.runner.runner import run_protocol

REPO = Path(__file__).resolve().parents[2]
STAMP = "2001-01-01T00:00:00+00:00"


def _built(name: str):
    return load_bat_any(str(REPO / "bats" / f"{name}.yaml")).built


@pytest.fixture(scope="module")
def ncaa():
    return load_protocol_any("ncaa-bbcor")


@pytest.fixture(scope="module")
def composite_run(ncaa):
    return run_protocol(_built("composite-bbcor-34"), ncaa.protocol, ncaa.ball,
                        get_engine("flexible"), STAMP)


def test_the_compression_force_is_the_stiffness_times_the_approach(ncaa):
    model = _built("bbcor-alloy-34").model
    test = ncaa.protocol.barrel_compression
    one = abi.compression(model, test)
    two = abi.compression(model, replace(test, deflection=2 * test.deflection))
    assert two.force == pytest.approx(2 * one.force, rel=1e-12)
    assert one.force == pytest.approx(one.stiffness * test.deflection, rel=1e-12)
    limited = abi.compression(model, replace(test, min=one.force * 1.01))
    assert limited.verdict == "fail" and limited.margin == pytest.approx(-0.01 * one.force)


def test_a_composite_barrel_is_rolled_until_its_compression_falls_by_the_target(composite_run,
                                                                                 ncaa):
    b = composite_run.break_in
    rule = ncaa.protocol.break_in
    assert b is not None and b.applies and not b.skipped and not b.measured
    forces = [s.force for s in b.steps]
    assert all(later < earlier for earlier, later in zip(forces, forces[1:], strict=False))
    assert b.steps[-1].drop >= rule.target_drop > b.steps[-2].drop
    assert b.steps[-1].damage == pytest.approx(rule.damage_per_pass * (len(b.steps) - 1))
    # the run is of the broken-in bat; the test before it is kept
    assert composite_run.compression.force == pytest.approx(forces[-1], rel=1e-12)
    assert b.value_before is not None and b.verdict_before in ("pass", "fail")
    assert composite_run.value > b.value_before  # softer barrel, livelier (docs/validation.md)


@pytest.mark.parametrize("name", ["bbcor-alloy-34", "hybrid-34"])
def test_a_metal_barrel_is_not_broken_in(ncaa, name):
    emulated = abi.emulate(_built(name).model, ncaa.protocol.barrel_compression,
                           ncaa.protocol.break_in)
    assert not emulated.record.applies and len(emulated.record.steps) == 1
    assert emulated.model is _built(name).model or emulated.model.wall_damage == 0.0


def test_a_measured_history_is_judged_by_the_same_rules(ncaa):
    rule = ncaa.protocol.break_in
    done = abi.measured_history([1000.0, 980.0, 960.0, 948.0], 1010.0, rule)
    assert not done.skipped and "5.20 %" in done.outcome
    short = abi.measured_history([1000.0, 980.0, 970.0], None, rule)
    assert "incomplete" in short.outcome
    skipped = abi.measured_history([800.0], 1000.0, rule)  # 20 % below the new bat's
    assert skipped.skipped and "skip rule" in skipped.outcome


def test_two_sliding_walls_are_livelier_and_ring_lower_than_one_of_the_same_weight(ncaa):
    from batcert.physics.barrel import hoop_frequency
    single, double = _built("bbcor-alloy-34"), _built("double-wall-alloy-34")
    assert double.model.mass == pytest.approx(single.model.mass, rel=1e-9)
    assert hoop_frequency(double.model) < 0.7 * hoop_frequency(single.model)
    engine = get_engine("flexible")
    one, two = (run_protocol(b, ncaa.protocol, ncaa.ball, engine, STAMP).value
                for b in (single, double))
    assert two > one


# -- a break-in of many passes (issue 40 item 6b) ---------------------------------------------
# a protocol may allow 10,000 passes of 0.01 % damage each: read one by one that took minutes
# (a reading is about 0.1 s); after the first ONE_BY_ONE passes, the pass that reaches the target
# is found by bisection, and the outcome says so


def _linear_barrel(monkeypatch, loss_at_full_damage: float):
    """A stand-in bat whose compression falls linearly with the damage (1000 N new): the model
    is its damage, so that a test of the procedure does not wait for the shell."""
    from types import SimpleNamespace

    from batcert.results.run import CompressionResult

    def compression(model, test):
        damage = model if isinstance(model, float) else 0.0
        force = 1000.0 * (1.0 - loss_at_full_damage * damage)
        return CompressionResult(0.15, 0.025, 0.001, force, force / 0.001, None, None, None)
    monkeypatch.setattr(abi, "compression", compression)
    monkeypatch.setattr(abi, "breaks_in", lambda model, z: True)
    monkeypatch.setattr(abi, "broken_in_model", lambda model, damage: damage)
    return SimpleNamespace(wall_damage=0.0, length=0.86)


def _first_pass_one_by_one(rule, loss_at_full_damage: float) -> int:
    n = 1
    while 1000.0 * (1.0 - loss_at_full_damage * n * rule.damage_per_pass) \
            > (1.0 - rule.target_drop) * 1000.0:
        n += 1
    return n


@pytest.mark.parametrize("damage_per_pass, loss", [(1e-4, 0.12), (3e-4, 0.07), (1e-4, 0.5)])
def test_a_long_break_in_finds_the_pass_that_reaches_the_target_by_bisection(
        ncaa, monkeypatch, damage_per_pass, loss):
    model = _linear_barrel(monkeypatch, loss)
    rule = replace(ncaa.protocol.break_in, damage_per_pass=damage_per_pass, max_passes=10000)
    emulated = abi.emulate(model, ncaa.protocol.barrel_compression, rule)
    steps = emulated.record.steps
    n = _first_pass_one_by_one(rule, loss)
    assert n > abi.ONE_BY_ONE
    assert [s.passes for s in steps[:abi.ONE_BY_ONE + 1]] == list(range(abi.ONE_BY_ONE + 1))
    assert steps[-1].passes == n and steps[-2].passes == n - 1  # the pass before misses it
    assert steps[-1].drop >= rule.target_drop > steps[-2].drop
    assert len(steps) < abi.ONE_BY_ONE + 20  # a few readings after the first hundred
    assert emulated.model == pytest.approx(n * damage_per_pass)
    assert emulated.record.outcome.startswith(f"rolled {n} passes until the compression fell")
    assert "then the first pass to reach the target found by bisection" in emulated.record.outcome
    assert "the protocol's limit 10000 passes" in emulated.record.outcome


def test_a_long_break_in_that_misses_the_target_stops_at_the_protocols_limit(ncaa, monkeypatch):
    model = _linear_barrel(monkeypatch, 0.12)  # 5 % at 4167 passes of 0.01 %
    rule = replace(ncaa.protocol.break_in, damage_per_pass=1e-4, max_passes=3000)
    calls = []
    monkeypatch.setattr(abi, "broken_in_model", lambda model, damage: calls.append(damage) or damage)
    with pytest.raises(ValueError, match=r"by 5 % within 3000 passes \(last 3\.60 %\)"):
        abi.emulate(model, ncaa.protocol.barrel_compression, rule)
    assert len(calls) == abi.ONE_BY_ONE + 1  # the first hundred, then the last allowed


def test_a_long_break_in_of_a_shipped_composite_bat(ncaa, monkeypatch):
    # the shell itself (a few bisection readings after three passes read one by one)
    monkeypatch.setattr(abi, "ONE_BY_ONE", 3)
    rule = replace(ncaa.protocol.break_in, damage_per_pass=1e-4, max_passes=10000)
    b = abi.emulate(_built("composite-bbcor-34").model, ncaa.protocol.barrel_compression,
                    rule).record
    assert b.applies and b.complete
    assert b.steps[-1].drop >= rule.target_drop > b.steps[-2].drop
    assert b.steps[-2].passes == b.steps[-1].passes - 1 > 3
    forces = [s.force for s in b.steps]
    assert all(later < earlier for earlier, later in zip(forces, forces[1:], strict=False))
