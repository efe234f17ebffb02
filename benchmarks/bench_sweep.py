"""Sweep throughput: impacts solved per second by a sweep, serial and with worker processes.
Prints figures; asserts nothing.

    python benchmarks/bench_sweep.py [--variants N] [--workers 1,2] [--bat ash-34]
                                     [--protocol proposed] [--vary pitch_speed]

An impact is one ball-bat collision the engine solves (every point of every sweet-spot search,
refinement and barrel-range variant counts), counted by wrapping the engine's ``solve_many``
in the parent process (serial) or from the serial run's count (the same chunks solve the same
impacts whatever runs them). The default is small enough for CI; the issue-11 figure of at
least 1e5 impacts is ``--variants 800`` (100,800 impacts) on ash-34 under proposed.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def _count_impacts(plan) -> tuple[int, float]:
    """Run the plan serially, counting the impacts the engine solves; (impacts, seconds)."""
    from batcert.engines.base import Job
    from batcert.engines.flexible import FlexibleEngine
    from batcert.engines.rigid import RigidEngine
    from batcert.sweeps.execute import execute
    counted = [0]
    originals = {}
    for cls in (FlexibleEngine, RigidEngine):
        originals[cls] = cls.solve_many

        def wrapped(self, jobs, _orig=originals[cls]):
            counted[0] += sum(len(Job.of(j).batch) for j in jobs)
            return _orig(self, jobs)
        cls.solve_many = wrapped  # type: ignore[method-assign]
    try:
        t0 = time.perf_counter()
        execute(plan)
        return counted[0], time.perf_counter() - t0
    finally:
        for cls, orig in originals.items():
            cls.solve_many = orig  # type: ignore[method-assign]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--variants", type=int, default=24)
    ap.add_argument("--workers", default="1,2")
    ap.add_argument("--bat", default="ash-34")
    ap.add_argument("--protocol", default="proposed")
    ap.add_argument("--vary", default="relative_speed=50m/s:70m/s")
    ap.add_argument("--engine", default="flexible")
    args = ap.parse_args()
    from batcert.commands.sweep import plan_sweep
    from batcert.sweeps.execute import execute
    plan = plan_sweep(args.bat, args.protocol, [f"{args.vary}:{args.variants}"], args.engine)
    print(f"sweep: {args.bat} under {args.protocol}, {args.vary}:{args.variants}, engine "
          f"{args.engine}, {os.cpu_count()} CPUs")
    impacts, serial = _count_impacts(plan)
    print(f"  workers 1: {args.variants} variants, {impacts} impacts in {serial:.2f} s: "
          f"{impacts / serial:,.0f} impacts/s, {serial / args.variants * 1e3:.1f} ms/variant")
    for w in [int(x) for x in args.workers.split(",") if int(x) > 1]:
        t0 = time.perf_counter()
        execute(plan, workers=w)
        dt = time.perf_counter() - t0
        print(f"  workers {w}: {impacts} impacts in {dt:.2f} s: {impacts / dt:,.0f} impacts/s "
              f"(speed-up {serial / dt:.2f}x, process start-up included)")


if __name__ == "__main__":
    main()
