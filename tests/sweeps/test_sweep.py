"""batcert.sweeps.sweep and batcert.sweeps.execute: a sweep's variants against `batcert run`,
the grid's order, failed variants, worker processes and resuming from the journal.

Comparisons are exact (``==``) wherever the same code runs on the same floats: the rigid
engine's closed forms, a sweep against itself run elsewhere (chunks are fixed, so worker
processes see the same engine batches) and a journal (JSON round-trips every double). The one
exception is a flexible-engine variant against `batcert run` of that variant alone: the engine
stacks a chunk's variants into one integration, and the stacked arithmetic differs from a solo
run's in the last bits, so that comparison allows 1e-12: measured 1.5e-13 relative, on a
stationary-bat exit speed (``v_b = v_p + J / m`` cancels about 5x) of a hollow bat, whose barrel
is read row by row when stacked and with one matrix product per bat when alone, and whose
residual compliance is the difference of two sums that agree to a few digits.
"""

from __future__ import annotations

import json
import re
from dataclasses import replace
from pathlib import Path

import pytest

from batcert.commands.sweep import plan_sweep, run_sweep
from batcert.engines import get_engine
from batcert.errors import OutputError, UsageProblem
from batcert.model.build import build_bat
from batcert.model.mass import mass_properties
from batcert.physics.rigid import rigid_sweet_spot
from batcert.results.sweep import CONDITION_FIELDS
from batcert.runner.runner import run_protocol
from batcert.sweeps import execute as execute_module
from batcert.sweeps.sweep import CHUNK_SIZE, collect, evaluate_chunk
from batcert.sweeps.variants import geometry_only

REPO = Path(__file__).resolve().parents[2]
SMITH = str(REPO / "protocols" / "studies" / "smith2001-bpf-sweet-spot.yaml")


def run_of(plan, built=None):
    """`batcert run` (run_protocol) of the plan's nominal bat, or of ``built``, under its
    protocol."""
    return run_protocol(built or plan.built, plan.base.protocol, plan.ball,
                        get_engine(plan.engine), plan.created)


def assert_point_is_run(result, k: int, run, rel: float = 0.0) -> None:
    """Variant ``k`` of a sweep has every number of ``run``: exactly, or to ``rel``."""
    def same(a, b) -> bool:
        return a == b if rel == 0 or a is None or b is None else a == pytest.approx(b, rel=rel)

    assert result.errors[k] is None and result.verdicts[k] == run.verdict
    mp, barrel = run.mass_properties, run.barrel
    expected = {"value": run.value, "margin": run.margin, "mass": mp.mass, "cg": mp.cg,
                "moi_pivot": mp.moi_pivot, "cop": mp.cop,
                "value_low": barrel.value_low if barrel else None,
                "value_high": barrel.value_high if barrel else None}
    for f, v in expected.items():
        assert same(result.series[f][k], v), f
    assert [c.name for c in result.conditions] == [c.name for c in run.conditions]
    for c, rc in zip(result.conditions, run.conditions, strict=True):
        for f in CONDITION_FIELDS:
            assert same(c.series[f][k], getattr(rc, f)), f"{c.name}.{f}"


# ---- against `batcert run` ------------------------------------------------------------------

@pytest.mark.parametrize("bat, protocol, vary", [
    ("ash-34", "ncaa-bbcor", "pitch_speed=100mph:136mph:2"),  # nominal 136 mph, the last point
    ("aluminium-34", "ncaa-bbcor", "pitch_speed=136mph:150mph:2"),  # nominal the first point
    ("ash-34", "ncaa-besr", "pitch_speed=60mph:70mph:2"),  # a linear bat speed stays
    ("ash-34", "stationary-ball", "bat_angular_speed=40rad/s:53rad/s:2"),
    ("ash-34", "proposed", "relative_speed=60m/s:70m/s:2"),  # matched conditions
    ("ash-34", "proposed", "pitch_speed=20m/s:31m/s:2"),
])
def test_rigid_point_at_the_nominal_value_is_batcert_run(bat, protocol, vary):
    plan = plan_sweep(bat, protocol, [vary], engine="rigid")
    axis = plan.axes[0]
    k = axis.values.index(axis.nominal)  # the quantities give the nominal exactly
    result = run_sweep(plan)
    assert_point_is_run(result, k, run_of(plan))
    assert result.nominal is None  # a protocol parameter keeps the bat as measured


def test_rigid_point_at_the_nominal_value_of_a_study_protocol():
    plan = plan_sweep("ash-34", SMITH, ["pitch_speed=31m/s:40m/s:2"], engine="rigid")
    assert plan.axes[0].nominal == plan.axes[0].values[0] == 31.0
    result = run_sweep(plan)
    stationary_ball = next(c for c in result.conditions if c.name == "stationary-ball")
    assert stationary_ball.series["pitch_speed"][0] == 0.0  # the ball stays at rest
    assert_point_is_run(result, 0, run_of(plan))


def test_a_swing_sweep_keeps_the_stationary_bat_at_rest():
    plan = plan_sweep("ash-34", SMITH, ["bat_angular_speed=40rad/s:53rad/s:2"], engine="rigid")
    result = run_sweep(plan)
    stationary_bat = next(c for c in result.conditions if c.name == "stationary-bat")
    assert stationary_bat.series["bat_angular_speed"] == [0.0, 0.0]
    assert_point_is_run(result, 1, run_of(plan))  # 53 rad/s, the study's swing


def test_flexible_point_at_the_nominal_wall_is_batcert_run(flexible_wall_sweep):
    """The nominal wall variant (run in one engine batch with three other variants) equals
    `batcert run` of the same geometry alone; the nominal bat as measured is reported apart."""
    plan, result = flexible_wall_sweep
    axis = plan.axes[0]
    assert axis.values[2] == axis.nominal == 2.7e-3  # 90 %..110 % in 5 steps: the middle
    geometric = build_bat(geometry_only(plan.base.bat))
    # stacked with three other variants in one integration: the last bits differ (docstring)
    assert_point_is_run(result, 2, run_of(plan, built=geometric), rel=1e-12)
    measured = run_of(plan)
    assert (result.nominal.value, result.nominal.margin, result.nominal.verdict) == (
        measured.value, measured.margin, measured.verdict)
    assert result.nominal.measured_mass == 0.863  # aluminium-34's measured 863 g
    assert result.nominal.error is None


def test_rigid_sweet_spot_is_eq7():
    """Smith 2001 Eq. 7 (batcert.physics.rigid.rigid_sweet_spot) of each variant's MOI and
    speeds. Exact: the same closed form of the same floats."""
    plan = plan_sweep("ash-34", SMITH, ["bat_angular_speed=10rad/s:60rad/s:6"], engine="rigid")
    result = run_sweep(plan)
    moi = mass_properties(plan.built, plan.base.protocol.pivot).moi_pivot
    # the measured MOI about the study's pivot, as reconciled (a density fit: 1e-12)
    assert moi == pytest.approx(0.209, rel=1e-12)
    assert result.series["moi_pivot"] == [moi] * 6
    ball_mass = plan.ball.model.mass
    swung = next(c for c in result.conditions if c.name == "pitched-and-swung")
    assert swung.series["bat_angular_speed"] == list(plan.axes[0].values)
    assert swung.series["pitch_speed"] == [-31.0] * 6
    for c in result.conditions:
        expected = [float(rigid_sweet_spot(i, ball_mass, vp, w)) if w else None for i, vp, w in
                    zip(result.series["moi_pivot"], c.series["pitch_speed"],
                        c.series["bat_angular_speed"], strict=True)]
        assert c.series["rigid_sweet_spot"] == expected, c.name


def test_rigid_sweet_spot_needs_a_swing():
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2"], engine="rigid")
    (c,) = run_sweep(plan).conditions
    assert not c.rigid_applies and c.series["rigid_sweet_spot"] == [None, None]


# ---- the grid, its arrays and failed variants --------------------------------------------
def test_arrays_align_with_values():
    plan = plan_sweep("ash-34", SMITH, ["bat_angular_speed=10rad/s:60rad/s:6"], engine="rigid")
    data = run_sweep(plan).to_dict()
    assert list(data)[:5] == ["schema", "kind", "parameter", "values", "metrics"]
    assert data["parameter"] == "bat_angular_speed"
    assert data["values"] == [10.0, 20.0, 30.0, 40.0, 50.0, 60.0]
    assert all(len(v) == 6 for v in data["metrics"].values())
    assert {"value", "margin", "verdict", "mass", "moi_pivot", "cop",
            "pitched-and-swung.sweet_spot", "stationary-bat.rigid_sweet_spot"} <= set(
        data["metrics"])
    assert json.loads(json.dumps(data, allow_nan=False)) == data  # plain JSON


def test_grid_first_axis_outermost():
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:3",
                                                "bat_angular_speed=0rad/s:20rad/s:2"],
                      engine="rigid")
    result = run_sweep(plan)
    pitch, swing = [50.0, 55.0, 60.0], [0.0, 20.0]
    assert result.points == [[p, w] for p in pitch for w in swing]
    (c,) = result.conditions
    # each row is the variant of its point, not only listed in its place
    assert c.series["pitch_speed"] == [-p for p in pitch for _ in swing]
    assert c.series["bat_angular_speed"] == [w for _ in pitch for w in swing]
    data = result.to_dict()
    assert data["parameter"] == ["pitch_speed", "bat_angular_speed"]
    assert data["values"] == result.points
    assert all(len(v) == 6 for v in data["metrics"].values())
    chunks = plan.chunks()
    assert [p for ch in chunks for p in ch.points] == list(enumerate(map(tuple, result.points)))
    assert all(len(ch.points) <= CHUNK_SIZE for ch in chunks)


def test_collect_does_not_depend_on_row_order():
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:6"], engine="rigid")
    rows = [r for ch in plan.chunks() for r in evaluate_chunk(ch)]
    assert collect(plan, rows, None).to_dict() == collect(plan, rows[::-1], None).to_dict()


def test_a_variant_that_cannot_be_built_gets_an_error_row():
    # ash-34 with its measured CG and MOI kept: 90 % of its mass gives a radius of gyration
    # longer than a uniform rod's, and 110 % needs a negative density near the knob
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["mass=90%:110%:3"], engine="rigid")
    assert len(plan.chunks()) == 1  # the failed and the good variants share one batch
    result = run_sweep(plan)
    assert result.errors[1] is None and result.verdicts[1] in ("pass", "fail")
    assert "radius of gyration" in result.errors[0]
    assert "cannot reconcile" in result.errors[2]
    for k in (0, 2):
        assert result.verdicts[k] is None
        assert all(v[k] is None for v in result.series.values())
        assert all(v[k] is None for c in result.conditions for v in c.series.values())
    assert result.warnings[0] == "2 of 3 variants have no result (see errors)"
    # the good variant is what it would be alone
    alone = plan_sweep("ash-34", "ncaa-bbcor", [f"mass={plan.axes[0].values[1]}kg"],
                       engine="rigid")
    assert run_sweep(alone).series == {k: [v[1]] for k, v in result.series.items()}


# ---- where it runs ------------------------------------------------------------------------
def test_two_worker_processes_give_the_serial_numbers(monkeypatch):
    # nine walls: the nominal bat and the first chunk are solved here, the two chunks left by
    # the workers (started whatever the work: WORKER_START 0)
    monkeypatch.setattr(execute_module, "WORKER_START", 0.0)
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", ["wall=90%:110%:9"], engine="flexible")
    assert len(plan.chunks()) == 3
    serial = run_sweep(plan)
    parallel = run_sweep(plan, workers=2)
    assert parallel.to_dict()["metrics"] == serial.to_dict()["metrics"]
    assert parallel.to_dict() == serial.to_dict()


def _timed_chunks(monkeypatch, seconds: float) -> list:
    """The first chunk timed at ``seconds`` whatever the machine's load (issue 40: the test
    failed on a loaded machine, where the real first chunk took long enough to start workers,
    which the mock below then never ran), and worker start-ups recorded, not made."""
    ticks = iter([0.0, seconds])
    monkeypatch.setattr(execute_module, "clock", lambda: next(ticks))
    started = []
    monkeypatch.setattr(execute_module, "_on_processes", lambda *a: started.append(a))
    return started


def test_a_short_sweep_with_workers_starts_none(monkeypatch):
    # issue 29: --workers 2 on a sweep of a fraction of a second took longer than serial (the
    # processes' start-up); the first chunk shows the rest is not worth them (a chunk of 20 ms:
    # the other chunk would take 20 ms here, against 2 x 0.5 s of start-up)
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:12"], engine="rigid")
    serial = run_sweep(plan).to_dict()
    started = _timed_chunks(monkeypatch, 0.02)
    assert run_sweep(plan, workers=2).to_dict() == serial
    assert started == []


def test_a_long_sweep_with_workers_starts_them(monkeypatch):
    # a sweep of 40 variants whose first chunk takes 5 s: the chunks left would take 45 s here,
    # against 2 x 0.5 s of start-up: the workers are started, once, with every chunk left
    started = _timed_chunks(monkeypatch, 5.0)
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:40"], engine="rigid")
    with pytest.raises(KeyError):  # the mock ran no chunk: the sweep cannot be collected
        run_sweep(plan, workers=2)
    assert len(started) == 1 and len(started[0][0]) == len(plan.chunks()) - 1


# ---- the journal ----------------------------------------------------------------------------

@pytest.fixture
def counted(monkeypatch):
    """The indices of the chunks evaluate_chunk is called on (in this process: serial runs)."""
    calls: list[int] = []

    def counting(chunk):
        calls.append(chunk.index)
        return evaluate_chunk(chunk)

    monkeypatch.setattr(execute_module, "evaluate_chunk", counting)
    return calls


def test_resume_evaluates_only_the_missing_chunks(tmp_path, counted):
    n = 2 * CHUNK_SIZE + 2  # three chunks, the last one short
    plan = plan_sweep("ash-34", "ncaa-bbcor", [f"pitch_speed=40m/s:60m/s:{n}"], engine="rigid")
    assert [len(c.points) for c in plan.chunks()] == [CHUNK_SIZE, CHUNK_SIZE, 2]
    journal = tmp_path / "sweep.partial.jsonl"
    whole = run_sweep(plan, journal_at=journal)
    assert counted == [0, 1, 2]
    lines = journal.read_text().splitlines()
    assert len(lines) == 4 and json.loads(lines[0])["created"] == plan.created

    # interrupted while writing the second chunk: header, first chunk, half a line
    journal.write_text("\n".join(lines[:2]) + "\n" + lines[2][: len(lines[2]) // 2])
    counted.clear()
    later = replace(plan, created="2099-01-01T00:00:00+00:00")  # a new invocation
    resumed = run_sweep(later, journal_at=journal, resume=True)
    assert counted == [1, 2]
    assert resumed.to_dict() == whole.to_dict()  # numbers and the first run's timestamp
    assert journal.read_text().splitlines()[:2] == lines[:2]  # the half line is gone
    assert len(journal.read_text().splitlines()) == 4

    # a complete journal: nothing left to evaluate
    counted.clear()
    assert run_sweep(later, journal_at=journal, resume=True).to_dict() == whole.to_dict()
    assert counted == []


def test_without_resume_the_journal_starts_afresh(tmp_path, counted):
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:5"], engine="rigid")
    journal = tmp_path / "sweep.partial.jsonl"
    run_sweep(plan, journal_at=journal)
    counted.clear()
    run_sweep(plan, journal_at=journal)
    assert counted == [0, 1]


@pytest.mark.parametrize("other", [
    ("ash-34", "ncaa-bbcor", "pitch_speed=40m/s:60m/s:6", "flexible"),  # another engine
    ("ash-34", "ncaa-bbcor", "pitch_speed=40m/s:61m/s:5", "rigid"),  # other values
    ("aluminium-34", "ncaa-bbcor", "pitch_speed=40m/s:60m/s:5", "rigid"),  # another bat
])
def test_a_journal_of_another_sweep_is_refused(tmp_path, counted, other):
    journal = tmp_path / "sweep.partial.jsonl"
    run_sweep(plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:5"], engine="rigid"),
              journal_at=journal)
    before = journal.read_text()
    counted.clear()
    bat, protocol, vary, engine = other
    with pytest.raises(UsageProblem, match="holds a sweep with other inputs"):
        run_sweep(plan_sweep(bat, protocol, [vary], engine=engine), journal_at=journal,
                  resume=True)
    assert counted == [] and journal.read_text() == before


def _journal_of(tmp_path, vary="pitch_speed=40m/s:60m/s:9"):
    """A whole journal of a rigid ash-34 sweep in three chunks (its lines), and the plan."""
    plan = plan_sweep("ash-34", "ncaa-bbcor", [vary], engine="rigid")
    journal = tmp_path / "sweep.partial.jsonl"
    run_sweep(plan, journal_at=journal)
    return plan, journal, journal.read_text().splitlines()


@pytest.mark.parametrize("damage", [
    "header cut",  # the first line damaged: it can no longer show which sweep it holds
    "middle line",  # a damaged line that is not the last one cut short
    "not an object", "no rows", "chunk as text", "a second, different copy",
    # issue 40 item 6f: a short chunk was a KeyError, a deeply nested line a RecursionError
    "short chunk", "a row without its fields", "a row of another variant", "a value as text",
    "a chunk the sweep lacks", "nested too deep",
])
def test_a_journal_that_cannot_prove_its_rows_is_refused(tmp_path, counted, damage):
    # issue 24: a journal whose first line was damaged used to skip the check that it belongs
    # to this sweep and report another sweep's rows as this one's, exit 0
    plan, journal, lines = _journal_of(tmp_path)
    entry = json.loads(lines[1])
    broken = {
        "header cut": [lines[0][:20], *lines[1:]],
        "middle line": [lines[0], lines[1][:30], *lines[2:]],
        "not an object": [lines[0], json.dumps([1, 2]), *lines[2:]],
        "no rows": [lines[0], json.dumps({**entry, "rows": None}), *lines[2:]],
        "chunk as text": [lines[0], json.dumps({**entry, "chunk": "0"}), *lines[2:]],
        "a second, different copy": [*lines, json.dumps({**entry, "rows": entry["rows"][:1]})],
        "short chunk": [lines[0], json.dumps({**entry, "rows": entry["rows"][:1]}), *lines[2:]],
        "a row without its fields": [lines[0], json.dumps(
            {**entry, "rows": [{"index": 0}, *entry["rows"][1:]]}), *lines[2:]],
        "a row of another variant": [lines[0], json.dumps(
            {**entry, "rows": [entry["rows"][1], *entry["rows"][1:]]}), *lines[2:]],
        "a value as text": [lines[0], json.dumps(
            {**entry, "rows": [{**entry["rows"][0], "value": "0.5"}, *entry["rows"][1:]]}),
            *lines[2:]],
        "a chunk the sweep lacks": [*lines, json.dumps({**entry, "chunk": 7})],
        "nested too deep": [lines[0], "[" * 100_000 + "]" * 100_000, *lines[2:]],
    }[damage]
    journal.write_text("\n".join(broken) + "\n")
    counted.clear()
    with pytest.raises(UsageProblem, match="the journal is not used"):
        run_sweep(plan, journal_at=journal, resume=True)
    assert counted == []


def test_every_line_must_be_of_this_sweep(tmp_path, counted):
    # Two sweeps of the same parameter over other values: a line of one spliced into the
    # other's journal (what sharing a journal did) is refused, at its line.
    plan, journal, lines = _journal_of(tmp_path)
    _, other, other_lines = _journal_of(tmp_path / "b", "pitch_speed=40m/s:61m/s:9")
    journal.write_text("\n".join([lines[0], lines[1], other_lines[2]]) + "\n")
    counted.clear()
    with pytest.raises(UsageProblem, match=r"line 3: the line is not of this sweep"):
        run_sweep(plan, journal_at=journal, resume=True)
    assert counted == []


def test_two_sweeps_of_one_parameter_keep_separate_journals(tmp_path):
    from batcert.commands.sweep import journal_path
    from batcert.sweeps.execute import sweep_key
    a = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:60m/s:9"], engine="rigid")
    b = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=40m/s:61m/s:9"], engine="rigid")
    assert journal_path(tmp_path, "s", sweep_key(a)) != journal_path(tmp_path, "s", sweep_key(b))
    assert journal_path(tmp_path, "s", sweep_key(a)) == journal_path(tmp_path, "s",
                                                                     sweep_key(a))


def test_a_binary_journal_is_refused_cleanly(tmp_path, counted):
    plan, journal, _ = _journal_of(tmp_path)
    journal.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(UsageProblem, match="not a text file"):
        run_sweep(plan, journal_at=journal, resume=True)


def test_a_warning_names_the_variants_it_came_from():
    """A warning of some variants says which (by their values), one of every variant says
    so: a user can find the variant to look at."""
    # the thin wall deflects past half its thickness (one warning, one variant); the nominal
    # and the thick wall do not (with the finite-strain footprint's softer contact the nominal
    # 2.7 mm wall no longer does; flexible engine, about 2 s)
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", ["wall=60%:140%:3"], engine="flexible")
    warnings = run_sweep(plan).warnings
    wall = [w for w in warnings if "wall deflects" in w]
    assert len(wall) == 1 and all(w.endswith(")") for w in wall)
    named = " ".join(wall)
    assert named.count("wall=0.00162 m") == 1, wall  # the variant's warning, once
    assert "wall=0.0027 m" not in named and "wall=0.00378 m" not in named
    assert all(re.search(r"\(1 of 3 variants: ", w) for w in wall)
    # one warning of every variant says so (a rigid ash bat's edge at every pitch speed)
    rigid = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=20m/s:70m/s:3"], engine="rigid")
    edge = [w for w in run_sweep(rigid).warnings if "search window's edge" in w]
    assert edge and all(w.endswith("(all 3 variants)") for w in edge)


def test_a_journal_removed_meanwhile_is_made_anew_and_never_written_through_a_link(tmp_path):
    """The same sweep run into one folder at once: the first to finish removes the shared
    journal while the other still appends (it failed with 'No such file', exit 4); appending
    makes the file anew, which a resume then refuses (no header). A link put at the path is
    never written through."""
    from batcert.sweeps.execute import Journal, JournalRefused
    journal = Journal(tmp_path / "j.partial.jsonl", "key", "2026-11-26T00:00:00+00:00")
    journal.start({})
    journal.path.unlink()  # the other run finished
    journal.add(0, [{"index": 0, "error": None}])
    assert journal.path.is_file()
    with pytest.raises(JournalRefused):
        Journal(journal.path, "key", "").load()
    victim = tmp_path / "bat.yaml"
    victim.write_text("name: x\n")
    journal.path.unlink()
    journal.path.symlink_to(victim)
    with pytest.raises(OutputError):
        journal.add(1, [{"index": 1, "error": None}])
    assert victim.read_text() == "name: x\n"


def test_a_fresh_journal_is_not_blocked_by_a_crashed_runs_staging_file(tmp_path):
    """A crashed run with the same process id left its staging file: a new journal still
    starts (with O_EXCL it failed, exit 4)."""
    import os

    from batcert.sweeps.execute import Journal
    journal = Journal(tmp_path / "j.partial.jsonl", "key", "2026-11-26T00:00:00+00:00")
    (tmp_path / f".j.partial.jsonl.{os.getpid()}.tmp").write_text("half a journal")
    journal.start({})
    assert Journal(journal.path, "key", "").load() == {}
