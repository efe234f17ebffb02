"""A lab session's measured accelerated break-in (the session's ``break_in`` block): judged by the
protocol's rules (batcert.runner.barrel_tests.measured_history) and shown on the certificate; a
composite bat reduced without one is warned about. The hits are the synthetic exact session's
(examples/lab), on the shipped composite bat."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from batcert.commands.reduce import run_reduce
from batcert.errors import UsageProblem

REPO = Path(__file__).resolve().parents[2]


def session(tmp_path: Path, bat: str, readings: str = "") -> Path:
    shutil.copy(REPO / "examples" / "lab" / "synthetic-exact.csv", tmp_path)
    text = (REPO / "examples" / "lab" / "synthetic-exact.yaml").read_text(encoding="utf-8")
    path = tmp_path / "session.yaml"
    path.write_text(text.replace("bat: aluminium-34", f"bat: {bat}") + readings,
                    encoding="utf-8")
    return path


READINGS = """
break_in:
  compression: [1800 lbf, 1770 lbf, {last}]
  new_compression: {new}
  source: synthetic
"""


def test_a_completed_break_in_is_on_the_certificate(tmp_path):
    got = run_reduce(str(session(tmp_path, "composite-bbcor-34",
                                 READINGS.format(last="1705 lbf", new="1810 lbf"))),
                     "ncaa-bbcor", engine="rigid")
    b = got.break_in
    assert b is not None and b.measured and not b.skipped
    assert b.steps[-1].drop == pytest.approx(1 - 1705 / 1800, rel=1e-12)
    assert not any("break-in" in w for w in got.warnings)


def test_an_incomplete_or_missing_break_in_is_warned_about(tmp_path):
    short = run_reduce(str(session(tmp_path, "composite-bbcor-34",
                                   READINGS.format(last="1760 lbf", new="1810 lbf"))),
                       "ncaa-bbcor", engine="rigid")
    assert any("do not follow a completed break-in" in w for w in short.warnings)
    missing = run_reduce(str(session(tmp_path, "composite-bbcor-34")), "ncaa-bbcor",
                         engine="rigid")
    assert missing.break_in is None
    assert any("gives no break-in readings" in w for w in missing.warnings)
    alloy = run_reduce(str(session(tmp_path, "bbcor-alloy-34")), "ncaa-bbcor", engine="rigid")
    assert not any("break-in" in w for w in alloy.warnings)


def test_the_skip_rule_reads_the_new_bat_s_compression(tmp_path):
    got = run_reduce(str(session(tmp_path, "composite-bbcor-34",
                                 READINGS.format(last="1705 lbf", new="2200 lbf"))),
                     "ncaa-bbcor", engine="rigid")
    assert got.break_in.skipped  # 1800 is 18 % below 2200


def test_readings_need_a_protocol_with_a_break_in(tmp_path):
    with pytest.raises(UsageProblem, match="has no break_in"):
        run_reduce(str(session(tmp_path, "composite-bbcor-34",
                               READINGS.format(last="1705 lbf", new="1810 lbf"))),
                   "astm-bpf", engine="rigid")
