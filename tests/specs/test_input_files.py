"""Reading input files (batcert.specs.yamlio.read_input): only regular files are read, never more
than a file kind's cap, and nothing blocks (a FIFO is refused before it is opened)."""

from __future__ import annotations

import os
import signal
from contextlib import contextmanager
from pathlib import Path

import pytest
from jsonout import result as result_of

from batcert.errors import InputError
from batcert.specs import hits, yamlio
from batcert.specs.bat import load_bat
from batcert.specs.hits import load_hits
from batcert.specs.session import session_for_hits

LAB = Path(__file__).resolve().parents[2] / "examples" / "lab"
HEAD = "hit,ball,inbound_speed [m/s],rebound_speed [m/s],impact_location [in from tip],valid,note"


@contextmanager
def within(seconds: int):
    """Fail instead of hanging (a blocked open of a FIFO, a read of /dev/zero)."""
    def hung(signum, frame):
        raise AssertionError(f"still reading after {seconds} s")
    old = signal.signal(signal.SIGALRM, hung)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def only_problem(exc: pytest.ExceptionInfo) -> yamlio.Problem:
    (problem,) = exc.value.problems
    return problem


@pytest.fixture
def fifo(tmp_path):
    def make(name: str) -> Path:
        path = tmp_path / name
        os.mkfifo(path)
        return path
    return make


def test_a_fifo_yaml_is_refused_without_blocking(fifo):
    path = fifo("bat.yaml")
    with within(5), pytest.raises(InputError) as exc:
        load_bat(path)
    assert only_problem(exc).message.startswith("is not a regular file")


def test_a_fifo_hits_csv_is_refused_without_blocking(fifo):
    path = fifo("hits.csv")
    with within(5):
        for read in (lambda: load_hits(path),
                     lambda: session_for_hits(path, "aluminium-34", "collegiate-baseball", 0.15)):
            with pytest.raises(InputError) as exc:
                read()
            problem = only_problem(exc)
            assert problem.file == str(path) and "not a regular file" in problem.message


def test_a_device_is_refused_before_it_is_read():
    """/dev/zero never ends: reading it whole would fill the memory."""
    with within(5):
        for read in (lambda: load_hits("/dev/zero"), lambda: yamlio.load_yaml("/dev/zero")):
            with pytest.raises(InputError, match="not a regular file"):
                read()


def test_a_hits_csv_over_its_cap_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "hits.csv"
    path.write_text(f"{HEAD}\n" + "1,B1,60.8,13,6,yes,\n" * 100, encoding="utf-8")
    monkeypatch.setattr(hits, "MAX_BYTES", 1000)
    with pytest.raises(InputError) as exc:
        load_hits(path)
    assert "larger than 0.001 MB" in only_problem(exc).message


def test_the_hits_cap_is_stated():
    assert hits.MAX_BYTES == 16_000_000 and yamlio.MAX_BYTES == 2_000_000


def test_a_yaml_file_over_its_cap_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "bat.yaml"
    path.write_text("name: x\n" + "# padding\n" * 200, encoding="utf-8")
    monkeypatch.setattr(yamlio, "MAX_BYTES", 1000)
    with pytest.raises(InputError) as exc:
        load_bat(path)
    assert "larger than 0.001 MB" in only_problem(exc).message


def test_the_cli_refuses_a_fifo_named_anywhere(batcert_cli, tmp_path, fifo):
    """As the session, as its hits, as a bare CSV, as the session's bat and as a bat on the
    command line: exit 3, the FIFO named, no traceback."""
    pipe_yaml, pipe_csv = fifo("pipe.yaml"), fifo("pipe.csv")
    text = (LAB / "synthetic-exact.yaml").read_text(encoding="utf-8")
    (tmp_path / "hits.csv").write_bytes((LAB / "synthetic-exact.csv").read_bytes())
    sessions = {}
    for name, old, new in (("s-hits.yaml", "hits: synthetic-exact.csv", "hits: pipe.csv"),
                           ("s-bat.yaml", "bat: aluminium-34", "bat: pipe.yaml")):
        sessions[name] = tmp_path / name
        sessions[name].write_text(text.replace(old, new).replace(
            "hits: synthetic-exact.csv", "hits: hits.csv"), encoding="utf-8")
    runs = {pipe_yaml: ["reduce", pipe_yaml, "-p", "ncaa-bbcor"],
            pipe_csv: ["reduce", pipe_csv, "--bat", "aluminium-34", "-p", "ncaa-bbcor"]}
    with within(30):
        for named, argv in [*runs.items(),
                            (pipe_csv, ["reduce", sessions["s-hits.yaml"], "-p", "ncaa-bbcor"]),
                            (pipe_yaml, ["reduce", sessions["s-bat.yaml"], "-p", "ncaa-bbcor"]),
                            (pipe_yaml, ["run", pipe_yaml, "-p", "ncaa-bbcor"]),
                            (pipe_yaml, ["validate", pipe_yaml])]:
            res = batcert_cli(*argv, *(["--engine", "rigid", "--no-reports"]
                                       if argv[0] != "validate" else []))
            assert res.exit_code == 3, (argv, res.output)
            lines = res.stderr.splitlines()
            assert lines[0] == "invalid input"
            assert lines[1] == f"{named}: is not a regular file (a FIFO, a device or a socket); " \
                f"give {'a hits CSV' if named.suffix == '.csv' else 'a YAML file'}", argv


def test_a_byte_order_mark_is_accepted_everywhere(batcert_cli, tmp_path):
    """A session YAML and its hits CSV as a spreadsheet saves them (UTF-8 with a BOM), and a
    bare CSV: reduced as without it."""
    bom = b"\xef\xbb\xbf"
    (tmp_path / "hits.csv").write_bytes(bom + (LAB / "synthetic-exact.csv").read_bytes())
    (tmp_path / "session.yaml").write_bytes(bom + (LAB / "synthetic-exact.yaml").read_bytes()
                                            .replace(b"hits: synthetic-exact.csv", b"hits: hits.csv"))
    for argv in (["reduce", tmp_path / "session.yaml"],
                 ["reduce", tmp_path / "hits.csv", "--bat", "aluminium-34"]):
        res = batcert_cli(*argv, "-p", "ncaa-bbcor", "--engine", "rigid", "--json")
        assert res.exit_code in (0, 1), res.stderr
        # the synthetic truth, to the speeds' rounding (docs/lab-reduction.md)
        assert result_of(res.stdout, "reduce")["value"] == pytest.approx(0.495, abs=2e-5)
