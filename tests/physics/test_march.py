"""batcert.physics.march: the two ways a step reads and forces the modes give the same impacts.

Rows that share their modes (one bat) are read and forced with one matrix product per run of
them; rows that do not, row by row (``march._SHARED_ROWS`` decides). The integration is the same
ETDRK4 step either way, so the two must agree to rounding; the tolerance (1e-12 relative) is
rounding accumulated over some 100 steps, far below the engine's 2e-4 accuracy target.
"""

from __future__ import annotations

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import ImpactBatch
from batcert.engines.flexible import FlexibleEngine
from batcert.physics import march
from batcert.physics.contact import compression_restitution, restitution_exponent

PIVOT = 0.1524  # [m from knob]


@pytest.fixture(scope="module")
def impacts():
    """A stacked system of a wood and an alloy bat (two runs of shared modes, the alloy bat's
    with its shell modes), with locations and speeds spread so that the impacts end at
    different times and finished rows are dropped as the march goes."""
    ball = load_protocol_any("proposed").ball.model
    engine = FlexibleEngine()
    systems = []
    for name in ("ash-34", "aluminium-34"):
        bat = load_bat_any(name).built.model
        r = np.linspace(bat.length - PIVOT - 0.25, bat.length - PIVOT - 0.05, 40)
        batch = ImpactBatch(r, np.where(np.arange(r.size) % 2, -60.0, -30.0),
                            np.where(np.arange(r.size) % 2, 0.0, 30.0 / r))
        system, _ = engine.linear_system(bat, ball, PIVOT, batch)
        systems.append((system, batch.relative_speed))
    stacked, _ = march.stack_systems([s for s, _ in systems])
    speed = np.concatenate([v for _, v in systems])
    return stacked, speed, ball


def _march(impacts, shared_rows: int, monkeypatch, restitution=True):
    system, speed, ball = impacts
    monkeypatch.setattr(march, "_SHARED_ROWS", shared_rows)
    law = compression_restitution(ball)
    beta = law(np.full(speed.size, 1e-12)) if restitution else \
        restitution_exponent(ball.alpha, ball.cor(speed))
    return march.march(system, ball.k1, ball.alpha, beta, speed, 12.5e-6, 5e-3,
                       law if restitution else None)


@pytest.mark.parametrize("restitution", [True, False])
def test_shared_runs_and_row_by_row_give_the_same_impacts(impacts, monkeypatch, restitution):
    shared = _march(impacts, 1, monkeypatch, restitution)  # two runs of 40 rows: shared
    rows = _march(impacts, 10**6, monkeypatch, restitution)  # every row its own
    assert shared.separated.all() and rows.separated.all()
    assert np.ptp(shared.time) > 0.1 * shared.time.max()  # rows finish at different times
    for name in ("impulse", "time", "peak_force", "max_compression", "barrel_share"):
        np.testing.assert_allclose(getattr(shared, name), getattr(rows, name), rtol=1e-12,
                                   err_msg=name)
    # the modal coordinates at separation, unscaled: compared against their largest
    scale = np.abs(rows.modal).max()
    np.testing.assert_allclose(shared.modal, rows.modal, rtol=0, atol=1e-12 * scale)


def test_the_runs_of_shared_modes_follow_the_rows_that_are_kept():
    # dropping finished rows keeps each remaining row with its own run's matrices
    group = np.array([0, 0, 0, 1, 1, 2, 2, 2])
    modal = march._Shared(e1=np.ones((3, 2), complex), R=np.zeros((3, 4, 4)), P=np.zeros((3, 3, 4)),
                          scale=np.arange(8.0)[:, None] * np.ones(4), group=group)
    assert modal.pieces == [(0, 3, 0), (3, 5, 1), (5, 8, 2)]
    kept = modal.take(np.array([1, 2, 5, 7]))
    assert kept.pieces == [(0, 2, 0), (2, 4, 2)]
    np.testing.assert_array_equal(kept.scale[:, 0], [1.0, 2.0, 5.0, 7.0])


def test_a_long_run_is_updated_in_pieces(monkeypatch):
    # pieces of at most _PIECE_ENTRIES impact-mode entries (here 2 rows of 2 modes), never
    # across two runs
    monkeypatch.setattr(march, "_PIECE_ENTRIES", 4)
    group = np.array([0, 0, 0, 0, 0, 1, 1])
    modal = march._Shared(e1=np.ones((2, 2), complex), R=np.zeros((2, 4, 4)), P=np.zeros((2, 3, 4)),
                          scale=np.ones((7, 4)), group=group)
    assert modal.pieces == [(0, 2, 0), (2, 4, 0), (4, 5, 0), (5, 7, 1)]


def test_pieces_change_nothing(impacts, monkeypatch):
    # the shared runs (40 rows each) updated in pieces of 7 rows, cutting every run, against
    # whole runs: the same impacts to rounding
    monkeypatch.setattr(march, "_SHARED_ROWS", 1)
    whole = _march(impacts, 1, monkeypatch)
    monkeypatch.setattr(march, "_PIECE_ENTRIES", 7 * impacts[0].omega.shape[1])
    cut = _march(impacts, 1, monkeypatch)
    for name in ("impulse", "time", "peak_force", "max_compression", "barrel_share"):
        np.testing.assert_allclose(getattr(cut, name), getattr(whole, name), rtol=1e-12,
                                   err_msg=name)
    np.testing.assert_allclose(cut.modal, whole.modal, rtol=0,
                               atol=1e-12 * np.abs(whole.modal).max())


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
    # _FRAME_STEPS steps (the impacts end between folds, so their state is read from inside a
    # frame), against folded back at every step, which is the plain propagation Y <- e1 Y:
    # the same impacts to rounding
    monkeypatch.setattr(march, "_SHARED_ROWS", 1)
    turning = _march(impacts, 1, monkeypatch)
    monkeypatch.setattr(march, "_FRAME_STEPS", 1)
    plain = _march(impacts, 1, monkeypatch)
    for name in ("impulse", "time", "peak_force", "max_compression", "barrel_share"):
        np.testing.assert_allclose(getattr(turning, name), getattr(plain, name), rtol=1e-12,
                                   err_msg=name)
    np.testing.assert_allclose(turning.modal, plain.modal, rtol=0,
                               atol=1e-12 * np.abs(plain.modal).max())


def test_a_damped_run_folds_its_frame_sooner():
    # each run folds after at most _FRAME_STEPS steps of its own, and before its most damped
    # mode's |1/e1^k| passes e^_FRAME_GROWTH: here 50 // 3 = 16 steps for a decay of 3 per
    # step. The frame's forcing is P / e1^(k+1) and its read-out R e1^(k+1).
    e1 = np.exp(np.array([[-1e-4 + 0.3j, -2e-3 + 1.0j], [-0.5 + 0.2j, -3.0 + 2.0j]]))
    rng = np.random.default_rng(0)
    R, P = rng.standard_normal((2, 4, 4)), rng.standard_normal((2, 3, 4))
    turns = march._Turns.of(e1, R, P)
    assert list(turns.steps) == [march._FRAME_STEPS, 16]
    for g, steps in enumerate(turns.steps):
        assert np.abs(1 / turns.turn[steps, g]).max() <= np.exp(march._FRAME_GROWTH)
    k, g = 5, 1
    np.testing.assert_allclose(turns.P[k, g].view(complex) * e1[g] ** (k + 1),
                               P[g].view(complex), rtol=1e-13)
    y = rng.standard_normal(4)  # Y as floats: Y = e1^(k+1) X
    x = (y.view(complex) / e1[g] ** (k + 1)).view(float)
    np.testing.assert_allclose(x @ turns.R[k, g], y @ R[g], rtol=1e-12)
