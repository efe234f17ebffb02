"""batcert.physics.barrel's cache of a wall's nominal modes: a run's numbers must not depend on
what the process computed before (sweeps compare runs made in different processes, and a
resumed journal with a fresh one, with ``==``; tests/sweeps/test_sweep.py)."""

from __future__ import annotations

from batcert import workspace
from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import get_engine
from batcert.model.diagnostics import SUMMARY_MAX_FREQUENCY
from batcert.physics import barrel
from batcert.runner.runner import run_protocol


def test_a_flexible_run_does_not_depend_on_the_barrel_cache(empty_barrel_cache):
    bat = load_bat_any("aluminium-34").built
    p = load_protocol_any("ncaa-bbcor")

    def bbcor() -> float:
        return run_protocol(bat, p.protocol, p.ball, get_engine("flexible")).value

    fresh = bbcor()  # the wall's nominal modes computed for the engine
    workspace.current().clear()
    barrel.cached_barrel_modes(bat.model, SUMMARY_MAX_FREQUENCY)  # as a rigid run's summary
    assert bbcor() == fresh  # the same code on the same bat: exactly the same number
