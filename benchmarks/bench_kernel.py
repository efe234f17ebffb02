"""numpy or a compiled kernel for the time stepping? Prints figures; asserts nothing.

    python benchmarks/bench_kernel.py [--impacts N] [--json FILE]

Issue 9 asks for a measured choice between the numpy stepping and a compiled kernel (numba, an
optional extra at most). This benchmark makes the measurement on a real hollow batch:

1. A random batch of ``aluminium-34`` impacts (the slowest shipped bat: 44 modes, a 12.5 us
   step) goes through the engine; the linear systems that :func:`batcert.physics.march.march`
   receives are kept, and the stepping's share of the engine's time is measured.
2. If numba is installed, the same stepping is compiled: the ETDRK4 step of
   :func:`batcert.physics.march._step` with its four force-law evaluations, the modal update
   and read-out, the turning-point refinement and separation, impact by impact, from the same
   step constants (:func:`batcert.physics.march._coefficients`), the real and imaginary parts
   in separate arrays so that the mode loop vectorises. It leaves out the ball's restitution
   re-evaluation and the barrel's energy share, so that both sides run with a fixed ``beta``
   and no shell share; the engine figure with it keeps the law's share of the time in the same
   proportion. Its results (impulses) are checked against the numpy stepping on the same
   inputs. Compiled twice: strict IEEE arithmetic, and ``fastmath`` (reassociation, which the
   mode loop's sums need to vectorise).
3. The numpy stepping again with only its modal update (``SharedRuns.advance``: the propagation,
   forcing and read-out of the modal state, the stepping's largest cost) compiled: a smaller
   kernel, with no physics of its own.
4. Printed: ns per impact-step of each, numba's import and compile cost, and what the engine's
   impacts per second would be with the compiled part in place of numpy's.

Without numba, part 2 is skipped with a message (``pip install numba`` to run it).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

import batcert.engines.flexible as flexible_module  # noqa: E402
import batcert.physics.march as march_module  # noqa: E402
from batcert.commands.inputs import load_bat_any, load_protocol_any  # noqa: E402
from batcert.engines import ImpactBatch  # noqa: E402
from batcert.engines.flexible import FlexibleEngine  # noqa: E402
from batcert.physics import modal_update  # noqa: E402

PIVOT = 0.1524
TARGET = 50_000  # impacts per second of one core (issue 9)


def random_batch(bat, n: int, seed: int = 1) -> ImpactBatch:
    """The large-batch benchmark's impacts (bench_engine.py): random points over the barrel's
    last 30 cm, pitch 20-45 m/s, swing 0-60 rad/s."""
    rng = np.random.default_rng(seed)
    z = rng.uniform(bat.length - 0.30, bat.length - 0.03, n)
    return ImpactBatch(z - PIVOT, -rng.uniform(20, 45, n), rng.uniform(0, 60, n))


def engine_run(n: int):
    """Solve ``n`` random aluminium-34 impacts; return the engine's wall time, the stepping's
    wall time, and the stepping's inputs (one per march call)."""
    bat = load_bat_any("aluminium-34").built.model
    ball = load_protocol_any("proposed").ball.model
    engine = FlexibleEngine()
    engine.solve(bat, ball, PIVOT, random_batch(bat, 5, seed=2))  # modes, barrel: not timed
    calls, spent = [], [0.0]
    real = march_module.march

    def timed_march(system, k1, alpha, beta, speed, step, max_time, restitution=None,
                    chunk=None):
        calls.append((system, k1, alpha, np.array(beta, dtype=float), np.array(speed), step,
                       max_time))
        t0 = time.perf_counter()
        out = real(system, k1, alpha, beta, speed, step, max_time, restitution, chunk)
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


def numpy_stepping(calls) -> tuple[float, int, list]:
    """The numpy stepping of every call with ``beta`` fixed (no restitution law): wall time,
    impact-steps, separations."""
    seps, steps, t0 = [], 0, time.perf_counter()
    for system, k1, alpha, beta, speed, step, max_time in calls:
        seps.append(march_module.march(system, k1, alpha, beta, speed, step, max_time))
    elapsed = time.perf_counter() - t0
    for (*_, step, _max_time), sep in zip(calls, seps, strict=True):
        steps += int(np.ceil(sep.time / step).sum())
    return elapsed, steps, seps


KERNEL = '''
import numpy as np
from numba import njit


@njit(cache=False, fastmath=FASTMATH)
def force(lk1, ab, beta, x, l_top):
    lx = np.log(max(x, 1e-300))
    return np.exp(lk1 + ab * max(lx, l_top) + beta * lx)


@njit(cache=False, fastmath=FASTMATH)
def hermite_max(u0, d0, u1, d1, h):
    a = 3 * (2 * u0 + h * d0 - 2 * u1 + h * d1)
    b = -6 * u0 - 4 * h * d0 + 6 * u1 - 2 * h * d1
    c = h * d0
    disc = np.sqrt(max(b * b - 4 * a * c, 0.0))
    q = -0.5 * (b + np.copysign(disc, b))
    best = max(u0, u1)
    for s in (q / a if a != 0 else np.nan, c / q if q != 0 else np.nan):
        s = min(max(s, 0.0), 1.0) if np.isfinite(s) else 0.0
        val = ((2 * s**3 - 3 * s**2 + 1) * u0 + (s**3 - 2 * s**2 + s) * h * d0
               + (-2 * s**3 + 3 * s**2) * u1 + (s**3 - s**2) * h * d1)
        best = max(best, val)
    return best


@njit(cache=False, fastmath=FASTMATH)
def march(e1, R, P, cg, ka, b0, c0, cb, ca, w6, v6, lk1, ab, beta, speed, h, n_steps,
          impulse, contact_time):
    n, k = cg.shape
    er, ei = e1.real.copy(), e1.imag.copy()  # the real and imaginary parts apart (SIMD)
    rr, ri = R[0::2].T.copy(), R[1::2].T.copy()
    pr0, pr1, pr2 = P[0, 0::2].copy(), P[1, 0::2].copy(), P[2, 0::2].copy()
    pi0, pi1, pi2 = P[0, 1::2].copy(), P[1, 1::2].copy(), P[2, 1::2].copy()
    yr, yi = np.zeros(k), np.zeros(k)
    for i in range(n):
        yr[:] = 0.0
        yi[:] = 0.0
        base0 = base1 = base2 = 0.0
        w, v, u, imp = 0.0, speed[i], 0.0, 0.0
        u_top, u_prev, du_prev = 1e-300, 0.0, 0.0
        t = 0.0
        for _ in range(n_steps):
            u2 = base0 + w + 0.5 * h * v
            u1 = base1 + w + h * v
            du = v + base2
            if du_prev > 0 and du <= 0 and u > 0:
                u_top = max(u_top, hermite_max(u_prev, du_prev, u, du, h))
            u_prev, du_prev = u, du
            l_top = np.log(u_top)
            f0 = force(lk1[i], ab[i], beta[i], u, l_top)
            fa = force(lk1[i], ab[i], beta[i], u2 + ka[i] * f0, l_top)
            fb = force(lk1[i], ab[i], beta[i], u2 + ka[i] * fa + b0[i] * f0, l_top)
            fc = force(lk1[i], ab[i], beta[i], u1 + c0[i] * f0 + cb[i] * fb + ca[i] * fa,
                       l_top)
            fab = fa + fb
            r0 = r1 = r2 = r3 = 0.0
            for j in range(k):  # Y <- e1 Y + cg (f P), then the four read-outs
                push = cg[i, j]
                nr = er[j] * yr[j] - ei[j] * yi[j] + push * (f0 * pr0[j] + fab * pr1[j]
                                                             + fc * pr2[j])
                ni = er[j] * yi[j] + ei[j] * yr[j] + push * (f0 * pi0[j] + fab * pi1[j]
                                                             + fc * pi2[j])
                yr[j], yi[j] = nr, ni
                r0 += rr[0, j] * nr + ri[0, j] * ni
                r1 += rr[1, j] * nr + ri[1, j] * ni
                r2 += rr[2, j] * nr + ri[2, j] * ni
                r3 += rr[3, j] * nr + ri[3, j] * ni
            base0, base1, base2 = r0, r1, r2
            s4 = f0 + 2.0 * fab + fc
            w = w + h * v + w6[i] * (f0 + fab)
            u_new = r3 + w
            v = v + v6[i] * s4
            imp = imp + (h / 6.0) * s4
            u_top = max(u_top, u_new)
            t += h
            if u_new <= 0.0 and u > 0.0:
                contact_time[i] = t - h + h * u / (u - u_new)
                break
            u = u_new
        impulse[i] = imp
'''


UPDATE = '''
import numpy as np
from numba import njit


@njit(cache=False, fastmath=True)
def advance(e1, R, P, scale, group, y, f, out):
    """SharedRuns.advance fused: Y <- e1 Y + scale (f P) and its read-out, row by row."""
    n, k2 = y.shape
    for i in range(n):
        g = group[i]
        f0, f1, f2 = f[i, 0], f[i, 1], f[i, 2]
        r0 = r1 = r2 = r3 = 0.0
        for j in range(k2 // 2):
            re, im = y[i, 2 * j], y[i, 2 * j + 1]
            er, ei = e1[g, j].real, e1[g, j].imag
            nr = er * re - ei * im + scale[i, 2 * j] * (
                f0 * P[g, 0, 2 * j] + f1 * P[g, 1, 2 * j] + f2 * P[g, 2, 2 * j])
            ni = er * im + ei * re + scale[i, 2 * j + 1] * (
                f0 * P[g, 0, 2 * j + 1] + f1 * P[g, 1, 2 * j + 1] + f2 * P[g, 2, 2 * j + 1])
            y[i, 2 * j], y[i, 2 * j + 1] = nr, ni
            r0 += R[g, 2 * j, 0] * nr + R[g, 2 * j + 1, 0] * ni
            r1 += R[g, 2 * j, 1] * nr + R[g, 2 * j + 1, 1] * ni
            r2 += R[g, 2 * j, 2] * nr + R[g, 2 * j + 1, 2] * ni
            r3 += R[g, 2 * j, 3] * nr + R[g, 2 * j + 1, 3] * ni
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = r0, r1, r2, r3
'''


def compiled_update(calls):
    """The numpy stepping with only its modal update (``SharedRuns.advance``) compiled: compile
    time, the stepping's wall time and its separations."""
    space: dict = {}
    exec(UPDATE, space)  # noqa: S102
    kernel = space["advance"]

    def advance(self, z, f):
        out = np.empty((z.shape[0], 4))
        kernel(self.e1, self.R, self.P, self.scale, self.group, z.view(float), f, out)
        return out

    t0 = time.perf_counter()
    system, k1, alpha, beta, speed, step, max_time = calls[0]
    rows = min(2, system.omega.shape[0])
    real = modal_update.SharedRuns.advance
    modal_update.SharedRuns.advance = advance
    try:
        k1, alpha = (np.broadcast_to(x, system.omega.shape[:1])[:rows] for x in (k1, alpha))
        march_module.march(system.rows(0, rows), k1, alpha, beta[:rows], speed[:rows], step,
                           max_time)
        t_compile = time.perf_counter() - t0
        elapsed, _, seps = numpy_stepping(calls)
    finally:
        modal_update.SharedRuns.advance = real
    return t_compile, elapsed, seps


def compiled_stepping(calls, fastmath: bool):
    """The compiled stepping's compile time, wall time and results."""
    space: dict = {}
    exec(KERNEL.replace("FASTMATH", str(fastmath)), space)  # noqa: S102
    kernel = space["march"]
    inputs = []
    for system, k1, alpha, beta, speed, step, max_time in calls:
        n = system.omega.shape[0]
        c = march_module._coefficients(system, step, k1, alpha, beta)
        if not isinstance(c.modal, modal_update.SharedRuns) or np.any(c.modal.group):
            raise SystemExit("bench_kernel: expected one bat's shared modes per call")
        inputs.append((c.modal.e1[0], c.modal.R[0], c.modal.P[0],
                       np.ascontiguousarray(c.modal.scale[:, 0::2]), c.ka, c.b0,
                       c.c0, c.cb, c.ca, c.w6, c.v6, c.lk1, c.ab, c.beta,
                       np.broadcast_to(speed, (n,)).astype(float), step,
                       int(np.ceil(max_time / step)), np.zeros(n), np.full(n, np.nan)))
    t0 = time.perf_counter()
    rows = inputs[0][3].shape[0]
    small = tuple(a[:2] if isinstance(a, np.ndarray) and a.ndim and a.shape[0] == rows else a
                  for a in inputs[0])
    kernel(*small)
    t_compile = time.perf_counter() - t0
    t0 = time.perf_counter()
    for args in inputs:
        kernel(*args)
    elapsed = time.perf_counter() - t0
    return t_compile, elapsed, [(a[-2], a[-1]) for a in inputs]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--impacts", type=int, default=8192)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()
    n = args.impacts
    figures: dict[str, float] = {}

    total, stepping, calls = engine_run(n)
    print(f"engine, {n} random aluminium-34 impacts: {n / total:7.0f} impacts/s "
          f"({1e6 * total / n:.1f} us per impact, of which stepping {1e6 * stepping / n:.1f} us "
          f"with the restitution law) [target {TARGET}]")
    t_np, steps, seps = numpy_stepping(calls)
    ns_np = 1e9 * t_np / steps
    print(f"numpy stepping, beta fixed: {ns_np:6.0f} ns per impact-step "
          f"({steps / n:.0f} steps per impact)")
    figures.update(engine_impacts_per_s=n / total, engine_us=1e6 * total / n,
                   stepping_us=1e6 * stepping / n, numpy_ns_per_impact_step=ns_np,
                   steps_per_impact=steps / n)
    try:
        t0 = time.perf_counter()
        import numba  # noqa: F401
        t_import = time.perf_counter() - t0
    except ImportError:
        print("numba is not installed: the compiled kernel is not measured "
              "(pip install numba, then run this again)")
    else:
        for fastmath in (False, True):
            t_compile, t_nb, res = compiled_stepping(calls, fastmath)
            impulse = np.concatenate([r[0] for r in res])
            ref = np.concatenate([s.impulse for s in seps])
            diff = float(np.max(np.abs(impulse - ref) / np.abs(ref)))
            ns_nb = 1e9 * t_nb / steps
            with_nb = total - stepping + t_nb * stepping / t_np  # the law's share kept as numpy's
            label = "fastmath" if fastmath else "strict"
            print(f"numba {label:8s}: {ns_nb:6.0f} ns per impact-step ({ns_np / ns_nb:.2f}x numpy); "
                  f"impulses differ from numpy's by at most {diff:.1e}; import {t_import:.2f} s, "
                  f"compile {t_compile:.2f} s; engine with it: about "
                  f"{n / with_nb:7.0f} impacts/s")
            figures[f"numba_{label}_ns_per_impact_step"] = ns_nb
            figures[f"numba_{label}_engine_impacts_per_s"] = n / with_nb
            figures["numba_import_s"] = t_import
            figures[f"numba_{label}_compile_s"] = t_compile
        t_compile, t_up, up = compiled_update(calls)
        diff = float(np.max(np.abs(np.concatenate([u.impulse for u in up]) - ref) / np.abs(ref)))
        with_up = total - stepping + t_up * stepping / t_np
        print(f"numba, the modal update alone (fastmath), the rest numpy: {1e9 * t_up / steps:6.0f} "
              f"ns per impact-step ({t_np / t_up:.2f}x numpy); impulses differ by at most "
              f"{diff:.1e}; compile {t_compile:.2f} s; engine with it: about "
              f"{n / with_up:7.0f} impacts/s")
        figures["numba_update_ns_per_impact_step"] = 1e9 * t_up / steps
        figures["numba_update_engine_impacts_per_s"] = n / with_up
    if args.json:
        args.json.write_text(json.dumps(figures, indent=2) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
