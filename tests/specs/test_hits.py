"""The hits CSV (batcert.specs.hits): every problem of a file reported at once with its line,
column and field; units from the header; gate times."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from batcert.errors import InputError
from batcert.specs.hits import load_hits

HEAD = "hit,ball,inbound_speed [mph],rebound_speed [m/s],impact_location [in from tip],valid,note"


def write(tmp_path, text):
    p = tmp_path / "hits.csv"
    p.write_text(text, encoding="utf-8")
    return p


def test_units_from_the_header(tmp_path):
    h = load_hits(write(tmp_path, f"# a comment\n{HEAD}\n1,B1,136,15.5,6,yes,first\n"))
    assert h.inbound_speed[0] == pytest.approx(136 * 0.44704, abs=1e-12)
    assert h.rebound_speed[0] == 15.5 and h.impact_location[0] == pytest.approx(6 * 0.0254)
    assert h.line == [3] and h.valid[0] and h.note == ["first"] and h.ball == ["B1"]
    assert np.isnan(h.bat_angular_speed_after[0])


def test_gate_times(tmp_path):
    text = ("hit,ball,inbound_gate_time [ms],rebound_gate_time [ms],impact_location [m from tip]"
            "\n1,B1,8.0,32.0,0.15\n")
    h = load_hits(write(tmp_path, text), gate_spacing=0.5)
    assert h.inbound_speed[0] == pytest.approx(62.5) and h.rebound_speed[0] == pytest.approx(15.625)
    with pytest.raises(InputError, match="gate times need the session's gate_spacing"):
        load_hits(write(tmp_path, text))


def test_every_problem_with_line_column_and_field(tmp_path):
    text = (f"{HEAD}\n"
            "1,B1,136,15.5,6,yes,\n"
            "2,B1,fast,15.5,6,maybe,\n"  # not a number; not yes/no
            "3,B1,136,15.5\n")  # too few fields
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, text))
    got = {(p.line, p.field, p.column) for p in err.value.problems}
    assert (3, "inbound_speed", 6) in got  # "fast" starts at character 6 of line 3
    assert (3, "valid", 18) in got  # "maybe" at character 18
    assert any(p.line == 4 and "fields" in p.message for p in err.value.problems)


def test_header_problems(tmp_path):
    text = ("hit,ball,inbound_sped [m/s],rebound_speed,impact_location [in from knob]\n"
            "1,B1,60,15,6\n")
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, text), location_from="tip")
    messages = " | ".join(p.message for p in err.value.problems)
    assert "did you mean 'inbound_speed'?" in messages
    assert "give the unit in brackets" in messages  # rebound_speed
    assert "the header says from the knob" in messages


def test_a_negative_rebound_and_an_empty_file(tmp_path):
    with pytest.raises(InputError, match="magnitude"):
        load_hits(write(tmp_path, f"{HEAD}\n1,B1,136,-15,6,yes,\n"))
    with pytest.raises(InputError, match="no hits"):
        load_hits(write(tmp_path, f"{HEAD}\n"))


def test_a_column_with_a_problem_is_reported_once(tmp_path):
    """A speed column without its unit is one problem, not also a missing speed pair."""
    text = "hit,ball,inbound_speed [m/s],rebound_speed,impact_location [in from tip]\n1,B1,60,15,6\n"
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, text))
    assert [(p.line, p.field) for p in err.value.problems] == [(1, "rebound_speed")]


def test_validate_checks_a_session_and_its_hits(tmp_path):
    from click.testing import CliRunner

    from batcert.cli import main
    lab = Path(__file__).resolve().parents[2] / "examples" / "lab"
    ok = CliRunner().invoke(main, ["validate", str(lab / "synthetic-scatter.yaml")])
    assert ok.exit_code == 0 and "(session)" in ok.output
    write(tmp_path, f"{HEAD}\n1,B1,136,x,6,yes,\n")
    session = (lab / "synthetic-scatter.yaml").read_text(encoding="utf-8").replace(
        "hits: synthetic-scatter.csv", "hits: hits.csv")
    (tmp_path / "s.yaml").write_text(session, encoding="utf-8")
    bad = CliRunner().invoke(main, ["validate", str(tmp_path / "s.yaml")])
    assert bad.exit_code == 3 and "hits.csv:2: rebound_speed: expected a number" in bad.output


def test_a_byte_order_mark_is_accepted(tmp_path):
    """Spreadsheets write a UTF-8 byte-order mark before the header; it is not part of it."""
    path = tmp_path / "hits.csv"
    path.write_bytes(b"\xef\xbb\xbf" + f"{HEAD}\n1,B1,136,15.5,6,yes,\n".encode())
    h = load_hits(path)
    assert h.line == [2] and h.inbound_speed[0] == pytest.approx(136 * 0.44704, abs=1e-12)


def test_a_bare_csv_with_a_byte_order_mark_keeps_its_header_end(tmp_path):
    from batcert.specs.session import session_for_hits
    path = tmp_path / "hits.csv"
    path.write_bytes(b"\xef\xbb\xbf" + HEAD.replace("from tip", "from knob").encode() + b"\n")
    assert session_for_hits(path, "aluminium-34", "collegiate-baseball", 0.15).location_from \
        == "knob"


def test_a_byte_that_is_not_utf8_is_pointed_at(tmp_path):
    path = tmp_path / "hits.csv"
    path.write_bytes(f"{HEAD}\n1,B1,136,15.5,6,yes,caf".encode() + b"\xe9\n")
    with pytest.raises(InputError) as err:
        load_hits(path)
    (problem,) = err.value.problems
    assert (problem.line, problem.column) == (2, 24) and "0xe9 is not UTF-8" in problem.message


@pytest.mark.parametrize("row, message", [
    ('1,B1,"136,15.5,6,yes,', "a quoted field is not closed"),
    ('1,B1,136,"15.5,6,yes,x', "a quoted field is not closed"),
    ('1,B1,"136"x,15.5,6,yes,', "text after a quoted field's closing"),
    ("1,B1,136,15.5,6,yes," + "x" * 140_000, "a field longer than 131,072 characters"),
    ('1,B1,136,15.5,6,yes,"' + "x" * 140_000 + '"', "a field longer than 131,072 characters"),
])
def test_a_malformed_csv_row_is_a_problem_at_its_line(tmp_path, row, message):
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, f"{HEAD}\n1,B1,136,15.5,6,yes,\n{row}\n"))
    (problem,) = err.value.problems
    assert problem.line == 3 and message in problem.message


def test_a_malformed_header_is_a_problem_at_its_line(tmp_path):
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, f'# lab export\n"hit,{HEAD[4:]}\n1,B1,136,15.5,6,yes,\n'))
    (problem,) = err.value.problems
    assert problem.line == 2 and "not closed" in problem.message


def test_quotes_inside_fields_keep_every_column_in_place(tmp_path):
    """A quote inside an unquoted field is text (``B"1``, ``a"b``), ``""`` is a quote inside a
    quoted field; the columns of the problems after them are still right."""
    row = '1,B"1,136,15.5,6,maybe,"a ""quoted"", note"'
    row2 = '2,"B,2",136,15.5,6,maybe,a"b'
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, f"{HEAD}\n{row}\n{row2}\n"))
    got = [(p.line, p.field, p.column) for p in err.value.problems]
    assert got == [(2, "valid", row.index("maybe") + 1), (3, "valid", row2.index("maybe") + 1)]
    head = 'hit,ball,"inbound_speed [m/s]",rebound_speed [m/s],impact_location [in from tip],va"lid'
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, f"{head}\n1,B1,136,15.5,6,yes\n"))
    assert [(p.field, p.column) for p in err.value.problems] == [('va"lid', head.index('va"') + 1)]


@given(st.lists(st.text(alphabet='ab,"x ', max_size=6), min_size=1, max_size=5))
def test_the_columns_agree_with_the_csv_module(fields):
    """For any row the csv module writes, each column found is where its field starts."""
    import csv
    import io

    from batcert.specs.hits import _cell_columns
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="").writerow(fields)
    raw = buffer.getvalue()
    starts = _cell_columns(raw)
    assert len(starts) == len(fields)
    for start, end, field in zip(starts, [*starts[1:], len(raw) + 2], fields, strict=True):
        cell = raw[start - 1:end - 2]
        assert (next(csv.reader([cell], strict=True)) or [""]) == [field]


def test_the_cli_reports_a_malformed_row_without_a_traceback(tmp_path, batcert_cli):
    path = write(tmp_path, f'{HEAD}\n1,B1,136,15.5,6,yes,\n2,B1,1.0,"2.0\n')
    res = batcert_cli("reduce", path, "--bat", "aluminium-34", "-p", "ncaa-bbcor",
                      "--engine", "rigid", "--no-reports")
    assert res.exit_code == 3
    lines = res.stderr.splitlines()
    assert lines[0] == "invalid input"
    assert lines[1].startswith(f"{path}:3: a quoted field is not closed on this line")


def test_a_dimensionless_unit_in_the_header_is_a_problem(tmp_path):
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, HEAD.replace("[mph]", "[dimensionless]") + "\n1,B1,1,1,6,yes,\n"))
    (problem,) = err.value.problems
    assert (problem.line, problem.field, problem.column) == (1, "inbound_speed", 10)
    assert "'1 dimensionless' is not a speed" in problem.message


GATES = "hit,ball,inbound_gate_time [s],rebound_gate_time [s],impact_location [in from tip]"


@pytest.mark.parametrize("row, field, message", [
    # 0.5 m in 1e-300 s: 5e299 m/s, which made the reduction's values and JSON non-finite
    ("1,B1,1e-300,0.04,6", "inbound_gate_time", "gives inbound speed 5e+299 m/s over the 0.5 m "
                                                "gate spacing, outside 1-300 m/s"),
    ("1,B1,0.0082,1e-300,6", "rebound_gate_time", "gives rebound speed 5e+299 m/s"),
    ("1,B1,5e-324,0.04,6", "inbound_gate_time", "gives inbound speed inf m/s"),  # 0.5 / 5e-324
    ("1,B1,0.0082,1e-310,6", "rebound_gate_time", "outside 0-300 m/s"),
    ("1,B1,1000,0.04,6", "inbound_gate_time", "gives inbound speed 0.0005 m/s"),
])
def test_a_gate_time_giving_an_impossible_speed_is_a_problem(tmp_path, row, field, message):
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, f"{GATES}\n{row}\n"), gate_spacing=0.5)
    (problem,) = err.value.problems
    assert (problem.line, problem.field) == (2, field) and message in problem.message
    assert problem.column == (6 if field == "inbound_gate_time" else row.index(",", 5) + 2)


@pytest.mark.parametrize("speed, message", [
    ("1e-300", "1e-300 m/s is outside 1-300 m/s, the inbound speeds of a ball-cannon test"),
    ("0.5", "0.5 m/s is outside 1-300 m/s"),
    ("1e308", "beyond any plausible speed"),
])
def test_an_inbound_speed_outside_a_ball_cannons_range_is_a_problem(tmp_path, speed, message):
    head = HEAD.replace("[mph]", "[m/s]")
    with pytest.raises(InputError) as err:
        load_hits(write(tmp_path, f"{head}\n1,B1,{speed},13,6,yes,\n"))
    (problem,) = err.value.problems
    assert (problem.line, problem.field, problem.column) == (2, "inbound_speed", 6)
    assert message in problem.message
