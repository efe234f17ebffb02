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
