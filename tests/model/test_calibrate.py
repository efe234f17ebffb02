"""Stiffness calibration to a measured first bending frequency (physics/calibrate.py)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from r161 import r161_bat  # noqa: E402

from batcert.errors import ModelError
from batcert.model.calibrate import calibrate_stiffness
from batcert.physics.modes import compute_modes


def test_matches_the_measured_fundamental_and_scales_every_mode():
    bat = r161_bat()
    before = compute_modes(bat, "free", 0.15, n_modes=5).frequencies_hz
    # Nathan 2000 Table II: 165 Hz, the R161's fundamental (REFERENCE-DATA.md, H)
    model, corr = calibrate_stiffness(bat, 165.0, 0.15)
    after = compute_modes(model, "free", 0.15, n_modes=5).frequencies_hz
    assert after[0] == pytest.approx(165.0, rel=1e-9)  # exact by construction
    # EI and kappa G A scaled together: every frequency scales by sqrt(s) (to solver precision)
    np.testing.assert_allclose(after / before, np.sqrt(corr["stiffness_scale"]), rtol=1e-9)
    assert model.mass == pytest.approx(bat.mass, rel=1e-15)  # mass untouched


def test_absurd_frequency_is_refused_naming_the_field():
    with pytest.raises(ModelError) as err:
        calibrate_stiffness(r161_bat(), 20.0, 0.15)
    assert err.value.field == "measured.first_bending_frequency"
    assert "stiffness x 0.01" in str(err.value)
