"""The in-play barrel sweep: the sweet zone's arithmetic, and the free bat's independence of
where the swing's axis is taken during contact."""

from __future__ import annotations

import numpy as np
import pytest

from batcert.engines import get_engine
from batcert.engines.base import ImpactBatch, Job
from batcert.inplay.barrel import barrel_grid, sweet_zone

MPH, INCH = 0.44704, 0.0254


def test_sweet_zone_of_a_parabola_is_its_closed_form():
    """y = top - a (x - x0)^2 is within d of its top over 2 sqrt(d / a). On the quarter-inch grid
    (h = 6.35 mm) the chord between the samples around a crossing sags below the parabola by
    up to a h^2 / 4 = 0.02 m/s, which moves each end by that over the slope 2 a |x - x0|: up to
    3.4e-4 m at the 1 mph ends here, so 1e-3 m (0.04 in) for the two ends is the tolerance."""
    x = barrel_grid()
    top, x0, a = 50.0, 0.16, 2000.0  # [m/s], [m], [m/s per m^2]
    zone = sweet_zone(x, top - a * (x - x0) ** 2)
    assert zone.best[0] == pytest.approx(top, abs=1e-9)  # the parabola's peak, exactly
    assert zone.at[0] == pytest.approx(x0, abs=1e-9)
    for length, drop in ((zone.length_1[0], 1 * MPH), (zone.length_5[0], 5 * MPH)):
        assert length == pytest.approx(2 * np.sqrt(drop / a), abs=1e-3)
    assert not zone.open[0]


def test_a_zone_reaching_the_window_end_is_marked_open():
    """A flat curve never drops 5 mph: the zone is the whole window, flagged as a lower bound."""
    x = barrel_grid()
    zone = sweet_zone(x, np.stack([40.0 - 0.01 * x, 50.0 - 2000.0 * (x - 0.16) ** 2]))
    assert zone.open.tolist() == [True, False]
    assert zone.length_5[0] == pytest.approx(x[-1] - x[0])


def test_free_bat_does_not_depend_on_its_support_during_contact():
    """Smith (2001) and Nathan (2000): the hands do not matter during the millisecond of
    contact, so a free bat and one pinned at the knob give the same batted-ball speed for the
    same motion before impact. Measured 3e-6 relative for ash-34 at 71 mph and 94 mph; 1e-3
    allows a bending wave that reaches the handle within the contact."""
    from batcert.commands.inputs import load_bat_any, load_batter_any
    ball = load_batter_any("pro").ball.model
    bat = load_bat_any("ash-34").built.model
    r = np.array([bat.length - 6.25 * INCH, bat.length - 4 * INCH])
    batch = ImpactBatch(r, np.full(2, -94.2 * MPH), np.full(2, 71.1 * MPH / (bat.length - 0.1524)))
    free, pinned = get_engine("flexible").solve_many(
        [Job(bat, ball, 0.0, batch, "free"), Job(bat, ball, 0.0, batch, "pinned")])
    assert free.exit_speed == pytest.approx(pinned.exit_speed, rel=1e-3)
    assert free.exit_speed[0] > free.exit_speed[1]  # nearer the sweet spot hits harder
