"""Every slow command as a user runs it (issue 29's table): the installed ``batcert``, each run a
fresh process, warm (the cache directory filled by a first run) and cold (an empty cache
directory each time), median and minimum wall time and the median's ratio to ``python -c
"import numpy"`` timed in the same rounds. Prints the table; asserts nothing.

    python benchmarks/bench_commands.py [--repeat 3] [--only NAME] [--json FILE]

(CI runs it with the default ``--repeat 1``: about a minute and a half on 2 cores; the
figures in docs/performance.md are of ``--repeat 3``.)

BLAS is pinned to one thread (``OPENBLAS_NUM_THREADS``, ``OMP_NUM_THREADS``,
``MKL_NUM_THREADS`` = 1), as a worker of a sweep runs; ``PYTHONDONTWRITEBYTECODE`` is dropped,
so that the modules run from compiled bytecode as an installed package's do (with it, every
command pays 0.05-0.1 s compiling). Commands run from a scratch directory,
so that shipped names resolve from the installation; reports go to a scratch folder. The
rounds alternate the commands with the baseline, so that a drifting machine loads all alike.
Targets (issue 29, 2-core machine, warm unless said): ``run --uncertainty 1000`` <= 1 s,
``reduce`` <= 0.6 s, ``design --solve wall`` <= 0.6 s (cold <= 1.5 s), ``compare --study
smith2001`` <= 0.5 s, ``--figures`` on the study <= 2 s, ``run`` <= 2.5 x the numpy import.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

from alternating import installed_batcert, timed_command

REPO = Path(__file__).resolve().parents[1]
LAB = REPO / "examples" / "lab" / "synthetic-scatter.yaml"

# name -> (arguments, target [s] or None, target as a ratio to the numpy import or None, cold)
COMMANDS: dict[str, tuple[list[str], float | None, float | None, bool]] = {
    "run ash-34 -p proposed": (["run", "ash-34", "-p", "proposed"], None, 2.5, True),
    "run aluminium-34 -p ncaa-bbcor": (["run", "aluminium-34", "-p", "ncaa-bbcor"], None, 2.5,
                                       True),
    "run aluminium-34 --engine rigid": (["run", "aluminium-34", "-p", "ncaa-bbcor", "--engine",
                                         "rigid"], None, 2.5, True),
    "run aluminium-34 --uncertainty 1000": (["run", "aluminium-34", "-p", "ncaa-bbcor",
                                             "--uncertainty", "1000"], 1.0, None, True),
    "reduce synthetic-scatter": (["reduce", str(LAB), "-p", "ncaa-bbcor"], 0.6, None, True),
    "design aluminium-34 --solve wall": (["design", "aluminium-34", "-p", "ncaa-bbcor",
                                          "--solve", "wall"], 0.6, None, True),
    "compare --study smith2001": (["compare", "--study", "smith2001"], 0.5, None, True),
    "sweep wall=60%:140%:9": (["sweep", "aluminium-34", "-p", "ncaa-bbcor", "--vary",
                               "wall=60%:140%:9"], None, None, True),
    "compare --study smith2001 --figures": (["compare", "--study", "smith2001", "--figures",
                                             "{figures}"], 2.0, None, False),
}
COLD_TARGETS = {"design aluminium-34 --solve wall": 1.5}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--only", action="append", help="run only commands whose name has this")
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()
    exe, python = installed_batcert()
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # compiled bytecode, as an installed package has
    chosen = {k: v for k, v in COMMANDS.items()
              if not args.only or any(o in k for o in args.only)}
    with tempfile.TemporaryDirectory() as tmp:
        cwd = Path(tmp)
        warm_env = dict(env, BATCERT_CACHE_DIR=str(cwd / "cache"))
        full = {k: [exe, *(a.format(figures=cwd / "figures") for a in cmd), "--out",
                    str(cwd / "reports")] for k, (cmd, *_rest) in chosen.items()}
        for cmd in full.values():  # the warm runs' cache, filled as a user's first run does
            timed_command(cmd, cwd, warm_env)
        times: dict[str, list[float]] = {"numpy import": []}
        for _ in range(args.repeat):
            times["numpy import"].append(timed_command([python, "-c", "import numpy"], cwd, env))
            for name, cmd in full.items():
                times.setdefault(f"{name} (warm)", []).append(timed_command(cmd, cwd, warm_env))
                if chosen[name][3]:
                    cold = cwd / "cold"
                    shutil.rmtree(cold, ignore_errors=True)
                    times.setdefault(f"{name} (cold)", []).append(
                        timed_command(cmd, cwd, dict(env, BATCERT_CACHE_DIR=str(cold))))
    base = statistics.median(times["numpy import"])
    print(f"{os.cpu_count()} CPUs, Python {sys.version.split()[0]}, median of {args.repeat}; "
          f"`python -c \"import numpy\"` {base * 1e3:.0f} ms")
    print(f"| {'command':46s} | median | minimum | x numpy | target |")
    print(f"|{'-' * 48}|--------|---------|---------|--------|")
    figures = {}
    for name, ts in times.items():
        if name == "numpy import":
            continue
        command, warm = name.rsplit(" (", 1)
        _, target, ratio, _ = chosen[command]
        if warm.startswith("cold"):
            target, ratio = COLD_TARGETS.get(command), None
        med = statistics.median(ts)
        aim = (f"{target:g} s" if target is not None else
               f"{ratio:g} x" if ratio is not None else "")
        met = ("" if not aim else " met" if (target is None or med <= target) and
               (ratio is None or med / base <= ratio) else " NOT met")
        print(f"| {name:46s} | {med:5.2f}s | {min(ts):6.2f}s | {med / base:6.1f}x | "
              f"{aim}{met} |")
        figures[name] = {"median": med, "minimum": min(ts), "ratio": med / base}
    if args.json:
        args.json.write_text(json.dumps({"numpy_import": base, "commands": figures}, indent=1))


if __name__ == "__main__":
    main()
