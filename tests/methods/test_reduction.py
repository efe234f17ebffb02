"""batcert.methods.reduction against hits computed by hand from docs/lab-reduction.md (R1-R7).

The hand numbers: a 145 g ball (0.145 kg) at 60 m/s rebounds at 15 m/s from a bat of MOI
0.2 kg m^2 about the pivot, struck 0.55 m from it: k = 0.145 * 0.55^2 / 0.2 = 0.21931250,
e_A = 0.25, BBCOR = 0.25 * 1.2193125 + 0.2193125 = 0.52414063, BESR = 0.75, w2 = 0.145 * 0.55 *
75 / 0.2 = 29.90625 rad/s. Exact arithmetic: compared to 1e-12 (floating-point rounding only).
"""

from __future__ import annotations

import numpy as np
import pytest

from batcert.methods.reduction import reduce_hits


def cor_half(v):
    return np.full_like(np.asarray(v, float), 0.5)


def test_a_hand_computed_hit():
    h = reduce_hits([60.0], [15.0], [0.55], 0.2, 0.145, cor_half)
    assert h.collision_efficiency[0] == pytest.approx(0.25, abs=1e-12)
    assert h.recoil_factor[0] == pytest.approx(0.2193125, abs=1e-12)
    assert h.bbcor[0] == pytest.approx(0.524140625, abs=1e-12)
    assert h.besr[0] == pytest.approx(0.75, abs=1e-12)
    assert h.bat_angular_speed_after[0] == pytest.approx(29.90625, abs=1e-12)
    assert h.bpf[0] == pytest.approx(0.524140625 / 0.5, abs=1e-12)
    assert np.isnan(h.measured_cor[0]) and np.isnan(h.measured_bpf[0])  # no w2 measured


def test_the_bpf_method_with_the_momentum_w2_is_bbcor():
    """(R4) with the w2 of (R2) is (R5): measuring the bat's speed changes nothing when
    momentum is conserved; a measured w2 10 % low lowers e by 10 % of k (1 + e_A)."""
    h = reduce_hits([60.0], [15.0], [0.55], 0.2, 0.145, cor_half, [29.90625])
    assert h.measured_cor[0] == pytest.approx(h.bbcor[0], abs=1e-12)
    low = reduce_hits([60.0], [15.0], [0.55], 0.2, 0.145, cor_half, [0.9 * 29.90625])
    assert h.bbcor[0] - low.measured_cor[0] == pytest.approx(0.1 * 0.2193125 * 1.25, abs=1e-12)


def test_arrays_and_the_ball_cor_at_the_inbound_speed():
    seen = []

    def cor(v):
        seen.append(np.asarray(v).copy())
        return 0.6 - 0.002 * np.asarray(v)

    h = reduce_hits([50.0, 60.0], [12.0, 15.0], [0.5, 0.55], 0.2, 0.145, cor)
    np.testing.assert_array_equal(seen[0], [50.0, 60.0])
    np.testing.assert_allclose(h.ball_cor, [0.5, 0.48], atol=1e-15)
    np.testing.assert_allclose(h.bpf, h.bbcor / h.ball_cor, rtol=1e-15)
