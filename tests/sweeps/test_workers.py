"""``batcert sweep --workers N`` in a real process: its worker processes (and multiprocessing's
resource tracker) end with it, however it ends, and SIGTERM stops it as Ctrl-C does.

Issue 24: after ``kill -9`` (or SIGTERM) of the sweep's process its workers computed on as
orphans, and kept the resource tracker alive. Each test starts the sweep in a session of its
own, so that every process it made is found by its process group in /proc (Linux), waits until
the workers have finished a chunk, stops the sweep and expects the group empty within
:data:`GONE_WITHIN`. About 4 s each (2 s of it the workers' start-up).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")

REPO = Path(__file__).resolve().parents[2]
# 401 flexible variants in 2 workers: about 8 s of work, far longer than the tests wait
SWEEP = ["sweep", "aluminium-34", "-p", "ncaa-bbcor", "--vary", "wall=50%:150%:401",
         "--workers", "2", "--no-reports", "-vv"]
GONE_WITHIN = 5.0  # [s] the workers check on their parent every 0.2 s; the tracker follows


def group(pgid: int) -> list[int]:
    """The processes alive in process group ``pgid`` (zombies are dead)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue  # ended meanwhile
        state, _, pgrp = stat.rsplit(")", 1)[1].split()[:3]  # after "(command name)"
        if int(pgrp) == pgid and state != "Z":
            found.append(int(entry.name))
    return found


@pytest.fixture
def running_sweep(tmp_path):
    """A ``batcert sweep --workers 2`` whose workers have finished a chunk; every
    process of its group is killed afterwards, whatever the test left."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH",
                                                                                    "")])}
    with subprocess.Popen([sys.executable, "-m", "batcert", *SWEEP], cwd=tmp_path, env=env,
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                          start_new_session=True) as proc:
        try:
            assert proc.stderr is not None
            # -vv logs "N of 401 variants" as chunks finish; the first chunk (8 variants) is
            # solved by the sweep's process before it starts the workers (execute.run_chunks)
            for line in proc.stderr:
                done = line.removeprefix("batcert: ").split(" of ")[0]
                if line.startswith("batcert: ") and done.isdigit() and int(done) > 8:
                    break
            else:
                pytest.fail(f"the sweep ended before a chunk was done (exit {proc.wait()})")
            assert len(group(proc.pid)) >= 4  # the sweep, 2 workers, the resource tracker
            yield proc
        finally:
            try:
                os.killpg(proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def wait_gone(pgid: int) -> list[int]:
    """The processes of the group still alive after :data:`GONE_WITHIN` (none, it is hoped)."""
    deadline = time.monotonic() + GONE_WITHIN
    while (left := group(pgid)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return left


def test_workers_end_when_the_sweep_is_killed(running_sweep):
    os.kill(running_sweep.pid, signal.SIGKILL)
    assert running_sweep.wait(timeout=5) == -signal.SIGKILL
    assert wait_gone(running_sweep.pid) == []


def test_sigterm_stops_the_sweep_as_ctrl_c_does(running_sweep):
    os.kill(running_sweep.pid, signal.SIGTERM)  # the sweep's process only, not its group
    assert running_sweep.wait(timeout=10) == 143
    assert running_sweep.stderr is not None
    rest = [line for line in running_sweep.stderr.read().splitlines()
            if not line.startswith("batcert: ")]  # the progress log of -vv
    assert rest == ["error: terminated"]  # one line, no traceback
    assert wait_gone(running_sweep.pid) == []
