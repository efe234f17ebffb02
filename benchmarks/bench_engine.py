"""Time the flexible impact engine: sweeps, the `proposed` protocol's load, and the speed ratio
against the solve_ivp reference integration kept in tests/physics/test_flexible.py.

Run from the repository root:  python benchmarks/bench_engine.py [--quick]
Prints figures only; nothing is asserted. Modes (and the residual compliance) are cached before
timing, as in a protocol run. Times are the minimum and the median of repeated calls (the
minimum is the machine's capability, the median what a loaded machine gives).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "engines"))

from r161 import r161_bat  # noqa: E402
from test_flexible import BALL, BARREL_D, hollow_bat, reference_impact  # noqa: E402

from batcert.engines import ImpactBatch  # noqa: E402
from batcert.engines.flexible import FlexibleEngine  # noqa: E402
from batcert.model.geometry import build_geometry  # noqa: E402
from batcert.physics.barrel import cached_barrel_modes, clear_barrel_cache  # noqa: E402
from batcert.physics.modes import cached_modes, clear_mode_cache  # noqa: E402
from batcert.specs.materials import LIBRARY  # noqa: E402

PIVOT = 0.15  # the study's pivot [m]
ASH = LIBRARY["ash-bat"][0]
REPEAT = 15


def timed(fn, repeat=REPEAT):
    fn()  # warm caches (modes, residual compliance)
    times = []
    for _ in range(repeat):
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


def proposed_batch(z):
    """The `proposed` protocol's three conditions at 60 m/s relative speed at every location:
    stationary bat, stationary ball, 31 m/s pitch plus the swing making up the rest."""
    r = z - PIVOT
    vp = np.concatenate([np.full(r.size, -60.0), np.zeros(r.size), np.full(r.size, -31.0)])
    w1 = np.concatenate([np.zeros(r.size), 60.0 / r, 29.0 / r])
    return ImpactBatch(np.tile(r, 3), vp, w1)


def main(quick: bool = False) -> None:
    bat = r161_bat()
    engine = FlexibleEngine()
    # the protocols' default search window, 3-30 cm from the tip
    z = np.linspace(bat.length - 0.30, bat.length - 0.03, 71)
    print(f"flexible engine: {engine.settings()['integrator']}; n_modes={engine.n_modes}, "
          f"time_step={engine.time_step * 1e6:.0f} us")

    one = ImpactBatch(z - PIVOT, -60.0, 0.0)
    lo, med = timed(lambda: engine.solve(bat, BALL, PIVOT, one))
    print(f"R161, 71-location sweep, one condition:        {lo:6.1f} ms (median {med:.1f})  "
          "[target 20 ms]")
    whole = ImpactBatch(np.linspace(0.40, 0.82, 71) - PIVOT, -60.0, 0.0)
    lo_w, med_w = timed(lambda: engine.solve(bat, BALL, PIVOT, whole))
    longest = engine.solve(bat, BALL, PIVOT, whole).diagnostics["contact_time"].max() * 1e3
    print(f"  same, 40-82 cm from the knob:                {lo_w:6.1f} ms (median {med_w:.1f}); "
          f"longest contact {longest:.1f} ms")

    three = proposed_batch(z)
    refine = [proposed_batch(np.linspace(0.66, 0.72, 7)),  # ~2 small batches, as the runner
              proposed_batch(np.linspace(0.68, 0.70, 7))]

    def protocol_load():
        engine.solve(bat, BALL, PIVOT, three)
        for b in refine:
            engine.solve(bat, BALL, PIVOT, b)

    lo3, med3 = timed(lambda: engine.solve(bat, BALL, PIVOT, three))
    lo_all, med_all = timed(protocol_load)
    print(f"R161, 3 conditions x 71 locations:            {lo3:6.1f} ms (median {med3:.1f})")
    print(f"  + 2 refinement batches (3 x 7 each):        {lo_all:6.1f} ms (median {med_all:.1f})  "
          "[target < 100 ms]")

    # hollow against solid: the same 34 in profile, as a 2.5 mm 7050 shell and as solid ash,
    # the same batch (the protocol load above on the hollow bat's window)
    hollow = hollow_bat(2.5e-3)
    solid = build_geometry("test-solid", "solid", 0.864, [0.0, 0.02, 0.30, 0.55, 0.864],
                           [0.040, 0.024, 0.024, BARREL_D, BARREL_D], ASH)
    zh = np.linspace(hollow.length - 0.30, hollow.length - 0.03, 71)
    three_h = proposed_batch(zh)
    (lo_s, med_s), (lo_h, med_h), ratio = timed_pair(
        lambda: engine.solve(solid, BALL, PIVOT, three_h),
        lambda: engine.solve(hollow, BALL, PIVOT, three_h))
    shell_modes = cached_barrel_modes(hollow).omega.size
    print(f"34 in solid, 3 conditions x 71 locations:     {lo_s:6.1f} ms (median {med_s:.1f})")
    print(f"  same profile hollow, 2.5 mm wall:           {lo_h:6.1f} ms (median {med_h:.1f}); "
          f"{shell_modes} shell modes; hollow / solid = {ratio:.2f} (median of alternated "
          "pairs)  [target <= 1.5]")
    clear_barrel_cache()
    t0 = time.perf_counter()
    cached_barrel_modes(hollow)
    print(f"  barrel shell (modes, static flexibility), once per bat: "
          f"{(time.perf_counter() - t0) * 1e3:6.0f} ms")
    fine = FlexibleEngine(time_step=5e-6)
    lo5, med5 = timed(lambda: fine.solve(bat, BALL, PIVOT, one))
    print(f"R161, 71-location sweep at a 5 us step:       {lo5:6.1f} ms (median {med5:.1f})")

    clear_mode_cache()
    t0 = time.perf_counter()
    engine.solve(bat, BALL, PIVOT, one)
    cold = (time.perf_counter() - t0) * 1e3
    print(f"R161, 71-location sweep, modes not cached:    {cold:6.1f} ms")

    # speed ratio against the reference integration (one impact at a time, solve_ivp DOP853)
    sweep = z if not quick else z[::7]
    modes = cached_modes(bat, "pinned", PIVOT, engine.n_modes)
    batch = ImpactBatch(sweep - PIVOT, -60.0, 0.0)
    t_batch, _ = timed(lambda: engine.solve(bat, BALL, PIVOT, batch), repeat=5)
    fast = engine.solve(bat, BALL, PIVOT, batch).exit_speed
    for rtol in (1e-6, 1e-10):
        t0 = time.perf_counter()
        ref = np.array([reference_impact(bat, BALL, PIVOT, "pinned", zi, -60.0, 0.0, modes,
                                         rtol=rtol, atol=1e-12 if rtol < 1e-8 else 1e-9)[0]
                        for zi in sweep])
        t_ref = (time.perf_counter() - t0) * 1e3
        agree = np.max(np.abs(fast - ref)) / 60.0
        print(f"reference solve_ivp (rtol {rtol:.0e}), {sweep.size} locations: {t_ref:8.0f} ms; "
              f"batch engine {t_batch:.1f} ms -> {t_ref / t_batch:6.0f}x faster; "
              f"max |difference| {agree:.1e} of the approach speed")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
