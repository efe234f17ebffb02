"""Where a hollow impact's time goes: the time stepping's share and cost per impact-step, for
each ball law. Prints figures; asserts nothing.

    python benchmarks/bench_kernel.py [--impacts N] [--json FILE]

A random batch of ``aluminium-34`` impacts (the slowest shipped bat: 44 modes, a 12.5 us step)
goes through the engine twice, with the shipped collegiate ball (viscoelastic) and with
Nathan's 2000 ball (rate-free hysteresis, batcert 0.2's law). For each: the engine's impacts
per second, the stepping's share (the time inside :func:`batcert.engines.kernel.march.march`), and the
stepping's cost per impact and step; then the stepping alone again on the same inputs, so the
figure does not include the engine's set-up. Figures are also printed as ratios to the time of
``python -c "import numpy"`` measured in the same run (the machine's yardstick).

Issue 9's measured choice between this numpy stepping and a compiled (numba) kernel was made on
batcert 0.2's law and is recorded in docs/performance.md ("What was measured and not kept").
That kernel encoded Nathan's law; with the ball laws behind a time-stepping protocol
(issue 23) it no longer applies and was removed rather than kept unrunnable.
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import batcert.engines.flexible as flexible_module  # noqa: E402
import batcert.engines.kernel.march as march_module  # noqa: E402
from batcert.commands.inputs import load_bat_any, load_protocol_any  # noqa: E402
from batcert.engines import ImpactBatch  # noqa: E402
from batcert.engines.flexible import FlexibleEngine  # noqa: E402
from batcert.specs.ball import load_ball  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PIVOT = 0.1524
TARGET = 50_000  # impacts per second of one core (issue 9)


def numpy_import_time(repeat: int = 5) -> float:
    """The fastest of ``repeat`` runs of ``python -c "import numpy"`` [s]."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import numpy"], check=True)
        best = min(best, time.perf_counter() - t0)
    return best


def random_batch(bat, n: int, seed: int = 1) -> ImpactBatch:
    """The large-batch benchmark's impacts (bench_engine.py): random points over the barrel's
    last 30 cm, pitch 20-45 m/s, swing 0-60 rad/s."""
    rng = np.random.default_rng(seed)
    z = rng.uniform(bat.length - 0.30, bat.length - 0.03, n)
    return ImpactBatch(z - PIVOT, -rng.uniform(20, 45, n), rng.uniform(0, 60, n))


def engine_run(bat, ball, n: int):
    """Solve ``n`` random impacts; the engine's wall time, the stepping's wall time, and the
    stepping's inputs (one per march call)."""
    engine = FlexibleEngine()
    engine.solve(bat, ball, PIVOT, random_batch(bat, 5, seed=2))  # modes, barrel: not timed
    calls, spent = [], [0.0]
    real = march_module.march

    def timed_march(system, law, speed, step, max_time, *rest, **kw):
        # the law's state advances as it steps: keep a fresh copy for the second run
        calls.append((system, copy.deepcopy(law), np.array(speed), step, max_time, rest, kw))
        t0 = time.perf_counter()
        out = real(system, law, speed, step, max_time, *rest, **kw)
        spent[0] += time.perf_counter() - t0
        return out

    flexible_module.march = timed_march
    try:
        t0 = time.perf_counter()
        engine.solve(bat, ball, PIVOT, random_batch(bat, n))
        total = time.perf_counter() - t0
    finally:
        flexible_module.march = real
    return total, spent[0], calls


def stepping_again(calls) -> tuple[float, int]:
    """The stepping of every call once more, from the same inputs: wall time, impact-steps."""
    steps, elapsed = 0, 0.0
    for system, law, speed, step, max_time, rest, kw in calls:
        t0 = time.perf_counter()
        sep = march_module.march(system, law, speed, step, max_time, *rest, **kw)
        elapsed += time.perf_counter() - t0
        steps += int(np.ceil(np.asarray(sep.time) / step).sum())
    return elapsed, steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--impacts", type=int, default=8192)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()
    n = args.impacts
    numpy_s = numpy_import_time()
    print(f"python -c 'import numpy': {1e3 * numpy_s:.0f} ms (the yardstick below)")
    figures: dict[str, float] = {"numpy_import_s": numpy_s}
    bat = load_bat_any("aluminium-34").built.model
    balls = {"viscoelastic": load_protocol_any("proposed").ball.model,
             "nathan": load_ball(ROOT / "protocols" / "balls" / "nathan-2000.yaml").model}
    for name, ball in balls.items():
        total, stepping, calls = engine_run(bat, ball, n)
        again, steps = stepping_again(calls)
        ns = 1e9 * again / steps
        print(f"{name:12s} ball, {n} random aluminium-34 impacts: {n / total:7.0f} impacts/s "
              f"[target {TARGET}] ({1e6 * total / n:.1f} us per impact, of which stepping "
              f"{1e6 * stepping / n:.1f} us); stepping alone {ns:.0f} ns per impact-step, "
              f"{steps / n:.0f} steps per impact; {n} impacts take {total / numpy_s:.2f} x "
              "the numpy import")
        figures.update({f"{name}_impacts_per_s": n / total, f"{name}_engine_us": 1e6 * total / n,
                        f"{name}_stepping_us": 1e6 * stepping / n,
                        f"{name}_ns_per_impact_step": ns, f"{name}_steps_per_impact": steps / n,
                        f"{name}_batch_over_numpy_import": total / numpy_s})
    if args.json:
        args.json.write_text(json.dumps(figures, indent=2) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
