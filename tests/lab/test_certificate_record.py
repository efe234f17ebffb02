"""The certificate's record (ISO/IEC 17025:2017, 7.8; docs/lab-reduction.md): every field of
``CERTIFICATE_FIELDS`` shown, from the session's ``lab:`` block, MISSING where not given, a
warning naming what is missing; a signature line per signatory; a warning when the MOI is the
model's or the serials disagree."""

from __future__ import annotations

from pathlib import Path

import pytest

from batcert.commands.reduce import run_reduce
from batcert.errors import InputError
from batcert.reports.write import render
from batcert.results.lab import CERTIFICATE_FIELDS

LAB = Path(__file__).resolve().parents[2] / "examples" / "lab"


@pytest.fixture(scope="module")
def full():
    return run_reduce(str(LAB / "synthetic-scatter.yaml"), "ncaa-bbcor", engine="rigid")


@pytest.fixture(scope="module")
def bare():
    return run_reduce(str(LAB / "synthetic-exact.yaml"), "ncaa-bbcor", engine="rigid")


def _session(tmp_path, lab_block: str) -> str:
    text = (LAB / "synthetic-exact.yaml").read_text().replace("hits: synthetic-exact.csv",
                                                              f"hits: {LAB / 'synthetic-exact.csv'}")
    path = tmp_path / "session.yaml"
    path.write_text(text + lab_block)
    return str(path)


def test_the_example_certificate_shows_every_field_with_a_value(full):
    md, html = render(full, "md"), render(full, "html")
    for f in CERTIFICATE_FIELDS:
        assert f"| {f.word} |" in md and f.clause in md
        assert f.word in html
    assert "| MISSING |" not in md and "<td>MISSING" not in html
    assert not [w for w in full.warnings if "ISO/IEC 17025" in w]
    # the parts of the blocks, as the session gives them
    assert "temperature 21.5 C, humidity 48 %" in md
    assert "lot EX-LOT-7" in md and "conditioned for 14 days" in md
    assert "MOI pendulum (identifier PD-03, calibrated 2026-06-15, due 2027-06-15)" in md
    # a signature and date line for the one signatory, and the 7.8.2.1 l statement
    assert md.count("Signature: ____") == 1 and "A. Reviewer, technical manager" in md
    assert html.count('class="signature"') == 1
    assert "relate only to the bat tested" in md and "relate only to the bat tested" in html


def test_a_session_without_a_lab_block_marks_every_field_missing(bare):
    md = render(bare, "md")
    for f in CERTIFICATE_FIELDS:
        if f.key != "standard":  # the protocol file's reference and version stand in
            assert f"| {f.word} | MISSING |" in md, f.word
    assert "| Method (standard, version) | NCAA BBCOR" in md
    assert "MISSING: no one named to approve" in md
    [warning] = [w for w in bare.warnings if "ISO/IEC 17025" in w]
    assert "lacks 16 of" in warning and "ball_lot" in warning and "standard" not in warning
    # the JSON carries every field, None where not given (a reader finds it marked, not absent)
    assert set(bare.lab) >= {f.key for f in CERTIFICATE_FIELDS}
    assert bare.lab["environment"] is None and bare.protocol_version == "1.0"


def test_missing_parts_of_a_block_are_named(tmp_path):
    r = run_reduce(_session(tmp_path, "lab:\n  ball_lot: {lot: L1}\n  equipment:\n"
                                      "    - {name: cannon, identifier: C1}\n"),
                   "ncaa-bbcor", engine="rigid")
    [warning] = [w for w in r.warnings if "ISO/IEC 17025" in w]
    assert "ball_lot.temperature" in warning and "ball_lot.age" in warning
    assert "equipment.calibrated" in warning and "ball_lot.lot" not in warning
    assert "cannon (identifier C1, calibrated MISSING, due MISSING)" in render(r, "md")


def test_equipment_needs_a_name_and_identifier(tmp_path):
    with pytest.raises(InputError) as err:
        run_reduce(_session(tmp_path, "lab:\n  equipment:\n    - {name: cannon}\n"),
                   "ncaa-bbcor", engine="rigid")
    assert "session.yaml:17: lab.equipment[0].identifier: required" in str(err.value)


def test_a_serial_that_disagrees_with_the_bat_file_is_a_warning(tmp_path):
    bat = tmp_path / "bat.yaml"
    text = (Path(__file__).resolve().parents[2] / "bats" / "aluminium-34.yaml").read_text()
    assert "identification:" not in text
    bat.write_text(text + "identification:\n  serial: AL34-9999\n")
    session = _session(tmp_path, "lab:\n  bat_serial: AL34-0001\n")
    Path(session).write_text(Path(session).read_text().replace("bat: aluminium-34",
                                                               f"bat: {bat}"))
    r = run_reduce(session, "ncaa-bbcor", engine="rigid")
    assert any("'AL34-0001' is not the bat file's ('AL34-9999')" in w for w in r.warnings)


def test_a_model_moi_is_a_warning(tmp_path):
    bat = tmp_path / "bat.yaml"
    lines = (Path(__file__).resolve().parents[2] / "bats" / "aluminium-34.yaml").read_text()
    bat.write_text("\n".join(ln for ln in lines.splitlines() if not ln.strip().startswith("moi:")))
    session = _session(tmp_path, "")
    Path(session).write_text(Path(session).read_text().replace("bat: aluminium-34",
                                                               f"bat: {bat}"))
    r = run_reduce(session, "ncaa-bbcor", engine="rigid")
    assert r.moi_source == "model"
    assert any("MOI about the pivot is the model's" in w for w in r.warnings)


def test_speeds_are_shown_in_the_labs_own_unit(tmp_path):
    # issue 40, item 13: a lab that entered mph read its hits back in m/s
    text = (LAB / "synthetic-exact.csv").read_text().splitlines()
    out = []
    for line in text:
        if line.startswith("#"):
            out.append(line)
        elif line.startswith("hit,"):
            out.append(line.replace("[m/s]", "[mph]"))
        else:
            cells = line.split(",")
            cells[2], cells[3] = (f"{float(c) / 0.44704:.4f}" for c in cells[2:4])
            out.append(",".join(cells))
    (tmp_path / "mph.csv").write_text("\n".join(out) + "\n")
    session = tmp_path / "session.yaml"
    session.write_text((LAB / "synthetic-exact.yaml").read_text().replace(
        "hits: synthetic-exact.csv", "hits: mph.csv"))
    r = run_reduce(str(session), "ncaa-bbcor", engine="rigid")
    assert r.speed_unit == "mph" and r.hits[0].inbound_speed == pytest.approx(60.8, abs=0.01)
    md = render(r, "md").replace("\\[", "[").replace("\\]", "]")  # Markdown's escapes
    assert "v_i [mph]" in md and "v_r [mph]" in md and "| 136.00 |" in md
    assert "v_i [m/s]" not in md
