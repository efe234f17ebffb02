"""batcert.engines.kernel.modal_update: how runs of rows that share their modes are cut into pieces,
follow the rows that are kept, and keep their state in turning frames. (That the whole march
gives the same impacts either way is tested in test_march.py.)"""

from __future__ import annotations

import numpy as np

from batcert.engines.kernel import modal_update


def test_the_runs_of_shared_modes_follow_the_rows_that_are_kept():
    # dropping finished rows keeps each remaining row with its own run's matrices
    group = np.array([0, 0, 0, 1, 1, 2, 2, 2])
    modal = modal_update.SharedRuns(e1=np.ones((3, 2), complex), R=np.zeros((3, 4, 4)),
                                    P=np.zeros((3, 3, 4)),
                                    scale=np.arange(8.0)[:, None] * np.ones(4), group=group)
    assert modal.pieces == [(0, 3, 0), (3, 5, 1), (5, 8, 2)]
    kept = modal.take(np.array([1, 2, 5, 7]))
    assert kept.pieces == [(0, 2, 0), (2, 4, 2)]
    np.testing.assert_array_equal(kept.scale[:, 0], [1.0, 2.0, 5.0, 7.0])


def test_a_long_run_is_updated_in_pieces(monkeypatch):
    # pieces of at most PIECE_ENTRIES impact-mode entries (here 2 rows of 2 modes), never
    # across two runs
    monkeypatch.setattr(modal_update, "PIECE_ENTRIES", 4)
    group = np.array([0, 0, 0, 0, 0, 1, 1])
    modal = modal_update.SharedRuns(e1=np.ones((2, 2), complex), R=np.zeros((2, 4, 4)),
                                    P=np.zeros((2, 3, 4)), scale=np.ones((7, 4)), group=group)
    assert modal.pieces == [(0, 2, 0), (2, 4, 0), (4, 5, 0), (5, 7, 1)]


def test_a_damped_run_folds_its_frame_sooner():
    # each run folds after at most FRAME_STEPS steps of its own, and before its most damped
    # mode's |1/e1^k| passes e^FRAME_GROWTH: here 50 // 3 = 16 steps for a decay of 3 per
    # step. The frame's forcing is P / e1^(k+1) and its read-out R e1^(k+1).
    e1 = np.exp(np.array([[-1e-4 + 0.3j, -2e-3 + 1.0j], [-0.5 + 0.2j, -3.0 + 2.0j]]))
    rng = np.random.default_rng(0)
    R, P = rng.standard_normal((2, 4, 4)), rng.standard_normal((2, 3, 4))
    turns = modal_update.Turns.of(e1, R, P)
    assert list(turns.steps) == [modal_update.FRAME_STEPS, 16]
    for g, steps in enumerate(turns.steps):
        assert np.abs(1 / turns.turn[steps, g]).max() <= np.exp(modal_update.FRAME_GROWTH)
    k, g = 5, 1
    np.testing.assert_allclose(turns.P[k, g].view(complex) * e1[g] ** (k + 1),
                               P[g].view(complex), rtol=1e-13)
    y = rng.standard_normal(4)  # Y as floats: Y = e1^(k+1) X
    x = (y.view(complex) / e1[g] ** (k + 1)).view(float)
    np.testing.assert_allclose(x @ turns.R[k, g], y @ R[g], rtol=1e-12)
