"""A ball lot calibrated on a reference bat (batcert.runner.lot): the shipped collegiate ball's
lot meets its reference bat's BBCOR, every command that loads the ball uses the lot, and a
reference that cannot be used is an input error at its line."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from batcert.commands.inputs import load_ball_lot, load_bat_any, load_protocol_any
from batcert.engines.flexible import FlexibleEngine
from batcert.errors import InputError
from batcert.runner import lot as lot_module
from batcert.runner.runner import run_protocol

REPO = Path(__file__).resolve().parents[2]
COLLEGIATE = REPO / "protocols" / "balls" / "collegiate-baseball.yaml"


@pytest.fixture(scope="module")
def bbcor():
    return load_protocol_any("ncaa-bbcor")


def test_the_shipped_lot_meets_its_reference_bat(bbcor):
    # the calibration's definition (the ball file: ash-34 under ncaa-bbcor, 0.490 +/- 0.010):
    # the model's BBCOR of the reference bat equals the value to the solver's tolerance
    ball = bbcor.ball
    assert ball.reference is not None and ball.lot is not None
    assert abs(ball.lot.model_value - 0.490) <= lot_module.TOLERANCE
    result = run_protocol(load_bat_any("ash-34").built, bbcor.protocol, ball, FlexibleEngine())
    assert result.value == pytest.approx(0.490, abs=lot_module.TOLERANCE)
    # a deader lot than the tested balls (measured -2.68 +/- 0.64 standard uncertainties): the
    # model puts a wood bat above the ball's tests, and the calibration takes that up
    assert -4.0 < ball.lot.shift < -1.0 and 0.3 < ball.lot.u_shift < 1.0
    assert ball.lot.u_shift == pytest.approx(0.010 / ball.lot.slope)


def test_the_lot_is_the_fitted_law_moved_along_its_fit(bbcor):
    # moving back by the shift gives the fitted (tested) balls' law: its value of every test
    # is the fit's (the move is linear in the fit's coordinates: exact to rounding)
    from batcert.physics.balls.fit import predict

    ball = bbcor.ball
    tested = ball.fit.moved(-ball.lot.shift)
    got = predict([tested], ball.fit.tests, float(ball.model.mass), ball.model.radius)[0]
    np.testing.assert_allclose(got, ball.fit.model, rtol=1e-9)
    # and the lot's COR lies below the tested balls' at every speed above 5 m/s
    speeds = np.array([5.0, 26.8, 45.0, 60.8])
    assert np.all(ball.model.law.wall_impact(ball.model.mass, speeds).cor
                  < tested.wall_impact(ball.model.mass, speeds).cor)


def test_every_way_in_loads_the_calibrated_lot(bbcor):
    from batcert.commands.inputs import load_batter_any
    from batcert.lab.session import load_lab_session

    assert load_ball_lot(COLLEGIATE).model.law == bbcor.ball.model.law
    assert load_batter_any("college").ball.model.law == bbcor.ball.model.law
    session = load_lab_session(REPO / "examples" / "lab" / "synthetic-scatter.yaml")
    assert session.ball.lot is not None


def _ball_file(tmp_path, reference: str, law: str = "viscoelastic-2") -> Path:
    text = COLLEGIATE.read_text(encoding="utf-8")
    head, _, _ = text.partition("reference_bat:")
    if law != "viscoelastic-2":
        head = head.replace("model: viscoelastic-2", f"model: {law}\n  k1: 6.53e7\n  alpha: 1.84")
        head = head.replace("  fast_relaxation_time: 0.030 ms\n", "")
    path = tmp_path / "ball.yaml"
    path.write_text(head + "reference_bat:\n" + reference, encoding="utf-8")
    return path


def _line_of(path: Path, text: str) -> int:
    """The line of the reference section that holds ``text``."""
    lines = path.read_text().splitlines()
    start = lines.index("reference_bat:")
    return next(i for i, ln in enumerate(lines[start + 1:], start + 2) if text in ln)


@pytest.mark.parametrize("reference, field, message", [
    ("  bat: no-such-bat\n  protocol: ncaa-bbcor\n  value: 0.49 +/- 0.01\n", "bat:",
     "unknown bat 'no-such-bat'"),
    ("  bat: ash-34\n  protocol: ncaa-bbcr\n  value: 0.49 +/- 0.01\n", "protocol:",
     "did you mean 'ncaa-bbcor'"),
    ("  bat: ash-34\n  protocol: ncaa-bbcor\n  value: 0.49\n", "value:",
     "needs its standard uncertainty"),
    ("  bat: ash-34\n  protocol: ncaa-bbcor\n  value: 0.49 +/- 0.01\n  vaule: 1\n", "vaule:",
     "did you mean"),
])
def test_a_reference_that_cannot_be_read_is_an_input_error_at_its_line(tmp_path, reference,
                                                                        field, message):
    path = _ball_file(tmp_path, reference)
    with pytest.raises(InputError) as exc:
        load_ball_lot(path)
    text = exc.value.render()
    assert f"{path}:{_line_of(path, field)}:" in text and message in text, text


def test_a_reference_bat_needs_a_fitted_law(tmp_path):
    path = _ball_file(tmp_path, "  bat: ash-34\n  protocol: ncaa-bbcor\n  value: 0.49 +/- 0.01\n",
                      law="power-law-hysteresis")
    with pytest.raises(InputError, match="only a viscoelastic law fitted to ball tests"):
        load_ball_lot(path)


def test_a_value_the_lot_cannot_reach_is_an_input_error(tmp_path):
    # BBCOR 0.95 from a wood bat: no lot within +/- 8 standard uncertainties of the tests gives it
    path = _ball_file(tmp_path, "  bat: ash-34\n  protocol: ncaa-bbcor\n  value: 0.95 +/- 0.01\n")
    with pytest.raises(InputError) as exc:
        load_ball_lot(path)
    text = exc.value.render()
    assert f"{path}:{_line_of(path, 'value:')}:" in text
    assert "cannot be calibrated on its reference bat" in text and "0.9500" in text


def test_a_metric_that_is_not_monotonic_near_the_tests_is_bracketed():
    # the secant from 0 and -1 meets a falling metric there (the linearised lot need not be
    # monotonic far from the tests): the grid over the bounds finds the sign change nearest 0
    # and regula falsi the root, to the tolerance; a value never reached is NaN with the nearest
    def gaps(shifts):
        k = np.asarray(shifts, dtype=float)
        return (k - 2.3) ** 2 - 1.0  # roots at 1.3 and 3.3 (off the grid); falling at 0 and -1

    assert lot_module._secant(gaps) is None
    cal = lot_module._bracketed(gaps, lambda k, slope, gap: lot_module.LotCalibration(
        k, 0.01 / slope, 0.49 + gap, slope), 0.49)
    assert cal.shift == pytest.approx(1.3, abs=1e-4)
    assert cal.slope == pytest.approx(-2.0, rel=0.1)  # the last secant's: the derivative -2
    never = lot_module._bracketed(lambda s: np.asarray(s, dtype=float) ** 2 + 0.05, None, 0.49)
    assert np.isnan(never.shift) and never.model_value == pytest.approx(0.54)
