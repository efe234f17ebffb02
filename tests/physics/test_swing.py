"""The swing-speed power law v = v_ref (I / I_ref)^-n (batcert.physics.swing)."""

from __future__ import annotations

import numpy as np
import pytest

from batcert.physics.swing import swing_speed


def test_the_reference_bat_gets_the_reference_speed():
    assert swing_speed(0.155, 38.0, 0.155, 0.25) == pytest.approx(38.0, rel=1e-15)


def test_exponent_zero_ignores_the_bat():
    np.testing.assert_allclose(swing_speed([0.05, 0.2, 0.4], 38.0, 0.155, 0.0), 38.0, rtol=1e-15)


def test_cross_and_bower_exponent():
    """n = 0.25 (softball bats, Cross & Bower 2006): a bat of twice the MOI is swung 2^-0.25 =
    0.8409 times as fast; a lighter-swinging bat faster. Exact arithmetic, rel=1e-12."""
    got = swing_speed(np.array([0.31, 0.0775]), 38.0, 0.155, 0.25)
    np.testing.assert_allclose(got, 38.0 * np.array([2 ** -0.25, 2 ** 0.25]), rtol=1e-12)
    assert got[0] < 38.0 < got[1]
