"""Fixtures of tests/sweeps: sweeps that more than one test module compares against."""

from __future__ import annotations

import pytest

from batcert.commands.sweep import plan_sweep, run_sweep


@pytest.fixture(scope="session")
def flexible_wall_sweep():
    """(plan, result) of aluminium-34 under ncaa-bbcor with the wall 90 % to 110 % of its
    2.7 mm in 5 steps, flexible engine, serial: 2 chunks (4 + 1 variants), about 2 s. The
    reference of the parallel and distributed runs, which must give the same numbers."""
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", ["wall=90%:110%:5"], engine="flexible")
    return plan, run_sweep(plan)
