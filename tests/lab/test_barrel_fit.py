"""The barrel calibrated from measured hits (batcert.lab.calibrate) and written back."""

from __future__ import annotations

from pathlib import Path

import pytest

from batcert.commands.inputs import load_protocol_any
from batcert.engines import get_engine
from batcert.lab.calibrate import _model_metric, fit_barrel, with_hoop_frequency
from batcert.lab.certify import certify
from batcert.lab.session import load_lab_session

REPO = Path(__file__).resolve().parents[2]
LAB = REPO / "examples" / "lab"


def test_the_fitted_barrel_meets_the_measurement():
    """At the fitted scale the model's BBCOR at the certified location is the measured value
    (Brent to 1e-6 in the scale, times a slope of about 0.2: 2e-7 in BBCOR); its uncertainty
    is u_c over the slope, and the equivalent hoop frequency scales with sqrt(scale)."""
    from batcert.physics import barrel
    pin = load_protocol_any("ncaa-bbcor")
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    _, c = certify(s, pin.protocol, 0.5)
    eng = get_engine("flexible")
    loc = c.scan[c.location].position
    (fit,) = fit_barrel(s, pin.protocol, pin.ball, eng, loc, c.value, c.u_c)
    assert _model_metric(s, pin.protocol, pin.ball, eng, loc, fit.scale) == \
        pytest.approx(c.value, abs=1e-6)
    assert fit.u_scale == pytest.approx(c.u_c / abs(fit.slope), rel=1e-12)
    assert fit.hoop_frequency == pytest.approx(barrel.hoop_frequency(s.built.model)
                                               * fit.scale ** 0.5, rel=1e-12)


def test_a_solid_bat_has_no_barrel_to_fit():
    pin = load_protocol_any("ncaa-bbcor")
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    from dataclasses import replace

    from batcert.commands.inputs import load_bat_any
    ash = replace(s, built=load_bat_any("ash-34").built)
    assert fit_barrel(ash, pin.protocol, pin.ball, get_engine("flexible"), 0.55, 0.49,
                      0.002) == []


def test_write_back_keeps_every_other_line():
    text = (REPO / "bats" / "aluminium-34.yaml").read_text(encoding="utf-8")
    out = with_hoop_frequency(text, 1320.4, "fitted")
    added = [ln for ln in out.splitlines() if ln not in text.splitlines()]
    assert added == ["  hoop_frequency: 1320 Hz  # fitted"]
    again = with_hoop_frequency(out, 1500.0, "refitted")  # replaces, does not add a second
    assert again.count("hoop_frequency:") == 1 and "1500 Hz  # refitted" in again
    with pytest.raises(ValueError, match="no measured: block"):
        with_hoop_frequency("name: x\nconstruction: hollow\n", 1300.0, "c")
