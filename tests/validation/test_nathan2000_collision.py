"""Validation against A. M. Nathan, "Dynamics of the baseball-bat collision", Am. J. Phys. 68
(2000) 979: the ball against a rigid wall and the R161 collision results,
as collected in shared/docs/REFERENCE-DATA.md.

The R161 is built from the published profile (tests/r161.py: 84 slices, 649 kg/m^3,
E = 1.814e10 Pa, G = 1.05e9 Pa) and reconciled to Table I (M = 0.885 kg, CG 0.564 m, radius of
gyration 0.23 m) with batcert's default density-profile correction: the profile alone gives
0.869 kg and CG 0.561 m, the correction adds 15.6 g (slice density x 0.98-1.07).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from batcert.engines import ImpactBatch
from batcert.engines.flexible import FlexibleEngine
from batcert.engines.rigid import RigidEngine
from batcert.model.reconcile import MeasuredMassProperties, reconcile
from batcert.physics.ball import BallModel
from batcert.physics.balls import PowerLawHysteresis
from batcert.physics.balls import hysteresis as contact
from batcert.physics.modes import cached_modes, mode_nodes

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/, for the shared helper
from r161 import r161_bat  # noqa: E402

MASS, RADIUS, K1, ALPHA = 0.145, 0.0366, 6.53e7, 1.84  # Nathan's ball
M_BAT, Z_CG, K_CG = 0.885, 0.564, 0.23  # Table I [kg, m from knob, m]


def nathan_ball(e0: float) -> BallModel:
    return BallModel("nathan-2000", MASS, RADIUS, PowerLawHysteresis(K1, ALPHA, (1.0,), (e0,)))


@pytest.fixture(scope="module")
def r161():
    """R161 reconciled to Table I mass, CG and radius of gyration (module notes)."""
    measured = MeasuredMassProperties(mass=M_BAT, balance_point=Z_CG,
                                      moi=M_BAT * (K_CG**2 + Z_CG**2), pivot=0.0)
    bat, _ = reconcile(r161_bat(), measured)
    assert bat.mass == pytest.approx(M_BAT) and bat.balance_point == pytest.approx(Z_CG)
    return bat


# -- the ball against a rigid wall ---------------------------------------------------------

@pytest.mark.parametrize("speed, e0, published_ms", [
    (1.0, 0.66, 2.2),  # e0 = 0.66: Nathan's fit to 1 m/s data
    (11.0, 0.53, 1.0),  # e0 = 0.53 (his 58 m/s value) at the three higher speeds
    (45.0, 0.53, 0.7),
    (67.0, 0.53, 0.6),
])
def test_rigid_wall_collision_time(speed, e0, published_ms):
    # REFERENCE-DATA.md (H): time for 99 % of the impulse. batcert takes the central 99 %
    # (0.5 % to 99.5 %). The published values have one or two significant figures, read at
    # 0.1 ms resolution: 15 % covers that rounding (0.6 ms means 0.55-0.65 ms, i.e. 8 %) plus the
    # choice of where the 1 % left out is taken. Model: 2.17, 1.00, 0.66, 0.58 ms.
    res = contact.rigid_wall_impact(speed, MASS, K1, ALPHA, e0)
    assert float(res.collision_time) * 1e3 == pytest.approx(published_ms, rel=0.15)


def test_rigid_wall_contact_time_at_67_m_s():
    # REFERENCE-DATA.md (H): full contact time about 1.1 ms at 67 m/s ("about": 15 %).
    res = contact.rigid_wall_impact(67.0, MASS, K1, ALPHA, 0.53)
    assert float(res.contact_time) * 1e3 == pytest.approx(1.1, rel=0.15)


def test_rigid_wall_compression_and_force_at_58_m_s():
    # REFERENCE-DATA.md (D): about 17.7 mm and 39 kN; 1 % covers the 3-figure rounding.
    res = contact.rigid_wall_impact(58.0, MASS, K1, ALPHA, 0.53)
    assert float(res.max_compression) == pytest.approx(17.7e-3, rel=0.01)
    assert float(res.peak_force) == pytest.approx(39e3, rel=0.01)
    assert float(res.cor) == pytest.approx(0.53, rel=1e-12)


# -- the game collision, free R161 -------------------------------------------------------
# (Nathan's law on a flat contact, as his model: contact_surface="flat")

def game_sweep(bat, z):
    """Ball 40 m/s toward the bat; bat CG at 24 m/s and 51 rad/s: rotation at 51 rad/s about
    the instantaneous centre z0 = z_cg - 24/51 from the knob, free support; e0 = 0.50; 18 modes."""
    z0 = bat.balance_point - 24.0 / 51.0
    batch = ImpactBatch(z - z0, -40.0, 51.0)
    ball = nathan_ball(0.50)
    flex = FlexibleEngine(n_modes=18, contact_surface="flat").solve(bat, ball, z0, batch,
                                                                     support="free")
    rig = RigidEngine().solve(bat, ball, z0, batch, support="free")
    return flex, rig


def test_game_exit_speed_peaks_near_72_cm_at_the_rigid_value(r161):
    # Nathan 2000 (H): the exit speed peaks 71-72 cm from the knob, where it equals the rigid
    # value (about 47 m/s). Window 70-73 cm: the published peak is read off a curve with ~1 cm
    # resolution. 1 %: "equals" in a figure; the model gives 71.0 cm and -0.51 % (46.90 vs 47.14
    # m/s) with the contact patch on Nathan's flat contact (+0.05 % with a point force,
    # contact_patch=False).
    z = np.arange(0.60, 0.80, 0.005)
    flex, rig = game_sweep(r161, z)
    i = int(np.argmax(flex.exit_speed))
    assert 0.70 <= z[i] <= 0.73
    assert flex.exit_speed[i] == pytest.approx(rig.exit_speed[i], rel=0.01)
    assert flex.exit_speed[i] == pytest.approx(47.0, rel=0.02)  # (D) about 47 m/s
    # beyond about 80 cm the exit speed falls sharply (H): here by over 30 % at 83 cm
    far, _ = game_sweep(r161, np.array([0.83]))
    assert far.exit_speed[0] < 0.7 * flex.exit_speed[i]


def test_game_exit_speed_at_60_cm_is_about_25_percent_below_rigid(r161):
    # Nathan 2000 (H/D): about 25 % below the rigid value (33 vs 44.6 m/s); the brief's band
    # 20-30 % spans the reading of his figure. Model: -22.2 % (34.7 vs 44.6 m/s; -21.8 % with a
    # point force).
    flex, rig = game_sweep(r161, np.array([0.60]))
    deficit = 1.0 - flex.exit_speed[0] / rig.exit_speed[0]
    assert 0.20 <= deficit <= 0.30
    assert rig.exit_speed[0] == pytest.approx(44.6, rel=0.01)


def test_modes_up_to_about_the_fourth_are_excited(r161):
    # Nathan 2000 (H): modes up to about the 4th are excited. "About": at least 85 % of the
    # bending energy left at separation lies in modes 1-4 for barrel impacts (model: 90-99 %).
    z = np.array([0.60, 0.65, 0.70, 0.75, 0.80])
    z0 = r161.balance_point - 24.0 / 51.0
    out = FlexibleEngine(n_modes=18, record_states=True, contact_surface="flat").solve(
        r161, nathan_ball(0.5), z0, ImpactBatch(z - z0, -40.0, 51.0), support="free")
    modes = cached_modes(r161, "free", z0, 18)
    d = out.diagnostics
    energy = 0.5 * (d["modal_velocity"][:, 2:] ** 2
                    + (modes.omega[2:] * d["bending_displacement"]) ** 2)
    assert np.all(energy[:, :4].sum(1) >= 0.85 * energy.sum(1))


def test_free_and_pinned_bats_give_the_same_exit_speed(r161):
    # Nathan 2000 (H): a bat pivoted 15 cm from the knob (56 rad/s) and a free bat give the same
    # flexible exit speed. 1 % (brief); the model agrees to 1e-5 over 60-75 cm, while the rigid
    # free and pinned bats differ by up to 3.2 % there.
    z = np.arange(0.60, 0.7501, 0.01)
    batch = ImpactBatch(z - 0.15, -40.0, 56.0)
    ball = nathan_ball(0.50)
    engine = FlexibleEngine(contact_surface="flat")
    free = engine.solve(r161, ball, 0.15, batch, support="free").exit_speed
    pinned = engine.solve(r161, ball, 0.15, batch, support="pinned").exit_speed
    np.testing.assert_allclose(free, pinned, rtol=0.01)


def test_low_speed_exit_speed_equals_rigid_at_the_mode_1_node(r161):
    # Nathan 2000 (H): 1 m/s ball on a stationary bat: the exit speed equals the rigid value at
    # the node of mode 1 (68 cm) and the rigid curve peaks at the CG. e0 = 0.66 (his 1 m/s fit).
    # 1 % at the node ("equals"; model +0.2 %); the rigid peak within the 1 cm grid of the CG.
    modes = cached_modes(r161, "free", 0.0, 24)
    node = mode_nodes(modes, 1)[-1]
    assert node == pytest.approx(0.68, abs=0.01)
    z = np.append(np.arange(0.40, 0.80, 0.01), node)
    batch = ImpactBatch(z, -1.0, 0.0)  # pivot at the knob: only a reference point here
    ball = nathan_ball(0.66)
    flex = FlexibleEngine(contact_surface="flat").solve(r161, ball, 0.0, batch,
                                                        support="free").exit_speed
    rig = RigidEngine().solve(r161, ball, 0.0, batch, support="free").exit_speed
    assert flex[-1] == pytest.approx(rig[-1], rel=0.01)
    assert abs(z[np.argmax(rig[:-1])] - r161.balance_point) <= 0.01
    assert np.all(flex[:-1] < rig[:-1] * 1.01)  # vibrations only take energy at low speed
