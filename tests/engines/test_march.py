"""batcert.engines.kernel.march: the two ways a step reads and forces the modes give the same impacts.

Rows that share their modes (one bat) are read and forced with one matrix product per run of
them; rows that do not, row by row (``modal_update.SHARED_ROWS`` decides). The integration is the same
ETDRK4 step either way, so the two must agree to rounding; the tolerance (1e-12 relative) is
rounding accumulated over some 100 steps, far below the engine's 2e-4 accuracy target.
"""

from __future__ import annotations

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import ImpactBatch
from batcert.engines.flexible import FlexibleEngine
from batcert.engines.kernel import march, modal_update
from batcert.engines.kernel.linear_system import stack_systems
from batcert.specs.ball import load_ball

PIVOT = 0.1524  # [m from knob]
NATHAN = "protocols/balls/nathan-2000.yaml"  # Nathan's hysteresis law (the shipped ball is viscoelastic)


@pytest.fixture(scope="module", params=["viscoelastic", "hysteresis"])
def impacts(request):
    """A stacked system of a wood and an alloy bat (two runs of shared modes, the alloy bat's
    with its shell modes, whose coupling follows the footprint), with locations and speeds
    spread so that the impacts end at different times and finished rows are dropped as the
    march goes; the shipped viscoelastic ball or Nathan's."""
    from pathlib import Path

    ball = (load_protocol_any("proposed").ball.model if request.param == "viscoelastic"
            else load_ball(Path(__file__).resolve().parents[2] / NATHAN).model)
    engine = FlexibleEngine()
    systems = []
    for name in ("ash-34", "aluminium-34"):
        bat = load_bat_any(name).built.model
        r = np.linspace(bat.length - PIVOT - 0.25, bat.length - PIVOT - 0.05, 40)
        batch = ImpactBatch(r, np.where(np.arange(r.size) % 2, -60.0, -30.0),
                            np.where(np.arange(r.size) % 2, 0.0, 30.0 / r))
        system, _ = engine.linear_system(bat, ball, PIVOT, batch)
        systems.append((system, batch.relative_speed))
    stacked, _ = stack_systems([s for s, _ in systems])
    speed = np.concatenate([v for _, v in systems])
    return stacked, speed, ball


def _march(impacts, shared_rows: int, monkeypatch, restitution=True):
    system, speed, ball = impacts
    monkeypatch.setattr(modal_update, "SHARED_ROWS", shared_rows)
    rule = "compression" if restitution else "relative-speed"
    state = type(ball.law).state_of([ball.law], [ball.mass], np.zeros(speed.size, int), 1.0,
                                    rule, speed)
    return march.march(system, state, speed, 12.5e-6, 5e-3)


def _assert_same_impacts(got, want):
    """Two marches' separations alike to rounding (1e-12, module notes); the modal coordinates
    at separation, unscaled, compared against their largest."""
    for name in ("impulse", "time", "peak_force", "max_compression", "barrel_share",
                 "absorbed"):
        if getattr(want, name) is None:
            assert getattr(got, name) is None, name
            continue
        np.testing.assert_allclose(getattr(got, name), getattr(want, name), rtol=1e-12,
                                   err_msg=name)
    np.testing.assert_allclose(got.modal, want.modal, rtol=0,
                               atol=1e-12 * np.abs(want.modal).max())


@pytest.mark.parametrize("restitution", [True, False])
def test_shared_runs_and_row_by_row_give_the_same_impacts(impacts, monkeypatch, restitution):
    shared = _march(impacts, 1, monkeypatch, restitution)  # two runs of 40 rows: shared
    rows = _march(impacts, 10**6, monkeypatch, restitution)  # every row its own
    assert shared.separated.all() and rows.separated.all()
    assert np.ptp(shared.time) > 0.1 * shared.time.max()  # rows finish at different times
    _assert_same_impacts(shared, rows)


def test_pieces_change_nothing(impacts, monkeypatch):
    # the shared runs (40 rows each) updated in pieces of 7 rows, cutting every run, against
    # whole runs: the same impacts to rounding
    monkeypatch.setattr(modal_update, "SHARED_ROWS", 1)
    whole = _march(impacts, 1, monkeypatch)
    monkeypatch.setattr(modal_update, "PIECE_ENTRIES", 7 * impacts[0].omega.shape[1])
    cut = _march(impacts, 1, monkeypatch)
    _assert_same_impacts(cut, whole)


def test_a_mode_that_nothing_drives_stays_at_rest(impacts, monkeypatch):
    # stacking pads the wood bat's rows with shell columns of zero gain: their modal
    # coordinates are kept scaled by the gain, and must come back as exactly zero
    system, _, _ = impacts
    sep = _march(impacts, 1, monkeypatch)
    idle = system.gain == 0
    assert idle.any()
    np.testing.assert_array_equal(sep.modal[idle], 0.0)


def test_the_turning_frames_change_nothing(impacts, monkeypatch):
    # the shared runs' state kept in frames that turn with the free modes, folded back every
    # FRAME_STEPS steps (the impacts end between folds, so their state is read from inside a
    # frame), against folded back at every step, which is the plain propagation Y <- e1 Y:
    # the same impacts to rounding
    monkeypatch.setattr(modal_update, "SHARED_ROWS", 1)
    turning = _march(impacts, 1, monkeypatch)
    monkeypatch.setattr(modal_update, "FRAME_STEPS", 1)
    plain = _march(impacts, 1, monkeypatch)
    _assert_same_impacts(turning, plain)
