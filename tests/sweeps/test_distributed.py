"""batcert.sweeps.execute on a dask.distributed cluster (``--scheduler``): the same numbers as a
serial run, and a scheduler that cannot be used is a usage error (exit 2), not a traceback.

The cluster is local: two worker processes of one thread (processes=True starts in about 0.7 s
here, so the real pickling path is tested, not threads sharing this process).
"""

from __future__ import annotations

import gc
import socket
import time

import pytest

from batcert.commands.sweep import plan_sweep, run_sweep
from batcert.sweeps.execute import SchedulerUnavailable

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as local:
        yield local


@pytest.fixture
def short_connect(monkeypatch):
    """The scheduler connection times out after 1 s instead of execute's fixed 10 s."""
    real = distributed.Client

    def client(address, **options):
        return real(address, **{**options, "timeout": "1s"})

    monkeypatch.setattr(distributed, "Client", client)


def free_port() -> int:
    """A local TCP port nothing listens on (bound, then released)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_cluster_gives_the_serial_numbers(cluster, flexible_wall_sweep):
    plan, serial = flexible_wall_sweep
    assert len(plan.chunks()) == 2  # one chunk for each worker
    remote = run_sweep(plan, scheduler=cluster.scheduler_address)
    assert remote.to_dict()["metrics"] == serial.to_dict()["metrics"]  # exact: see test_sweep
    assert remote.to_dict() == serial.to_dict()


def test_unreachable_scheduler(short_connect):
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=100mph:136mph:2"], engine="rigid")
    address = f"tcp://127.0.0.1:{free_port()}"
    start = time.perf_counter()
    with pytest.raises(SchedulerUnavailable, match=f"cannot reach the dask scheduler at "
                                                   f"{address}"):
        run_sweep(plan, scheduler=address)
    assert time.perf_counter() - start < 5.0  # the 1 s connect timeout, not a hang


def test_malformed_scheduler_address(monkeypatch):
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=100mph:136mph:2"], engine="rigid")
    # the half-made Client would block 20 s in __del__ when collected: collect it here, muted
    monkeypatch.setattr(distributed.Client, "__del__", lambda self: None)
    try:
        run_sweep(plan, scheduler="nonsense://x")
        raised: type[BaseException] | None = None
    except Exception as exc:  # noqa: BLE001 - the type is what is tested
        raised = type(exc)
    gc.collect()
    assert raised is SchedulerUnavailable
