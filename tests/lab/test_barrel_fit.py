"""The barrel calibrated from measured hits (batcert.lab.calibrate) and written back."""

from __future__ import annotations

from pathlib import Path

import pytest

from batcert.commands.inputs import load_protocol_any
from batcert.engines import get_engine
from batcert.lab.calibrate import _model_metrics, fit_barrel, with_hoop_frequency
from batcert.lab.certify import certify
from batcert.lab.session import load_lab_session

REPO = Path(__file__).resolve().parents[2]
LAB = REPO / "examples" / "lab"


def test_the_fitted_barrel_meets_the_measurement():
    """At the fitted scale the model's BBCOR at the certified location is the measured value
    (Brent to 1e-6 in the scale, times a slope of about 0.02: 2e-8 in BBCOR); its uncertainty
    is u_c over the slope, and the equivalent hoop frequency scales with sqrt(scale). The
    "measurement" is the model's own BBCOR at 1.7 x the barrel's stiffness (the synthetic
    session's 0.495 lies beyond x4 for the model's aluminium-34, docs/validation.md), so the
    fit must find 1.7."""
    from batcert.physics import barrel
    pin = load_protocol_any("ncaa-bbcor")
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    _, c = certify(s, pin.protocol, 0.5)
    eng = get_engine("flexible")
    loc = c.scan[c.location].position
    measured = _model_metrics(s, pin.protocol, pin.ball, eng, loc, [1.7])[0]
    (fit,) = fit_barrel(s, pin.protocol, pin.ball, eng, loc, measured, c.u_c)
    assert fit.scale == pytest.approx(1.7, abs=1e-5)
    assert _model_metrics(s, pin.protocol, pin.ball, eng, loc, [fit.scale])[0] == \
        pytest.approx(measured, abs=1e-6)
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


def test_a_measurement_beyond_the_bounds_says_how_far_the_model_is():
    # The synthetic session's certified BBCOR (0.4933) is below anything the model's
    # aluminium-34 gives at x0.25-x4 (docs/lab-reduction.md): no fit, the model's range instead,
    # and the reduction's warning says so rather than leaving the row blank.
    from types import SimpleNamespace

    from batcert.commands.reduce import _barrel_fits
    from batcert.lab.calibrate import calibrate_barrel
    pin = load_protocol_any("ncaa-bbcor")
    s = load_lab_session(LAB / "synthetic-scatter.yaml")
    _, c = certify(s, pin.protocol, 0.5)
    eng = get_engine("flexible")
    loc = c.scan[c.location].position
    cal = calibrate_barrel(s, pin.protocol, pin.ball, eng, loc, c.value, c.u_c)
    assert cal.fits == [] and cal.span is not None
    lo, hi = cal.span
    assert c.value < lo < hi
    # the range covers the model's own values at the bounds (its grid includes both ends)
    ends = _model_metrics(s, pin.protocol, pin.ball, eng, loc, [0.25, 4.0])
    assert lo <= min(ends) + 1e-12 and hi >= max(ends) - 1e-12
    fits, warnings = _barrel_fits(s, pin.protocol, pin.ball, "flexible",
                                  SimpleNamespace(value=c.value, location=c.location,
                                                  scan=c.scan, u_c=c.u_c))
    assert fits == []
    (warning,) = warnings
    assert "cannot be calibrated" in warning and f"{lo:.4f} to {hi:.4f}" in warning
