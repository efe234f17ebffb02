"""A ball lot in one engine batch (batcert.engines.flexible._laws and
batcert.physics.contact.compression_restitution_rows): balls that share a contact law and the
speeds of their COR points but differ in mass or COR (the draws of a Monte Carlo) share one
vectorised restitution law, and each job must come out exactly as if solved alone (with its own
ball's compression_restitution)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import batcert.physics.march as march_module
from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import ImpactBatch, get_engine
from batcert.engines.flexible import _laws
from batcert.physics import contact
from batcert.physics.ball import BallModel

PIVOT = 0.1524  # 6 in [m from knob]
# (COR shift of the whole curve, relative mass change): a lot's spread, as the Monte Carlo
# draws it (the shipped ball: COR +/- 0.032, mass +/- 2.4 %, uniform)
LOT = [(0.0, 0.0), (0.02, 0.0), (-0.03, 0.0), (0.0, 0.02), (0.01, -0.02), (-0.032, 0.024)]


@pytest.fixture(scope="module")
def ball():
    return load_protocol_any("ncaa-bbcor").ball.model  # the collegiate ball, 3 COR points


@pytest.fixture(scope="module")
def lot(ball):
    return [dataclasses.replace(ball, cor_values=tuple(float(e) + de for e in ball.cor_values),
                                mass=float(ball.mass) * (1.0 + dm)) for de, dm in LOT]


@pytest.fixture(scope="module")
def bats():
    return [load_bat_any(name).built.model for name in ("ash-34", "aluminium-34")]


def cannon(z):
    """BBCOR-style impacts: 60.8 m/s ball (136 mph) on the stationary pinned bat."""
    z = np.asarray(z, float)
    return ImpactBatch(z, np.full(z.size, -60.8), np.zeros(z.size))


def swing(z):
    """Game-like impacts: 31 m/s pitch, 50 rad/s swing."""
    z = np.asarray(z, float)
    return ImpactBatch(z, np.full(z.size, -31.0), np.full(z.size, 50.0))


def test_the_lot_shares_one_vectorised_law(lot, ball):
    # the premise of the tests below: the lot is one law, not one law per ball ...
    laws, owner = _laws(lot, [2] * len(lot))
    assert len(laws) == 1 and np.all(owner == 0)
    # ... and a ball with another contact law gets its own
    other = dataclasses.replace(ball, k1=5.0e7)
    laws, owner = _laws(lot + [other], [2] * (len(lot) + 1))
    assert len(laws) == 2
    np.testing.assert_array_equal(owner, [0] * 2 * len(lot) + [1, 1])


@pytest.mark.parametrize("chunk", [4096, 2])
def test_a_lot_solved_together_equals_each_ball_alone(lot, bats, chunk, monkeypatch):
    # Each job alone uses its ball's own compression_restitution (np.interp of the COR); the
    # batch uses compression_restitution_rows for the whole lot. The same arithmetic up to the
    # interpolation's rounding (1e-16 in e0), so the exit speeds agree to rounding: measured
    # 3.7e-14 relative (e0: 2.2e-16); 1e-12. chunk=2 cuts the march into pieces smaller than
    # one job, so the law must find its rows by their offset in the batch.
    solid, hollow = bats
    jobs = [(solid, b, PIVOT, cannon([0.35, 0.40, 0.45]), "pinned") for b in lot]
    jobs += [(hollow, b, PIVOT, cannon([0.40, 0.46]), "pinned") for b in lot[:3]]
    jobs += [(solid, b, PIVOT, swing([0.42]), "free") for b in lot[3:]]
    engine = get_engine("flexible")
    alone = [engine.solve(*job) for job in jobs]
    monkeypatch.setattr(march_module.march, "__defaults__", (None, chunk))
    together = engine.solve_many(jobs)
    for a, b in zip(alone, together, strict=True):
        np.testing.assert_allclose(b.exit_speed, a.exit_speed, rtol=1e-12)
        np.testing.assert_allclose(b.cor, a.cor, rtol=1e-12)
        np.testing.assert_allclose(b.diagnostics["e0"], a.diagnostics["e0"], rtol=1e-12)
        np.testing.assert_allclose(b.diagnostics["max_compression"],
                                   a.diagnostics["max_compression"], rtol=1e-12)
    # and the balls really differ: a livelier ball leaves faster, a heavier one slower
    speed = [out.exit_speed[0] for out in alone[:len(lot)]]
    assert speed[1] > speed[0] > speed[2]
    assert speed[3] < speed[0]


def wall_compressions(ball, speeds):
    """Compressions [m] of ``ball`` against a rigid wall at ``speeds``: below, at and between
    its COR points and beyond the last."""
    return contact.max_compression(np.asarray(speeds, float), float(ball.mass), ball.k1,
                                   ball.alpha)


SPEEDS = [0.2, 0.5, 1.0, 5.0, 20.0, 25.908, 40.0, 60.0, 71.0, 80.0, 120.0]  # [m/s]


def test_rows_law_of_one_ball_is_its_own_law(ball):
    # compression_restitution_rows interpolates like BallModel.cor (np.interp: linear between
    # the points, held beyond them); the two differ by the rounding of the interpolation:
    # measured 4.4e-16 relative in beta; 1e-13.
    u = wall_compressions(ball, SPEEDS)
    rows = np.zeros(u.size, dtype=int)
    own = contact.compression_restitution(ball)(u, rows)
    law = contact.compression_restitution_rows(
        ball.k1, ball.alpha, ball.cor_speeds, np.array([float(ball.mass)]),
        np.array([[float(e) for e in ball.cor_values]]))
    np.testing.assert_allclose(law(u, rows), own, rtol=1e-13)
    # the held ends: below the first point and beyond the last, beta is that point's
    e_first, e_last = float(ball.cor_values[0]), float(ball.cor_values[-1])
    np.testing.assert_allclose(own[[0, 1]], (1 + ball.alpha) / e_first**2 - 1, rtol=1e-13)
    np.testing.assert_allclose(own[[-2, -1]], (1 + ball.alpha) / e_last**2 - 1, rtol=1e-13)


def test_rows_law_gives_each_row_its_ball(lot):
    # rows of several balls in one call, in shuffled order: each row gets its own ball's law
    # (its mass sets the equivalent wall speed, its COR values the interpolation); 1e-13 as
    # above
    ball0 = lot[0]
    law = contact.compression_restitution_rows(
        ball0.k1, ball0.alpha, ball0.cor_speeds, np.array([b.mass for b in lot]),
        np.array([b.cor_values for b in lot], dtype=float))
    rng = np.random.default_rng(1)
    which = rng.integers(0, len(lot), 40)
    u = np.concatenate([wall_compressions(lot[k], rng.uniform(0.3, 100.0, 1)) for k in which])
    expected = [contact.compression_restitution(lot[k])(u[i:i + 1])[0]
                for i, k in enumerate(which)]
    np.testing.assert_allclose(law(u, which), expected, rtol=1e-13)


def test_rows_law_with_one_cor_point():
    # a ball whose COR is one number (the branch without interpolation)
    balls = [BallModel("one-point", m, 0.0366, (25.0,), (e,))
             for m, e in [(0.145, 0.55), (0.150, 0.50), (0.140, 0.60)]]
    law = contact.compression_restitution_rows(6.53e7, 1.84, (25.0,),
                                               np.array([b.mass for b in balls]),
                                               np.array([b.cor_values for b in balls]))
    u = np.array([0.004, 0.012, 0.020])
    rows = np.array([0, 1, 2])
    expected = [(1 + 1.84) / b.cor_values[0] ** 2 - 1 for b in balls]
    np.testing.assert_allclose(law(u, rows), expected, rtol=1e-13)
