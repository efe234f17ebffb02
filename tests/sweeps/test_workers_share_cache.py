"""Worker processes keep what they compute in the sweep's cache directory (issue 29: they
ignored it, so a warm wall sweep with --workers 2 took 2.4 s against 0.5 s serial, every
worker computing every barrel afresh)."""

import pytest

from batcert import cache, workspace
from batcert.commands.sweep import plan_sweep, run_sweep
from batcert.sweeps import execute
from batcert.sweeps.sweep import CHUNK_SIZE, LARGE_CHUNK_SIZE, LARGE_SWEEP, chunk_size


def _entries(root, folder):
    where = root / folder
    return sorted(p.name for p in where.iterdir()) if where.is_dir() else []


# thirteen walls: the nominal bat and the first chunk (four walls) are solved in this process,
# the other three chunks (nine walls) by the workers, started whatever the work
WALLS = ["wall=80%:120%:13"]


@pytest.fixture
def workers_always(monkeypatch):
    monkeypatch.setattr(execute, "WORKER_START", 0.0)


@pytest.mark.slow
def test_worker_processes_keep_their_barrels_in_the_cache_directory(tmp_path, monkeypatch,
                                                                   workers_always):
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path))
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", WALLS, engine="flexible")
    with workspace.active(workspace.Workspace()) as ws:
        ws.attach(cache.disk_stores())
        parallel = run_sweep(plan, workers=2)
    # one barrel per wall; nine of them only the workers computed, and they kept them here
    assert len(_entries(tmp_path, "barrels")) >= 13
    with workspace.active(workspace.Workspace()):
        assert parallel.to_dict() == run_sweep(plan).to_dict()


@pytest.mark.slow
def test_workers_of_a_process_without_a_cache_keep_nothing(tmp_path, monkeypatch,
                                                           workers_always):
    monkeypatch.setenv("BATCERT_CACHE_DIR", str(tmp_path))
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", WALLS, engine="flexible")
    with workspace.active(workspace.Workspace()):  # no disk store attached: use_cache(False)
        run_sweep(plan, workers=2)
    assert _entries(tmp_path, "barrels") == []


@pytest.mark.parametrize("variants, size", [(1, CHUNK_SIZE), (255, CHUNK_SIZE),
                                            (LARGE_SWEEP, LARGE_CHUNK_SIZE), (800, 8)])
def test_the_chunk_size_depends_only_on_the_number_of_variants(variants, size):
    # the chunks are the same whoever runs them, so the numbers are too (an engine batch's
    # last bits depend on what shares it)
    assert chunk_size(variants) == size


def test_a_large_sweep_has_several_chunks_for_each_of_sixteen_workers():
    plan = plan_sweep("ash-34", "proposed", ["relative_speed=40m/s:80m/s:800"], engine="rigid")
    chunks = plan.chunks()
    assert len(chunks) == 100 and all(len(c.points) == 8 for c in chunks)
