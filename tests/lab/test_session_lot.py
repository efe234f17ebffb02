"""A session's ball lot calibrated on its reference bat's measured hits (batcert.lab.lot;
docs/lab-reduction.md, "The ball lot"), on the shipped example examples/lab/synthetic-lot.yaml
and on broken copies of it."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from batcert.commands.inputs import load_protocol_any
from batcert.commands.reduce import run_reduce
from batcert.engines import get_engine
from batcert.errors import InputError
from batcert.lab.lot import with_session_lot
from batcert.lab.session import load_lab_session
from batcert.runner.lot import TOLERANCE
from batcert.runner.runner import run_protocol

LAB = Path(__file__).resolve().parents[2] / "examples" / "lab"
# the reference bat's true BBCOR at its peak, 6 in from the tip (scripts/make_synthetic_hits.py):
# its exact hits give it back within the speeds' rounding (1.3e-5, as synthetic-exact)
REFERENCE_TRUTH = 0.485


@pytest.fixture(scope="module")
def bbcor():
    return load_protocol_any("ncaa-bbcor").protocol


@pytest.fixture(scope="module")
def lot_result():
    return run_reduce(str(LAB / "synthetic-lot.yaml"), "ncaa-bbcor")


def test_the_reference_bats_hits_calibrate_the_lot(bbcor):
    """The calibrated lot makes the model's BBCOR of the reference bat equal its certified
    value (the calibration's definition, to the search's TOLERANCE), and that value is the
    reference hits' truth."""
    session = load_lab_session(LAB / "synthetic-lot.yaml")
    calibrated, ref = with_session_lot(session, bbcor)
    assert ref is not None and ref.value == pytest.approx(REFERENCE_TRUTH, abs=1.3e-5)
    assert calibrated.ball.reference.value == ref.value
    assert calibrated.ball.reference.uncertainty == ref.uncertainty > 0
    model = run_protocol(ref.session.built, bbcor, calibrated.ball, get_engine("flexible"))
    assert model.value == pytest.approx(ref.value, abs=TOLERANCE)
    # the ball file's own reference (ash-34 at 0.490) gives a livelier lot than 0.485 does
    assert calibrated.ball.lot.shift < session.ball.lot.shift


def test_the_measured_values_do_not_depend_on_the_lot(lot_result):
    """The aluminium bat's hits are synthetic-exact.csv's: the certified BBCOR is the same with
    and without the reference (it is reduced from speeds, location, MOI and ball mass); the
    model's prediction and the BPF (the ball's COR) follow the deader lot."""
    plain = run_reduce(str(LAB / "synthetic-exact.yaml"), "ncaa-bbcor")
    assert lot_result.value == plain.value
    assert [h.bbcor for h in lot_result.hits] == [h.bbcor for h in plain.hits]
    assert lot_result.model["value"] < plain.model["value"]
    assert all(a.bpf > b.bpf for a, b in zip(lot_result.hits, plain.hits, strict=True))


def test_the_certificate_states_the_calibration_and_its_inputs(lot_result):
    lot = lot_result.lot_calibration
    assert lot["calibrated"] and lot["calibrated_on"] == "session"
    assert lot["reference_bat"] == "ash-34" and lot["protocol"] == "ncaa-bbcor"
    assert lot["reference_session"].endswith("synthetic-reference-ash.yaml")
    roles = {i["role"]: i for i in lot_result.inputs}
    for role in ("reference session", "reference hits", "reference bat"):
        assert len(roles[role]["sha256"]) == 64
    from batcert.reports.lab_view import lab_view
    facts = dict(lab_view(lot_result, charts=False)["facts"])
    assert "CALIBRATED (an input) on this session's reference bat" in facts["Ball lot of the model"]
    plain = json.loads(json.dumps(lot_result.to_dict()))
    assert plain["lot_calibration"]["value"] == pytest.approx(REFERENCE_TRUTH, abs=1.3e-5)


def test_without_a_reference_the_ball_files_calibration_is_stated():
    result = run_reduce(str(LAB / "synthetic-exact.yaml"), "ncaa-bbcor")
    lot = result.lot_calibration
    assert lot["calibrated_on"] == "ball file" and lot["value"] == 0.490
    assert lot["reference_session"] is None


def _copy(tmp_path: Path, edit: tuple[str, str] = ("", ""), ref_edit: tuple[str, str] = ("", "")
          ) -> Path:
    for name in ("synthetic-exact.csv", "synthetic-reference-ash.csv"):
        shutil.copy(LAB / name, tmp_path / name)
    ref = (LAB / "synthetic-reference-ash.yaml").read_text(encoding="utf-8")
    (tmp_path / "synthetic-reference-ash.yaml").write_text(ref.replace(*ref_edit), "utf-8")
    text = (LAB / "synthetic-lot.yaml").read_text(encoding="utf-8")
    (tmp_path / "s.yaml").write_text(text.replace(*edit), encoding="utf-8")
    return tmp_path / "s.yaml"


REFERENCE_LINE = "reference_session: synthetic-reference-ash.yaml"


@pytest.mark.parametrize("edit, ref_edit, message", [
    ((REFERENCE_LINE, "reference_session: missing.yaml"), ("", ""), "no such file"),
    ((REFERENCE_LINE, "reference_session: synthetic-reference-ash.csv"), ("", ""),
     "not a bare hits CSV"),
    ((REFERENCE_LINE, "reference_session: s.yaml"), ("", ""), "its own reference"),
    (("", ""), ("ball: collegiate-baseball", "ball: nathan-2000"), "is not this session's"),
    (("", ""), ("location_from: tip", "location_from: tip\nreference_session: s.yaml"),
     "a reference session of its own"),
    (("", ""), ("hits: synthetic-reference-ash.csv", "hits: synthetic-reference-ash.csv\n"
                "hits_required: 7"), "certify no BBCOR"),  # six hits a location
    (("", ""), ("pivot: 6 in", "pivot: 7 in"), "must be measured at its pivot"),
])
def test_a_reference_that_cannot_serve_is_an_input_error_at_its_line(tmp_path, bbcor, edit,
                                                                     ref_edit, message):
    path = _copy(tmp_path, edit, ref_edit)
    session = load_lab_session(path)
    with pytest.raises(InputError) as err:
        with_session_lot(session, bbcor)
    (problem,) = err.value.problems
    line = next(n for n, t in enumerate(path.read_text().splitlines(), 1)
                if t.startswith("reference_session"))
    assert (problem.file, problem.line, problem.field) == (str(path), line, "reference_session")
    assert message in problem.message


def test_a_ball_without_a_fit_cannot_be_calibrated(tmp_path, bbcor):
    path = _copy(tmp_path, ("ball: collegiate-baseball", "ball: nathan-2000"),
                 ("ball: collegiate-baseball", "ball: nathan-2000"))
    with pytest.raises(InputError, match="no law fitted to ball tests"):
        with_session_lot(load_lab_session(path), bbcor)


@pytest.mark.slow  # the lot search runs its grid of 17 protocol runs before it refuses (~15 s)
def test_a_reference_value_no_lot_reaches_is_an_input_error(tmp_path, bbcor):
    """A reference bat whose hits say BBCOR 0.30 (a dead lot far beyond 8 standard
    uncertainties of the ball tests): refused at the session's line, nothing certified."""
    path = _copy(tmp_path)
    csv = tmp_path / "synthetic-reference-ash.csv"
    rows = csv.read_text(encoding="utf-8").splitlines()
    out = rows[:2] + [",".join(r.split(",")[:3] + [f"{float(r.split(',')[3]) * 0.3:.3f}"]
                               + r.split(",")[4:]) for r in rows[2:]]
    csv.write_text("\n".join(out) + "\n", encoding="utf-8")
    with pytest.raises(InputError, match="cannot be calibrated on its reference bat") as err:
        with_session_lot(load_lab_session(path), bbcor)
    assert err.value.problems[0].field == "reference_session"


def test_the_calibration_points_into_the_session_file(bbcor):
    """The lot's reference is the session's (its file and field), so a lot that later cannot
    be used is reported there, not in the ball file."""
    session = load_lab_session(LAB / "synthetic-lot.yaml")
    calibrated, _ = with_session_lot(session, bbcor)
    ref = calibrated.ball.reference
    assert (ref.path, ref.field) == (session.spec.path, "reference_session")
    assert ref.bat.endswith("ash-34.yaml") and ref.protocol.endswith("ncaa-bbcor.yaml")
