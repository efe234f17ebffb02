"""batcert.lab.session on the shipped example sessions (examples/lab/, made by
scripts/make_synthetic_hits.py from a chosen true BBCOR; docs/lab-reduction.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from batcert.lab.session import load_lab_session, reduce_session
from batcert.model.mass import mass_properties

LAB = Path(__file__).resolve().parents[2] / "examples" / "lab"
INCH = 0.0254


def true_bbcor(x):
    """The generator's chosen truth at x [m] from the tip (scripts/make_synthetic_hits.py)."""
    return 0.495 - 10.0 * (np.asarray(x) - 0.1524) ** 2


def test_the_exact_session_gives_back_its_true_bbcor():
    """Every hit's BBCOR equals the value it was made from, to within the speeds' rounding to
    0.001 m/s: |d BBCOR| <= (1 + k) 0.0005 (1 + e_A) / v_i (docs/lab-reduction.md)."""
    s = load_lab_session(LAB / "synthetic-exact.yaml")
    h = reduce_session(s)
    x = s.hits.impact_location  # the CSV gives inches from the tip
    bound = (1 + h.recoil_factor) * 0.0005 * (1 + h.collision_efficiency) \
        / s.hits.inbound_speed
    assert len(x) == 42 and s.moi_source == "measured"
    assert np.all(np.abs(h.bbcor - true_bbcor(x)) <= bound)
    assert bound.max() < 1.4e-5
    noted = [float(n.split()[-1]) for n in s.hits.note]  # the truth written beside each hit
    np.testing.assert_allclose(noted, true_bbcor(x), atol=5e-7)  # printed to 6 decimals


def test_the_session_reads_the_bat_ball_and_pivot():
    s = load_lab_session(LAB / "synthetic-exact.yaml")
    mp = mass_properties(s.built, 6 * INCH)
    assert s.moi_pivot == mp.measured_moi_pivot  # the measured MOI moved to the test pivot
    assert s.ball.model.mass == 5.125 * 0.028349523125  # the collegiate baseball's 5.125 oz
    length = s.built.model.length
    np.testing.assert_allclose(s.impact_location, length - 6 * INCH - s.hits.impact_location)


def test_the_scatter_session_keeps_its_invalid_hit():
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    assert list(np.flatnonzero(~s.hits.valid) + 1) == [19]  # the first hit at 6 in
    assert "seam strike" in s.hits.note[18]
    h = reduce_session(s)
    assert np.all(np.isfinite(h.bbcor))  # an invalid hit is reduced and shown, not dropped
    # the scatter is what the generator put in: e_A 0.004 -> BBCOR about 0.005
    resid = h.bbcor - true_bbcor(s.hits.impact_location)
    assert 0.002 < np.std(resid) < 0.009
