"""Batted-ball flight (batcert.physics.trajectory): limits with closed forms and invariants."""

from __future__ import annotations

import numpy as np
import pytest

from batcert.physics import trajectory as tr

VACUUM = tr.Aerodynamics(cd0=0.0, cd_spin=0.0, cl2=0.0)


@pytest.mark.parametrize("angle_deg", [10.0, 30.0, 45.0, 60.0])
def test_without_air_the_projectile_closed_form(angle_deg):
    """No drag, no lift: range from a launch height h is v cos(a) (v sin(a) + sqrt(v^2 sin(a)^2
    + 2 g h)) / g (plus the start 2 ft toward centre field); RK4 is exact for constant
    acceleration and the landing cubic too, so 1e-9 m."""
    v, a, h = 40.0, np.radians(angle_deg), 3 * tr.FT
    got = tr.fly(v, a, 2000 * tr.RPM, aero=VACUUM)
    vz = v * np.sin(a)
    t = (vz + np.sqrt(vz**2 + 2 * tr.GRAVITY * h)) / tr.GRAVITY
    assert got.hang_time[0] == pytest.approx(t, abs=1e-9)
    assert got.distance[0] == pytest.approx(2 * tr.FT + v * np.cos(a) * t, abs=1e-9)
    assert got.apex[0] == pytest.approx(h + vz**2 / (2 * tr.GRAVITY), abs=1e-4)


def test_a_batch_flies_each_ball_as_alone():
    speeds, angles = np.array([35.0, 45.0, 50.0]), np.radians([15.0, 28.0, 40.0])
    batch = tr.fly(speeds, angles, 1800 * tr.RPM)
    for i in range(3):
        one = tr.fly(speeds[i], angles[i], 1800 * tr.RPM)
        assert one.distance[0] == pytest.approx(batch.distance[i], rel=1e-12)


def test_the_step_is_converged():
    """The default 5 ms step against 1 ms: 1e-4 m."""
    a = tr.fly(46.0, np.radians(28), 2200 * tr.RPM)
    b = tr.fly(46.0, np.radians(28), 2200 * tr.RPM, step=0.001)
    assert a.distance[0] == pytest.approx(b.distance[0], abs=1e-4)


def test_backspin_carries_a_line_drive_and_thin_air_carries():
    """Lift from backspin lengthens a 15 deg line drive (at 28 deg the spin's added drag wins
    above about 2000 rpm, as in Nathan's calculator); thinner air (1600 m) lengthens it too."""
    base = tr.fly(44.7, np.radians(15), 1500 * tr.RPM).distance[0]
    assert tr.fly(44.7, np.radians(15), 2500 * tr.RPM).distance[0] > base
    thin = tr.air_density(elevation=1600.0)
    assert tr.fly(44.7, np.radians(15), 1500 * tr.RPM, air=thin).distance[0] > base


def test_dry_air_density_at_its_definition():
    """1.2929 kg/m^3 for dry air at 0 deg C and 760 mmHg (the calculator's constant)."""
    assert tr.air_density(273.15, 101_325.0, 0.0, 0.0) == pytest.approx(1.2929, rel=1e-12)


def test_a_ball_that_never_lands_is_refused():
    with pytest.raises(ValueError, match="still in the air"):
        tr.fly(40.0, np.radians(80), 0.0, max_time=1.0)
