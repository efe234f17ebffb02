"""A ball lot in one engine batch: the draws of a Monte Carlo (balls that differ in mass or
COR) stacked into one integration must each come out exactly as if solved alone. Nathan's law
(batcert.physics.balls.hysteresis: compression_restitution_rows gives the balls that share
alpha and the speeds of their COR points one vectorised restitution law) and the fitted
viscoelastic ball (each draw moved along its fit, a law of its own per row)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import batcert.engines.kernel.march as march_module
from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import ImpactBatch, get_engine
from batcert.physics.ball import BallModel
from batcert.physics.balls import PowerLawHysteresis, impact1d
from batcert.physics.balls import hysteresis as contact
from batcert.physics.balls.hysteresis import HysteresisMarch

PIVOT = 0.1524  # 6 in [m from knob]
# (COR shift of the whole curve, relative mass change): a lot's spread, as the Monte Carlo
# draws it (the shipped ball: COR +/- 0.032, mass +/- 2.4 %, uniform)
LOT = [(0.0, 0.0), (0.02, 0.0), (-0.03, 0.0), (0.0, 0.02), (0.01, -0.02), (-0.032, 0.024)]


@pytest.fixture(scope="module")
def ball():
    """A collegiate ball with Nathan's law and three COR points (batcert 0.2's shipped ball)."""
    return BallModel("hysteresis", 0.14529, 0.0369,
                     PowerLawHysteresis(6.53e7, 1.84, (1.0, 25.908, 71.0), (0.64, 0.546, 0.50)))


def _moved(ball, de):
    law = ball.law
    return dataclasses.replace(law, cor_values=tuple(float(e) + de for e in law.cor_values))


@pytest.fixture(scope="module")
def lot(ball):
    return [dataclasses.replace(ball, law=_moved(ball, de), mass=float(ball.mass) * (1.0 + dm))
            for de, dm in LOT]


@pytest.fixture(scope="module")
def visco_lot():
    """Draws of the shipped viscoelastic ball: its COR tests moved together by k of their
    standard uncertainties (the law along its fit) and its mass moved."""
    spec = load_protocol_any("ncaa-bbcor").ball
    return [dataclasses.replace(spec.model, law=spec.fit.moved(k),
                                mass=float(spec.model.mass) * (1.0 + dm))
            for k, dm in [(0.0, 0.0), (1.0, 0.0), (-1.5, 0.01), (0.5, -0.02)]]


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


def test_the_lot_shares_one_vectorised_law(lot, ball, monkeypatch):
    # the premise of the tests below: the lot is one law, not one law per ball (one call of
    # compression_restitution_rows); a ball with another exponent gets its own
    calls = []
    real = contact.compression_restitution_rows
    monkeypatch.setattr(contact, "compression_restitution_rows",
                        lambda *a: calls.append(a) or real(*a))
    which = np.repeat(np.arange(len(lot)), 2)
    HysteresisMarch.of([b.law for b in lot], [b.mass for b in lot], which)
    assert len(calls) == 1
    other = dataclasses.replace(ball, law=dataclasses.replace(ball.law, alpha=1.6))
    HysteresisMarch.of([b.law for b in lot + [other]], [b.mass for b in lot + [other]],
                       np.append(which, [len(lot)] * 2))
    assert len(calls) == 2  # the lot's family once more; the other ball has a law of its own


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
    # Where the footprint is taken (u_rep) comes from each ball's wall table when a batch has
    # few balls and from one batched integration when it has many (impact1d.MANY_BALLS): here
    # both from the tables, so that the stepping itself is compared (the batched integration's
    # own agreement is the next test)
    monkeypatch.setattr(impact1d, "MANY_BALLS", 10**6)
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


def test_a_lot_with_its_footprints_integrated_together_is_within_their_accuracy(bats):
    # A batch of more than impact1d.MANY_BALLS balls integrates every row's u_rep together at
    # impact1d.STEPS per contact time, where each ball alone reads its wall table: for the
    # viscoelastic ball the two agree to about 2e-6 in u_rep (Nathan's law: to rounding). The
    # exit speeds then differ by what that moves the footprint: measured 5.8e-9 relative (six
    # draws of the shipped ball); 1e-6 allows the footprint's full 2e-6 with a margin.
    spec = load_protocol_any("ncaa-bbcor").ball
    lot = [dataclasses.replace(spec.model, law=spec.fit.moved(k)) for k in (-2, -1, 0, 0.5, 1, 2)]
    assert len(lot) > impact1d.MANY_BALLS
    solid, hollow = bats
    jobs = [(solid, b, PIVOT, cannon([0.35, 0.45]), "pinned") for b in lot]
    jobs += [(hollow, b, PIVOT, cannon([0.40, 0.46]), "pinned") for b in lot[:3]]
    engine = get_engine("flexible")
    alone = [engine.solve(*job) for job in jobs]
    together = engine.solve_many(jobs)
    worst = max(float(np.max(np.abs(b.exit_speed / a.exit_speed - 1.0)))
                for a, b in zip(alone, together, strict=True))
    assert 0.0 < worst < 1e-6


@pytest.mark.parametrize("chunk", [4096, 2])
def test_a_viscoelastic_lot_solved_together_equals_each_ball_alone(visco_lot, bats, chunk,
                                                                    monkeypatch):
    # each draw's own law (ViscoelasticMarch.of: one row's parameters per ball) stacked in one
    # integration, with the barrel's coupling: to rounding (1e-12), as each alone
    solid, hollow = bats
    jobs = [(solid, b, PIVOT, cannon([0.38, 0.45]), "pinned") for b in visco_lot]
    jobs += [(hollow, b, PIVOT, cannon([0.40, 0.46]), "pinned") for b in visco_lot[:2]]
    engine = get_engine("flexible")
    alone = [engine.solve(*job) for job in jobs]
    monkeypatch.setattr(march_module.march, "__defaults__", (None, chunk))
    together = engine.solve_many(jobs)
    for a, b in zip(alone, together, strict=True):
        np.testing.assert_allclose(b.exit_speed, a.exit_speed, rtol=1e-12)
        np.testing.assert_allclose(b.diagnostics["ball_energy_loss"],
                                   a.diagnostics["ball_energy_loss"], rtol=1e-12)
    # a livelier lot (k = +1) leaves faster than the tested balls, a deader one slower
    speed = [out.exit_speed[0] for out in alone[:len(visco_lot)]]
    assert speed[1] > speed[0] > speed[2]


def wall_compressions(ball, speeds):
    """Compressions [m] of ``ball`` against a rigid wall at ``speeds``: below, at and between
    its COR points and beyond the last."""
    return contact.max_compression(np.asarray(speeds, float), float(ball.mass), ball.law.k1,
                                   ball.law.alpha)


SPEEDS = [0.2, 0.5, 1.0, 5.0, 20.0, 25.908, 40.0, 60.0, 71.0, 80.0, 120.0]  # [m/s]


def test_rows_law_of_one_ball_is_its_own_law(ball):
    # compression_restitution_rows interpolates like BallModel.cor (np.interp: linear between
    # the points, held beyond them); the two differ by the rounding of the interpolation:
    # measured 4.4e-16 relative in beta; 1e-13.
    u = wall_compressions(ball, SPEEDS)
    rows = np.zeros(u.size, dtype=int)
    law_ = ball.law
    own = contact.compression_restitution(law_, ball.mass)(u, rows)
    law = contact.compression_restitution_rows(
        law_.k1, law_.alpha, law_.cor_speeds, np.array([float(ball.mass)]),
        np.array([[float(e) for e in law_.cor_values]]))
    np.testing.assert_allclose(law(u, rows), own, rtol=1e-13)
    # the held ends: below the first point and beyond the last, beta is that point's
    e_first, e_last = float(law_.cor_values[0]), float(law_.cor_values[-1])
    np.testing.assert_allclose(own[[0, 1]], (1 + law_.alpha) / e_first**2 - 1, rtol=1e-13)
    np.testing.assert_allclose(own[[-2, -1]], (1 + law_.alpha) / e_last**2 - 1, rtol=1e-13)


def test_rows_law_gives_each_row_its_ball(lot):
    # rows of several balls in one call, in shuffled order: each row gets its own ball's law
    # (its mass sets the equivalent wall speed, its COR values the interpolation); 1e-13 as
    # above
    ball0 = lot[0].law
    law = contact.compression_restitution_rows(
        ball0.k1, ball0.alpha, ball0.cor_speeds, np.array([b.mass for b in lot]),
        np.array([b.law.cor_values for b in lot], dtype=float))
    rng = np.random.default_rng(1)
    which = rng.integers(0, len(lot), 40)
    u = np.concatenate([wall_compressions(lot[k], rng.uniform(0.3, 100.0, 1)) for k in which])
    expected = [contact.compression_restitution(lot[k].law, lot[k].mass)(u[i:i + 1])[0]
                for i, k in enumerate(which)]
    np.testing.assert_allclose(law(u, which), expected, rtol=1e-13)


def test_rows_law_with_one_cor_point():
    # a ball whose COR is one number (the branch without interpolation)
    balls = [BallModel("one-point", m, 0.0366, PowerLawHysteresis(6.53e7, 1.84, (25.0,), (e,)))
             for m, e in [(0.145, 0.55), (0.150, 0.50), (0.140, 0.60)]]
    law = contact.compression_restitution_rows(6.53e7, 1.84, (25.0,),
                                               np.array([b.mass for b in balls]),
                                               np.array([b.law.cor_values for b in balls]))
    u = np.array([0.004, 0.012, 0.020])
    rows = np.array([0, 1, 2])
    expected = [(1 + 1.84) / b.law.cor_values[0] ** 2 - 1 for b in balls]
    np.testing.assert_allclose(law(u, rows), expected, rtol=1e-13)
