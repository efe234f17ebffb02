"""Time the flexible impact engine through its API, and its accuracy against its converged
limit. Prints figures; asserts nothing.

    python benchmarks/bench_engine.py [--quick] [--json FILE]

Sections: sweeps of one bat; a hollow bat against a solid one of the same profile; the 2001
study's replay (every protocol of both bats, engine only: the bats' modes and barrels are
computed beforehand, the engine's own caches emptied); large batches (impacts per second of one
core); every shipped result against the converged engine; and the speed ratio to a solve_ivp
integration of the same equations (tests/engines/test_flexible.py). Times are the minimum and
the median of repeated calls (the minimum is the machine's capability, the median what a loaded
machine gives). Targets (issue 9, 2-core machine): the study's engine time <= 0.1 s, >= 50,000
impacts per second, every result within 0.02 % of the converged engine.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "engines"))

from r161 import r161_bat  # noqa: E402
from test_convergence import CONVERGED  # noqa: E402  (the converged engine's settings)
from test_flexible import BALL, BARREL_D, hollow_bat, reference_impact  # noqa: E402

import batcert.engines.flexible as flexible_module  # noqa: E402
import batcert.physics.barrel as barrel_module  # noqa: E402
from batcert import workspace  # noqa: E402
from batcert.commands.inputs import load_bat_any, load_protocol_any  # noqa: E402
from batcert.engines import ImpactBatch  # noqa: E402
from batcert.engines.flexible import FlexibleEngine  # noqa: E402
from batcert.model.geometry import build_geometry  # noqa: E402
from batcert.physics.modes import cached_modes  # noqa: E402
from batcert.runner.runner import run_protocols  # noqa: E402
from batcert.specs.materials import LIBRARY  # noqa: E402

PIVOT = 0.15  # the study's pivot [m]
ASH = LIBRARY["ash-bat"][0]
REPEAT = 15
SHIPPED_BATS = ["ash-34", "r161", "aluminium-34", "bbcor-alloy-34"]
SHIPPED_PROTOCOLS = ["astm-bpf", "ncaa-bbcor", "ncaa-besr", "proposed", "stationary-ball"]
STUDY = ["smith2001-bpf-cop.yaml", "smith2001-besr-sweet-spot.yaml",
         "smith2001-bpf-sweet-spot.yaml", "proposed", "smith2001-besr-matched.yaml"]
figures: dict[str, float] = {}


def timed(fn, repeat=REPEAT, before=None):
    """Minimum and median wall time [ms] of ``fn`` (``before`` runs untimed before each)."""
    if before:
        before()
    fn()  # warm
    times = []
    for _ in range(repeat):
        if before:
            before()
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times) * 1e3, float(np.median(times)) * 1e3


def timed_pair(fa, fb, repeat=3 * REPEAT):
    """Time two calls alternately (so that a drifting machine loads both alike): the minimum
    and median of each [ms] and the median of the per-pair ratio b / a."""
    fa(), fb()
    ta, tb = [], []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fa()
        t1 = time.perf_counter()
        fb()
        ta.append(t1 - t0)
        tb.append(time.perf_counter() - t1)
    a, b = np.array(ta) * 1e3, np.array(tb) * 1e3
    return ((a.min(), float(np.median(a))), (b.min(), float(np.median(b))),
            float(np.median(b / a)))


def report(key: str, text: str, value: float) -> None:
    figures[key] = value
    print(text)


def proposed_batch(z):
    """The `proposed` protocol's three conditions at 60 m/s relative speed at every location:
    stationary bat, stationary ball, 31 m/s pitch plus the swing making up the rest."""
    r = z - PIVOT
    vp = np.concatenate([np.full(r.size, -60.0), np.zeros(r.size), np.full(r.size, -31.0)])
    w1 = np.concatenate([np.zeros(r.size), 60.0 / r, 29.0 / r])
    return ImpactBatch(np.tile(r, 3), vp, w1)


def clear_engine_caches() -> None:
    """The caches a fresh process starts without (the bats' modes and barrels are kept)."""
    ws = workspace.current()
    for kind in ("step-exponentials", "beam-response", "patch-flexibility", "patch-factors"):
        ws.clear(kind)


def sweeps(engine: FlexibleEngine) -> None:
    bat = r161_bat()
    z = np.linspace(bat.length - 0.30, bat.length - 0.03, 71)
    lo, med = timed(lambda: engine.solve(bat, BALL, PIVOT, ImpactBatch(z - PIVOT, -60.0, 0.0)))
    report("sweep_71_ms", f"R161, 71-location sweep, one condition:      {lo:6.1f} ms "
           f"(median {med:.1f})", lo)
    lo, med = timed(lambda: engine.solve(bat, BALL, PIVOT, proposed_batch(z)))
    report("sweep_3x71_ms", f"R161, 3 conditions x 71 locations:          {lo:6.1f} ms "
           f"(median {med:.1f})", lo)


def hollow_against_solid(engine: FlexibleEngine) -> None:
    hollow = hollow_bat(2.5e-3)
    solid = build_geometry("test-solid", "solid", 0.864, [0.0, 0.02, 0.30, 0.55, 0.864],
                           [0.040, 0.024, 0.024, BARREL_D, BARREL_D], ASH)
    batch = proposed_batch(np.linspace(hollow.length - 0.30, hollow.length - 0.03, 71))
    (lo_s, med_s), (lo_h, med_h), ratio = timed_pair(
        lambda: engine.solve(solid, BALL, PIVOT, batch),
        lambda: engine.solve(hollow, BALL, PIVOT, batch))
    shell_modes = barrel_module.cached_barrel_modes(hollow).omega.size
    print(f"34 in solid, 3 conditions x 71 locations:   {lo_s:6.1f} ms (median {med_s:.1f})")
    report("hollow_over_solid", f"  same profile hollow, 2.5 mm wall:         {lo_h:6.1f} ms "
           f"(median {med_h:.1f}); {shell_modes} shell modes; hollow / solid = {ratio:.2f} "
           "(median of alternated pairs; the default steps differ)", ratio)
    same_step = FlexibleEngine(time_step=flexible_module.HOLLOW_STEP)
    *_, ratio = timed_pair(lambda: same_step.solve(solid, BALL, PIVOT, batch),
                           lambda: same_step.solve(hollow, BALL, PIVOT, batch))
    report("hollow_over_solid_same_step", f"  the barrel's own cost (both at the hollow step): "
           f"hollow / solid = {ratio:.2f}  [target <= 1.5]", ratio)
    workspace.current().clear("barrel")
    workspace.current().clear("barrel-scaled")
    t0 = time.perf_counter()
    barrel_module.cached_barrel_modes(hollow)
    report("barrel_setup_ms", "  barrel shell (modes, static flexibility), once per bat: "
           f"{(time.perf_counter() - t0) * 1e3:6.0f} ms", (time.perf_counter() - t0) * 1e3)


def study(engine: FlexibleEngine) -> None:
    bats = [load_bat_any(b).built for b in ("ash-34", "aluminium-34")]
    protocols = [load_protocol_any(str(ROOT / "protocols" / "studies" / p) if p.endswith(".yaml")
                                   else p) for p in STUDY]
    jobs = [(b, p.protocol, p.ball) for b in bats for p in protocols]
    run_protocols(jobs, engine)  # the bats' modes and barrels, computed once per bat
    lo, med = timed(lambda: run_protocols(jobs, engine), repeat=5, before=clear_engine_caches)
    report("study_engine_ms", f"Smith 2001 replay, 2 bats x 5 protocols, engine: {lo:6.0f} ms "
           f"(median {med:.0f})  [target 100 ms]", lo)


def large_batches(engine: FlexibleEngine, quick: bool) -> None:
    ball = load_protocol_any("proposed").ball.model
    for name in ("ash-34", "aluminium-34"):
        bat = load_bat_any(name).built.model
        rng = np.random.default_rng(1)
        sizes = (1000, 10_000) if quick else (1000, 10_000, 100_000)
        for n in sizes:
            z = rng.uniform(bat.length - 0.30, bat.length - 0.03, n)
            batch = ImpactBatch(z - 0.1524, -rng.uniform(20, 45, n), rng.uniform(0, 60, n))
            engine.solve(bat, ball, 0.1524, ImpactBatch(batch.impact_location[:5],
                                                        batch.pitch_speed[:5],
                                                        batch.bat_angular_speed[:5]))
            times = []
            for _ in range(3 if n <= 10_000 else 1):  # the best of 3 where that is cheap
                clear_engine_caches()
                t0 = time.perf_counter()
                engine.solve(bat, ball, 0.1524, batch)
                times.append(time.perf_counter() - t0)
            rate = n / min(times)
            report(f"impacts_per_s_{name}_{n}", f"{name:<13} {n:>7} random impacts in one "
                   f"batch: {rate:8.0f} impacts per second{' (best of 3)' * (len(times) > 1)}"
                   f"  [target 50,000]", rate)
            if n in (sizes[0], sizes[-1]):  # memory stays bounded: passes and chunks
                clear_engine_caches()
                tracemalloc.start()
                engine.solve(bat, ball, 0.1524, batch)
                peak = tracemalloc.get_traced_memory()[1] / 1e6
                tracemalloc.stop()
                report(f"peak_mb_{name}_{n}", f"{name:<13} {n:>7} random impacts, peak memory "
                       f"allocated: {peak:7.1f} MB ({peak * 1e3 / n:.1f} kB per impact)", peak)


def protocol_values(jobs, engine) -> list[list[float]]:
    """Every condition's exit speed and the metric of each ``(built bat, protocol, ball)`` job
    (tests/engines/test_convergence.py compares the same numbers)."""
    return [[c.exit_speed for c in r.conditions] + [r.value] for r in run_protocols(jobs, engine)]


def largest_difference(values, converged, rows) -> float:
    """The largest relative difference of ``values`` from ``converged`` over the jobs ``rows``."""
    return max(abs(a / b - 1) for k in rows for a, b in zip(values[k], converged[k], strict=True))


def accuracy() -> None:
    bats = [load_bat_any(b).built for b in SHIPPED_BATS]
    protocols = [load_protocol_any(p) for p in SHIPPED_PROTOCOLS]
    jobs = [(b, p.protocol, p.ball) for b in bats for p in protocols]
    converged = protocol_values(jobs, FlexibleEngine(**CONVERGED))
    default = protocol_values(jobs, FlexibleEngine())
    for i, bat in enumerate(SHIPPED_BATS):
        err = largest_difference(default, converged,
                                 range(i * len(protocols), (i + 1) * len(protocols)))
        report(f"error_{bat}", f"{bat:<15} every exit speed and metric, all protocols: "
               f"largest relative difference from converged {err:.1e}  [target 2e-4]", err)


def against_reference(engine: FlexibleEngine, quick: bool) -> None:
    bat = r161_bat()
    z = np.linspace(bat.length - 0.30, bat.length - 0.03, 11 if quick else 71)
    modes = cached_modes(bat, "pinned", PIVOT, engine.n_modes)
    batch = ImpactBatch(z - PIVOT, -60.0, 0.0)
    t_batch, _ = timed(lambda: engine.solve(bat, BALL, PIVOT, batch), repeat=5)
    fast = engine.solve(bat, BALL, PIVOT, batch).exit_speed
    t0 = time.perf_counter()
    ref = np.array([reference_impact(bat, BALL, PIVOT, "pinned", zi, -60.0, 0.0, modes,
                                     rtol=1e-10, atol=1e-12)[0] for zi in z])
    t_ref = (time.perf_counter() - t0) * 1e3
    report("speedup_over_solve_ivp", f"solve_ivp (rtol 1e-10), {z.size} locations: "
           f"{t_ref:7.0f} ms; batch engine {t_batch:.1f} ms -> {t_ref / t_batch:5.0f}x faster; "
           f"max |difference| {np.max(np.abs(fast - ref)) / 60.0:.1e} of the approach speed",
           t_ref / t_batch)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller batches, fewer locations")
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    args = parser.parse_args()
    engine = FlexibleEngine()
    print(f"flexible engine: {engine.settings()['integrator']}; n_modes={engine.n_modes}, "
          f"time step {engine.settings()['time_step']} s")
    sweeps(engine)
    hollow_against_solid(engine)
    study(engine)
    large_batches(engine, args.quick)
    accuracy()
    against_reference(engine, args.quick)
    if args.json:
        args.json.write_text(json.dumps(figures, indent=1) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
