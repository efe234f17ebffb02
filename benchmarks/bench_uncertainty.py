"""`batcert run BAT -p ncaa-bbcor --uncertainty N` as a user runs it: the wall time of the whole
command (imports, nominal run, the Monte Carlo, reports), warm (a first, untimed run fills a
scratch cache directory), with each propagation method (docs/uncertainty.md: the response
surface checked against the engine, and every draw solved by the engine), as a ratio to
``python -c "import numpy"`` timed in the same rounds; and the surface's distribution against
the full draws' (the same seed draws the same inputs, so the two agree draw by draw). Prints
the tables; asserts nothing.

    python benchmarks/bench_uncertainty.py [--draws N] [--repeat R] [--bats B ...]
        [--methods surrogate,full] [--before DIR] [--json FILE]

Uses the `batcert` on PATH (the installed package, as CI does), from a scratch directory, with
BLAS pinned to one thread as bench_commands.py does. ``--before DIR`` also times, in the same
rounds, the batcert of a source tree (``python -m batcert`` with ``PYTHONPATH=DIR``, without
``--uncertainty-method``; e.g. ``git archive`` of an earlier commit, for a before-and-after
table).
Targets (issue 42, 2-core machine): about 1 s, at most 10 x the numpy import, with N = 1000.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import tempfile
from pathlib import Path

import numpy as np
from alternating import installed_batcert, timed_command

BATS = ("ash-34", "aluminium-34", "bbcor-alloy-34", "r161")
TARGET_RATIO = 10.0  # x the numpy import


def _command(exe: list[str], bat: str, draws: int, method: str, out: Path) -> list[str]:
    cmd = [*exe, "run", bat, "-p", "ncaa-bbcor", "--uncertainty", str(draws), "--out", str(out)]
    return cmd if method == "before" else [*cmd, "--uncertainty-method", method]


def _report(cmd: list[str], cwd: Path, env: dict[str, str]) -> dict:
    proc = subprocess.run([*cmd, "--json"], cwd=cwd, capture_output=True, text=True, env=env)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)} failed ({proc.returncode}):\n{proc.stderr}")
    return json.loads(proc.stdout)["results"][0]


def _accuracy(reports: dict[tuple[str, str], dict], bats: list[str]) -> None:
    """The surface's distribution against the full draws' (same seed, same draws)."""
    print("\n| bat | method | mean | std | 2.5 % | 97.5 % | P(pass) | largest |surface - full| "
          "over all draws | surrogate check (engine runs) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---|")
    for bat in bats:
        full = reports.get((bat, "full"))
        for method in ("surrogate", "full"):
            r = reports.get((bat, method))
            if r is None:
                continue
            u = r["uncertainty"]
            p = u.get("propagation") or {}
            gap = "" if full is None or method == "full" else (
                f"{np.abs(np.array(u['values']) - full['uncertainty']['values']).max():.1e}")
            check = ("" if p.get("largest_difference") is None else
                     f"{p['largest_difference']:.1e} <= {p['bound']:g}? "
                     f"{p['method']} ({p['engine_draws']} runs)")
            print(f"| {bat} | {method} | {u['mean']:.6f} | {u['standard_deviation']:.6f} | "
                  f"{u['interval_low']:.5f} | {u['interval_high']:.5f} | "
                  f"{u['pass_probability']:.3f} | {gap} | {check} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--bats", nargs="+", default=list(BATS))
    parser.add_argument("--methods", default="surrogate,full", help="comma-separated")
    parser.add_argument("--before", type=Path, help="also time the batcert of this source tree")
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    args = parser.parse_args()
    exe, python = installed_batcert()
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    methods = args.methods.split(",") + (["before"] if args.before else [])
    cases = [(bat, m) for bat in args.bats for m in methods]
    with tempfile.TemporaryDirectory() as tmp:
        cwd = Path(tmp)
        env["BATCERT_CACHE_DIR"] = str(cwd / "cache")
        before = dict(env, PYTHONPATH=str(args.before.resolve())) if args.before else env

        def run(c, time_it):
            exe_env = (([python, "-m", "batcert"], before) if c[1] == "before" else ([exe], env))
            cmd = _command(exe_env[0], c[0], args.draws, c[1], cwd / "reports")
            return (timed_command(cmd, cwd, exe_env[1]) if time_it
                    else _report(cmd, cwd, exe_env[1]))

        reports = {c: run(c, False) for c in cases}  # also warms the cache
        times: dict[object, list[float]] = {"numpy": [], **{c: [] for c in cases}}
        for _ in range(args.repeat):  # in turns, so that a drifting machine loads all alike
            times["numpy"].append(timed_command([python, "-c", "import numpy"], cwd, env))
            for c in cases:
                times[c].append(run(c, True))
    base = statistics.median(times["numpy"])
    print(f"batcert {exe}" + (f", before: {args.before}" if args.before else "")
          + f"; {args.repeat} rounds; `python -c \"import numpy\"` {base:.3f} s")
    print(f"| run BAT -p ncaa-bbcor --uncertainty {args.draws} | method | median | minimum | "
          f"x numpy | target x{TARGET_RATIO:g} |")
    print("|---|---|---:|---:|---:|---|")
    figures = {}
    for c in cases:
        med = statistics.median(times[c])
        ratio = med / base
        print(f"| {c[0]} | {c[1]} | {med:.2f} s | {min(times[c]):.2f} s | {ratio:.1f} | "
              f"{'met' if ratio <= TARGET_RATIO else 'not met'} |")
        u = reports[c]["uncertainty"]
        figures[f"{c[0]} {c[1]}"] = {
            "median_s": med, "min_s": min(times[c]), "ratio_to_numpy": ratio,
            "mean": u["mean"], "standard_deviation": u["standard_deviation"],
            "pass_probability": u["pass_probability"],
            "full_run_difference": u["full_run_difference"],
            "propagation": u.get("propagation")}
    _accuracy(reports, args.bats)
    if args.json:
        args.json.write_text(json.dumps({"batcert": exe, "draws": args.draws,
                                         "numpy_import_s": base, "figures": figures},
                                        indent=1) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
