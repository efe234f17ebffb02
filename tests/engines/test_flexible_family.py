"""A family of bats (a Monte Carlo's drawn masses and balls) built together
(:mod:`batcert.engines.flexible_family`) gives each member what it gets alone.

The tolerance, 1e-10 relative on the exit speed, is rounding: built together, a member's
barrel is read on the shared nominal wall and scaled (exact in arithmetic), its products are
taken in another order, and its rows share a march with the others (an engine batch's last
bits depend on what shares it, about 1e-14, docs/performance.md). A wrong scale, a member's
modes or balls mixed with another's, would move the exit speed by 1e-5 or more (a 1 % mass
change moves it by about 1e-3).
"""

from __future__ import annotations

import copy as copy_module
import dataclasses

import numpy as np
import pytest

import batcert.engines.flexible_family as family
from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import get_engine
from batcert.engines.base import ImpactBatch, Job
from batcert.physics import barrel
from batcert.physics.ritz import reduced_modes_many, ritz_basis
from batcert.uncertainty.propagate import BASIS_MODES

ROUNDING = 1e-10


def members(bat: str, protocol: str, scales, ball_masses, **engine_options):
    """Jobs of the bat with its density scaled by each of ``scales`` and the protocol's ball
    of each of ``ball_masses`` [kg], with Ritz modes as the Monte Carlo gives them."""
    loaded, p = load_bat_any(bat), load_protocol_any(protocol)
    engine = get_engine("flexible", **engine_options)
    nominal = loaded.built.model
    pivot, support = p.protocol.pivot, p.protocol.support
    bats = [dataclasses.replace(nominal, linear_density=np.asarray(nominal.linear_density) * c)
            for c in scales]
    rb, _ = ritz_basis(nominal, support, pivot, BASIS_MODES, engine.refine)
    modes = reduced_modes_many(rb, bats, engine.n_modes)
    r = np.array([0.10, 0.13, 0.15, 0.17])
    batch = ImpactBatch(r, np.full(r.size, -60.8), np.zeros(r.size))
    return engine, [Job(b, dataclasses.replace(p.ball.model, mass=m), pivot, batch, support, md)
                    for b, md, m in zip(bats, modes, ball_masses, strict=True)]


def spied(monkeypatch):
    """Record each family built together: its size and whether it was (not None)."""
    seen: list[tuple[int, bool]] = []
    real = family._family

    def spy(jobs, s, compressions):
        out = real(jobs, s, compressions)
        seen.append((len(jobs), out is not None))
        return out

    monkeypatch.setattr(family, "_family", spy)
    return seen


def exit_speeds_alone_and_together(engine, jobs):
    alone = np.concatenate([engine.solve_many([j])[0].exit_speed for j in jobs])
    together = np.concatenate([o.exit_speed for o in engine.solve_many(jobs)])
    return alone, together


@pytest.mark.parametrize("bat,protocol", [("aluminium-34", "ncaa-bbcor"),
                                          ("composite-bbcor-34", "ncaa-bbcor"),
                                          ("ash-34", "proposed")])
def test_a_family_of_drawn_masses_and_balls_is_each_member_alone(bat, protocol, monkeypatch):
    engine, jobs = members(bat, protocol, [1.0, 0.997, 1.004, 1.001],
                           [0.1420, 0.1445, 0.1460, 0.1431])
    seen = spied(monkeypatch)
    alone, together = exit_speeds_alone_and_together(engine, jobs)
    assert seen[-1] == (4, True)  # built as one family
    np.testing.assert_allclose(together, alone, rtol=ROUNDING, atol=0.0)
    # the members do differ, by far more than the tolerance
    assert np.ptp(alone.reshape(4, -1), axis=0).min() > 1e-4 * alone.max()


def test_members_that_keep_different_shell_modes_are_built_apart(monkeypatch):
    # a 10 % lighter wall lifts its modes by 5 %: aluminium-34's 9.72 kHz mode crosses a
    # 10 kHz cut (the engine's before issue 39), so that member keeps one mode fewer
    engine, jobs = members("aluminium-34", "ncaa-bbcor", [1.0, 0.9, 1.002],
                           [0.1420, 0.1420, 0.1420], shell_max_frequency=10_000.0)
    shared = barrel.shared_wall([j.bat for j in jobs], engine.shell_max_frequency)
    assert shared is not None
    base, stiffness, masses = shared
    kept = (base.omega[None, :] * np.sqrt(stiffness / masses)[:, None]
            <= 2 * np.pi * engine.shell_max_frequency).sum(axis=1)
    assert kept[1] < kept[0] == kept[2]
    seen = spied(monkeypatch)
    alone, together = exit_speeds_alone_and_together(engine, jobs)
    assert seen[-1] == (3, True)
    np.testing.assert_allclose(together, alone, rtol=ROUNDING, atol=0.0)


def test_walls_that_differ_otherwise_are_built_one_by_one(monkeypatch):
    engine, jobs = members("aluminium-34", "ncaa-bbcor", [1.0, 1.002], [0.1420, 0.1430])
    stiffer = dataclasses.replace(jobs[1].bat, barrel_stiffness_scale=1.05)
    jobs[1] = dataclasses.replace(jobs[1], bat=stiffer)
    assert barrel.shared_wall([j.bat for j in jobs]) is None
    seen = spied(monkeypatch)
    alone, together = exit_speeds_alone_and_together(engine, jobs)
    assert seen[-1] == (2, False)  # refused, then each built alone
    np.testing.assert_allclose(together, alone, rtol=ROUNDING, atol=0.0)


def test_shared_wall_gives_each_bats_mass_scale():
    nominal = load_bat_any("aluminium-34").built.model
    bats = [dataclasses.replace(nominal, linear_density=np.asarray(nominal.linear_density) * c)
            for c in (1.0, 1.01, 0.98)]
    base, stiffness, masses = barrel.shared_wall(bats)
    np.testing.assert_allclose(masses / masses[0], [1.0, 1.01, 0.98], rtol=1e-12)
    # each bat's barrel as the cache computes it for it alone: the same frequencies
    for bat, m in zip(bats, masses, strict=True):
        own = barrel.cached_barrel_modes(bat)
        scaled = base.scaled(barrel.barrel_shell(bat), stiffness, m, barrel.MAX_FREQUENCY)
        np.testing.assert_allclose(scaled.omega, own.omega, rtol=1e-12)


def test_a_drawn_composite_wall_with_its_own_copy_of_the_layup_shares_the_wall():
    # each drawn bat is built anew, so its layup is an equal copy, not the same object: the
    # walls are compared by value (a layup of another ply angle is another wall)
    nominal = load_bat_any("composite-bbcor-34").built.model
    assert nominal.layup is not None
    copy = dataclasses.replace(nominal, layup=copy_module.deepcopy(nominal.layup),
                               linear_density=np.asarray(nominal.linear_density) * 1.003)
    assert barrel.shared_wall([nominal, copy]) is not None
    stack = nominal.layup.stacks[0]
    first, *rest = stack.walls[0]
    turned = dataclasses.replace(first, angle=first.angle + 0.1)
    other = dataclasses.replace(nominal, layup=dataclasses.replace(
        nominal.layup, stacks=(dataclasses.replace(stack, walls=((turned, *rest),
                                                                 *stack.walls[1:])),
                               *nominal.layup.stacks[1:])))
    assert barrel.shared_wall([nominal, other]) is None
