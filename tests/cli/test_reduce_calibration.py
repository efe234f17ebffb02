"""`batcert reduce --write-calibration FILE`: the calibrated bat is written atomically to a new
or regular file, never over an input of the run (the session, its hits CSV, its bat, ball or
protocol file) nor over a device, FIFO or directory, and the target is checked before any
work (exit 4, as for reports that cannot be written)."""

from __future__ import annotations

import csv
import os
import shutil
from pathlib import Path

import pytest

import batcert.commands.reduce as reduce_module
from batcert.specs.bat import load_bat

REPO = Path(__file__).resolve().parents[2]
LAB = REPO / "examples" / "lab"


@pytest.fixture
def session(tmp_path):
    """The exact synthetic session with its bat as a file of its own beside it."""
    shutil.copy(LAB / "synthetic-exact.csv", tmp_path / "hits.csv")
    shutil.copy(REPO / "bats" / "aluminium-34.yaml", tmp_path / "bat.yaml")
    text = (LAB / "synthetic-exact.yaml").read_text(encoding="utf-8")
    text = text.replace("bat: aluminium-34", "bat: bat.yaml")
    text = text.replace("hits: synthetic-exact.csv", "hits: hits.csv")
    (tmp_path / "session.yaml").write_text(text, encoding="utf-8")
    return tmp_path


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


def _no_work(monkeypatch):
    monkeypatch.setattr(reduce_module, "run_reduce",
                        lambda *a, **k: pytest.fail("the reduction ran before the check"))


@pytest.mark.parametrize("target", ["session.yaml", "hits.csv", "bat.yaml"])
def test_an_input_is_never_written_over(batcert_cli, session, monkeypatch, target):
    before = _snapshot(session)
    _no_work(monkeypatch)
    res = batcert_cli("reduce", session / "session.yaml", "-p", "ncaa-bbcor", "--no-reports",
                      "--write-calibration", session / target)
    assert res.exit_code == 4
    assert "is an input of this run" in res.stderr and "never writes over an input" in res.stderr
    assert _snapshot(session) == before


def test_a_link_to_an_input_is_an_input(batcert_cli, session, monkeypatch):
    (session / "link.csv").symlink_to(session / "hits.csv")
    before = (session / "hits.csv").read_bytes()
    _no_work(monkeypatch)
    res = batcert_cli("reduce", session / "session.yaml", "-p", "ncaa-bbcor", "--no-reports",
                      "--write-calibration", session / "link.csv")
    assert res.exit_code == 4 and "is an input of this run" in res.stderr
    assert (session / "hits.csv").read_bytes() == before
    assert (session / "link.csv").is_symlink()


def test_the_bare_csv_and_its_bat_are_inputs_too(batcert_cli, session, monkeypatch):
    _no_work(monkeypatch)
    for target in ("hits.csv", "bat.yaml"):
        res = batcert_cli("reduce", session / "hits.csv", "--bat", session / "bat.yaml",
                          "-p", "ncaa-bbcor", "--no-reports", "--write-calibration",
                          session / target)
        assert res.exit_code == 4 and "is an input of this run" in res.stderr, target


@pytest.mark.parametrize("kind", ["directory", "fifo", "device"])
def test_a_target_that_is_not_a_regular_file_is_refused(batcert_cli, session, monkeypatch,
                                                         kind):
    if kind == "directory":
        target = session / "folder"
        target.mkdir()
    elif kind == "fifo":
        target = session / "pipe"
        os.mkfifo(target)
    else:
        target = Path("/dev/null")
    _no_work(monkeypatch)
    res = batcert_cli("reduce", session / "session.yaml", "-p", "ncaa-bbcor", "--no-reports",
                      "--write-calibration", target)
    # click refuses a directory for a dir_okay=False path (usage, 2); the rest exit 4
    assert res.exit_code in ((2, 4) if kind == "directory" else (4,))
    assert "not a regular file" in res.stderr or "directory" in res.stderr


def test_the_calibrated_bat_is_written_to_a_new_file(batcert_cli, session):
    # The synthetic truth (0.495) is below anything the model's aluminium-34 gives since the
    # viscoelastic ball (docs/lab-reduction.md); rebound speeds x 1.3 put the certified BBCOR
    # at about 0.58, inside the model's range at x0.25-x4 (0.555-0.658), so a barrel fits.
    rows = list(csv.reader((session / "hits.csv").read_text(encoding="utf-8").splitlines()))
    column = rows[1].index("rebound_speed [m/s]")
    for row in rows[2:]:
        row[column] = f"{float(row[column]) * 1.3:.3f}"
    (session / "hits.csv").write_text("\n".join(",".join(r) for r in rows) + "\n",
                                      encoding="utf-8")
    before = _snapshot(session)
    target = session / "calibrated.yaml"
    res = batcert_cli("reduce", session / "session.yaml", "-p", "ncaa-bbcor", "--no-reports",
                      "--write-calibration", target)
    assert res.exit_code in (0, 1), res.stderr  # the verdict; the file is the point here
    assert "wrote the calibrated bat" in res.stderr + res.stdout
    assert _snapshot(session) == {**before, "calibrated.yaml": target.read_bytes()}
    text = target.read_text(encoding="utf-8")
    assert "hoop_frequency:" in text and "fitted by batcert reduce" in text
    assert load_bat(target).measured.hoop_frequency > 0
    # a later run may replace its own output (a regular file that is not an input)
    again = batcert_cli("reduce", session / "session.yaml", "-p", "ncaa-bbcor", "--no-reports",
                        "--write-calibration", target)
    assert again.exit_code in (0, 1) and target.read_text(encoding="utf-8").count(
        "hoop_frequency:") == 1
