"""How far a sweep scales: its serial fraction and per-chunk overhead, measured on this machine,
the speed-up they imply at 16 workers (Amdahl), and the measured one at 2. Prints figures;
asserts nothing.

    python benchmarks/bench_scaling.py [--full] [--repeat 3] [--json FILE]

With ``--full``, issue 29's two sweeps: a 64-variant wall sweep of aluminium-34 under
ncaa-bbcor and an 800-variant relative-speed sweep of ash-34 under proposed (about 3 minutes
on 2 cores); without it (as CI runs it), a 16-variant wall sweep in the process only. Warm
(the cache directory filled by a first run). In this process, through the library, each is timed in its parts:

- the parallel part: every chunk's evaluation (:func:`batcert.sweeps.sweep.evaluate_chunk`,
  timed one by one; the nominal bat is one of them), which workers share;
- the serial part: the rest of the sweep command once the modules are loaded: planning,
  merging the rows (``collect``), and writing the Markdown, HTML and JSON reports. The
  interpreter's start and the imports (about 0.25 s) are not in it: a library user pays them
  once, and a worker pays its own in parallel. They are printed apart.

The serial fraction ``s`` is the serial part over the whole; Amdahl's speed-up at ``N`` workers
is ``1 / (s + (1 - s) / N)``. The per-chunk overhead is what a chunk costs besides its variants:
the first ``k`` variants solved as ``k`` chunks of one, against one chunk of ``k``, over ``k -
1``. A worker's start (a spawned interpreter importing batcert) is measured too; the
speed-up with it, ``T1 / (serial + start + T_parallel / N)``, is printed beside Amdahl's.
Then the installed command, serial and ``--workers 2``, alternating (needs ``pip install .``).
BLAS is pinned to one thread (``OPENBLAS_NUM_THREADS=1`` etc.).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

SWEEPS = {
    "wall x64 (aluminium-34, ncaa-bbcor)": ("aluminium-34", "ncaa-bbcor", "wall=60%:140%:64"),
    "relative_speed x800 (ash-34, proposed)": ("ash-34", "proposed",
                                               "relative_speed=40m/s:80m/s:800"),
}
QUICK = {"wall x16 (aluminium-34, ncaa-bbcor)": ("aluminium-34", "ncaa-bbcor",
                                                 "wall=60%:140%:16")}


def parts(bat: str, protocol: str, vary: str) -> dict[str, float]:
    """One warm sweep, timed in its parts [s] (module notes)."""
    from batcert.commands.sweep import plan_sweep
    from batcert.reports.write import write_reports
    from batcert.sweeps import execute as execute_module
    from batcert.sweeps.sweep import collect, evaluate_chunk, nominal_run

    chunk_times: list[float] = []

    def timed(chunk):
        t = time.perf_counter()
        rows = evaluate_chunk(chunk)
        chunk_times.append(time.perf_counter() - t)
        return rows

    t0 = time.perf_counter()
    plan = plan_sweep(bat, protocol, [vary])
    t1 = time.perf_counter()
    original = execute_module.evaluate_chunk
    execute_module.evaluate_chunk = timed
    try:
        rows, nominal_row = execute_module.execute(plan, nominal=True)
    finally:
        execute_module.evaluate_chunk = original
    t2 = time.perf_counter()
    result = collect(plan, rows, nominal_run(plan, nominal_row))
    t3 = time.perf_counter()
    with tempfile.TemporaryDirectory() as out:
        write_reports(result, Path(out))
    t4 = time.perf_counter()
    parallel = sum(chunk_times)
    return {"plan": t1 - t0, "chunks": parallel, "execute_rest": (t2 - t1) - parallel,
            "collect": t3 - t2, "write": t4 - t3, "total": t4 - t0,
            "chunk_count": len(chunk_times)}


def chunk_overhead(bat: str, protocol: str, vary: str, k: int = 8) -> float:
    """What a chunk costs besides its variants [s] (module notes)."""
    from dataclasses import replace

    from batcert.commands.sweep import plan_sweep
    from batcert.sweeps.sweep import evaluate_chunk
    plan = plan_sweep(bat, protocol, [vary])
    points = tuple(enumerate(plan.points))[:k]
    first = plan.chunks()[0]
    together = replace(first, points=points)
    apart = [replace(first, index=i, points=(p,)) for i, p in enumerate(points)]
    evaluate_chunk(together)  # warm
    best_together = best_apart = float("inf")
    for _ in range(2):
        t = time.perf_counter()
        evaluate_chunk(together)
        best_together = min(best_together, time.perf_counter() - t)
        t = time.perf_counter()
        for c in apart:
            evaluate_chunk(c)
        best_apart = min(best_apart, time.perf_counter() - t)
    return (best_apart - best_together) / (len(points) - 1)


def worker_start(repeat: int) -> float:
    """A spawned worker's start [s]: an interpreter that imports what a chunk needs."""
    code = ("import batcert.sweeps.execute, batcert.runner.runner, batcert.engines.flexible, "
            "batcert.model.build")
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def amdahl(s: float, n: int) -> float:
    return 1.0 / (s + (1.0 - s) / n)


def command_times(args: list[str], repeat: int) -> dict[str, float]:
    """The installed command, serial and with two workers, alternating with the numpy
    baseline: median [s] of each."""
    sys.path.insert(0, str(Path(__file__).parent))
    from alternating import installed_batcert, timed_command
    exe, python = installed_batcert()
    env, cwd = dict(os.environ), Path.cwd()
    runs = {"numpy import": [python, "-c", "import numpy"],
            "serial": [exe, *args, "--no-reports", "-q"],
            "--workers 2": [exe, *args, "--workers", "2", "--no-reports", "-q"]}
    times: dict[str, list[float]] = {k: [] for k in runs}
    for cmd in runs.values():  # a first round fills the cache directory
        timed_command(cmd, cwd, env)
    for _ in range(repeat):
        for k, cmd in runs.items():
            times[k].append(timed_command(cmd, cwd, env))
    return {k: statistics.median(v) for k, v in times.items()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--full", action="store_true",
                    help="issue 29's two sweeps and the installed command (else one small "
                    "wall sweep in the process)")
    ap.add_argument("--json", type=Path)
    ap.add_argument("--no-command", action="store_true", help="skip the installed command")
    args = ap.parse_args()
    import batcert.api as api
    api.use_cache()
    start = worker_start(args.repeat)
    print(f"{os.cpu_count()} CPUs; a worker's start (spawned interpreter, imports): "
          f"{start:.2f} s")
    figures: dict[str, dict] = {}
    for name, (bat, protocol, vary) in (SWEEPS if args.full else QUICK).items():
        parts(bat, protocol, vary)  # fills the cache directory
        p = min((parts(bat, protocol, vary) for _ in range(args.repeat)),
                key=lambda d: d["total"])
        serial = p["total"] - p["chunks"]
        s = serial / p["total"]
        overhead = chunk_overhead(bat, protocol, vary)
        modelled = p["total"] / (serial + start + p["chunks"] / 16)
        figures[name] = {**p, "serial": serial, "serial_fraction": s,
                         "chunk_overhead": overhead, "amdahl_16": amdahl(s, 16),
                         "with_worker_start_16": modelled, "worker_start": start}
        print(f"{name}: {p['chunk_count']} chunks, whole {p['total']:.2f} s; chunks "
              f"{p['chunks']:.2f} s, serial {serial * 1e3:.0f} ms (plan "
              f"{p['plan'] * 1e3:.0f}, execute's own {p['execute_rest'] * 1e3:.0f}, collect "
              f"{p['collect'] * 1e3:.0f}, write {p['write'] * 1e3:.0f}): serial fraction "
              f"{s * 100:.2f} %; Amdahl at 16 workers {amdahl(s, 16):.1f}x (with each "
              f"worker's start {modelled:.1f}x); per-chunk overhead {overhead * 1e3:.0f} ms")
        if args.full and not args.no_command:
            cmd = ["sweep", bat, "-p", protocol, "--vary", vary]
            t = command_times(cmd, args.repeat)
            figures[name]["command"] = t
            print(f"  installed command, warm, median of {args.repeat}: serial "
                  f"{t['serial']:.2f} s, --workers 2 {t['--workers 2']:.2f} s (speed-up "
                  f"{t['serial'] / t['--workers 2']:.2f}x); numpy import "
                  f"{t['numpy import']:.3f} s")
    if args.json:
        args.json.write_text(json.dumps(figures, indent=1))


if __name__ == "__main__":
    main()
