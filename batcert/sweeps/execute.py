"""Where a sweep's chunks run (its journal is :mod:`batcert.sweeps.journal`): in this process, in worker processes
(``--workers N``) or on a dask.distributed cluster (``--scheduler ADDRESS``), each finished chunk
appended to a journal so that ``--resume`` continues an interrupted sweep without redoing it.

The nominal bat, when the result shows it (:func:`~batcert.sweeps.sweep.needs_nominal`), is
solved as one more chunk, so that with workers no engine work is left to the serial part.
Worker processes and dask workers keep what they compute in the same cache directory as this
process when it keeps one (the barrels of a wall sweep are then computed once on the machine,
not once per worker, and a second run reads them).

Every chunk is the same whatever runs it (:mod:`batcert.sweeps.sweep`), and a row is stored
as JSON, which round-trips every float exactly, so a serial, parallel, distributed or resumed
sweep gives the same numbers.
"""

from __future__ import annotations

import os
import re
import sys
import time
from collections.abc import Callable
from concurrent.futures import Future, ProcessPoolExecutor, as_completed

from batcert.errors import SchedulerUnavailable, UsageProblem
from batcert.sweeps.journal import JOURNAL, Journal, JournalRefused, sweep_key
from batcert.sweeps.sweep import Chunk, Plan, Row, evaluate_chunk, needs_nominal

# the journal's names, where callers have long found them
__all__ = ["JOURNAL", "Journal", "JournalRefused", "execute", "run_chunks", "sweep_key"]

def evaluate_in_worker(chunk: Chunk, cache: bool = False) -> list[Row]:
    """:func:`~batcert.sweeps.sweep.evaluate_chunk` in a worker (top-level, for process and
    dask workers); ``cache``: keep what is computed in the worker's cache directory, as the
    process that planned the sweep does (a worker starts without it)."""
    if cache:
        _attach_cache()
    from batcert.cache import warnings_as_lines
    with warnings_as_lines(lambda m: print(f"  warning: {m}", file=sys.stderr)):
        return evaluate_chunk(chunk)


def _attach_cache() -> None:
    """Keep the physics' costly results in this process's cache directory, once."""
    from batcert import cache, workspace
    ws = workspace.current()
    if not ws.attached:
        ws.attach(cache.disk_stores())


clock = time.perf_counter  # times the first chunk (a test sets its own: load must not matter)

# [s] what starting a worker process costs (a spawned interpreter importing batcert, 0.25-0.3 s
# measured, and its first reads of the cache directory): with w workers the rest of a sweep is
# sent to them only when it would take longer than WORKER_START * w / (w - 1) in this process,
# where they save more than they cost
WORKER_START = 0.5


def run_chunks(chunks: list[Chunk], on_done: Callable[[Chunk, list[Row]], None],
               workers: int = 1, scheduler: str | None = None) -> None:
    """Evaluate every chunk, calling ``on_done(chunk, rows)`` as each finishes (in completion
    order). ``workers`` > 1 uses that many processes, once the first chunk with variants,
    solved here, shows that the rest is worth them (:data:`WORKER_START`: a short sweep is
    never slower with ``--workers`` than without); ``scheduler`` a dask.distributed
    scheduler's address."""
    if not chunks:
        return
    if scheduler is not None:
        _on_dask(chunks, on_done, scheduler)
        return
    rest = list(chunks)
    if workers > 1 and len(chunks) > 1:
        first = next(k for k, c in enumerate(rest) if c.points or k == len(rest) - 1) + 1
        start = clock()
        for chunk in rest[:first]:
            on_done(chunk, evaluate_chunk(chunk))
        per_chunk = (clock() - start) / first
        rest = rest[first:]
        if per_chunk * len(rest) > WORKER_START * workers / (workers - 1) and len(rest) > 1:
            _on_processes(rest, on_done, workers)
            return
    for chunk in rest:
        on_done(chunk, evaluate_chunk(chunk))


def _on_processes(chunks: list[Chunk], on_done, workers: int) -> None:
    import multiprocessing

    from batcert import workspace
    cached = workspace.current().attached
    # spawn: the parent may run a progress display's thread, which fork would copy mid-state
    pool = ProcessPoolExecutor(max_workers=min(workers, len(chunks)),
                               mp_context=multiprocessing.get_context("spawn"),
                               initializer=_start_worker, initargs=(os.getpid(), cached))
    try:
        futures: dict[Future, Chunk] = {pool.submit(evaluate_in_worker, c): c for c in chunks}
        for fut in as_completed(futures):
            on_done(futures[fut], fut.result())
    except BaseException:
        _stop_workers(pool)  # interrupted (Ctrl-C, SIGTERM) or failed: no chunk is waited for
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _start_worker(parent: int, cached: bool) -> None:
    """A worker process's initializer: it follows its parent (:func:`_follow_parent`) and
    keeps what it computes in the cache directory when the parent does."""
    _follow_parent(parent)
    if cached:
        _attach_cache()


def _stop_workers(pool: ProcessPoolExecutor) -> None:
    """End the pool's worker processes now (``ProcessPoolExecutor.terminate_workers`` from
    Python 3.14; before it, the processes the pool keeps)."""
    terminate = getattr(pool, "terminate_workers", None)
    if terminate is not None:
        terminate()
        return
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        process.terminate()


PARENT_CHECK = 0.2  # [s] how often a worker checks that the sweep's process is alive


def _follow_parent(parent: int) -> None:
    """A worker's initializer: the worker ends when the sweep's process ``parent`` does, however
    it ends (``kill -9`` included), instead of computing on as an orphan that keeps the
    resource tracker alive too. On Linux the kernel kills the worker (``PR_SET_PDEATHSIG``);
    everywhere a daemon thread sees the worker re-parented within :data:`PARENT_CHECK`."""
    import sys
    import threading
    import time
    if sys.platform == "linux":
        import ctypes
        import signal
        try:
            ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # 1: PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            pass  # the thread below still watches

    def watch() -> None:
        while os.getppid() == parent:  # also false when the parent died before this ran
            time.sleep(PARENT_CHECK)
        os._exit(1)

    threading.Thread(target=watch, name="batcert-parent-watch", daemon=True).start()


_ADDRESS = re.compile(r"^(?:(?:tcp|tls|ucx|ws|wss|inproc)://)?[\w.\-\[\]:]+/?$")
CONNECT_TIMEOUT = 10.0  # [s] to connect to the scheduler and exchange dask's handshake
WORKERS_TIMEOUT = 60.0  # [s] for a scheduler without workers to get one


def _on_dask(chunks: list[Chunk], on_done, address: str) -> None:
    try:
        from distributed import Client
        from distributed import as_completed as dask_completed
    except ImportError:
        raise SchedulerUnavailable("--scheduler needs dask.distributed: pip install "
                                   "'batcert[distributed]'") from None
    if not _ADDRESS.match(address):
        raise UsageProblem(f"--scheduler {address!r} is not a scheduler address "
                           "(e.g. tcp://10.0.0.5:8786)")
    _handshake(address)
    try:
        client = Client(address, timeout=f"{CONNECT_TIMEOUT}s")  # the default client meanwhile
    except (OSError, ValueError, TimeoutError) as exc:
        raise _unreachable(address, exc) from None
    try:
        try:
            client.wait_for_workers(1, timeout=WORKERS_TIMEOUT)
        except TimeoutError:
            raise SchedulerUnavailable(f"the dask scheduler at {address} has no workers (waited "
                                       f"{WORKERS_TIMEOUT:g} s)") from None
        from batcert import workspace
        futures = client.map(evaluate_in_worker, chunks, cache=workspace.current().attached,
                             pure=False)
        where = {f.key: c for f, c in zip(futures, chunks, strict=True)}
        for fut in dask_completed(futures):
            on_done(where[fut.key], fut.result())
    finally:
        client.close()


def _handshake(address: str) -> None:
    """Connect to ``address`` and exchange dask's handshake, all within
    :data:`CONNECT_TIMEOUT` (dask bounds the connecting only, then waits for the handshake for
    ever, or reads a length from what another server sends and tries to allocate it): an
    address that cannot be used is refused here, as :class:`SchedulerUnavailable`."""
    import asyncio
    import importlib.util
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect
    from distributed.security import Security

    scheme = address.split("://", 1)[0] if "://" in address else "tcp"
    options = Security().get_connection_args("client")
    if scheme == "tls" and options["ssl_context"] is None:
        raise SchedulerUnavailable(f"cannot reach the dask scheduler at {address}: {scheme}:// "
                                   "needs TLS settings in dask's configuration "
                                   "(distributed.comm.tls)")
    if scheme == "ucx" and importlib.util.find_spec("distributed_ucxx") is None:
        raise SchedulerUnavailable(f"cannot reach the dask scheduler at {address}: ucx:// "
                                   "needs the distributed-ucxx package")

    async def exchange() -> None:
        comm = await connect(address, timeout=CONNECT_TIMEOUT, **options)
        await comm.close()

    async def bounded() -> None:
        await asyncio.wait_for(exchange(), CONNECT_TIMEOUT)

    try:
        with ThreadPoolExecutor(1) as thread:  # an event loop of its own, whoever calls
            thread.submit(lambda: asyncio.run(bounded())).result()
    except Exception as exc:  # noqa: BLE001 - whatever answers, the address cannot be used
        raise _unreachable(address, exc) from None


def _unreachable(address: str, exc: BaseException) -> SchedulerUnavailable:
    """The one line that says why ``address`` cannot be used, from what connecting raised."""
    if isinstance(exc, TimeoutError):
        why = f"no dask scheduler answered within {CONNECT_TIMEOUT:g} s"
    elif isinstance(exc, OSError):
        why = str(exc)
    else:  # an answer that is not dask's: a web server, another protocol
        detail = str(exc).splitlines()[0] if str(exc) else ""
        why = f"it does not speak dask's protocol ({type(exc).__name__}: {detail})"
    return SchedulerUnavailable(f"cannot reach the dask scheduler at {address}: {why}")


def execute(plan: Plan, journal: Journal | None = None, done: dict[int, list[Row]] | None = None,
            workers: int = 1, scheduler: str | None = None,
            on_progress: Callable[[int, int], None] | None = None, nominal: bool = False
            ) -> tuple[list[Row], Row | None]:
    """Every variant's row: the chunks already ``done`` (read from ``journal`` to resume) and
    the rest, run where asked, each added to ``journal`` as it finishes; and with ``nominal``
    the nominal bat's row when the sweep shows it (:func:`~batcert.sweeps.sweep.
    needs_nominal`; else None), solved among the chunks (by a worker, when there are workers:
    it is not left to the serial part). ``on_progress(variants_done, variants)`` follows the
    work."""
    chunks = plan.chunks()
    done = dict(done or {})
    if journal is not None:
        journal.check(done, chunks)
        journal.start(done)
    total = sum(len(c.points) for c in chunks)
    finished = [sum(len(r) for r in done.values())]
    if on_progress:
        on_progress(finished[0], total)
    nominal_row: list[Row] = []

    def on_done(chunk: Chunk, rows: list[Row]) -> None:
        if not chunk.points:  # the nominal bat
            nominal_row.extend(rows)
            return
        done[chunk.index] = rows
        if journal is not None:
            journal.add(chunk.index, rows)
        finished[0] += len(rows)
        if on_progress:
            on_progress(finished[0], total)

    todo = [c for c in chunks if c.index not in done]
    if nominal and needs_nominal(plan):
        todo.insert(0, plan.nominal_chunk())
    fresh = not done
    try:
        run_chunks(todo, on_done, workers, scheduler)
    except SchedulerUnavailable:
        if journal is not None and fresh and not done:
            journal.discard()  # nothing ran: a journal of nothing would be left behind
        raise
    return [row for k in sorted(done) for row in done[k]], nominal_row[0] if nominal_row else None
