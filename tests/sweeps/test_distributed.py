"""batcert.sweeps.execute on a dask.distributed cluster (``--scheduler``): the same numbers as a
serial run, and a scheduler that cannot be used is refused in bounded time as
:class:`SchedulerUnavailable` (one line, exit 5), never a traceback or a hang; a malformed
address is a usage error (exit 2).

The cluster is local: two worker processes of one thread (processes=True starts in about 0.7 s
here, so the real pickling path is tested, not threads sharing this process).
"""

from __future__ import annotations

import contextlib
import gc
import socket
import threading
import time

import pytest

from batcert.commands.sweep import plan_sweep, run_sweep
from batcert.errors import UsageProblem
from batcert.sweeps import execute
from batcert.sweeps.execute import SchedulerUnavailable

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def cluster():
    # the dashboard on a free port: on the default 8787, taken by any other cluster on the
    # machine, distributed warns, and the warning fails the test
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as local:
        yield local


@pytest.fixture
def short_connect(monkeypatch):
    """Connecting and dask's handshake time out after 1 s instead of execute's 10 s."""
    monkeypatch.setattr(execute, "CONNECT_TIMEOUT", 1.0)


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


@contextlib.contextmanager
def not_dask(reply: bytes):
    """The address of a local TCP server that accepts every connection, sends ``reply`` (b"":
    nothing) and keeps the connection open, silent, until the block ends."""
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(0.05)
    accepted: list[socket.socket] = []
    stop = threading.Event()

    def serve() -> None:
        while not stop.is_set():
            try:
                conn, _ = listener.accept()
            except TimeoutError:
                continue
            accepted.append(conn)
            conn.sendall(reply)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{listener.getsockname()[1]}"
    finally:
        stop.set()
        thread.join()
        for conn in accepted:
            conn.close()
        listener.close()


HTTP = b"HTTP/1.1 400 Bad Request\r\nContent-Length: 11\r\n\r\nbad request" * 4


@pytest.mark.parametrize("reply, why", [
    (b"", "no dask scheduler answered within 1 s"),  # accepts, never speaks: hung for ever
    (HTTP, "it does not speak dask's protocol"),  # a web server: a traceback (MemoryError)
])
def test_a_server_that_is_not_dask_is_refused(short_connect, reply, why):
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=100mph:136mph:2"], engine="rigid")
    with not_dask(reply) as address:
        start = time.perf_counter()
        with pytest.raises(SchedulerUnavailable, match=f"cannot reach the dask scheduler at "
                                                       f"{address}: {why}"):
            run_sweep(plan, scheduler=address)
        assert time.perf_counter() - start < 5.0  # the 1 s bound on the handshake


@pytest.mark.parametrize("address, why", [
    ("tls://127.0.0.1:9", "tls:// needs TLS settings in dask's configuration"),
    ("ucx://127.0.0.1:9", "ucx:// needs the distributed-ucxx package"),
])
def test_a_transport_that_cannot_be_used_is_refused(address, why):
    # issue 24: a TypeError's traceback each, from deep inside distributed
    if address.startswith("tls") and distributed.security.Security().get_connection_args(
            "client")["ssl_context"] is not None:
        pytest.skip("dask's configuration here sets up TLS")
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=100mph:136mph:2"], engine="rigid")
    with pytest.raises(SchedulerUnavailable, match=f"at {address}: {why}"):
        run_sweep(plan, scheduler=address)


def test_a_scheduler_without_workers_is_refused(monkeypatch):
    # issue 24: the sweep waited for ever for a result no worker would compute
    monkeypatch.setattr(execute, "WORKERS_TIMEOUT", 1.0)
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=100mph:136mph:2"], engine="rigid")
    with distributed.LocalCluster(n_workers=0, processes=False, protocol="tcp://",
                                  dashboard_address=":0") as empty:
        start = time.perf_counter()
        with pytest.raises(SchedulerUnavailable, match=f"the dask scheduler at "
                                                       f"{empty.scheduler_address} has no "
                                                       "workers"):
            run_sweep(plan, scheduler=empty.scheduler_address)
        assert time.perf_counter() - start < 5.0


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
    assert raised is UsageProblem  # the option's value is wrong: a usage error, exit 2
