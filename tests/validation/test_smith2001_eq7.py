"""L. V. Smith, "Evaluating baseball bat performance", Sports Engineering 4 (2001) 205-214, Eq. 7:
the rigid-body sweet spot r_s = v_p / w1 + sqrt(I / m + (v_p / w1)^2), and the study's point that
it cannot locate the sweet spot of a real bat.

Inputs: the study's speeds (pitch 31 m/s, swing 53 rad/s about a pivot 150 mm from the knob),
its bats' MOI (Table 1: ash 0.209, aluminium 0.198 kg m^2) and the shipped collegiate ball,
5 1/8 oz = 0.145291 kg (the study's ball mass is not given).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import get_engine
from batcert.physics.rigid import rigid_sweet_spot
from batcert.runner.runner import run_protocol

REPO = Path(__file__).resolve().parents[2]
BALL = 5.125 * 0.028349523125  # [kg]
TIP = 0.860 - 0.150  # the tip's distance from the pivot [m]
# Eq. 7 by hand: with a = v_p / w1 = -31 / 53 = -0.584906,
#   ash        I/m = 0.209 / 0.145291 = 1.438494; r_s = a + sqrt(1.438494 + 0.342115) = 0.749487 m
#   aluminium  I/m = 0.198 / 0.145291 = 1.362784; r_s = a + sqrt(1.362784 + 0.342115) = 0.720810 m
#   stationary ball (v_p = 0): r_s = sqrt(I/m) = 1.199370 m (ash), 1.167381 m (aluminium)
PITCHED = {0.209: 0.749487, 0.198: 0.720810}
STATIONARY_BALL = {0.209: 1.199370, 0.198: 1.167381}


@pytest.mark.parametrize("moi", sorted(PITCHED))
def test_eq7_at_the_study_speeds(moi):
    # hand-worked values to 6 digits: tolerance 2e-6 m
    assert rigid_sweet_spot(moi, BALL, -31.0, 53.0) == pytest.approx(PITCHED[moi], abs=2e-6)
    assert rigid_sweet_spot(moi, BALL, 0.0, 53.0) == pytest.approx(STATIONARY_BALL[moi],
                                                                    abs=2e-6)


def test_eq7_puts_the_sweet_spot_beyond_the_tip():
    # The study: rigid-body dynamics cannot locate the sweet spot. At its speeds Eq. 7 falls
    # beyond the tip of both bats (0.710 m from the pivot), and with a stationary ball far beyond.
    for moi in PITCHED:
        assert rigid_sweet_spot(moi, BALL, -31.0, 53.0) > TIP
        assert rigid_sweet_spot(moi, BALL, 0.0, 53.0) > 1.6 * TIP


def test_eq7_is_undefined_for_a_stationary_bat():
    assert math.isnan(rigid_sweet_spot(0.209, BALL, -31.0, 0.0))


def test_flexible_sweet_spot_lies_in_the_barrel_and_moves_far_less_than_eq7():
    # The study's finding (DESIGN.md section 1): the sweet spot moves with swing and pitch speed
    # far less than Eq. 7 says. Checked with the flexible engine on the shipped ash bat under the
    # replayed BPF-at-sweet-spot protocol: the located sweet spot lies in the barrel, 10-21 cm
    # from the tip (the study's and Nathan's 2000 barrels peak 13-18 cm from the tip; the band
    # is wider because this bat's profile is not the study's; measured 12.4, 15.7 and, for the
    # stationary bat, 20.2 cm with the shipped ball lot), and between the two conditions
    # where Eq. 7 is defined it moves less than a quarter as far as Eq. 7 does (45 cm).
    bat = load_bat_any("ash-34").built
    p = load_protocol_any(str(REPO / "protocols" / "studies" / "smith2001-bpf-sweet-spot.yaml"))
    result = run_protocol(bat, p.protocol, p.ball, get_engine("flexible"))
    assert all(0.10 <= TIP - c.sweet_spot <= 0.21 for c in result.conditions)
    swung = [c for c in result.conditions if c.rigid_sweet_spot is not None]
    assert len(swung) == 2
    model = abs(swung[0].sweet_spot - swung[1].sweet_spot)
    rigid = abs(swung[0].rigid_sweet_spot - swung[1].rigid_sweet_spot)
    assert rigid > TIP / 2 and model < 0.25 * rigid
