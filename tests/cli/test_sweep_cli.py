"""`batcert sweep` and `batcert design`: exit codes, clean --json, the written report set and
figures, resuming from the journal.

All runs use the rigid engine on the solid ash bat (closed forms, a few milliseconds a
variant); tests/sweeps/ checks the numbers.
"""

from __future__ import annotations

import json
import os
import re
import shlex
from pathlib import Path

import pytest
from jsonout import result as result_of

from batcert.commands.sweep import journal_path, plan_sweep, run_sweep
from batcert.sweeps import execute as execute_module
from batcert.sweeps.execute import sweep_key
from batcert.sweeps.sweep import evaluate_chunk

REPO = Path(__file__).resolve().parents[2]
SWEEP = ("sweep", "ash-34", "-p", "ncaa-bbcor", "--vary", "pitch_speed=40m/s:60m/s:6",
         "--engine", "rigid")
STEM = "sweep--ncaa-bbcor-pitch-speed--ash-34"


@pytest.fixture
def bbcor_052(fixtures_dir) -> Path:
    """ncaa-bbcor with a 0.52 limit: the rigid ash bat meets it at about 58.7 m/s
    (tests/sweeps/test_design.py derives it)."""
    return fixtures_dir / "good" / "bbcor-052.yaml"


def check_sweep_json(data: dict, n: int) -> None:
    """The document leads with its schema and kind, then parameter, values and metrics, every
    metric an array of ``n``."""
    assert list(data)[:5] == ["schema", "kind", "parameter", "values", "metrics"]
    assert len(data["values"]) == n
    assert data["metrics"] and all(len(v) == n for v in data["metrics"].values())


@pytest.mark.parametrize("command, needles", [
    ("sweep", ("0 every variant was evaluated", "2 usage error", "3 invalid input",
               "4 the reports (or the sweep's journal) cannot be written",
               "5 the dask scheduler cannot be used", "130 interrupted (Ctrl-C)",
               "keeps the finished variants for --resume", "143 terminated (SIGTERM)")),
    ("design", ("0 the limit is met somewhere in the range",
                "1 no value in the range meets the limit", "2 usage error", "3 invalid input",
                "5 the dask scheduler (--scheduler) cannot be used", "143 terminated")),
])
def test_help_lists_exit_codes(batcert_cli, command, needles):
    result = batcert_cli(command, "--help")
    assert result.exit_code == 0
    text = " ".join(result.stdout.split())
    for needle in needles:
        assert needle in text


def test_sweep_writes_the_report_set(batcert_cli, tmp_path):
    out = tmp_path / "r"
    result = batcert_cli(*SWEEP, "--out", out)
    assert result.exit_code == 0, result.stderr
    assert "Sweep: Ash 34 in (Smith 2001), ncaa-bbcor, pitch_speed" in result.stdout
    # the set, and no journal left once the reports are written
    assert sorted(p.name for p in out.glob("[!.]*")) == [f"{STEM}.html", f"{STEM}.json",
                                                     f"{STEM}.md"]
    data = json.loads((out / f"{STEM}.json").read_text())
    check_sweep_json(data, 6)
    assert data["parameter"] == "pitch_speed"
    assert data["values"] == [40.0, 44.0, 48.0, 52.0, 56.0, 60.0]
    # a rigid ash bat's BBCOR is under 0.5 (about 0.48-0.49) and falls as the ball's speed
    # rises, as the ball's COR does (ball tests: Shenoy, Smith & Axtell 2001; docs/physics.md)
    assert data["metrics"]["verdict"] == ["pass"] * 6
    values = data["metrics"]["value"]
    assert all(b < a for a, b in zip(values, values[1:], strict=False))
    assert "pitch_speed" in (out / f"{STEM}.md").read_text()


def test_json_only_on_stdout(batcert_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = batcert_cli(*SWEEP, "--json")
    assert result.exit_code == 0, result.stderr
    data = result_of(result.stdout, "sweep")  # nothing but the JSON
    check_sweep_json(data, 6)
    assert list(tmp_path.iterdir()) == []  # --json writes no reports without --out


def test_grid_json(batcert_cli):
    result = batcert_cli("sweep", "ash-34", "-p", "ncaa-bbcor", "--vary",
                         "pitch_speed=50m/s:60m/s:3", "--vary", "bat_angular_speed=0rad/s:20rad/s:2",
                         "--engine", "rigid", "--json")
    assert result.exit_code == 0, result.stderr
    data = result_of(result.stdout, "sweep")
    check_sweep_json(data, 6)
    assert data["parameter"] == ["pitch_speed", "bat_angular_speed"]
    assert data["values"] == [[p, w] for p in (50.0, 55.0, 60.0) for w in (0.0, 20.0)]


@pytest.mark.parametrize("vary, message", [
    ("wal=60%:140%:5", "did you mean 'wall'?"),
    ("wall=2mm:3mm:3", "wall needs a hollow bat"),  # ash-34 is solid
    ("pitch_speed=40m/s:60:3", "a unit is required"),  # the stop lacks the unit
    ("pitch_speed=40m/s:60m/s:1", "N >= 2"),
    # issue 24: more digits than Python reads into an int gave a ValueError's traceback
    ("pitch_speed=40m/s:60m/s:" + "9" * 5000, "at most 100000 values per parameter"),
])
def test_usage_errors_exit_2(batcert_cli, tmp_path, vary, message):
    result = batcert_cli("sweep", "ash-34", "-p", "ncaa-bbcor", "--vary", vary, "--engine",
                         "rigid", "--out", tmp_path / "r")
    assert result.exit_code == 2
    assert message in " ".join(result.stderr.split())
    assert not (tmp_path / "r").exists()  # nothing written before the work


@pytest.mark.parametrize("command", [
    [*SWEEP, "--no-reports"],
    ["design", "ash-34", "-p", "ncaa-bbcor", "--solve", "pitch_speed", "--engine", "rigid",
     "--no-reports"],
])
def test_a_scheduler_that_cannot_be_used_is_one_line_exit_5(batcert_cli, command):
    # issue 24: a traceback from inside distributed (tls:// without TLS settings)
    distributed = pytest.importorskip("distributed")
    if distributed.security.Security().get_connection_args("client")["ssl_context"] is not None:
        pytest.skip("dask's configuration here sets up TLS")
    result = batcert_cli(*command, "--scheduler", "tls://127.0.0.1:9")
    assert result.exit_code == 5
    assert result.stderr.splitlines() == [
        "error: cannot reach the dask scheduler at tls://127.0.0.1:9: tls:// needs TLS "
        "settings in dask's configuration (distributed.comm.tls)"]


def test_a_malformed_scheduler_address_is_a_usage_error(batcert_cli):
    result = batcert_cli(*SWEEP, "--no-reports", "--scheduler", "tcp://a b")
    assert result.exit_code == 2
    assert "--scheduler 'tcp://a b' is not a scheduler address" in result.stderr


def test_a_grid_of_too_many_variants_is_refused_before_any_work(batcert_cli, monkeypatch):
    # issue 24: each parameter was capped at 100000 values but not their product, so a grid of
    # 1e5 x 1e5 made 1e10 points (and ran out of memory) before anything was said
    from batcert.sweeps import sweep
    made = []
    monkeypatch.setattr(sweep, "variant_case", lambda *a: made.append(a))
    result = batcert_cli("sweep", "ash-34", "-p", "ncaa-bbcor", "--vary",
                         "pitch_speed=40m/s:60m/s:100000", "--vary",
                         "bat_angular_speed=0rad/s:20rad/s:100000", "--engine", "rigid",
                         "--no-reports")
    assert result.exit_code == 2
    assert ("--vary: 100000 (pitch_speed) x 100000 (bat_angular_speed) = 10000000000 variants; "
            "a sweep has at most 100000") in " ".join(result.stderr.split())
    assert made == []  # not one variant made


def test_resume_needs_the_report_directory(batcert_cli):
    for extra in (("--no-reports",), ("--json",)):
        result = batcert_cli(*SWEEP, "--resume", *extra)
        assert result.exit_code == 2
        assert "--resume needs the report directory" in " ".join(result.stderr.split())


def test_resume_continues_an_interrupted_sweep(batcert_cli, tmp_path, monkeypatch):
    out = tmp_path / "r"
    assert batcert_cli(*SWEEP, "--out", out, "--format", "json").exit_code == 0
    whole = json.loads((out / f"{STEM}.json").read_text())
    # the journal an interrupted `batcert sweep` leaves: header, first chunk, half a line
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:6"], "rigid")
    journal = journal_path(out, STEM, sweep_key(plan))
    run_sweep(plan, journal_at=journal)
    lines = journal.read_text().splitlines()
    assert len(lines) == 3  # header and two chunks (4 + 2 variants)
    journal.write_text(lines[0] + "\n" + lines[1] + "\n" + lines[2][:40])
    calls: list[int] = []

    def counting(chunk):
        calls.append(chunk.index)
        return evaluate_chunk(chunk)

    monkeypatch.setattr(execute_module, "evaluate_chunk", counting)
    result = batcert_cli(*SWEEP, "--out", out, "--format", "json", "--resume")
    assert result.exit_code == 0, result.stderr
    assert calls == [1]  # only the chunk the journal lacked
    assert not journal.exists()
    resumed = json.loads((out / f"{STEM}.json").read_text())
    assert resumed["metrics"] == whole["metrics"]


def test_design_exit_0_when_the_limit_is_met(batcert_cli, bbcor_052):
    result = batcert_cli("design", "ash-34", "-p", bbcor_052, "--solve", "pitch_speed",
                         "--range", "40m/s:75m/s", "--engine", "rigid", "--json")
    assert result.exit_code == 0, result.stderr
    data = result_of(result.stdout, "design")
    assert data["kind"] == "design"
    check_sweep_json(data, 9)  # the margin curve, --points 9
    (root,) = data["design"]["roots"]
    assert root["value"] == pytest.approx(58.657, abs=0.01)  # the default tolerance, 0.01 m/s
    assert root["passes_above"] is True


def test_design_exit_1_without_a_root(batcert_cli, bbcor_052):
    result = batcert_cli("design", "ash-34", "-p", bbcor_052, "--solve", "pitch_speed",
                         "--range", "40m/s:45m/s", "--points", "3", "--engine", "rigid",
                         "--no-reports")
    assert result.exit_code == 1, result.stderr
    text = " ".join(result.stdout.split())
    assert "No pitch_speed from 40 m/s" in text and "fails over the whole range" in text


@pytest.mark.parametrize("args, message", [
    (("-p", "proposed", "--solve", "relative_speed", "--range", "50m/s:70m/s"), "sets no limit"),
    pytest.param(("-p", "proposed", "--solve", "relative_speed"), "sets no limit",
                 id="proposed-default-range"),
    (("-p", "ncaa-bbcor", "--solve", "pich_speed"), "did you mean 'pitch_speed'?"),
    (("-p", "ncaa-bbcor", "--solve", "pitch_speed", "--tolerance", "0 m/s"), "above zero"),
    # issue 24: a third part bypassed --points (at most 1001) with up to 100000 variants
    (("-p", "ncaa-bbcor", "--solve", "pitch_speed", "--range", "40m/s:60m/s:100000"),
     "--range '40m/s:60m/s:100000': give A:B"),
])
def test_design_usage_errors_exit_2(batcert_cli, args, message):
    result = batcert_cli("design", "ash-34", *args, "--engine", "rigid", "--no-reports")
    assert result.exit_code == 2
    assert message in " ".join(result.stderr.split())


def test_figures(batcert_cli, tmp_path):
    pytest.importorskip("matplotlib")
    figures = tmp_path / "f"
    result = batcert_cli("sweep", "ash-34", "-p", "ncaa-bbcor", "--vary",
                         "pitch_speed=50m/s:60m/s:2", "--engine", "rigid", "--no-reports",
                         "--figures", figures)
    assert result.exit_code == 0, result.stderr
    files = sorted(figures.iterdir())
    stems = {p.stem for p in files}
    assert stems and all(s.startswith(STEM + "--") for s in stems)
    assert sorted(p.name for p in files) == sorted(f"{s}.{x}" for s in stems
                                                   for x in ("pdf", "png", "svg"))
    magic = {".pdf": b"%PDF", ".png": b"\x89PNG"}
    for p in files:
        head = p.read_bytes()[:512]
        assert head.startswith(magic[p.suffix]) if p.suffix in magic else b"<svg" in head, p
    assert f"{STEM}--metric" in stems  # the protocol's metric against the parameter


@pytest.mark.parametrize("example", [
    "ash-34 -p protocols/studies/smith2001-bpf-sweet-spot.yaml "
    "--vary bat_angular_speed=5rad/s:60rad/s:12",
    "aluminium-34 -p proposed --vary wall=80%:120%:5 --vary relative_speed=50:70m/s:3",
])
def test_help_examples_run(batcert_cli, monkeypatch, example):
    """The examples `batcert sweep --help` shows run as written (on the rigid engine, no
    reports)."""
    shown = " ".join(batcert_cli("sweep", "--help").stdout.replace("\\\n", " ").split())
    assert f"batcert sweep {example}" in shown
    monkeypatch.chdir(REPO)
    result = batcert_cli("sweep", *shlex.split(example), "--engine", "rigid", "--no-reports")
    assert result.exit_code == 0, result.stderr


def _damage(journal: Path, form: str) -> None:
    """Put a damaged journal of the form ``form`` at ``journal``."""
    if form == "directory":
        journal.mkdir()
    elif form == "fifo":
        os.mkfifo(journal)
    else:
        journal.write_bytes({
            "binary garbage": b"\x89PNG\r\n\x1a\n\x00\xff\xfe garbage",
            "control bytes": b"\x00\x01\x02\n",  # UTF-8, but not JSON
            "first line cut": b'{"key": "0123',
            "blank lines": b"\n\n",
            "a string": b'"a journal"\n',
            "null": b"null\n",
            "a number": b"12\n",
            "empty": b"",
        }[form])


@pytest.mark.parametrize("form, code, message", [
    ("binary garbage", 2, "it is not a text file; the journal is not used"),
    ("control bytes", 2, "line 1: the line is damaged"),
    ("first line cut", 2, "line 1: the line is damaged"),
    ("blank lines", 2, "line 1: the line is damaged"),
    ("a string", 2, "line 1: it holds a sweep with other inputs"),
    ("null", 2, "line 1: it holds a sweep with other inputs"),
    ("a number", 2, "line 1: it holds a sweep with other inputs"),
    ("empty", 0, ""),  # nothing recorded yet (killed before the header): runs it all
    # issue 24: a FIFO hung the sweep for ever, with or without --resume; a directory said
    # "cannot write reports"
    ("directory", 4, "cannot write the sweep's journal to"),
    ("fifo", 4, "cannot write the sweep's journal to"),
])
@pytest.mark.parametrize("resume", [True, False])
def test_a_damaged_journal_is_refused_cleanly(batcert_cli, tmp_path, form, code, message,
                                              resume):
    if form == "fifo" and not hasattr(os, "mkfifo"):
        pytest.skip("no FIFOs here")
    out = tmp_path / "r"
    out.mkdir()
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:6"], "rigid")
    journal = journal_path(out, STEM, sweep_key(plan))
    _damage(journal, form)
    result = batcert_cli(*SWEEP, "--out", out, *(["--resume"] if resume else []))
    if not resume and code == 2:  # without --resume the journal is not read: written afresh
        code, message = 0, ""
    assert result.exit_code == code, result.stderr
    lines = result.stderr.splitlines()
    if code:
        assert len(lines) == 1 if code == 4 else lines[0].startswith("Usage:")  # no traceback
        assert message in lines[-1]
        assert str(journal) in lines[-1]
    else:
        assert (out / f"{STEM}.json").is_file() and not journal.exists()


def test_resume_without_a_journal_of_this_sweep_says_so(batcert_cli, tmp_path):
    # another sweep's journal in the folder (same bat, protocol and parameter, other values)
    # is neither read nor touched; this sweep says it starts from the beginning
    out = tmp_path / "r"
    other = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:61m/s:6"], "rigid")
    theirs = journal_path(out, STEM, sweep_key(other))
    run_sweep(other, journal_at=theirs)
    before = theirs.read_text()
    result = batcert_cli(*SWEEP, "--out", out, "--format", "json", "--resume")
    assert result.exit_code == 0, result.stderr
    assert "no journal of this sweep" in " ".join(result.stderr.split())
    assert theirs.read_text() == before


def test_a_geometric_sweep_says_why_its_nominal_row_is_not_runs(batcert_cli):
    # Issue 24: the 100 % row of a wall sweep (the geometry's 805 g) differs from `run` on the
    # same bat (reconciled to the measured 863 g) and the terminal said nothing
    res = batcert_cli("sweep", "aluminium-34", "-p", "ncaa-bbcor", "--vary", "wall=90%:110%:3",
                      "--engine", "rigid", "--no-reports")
    assert res.exit_code == 0, res.stderr
    text = " ".join(res.stdout.split())
    assert "The variants are built from the bat's geometry (mass 0.805 kg" in text
    assert "the bat as measured (0.863 kg (30.44 oz)) gives BBCOR" in text
    # a parameter of the test, not of the geometry, keeps the measured bat: nothing to say
    res = batcert_cli(*SWEEP, "--no-reports")
    assert "built from the bat's geometry" not in res.stdout


def test_the_help_and_the_docs_list_every_parameter_of_the_registry(batcert_cli):
    """A new sweep parameter is its registry entry only: the help lists it, and the docs table
    is generated from the registry (scripts/gen_doc_tables.py; tests/sweeps/test_doc_tables.py
    fails until it is regenerated)."""
    from batcert.sweeps.variants import PARAMETERS
    for command in ("sweep", "design"):
        text = " ".join(batcert_cli(command, "--help").stdout.split())
        for name in PARAMETERS:
            assert name in text.split("Parameters:")[1], (command, name)
    rows = re.findall(r"^\| `(\w+)` \| ", (REPO / "docs" / "sweeps.md").read_text(
        encoding="utf-8"), re.M)
    assert rows == list(PARAMETERS)


@pytest.mark.parametrize("command, varied", [
    (("sweep", "aluminium-34", "-p", "ncaa-bbcor", "--vary", "wall=60%:140%:5"), "wall"),
    (("design", "ash-34", "-p", "ncaa-bbcor", "--solve", "density", "--points", "3"), "density"),
])
def test_rigid_engine_varying_the_construction_warns_once(batcert_cli, command, varied):
    """Issue 40, item 4: the rigid engine does not see a wall, a material or a barrel; a sweep
    or design of one says so once, in one line, as `batcert league` does (the same text,
    the engine's), on stderr and in the JSON."""
    from batcert.engines.rigid import RigidEngine
    text = RigidEngine.construction_warning
    assert text
    result = batcert_cli(*command, "--engine", "rigid", "--json")
    assert result.exit_code in (0, 1), result.stderr
    data = result_of(result.stdout, command[0])
    assert [w for w in data["warnings"] if text in w] == [
        f"{text} (varied: {varied}, which shows "
        "only in the mass properties, if at all)"]
    lines = [ln for ln in result.stderr.splitlines() if text[:40] in ln]
    assert len(lines) == 1 and lines[0].startswith("  warning: ")


def test_rigid_engine_varying_a_speed_does_not_warn_of_the_construction(batcert_cli):
    from batcert.engines.rigid import RigidEngine
    result = batcert_cli(*SWEEP, "--json")
    assert result.exit_code == 0, result.stderr
    assert RigidEngine.construction_warning[:40] not in result.stderr
