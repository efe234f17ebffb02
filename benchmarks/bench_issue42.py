"""Issue 42's table: the commands a user feels, before and after, in one run. Prints figures;
asserts nothing.

    python benchmarks/bench_issue42.py [--repeat 5] [--before EXE] [--json FILE]

Each command is run by the installed ``batcert`` (and, with ``--before``, by another
installation's ``batcert``, e.g. a virtual environment with an older version), each run a fresh
process, warm (each installation's own cache directory, filled by a first run) unless said,
in rounds that alternate every command of both installations with ``python -c "import
numpy"``, so that a drifting machine loads all alike. The figure is the median of the rounds
and its ratio to the numpy import's median. Then hollow impacts per second: 10,000 random
impacts on ``aluminium-34`` through the flexible engine in one batch, best of 3, in each
installation's Python (the engine's caches emptied before each).

BLAS is pinned to one thread (as the command pins it since issue 42, and as a sweep's workers
run); ``PYTHONDONTWRITEBYTECODE`` is dropped (compiled bytecode, as an installed package has).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from alternating import installed_batcert, timed_command

# name -> (arguments, aim as a ratio to the numpy import, aim [s] or None, cold)
COMMANDS: dict[str, tuple[list[str], float | None, float | None, bool]] = {
    "run ash-34 -p proposed": (["run", "ash-34", "-p", "proposed"], 2.5, None, False),
    "run aluminium-34 -p ncaa-bbcor": (["run", "aluminium-34", "-p", "ncaa-bbcor"], 2.5, None,
                                       False),
    "compare --study smith2001": (["compare", "--study", "smith2001"], 3.0, None, False),
    "sweep aluminium-34 --vary wall=60%:140%:9": (["sweep", "aluminium-34", "-p", "ncaa-bbcor",
                                                   "--vary", "wall=60%:140%:9"], 5.0, None,
                                                  False),
    "design aluminium-34 --solve wall": (["design", "aluminium-34", "-p", "ncaa-bbcor",
                                          "--solve", "wall"], 5.0, None, False),
    "design aluminium-34 --solve wall (cold)": (["design", "aluminium-34", "-p", "ncaa-bbcor",
                                                 "--solve", "wall"], None, 1.5, True),
    "field bbcor-alloy-34 --batter college": (["field", "bbcor-alloy-34", "--batter",
                                               "college"], 4.0, None, False),
    "run aluminium-34 --uncertainty 1000": (["run", "aluminium-34", "-p", "ncaa-bbcor",
                                             "--uncertainty", "1000"], 10.0, None, False),
}

IMPACTS = """
import sys, time
import numpy as np
from batcert import workspace
from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import ImpactBatch
from batcert.engines.flexible import FlexibleEngine
engine = FlexibleEngine()
ball = load_protocol_any("proposed").ball.model
bat = load_bat_any("aluminium-34").built.model
rng = np.random.default_rng(1)
n = 10_000
z = rng.uniform(bat.length - 0.30, bat.length - 0.03, n)
batch = ImpactBatch(z - 0.1524, -rng.uniform(20, 45, n), rng.uniform(0, 60, n))
engine.solve(bat, ball, 0.1524, ImpactBatch(batch.impact_location[:5], batch.pitch_speed[:5],
                                            batch.bat_angular_speed[:5]))
best = float("inf")
for _ in range(3):
    for kind in ("step-exponentials", "beam-response", "patch-flexibility", "patch-factors"):
        workspace.current().clear(kind)  # what a fresh process starts without (bench_engine)
    t = time.perf_counter()
    engine.solve(bat, ball, 0.1524, batch)
    best = min(best, time.perf_counter() - t)
print(n / best)
"""


def _python_of(exe: str) -> str:
    python = Path(exe).with_name("python")
    return str(python) if python.exists() else sys.executable


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--before", help="another installation's batcert executable")
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()
    now_exe, python = installed_batcert()
    exes = {"now": now_exe, **({"before": args.before} if args.before else {})}
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    times: dict[tuple[str, str], list[float]] = {}
    base: list[float] = []
    with tempfile.TemporaryDirectory() as tmp:
        cwd = Path(tmp)

        def command(who: str, name: str) -> tuple[list[str], dict[str, str]]:
            argv, _, _, cold = COMMANDS[name]
            cache = cwd / f"cache-{who}"
            if cold:
                cache = cwd / f"cold-{who}"
                shutil.rmtree(cache, ignore_errors=True)
            return ([exes[who], *argv, "--out", str(cwd / f"reports-{who}")],
                    dict(env, BATCERT_CACHE_DIR=str(cache)))

        for who in exes:  # each installation's warm cache, filled as a user's first run does
            for name in COMMANDS:
                argv, run_env = command(who, name)
                timed_command(argv, cwd, run_env)
        for _ in range(args.repeat):
            base.append(timed_command([python, "-c", "import numpy"], cwd, env))
            for name in COMMANDS:
                for who in exes:
                    argv, run_env = command(who, name)
                    times.setdefault((who, name), []).append(timed_command(argv, cwd, run_env))
        rates = {who: float(subprocess.run([_python_of(exe), "-c", IMPACTS], cwd=cwd, env=env,
                                           capture_output=True, text=True, check=True)
                            .stdout.split()[-1]) for who, exe in exes.items()}
    numpy_s = statistics.median(base)
    print(f"{os.cpu_count()} CPUs, median of {args.repeat}; `python -c \"import numpy\"` "
          f"{numpy_s * 1e3:.0f} ms")
    whos = list(exes)[::-1]  # before, now
    print("| command | " + " | ".join(whos) + " | aim |")
    print("|---|" + "---|" * len(whos) + "---|")
    figures: dict[str, dict[str, float]] = {}
    for name, (_, ratio, seconds, _) in COMMANDS.items():
        cells = []
        for who in whos:
            med = statistics.median(times[(who, name)])
            figures.setdefault(name, {})[who] = med
            cells.append(f"{med:.2f} s = {med / numpy_s:.1f}x")
        aim = f"<= {ratio:g}x" if ratio is not None else f"<= {seconds:g} s"
        print(f"| {name} | " + " | ".join(cells) + f" | {aim} |")
    print("| hollow impacts per second (10,000 in a batch) | "
          + " | ".join(f"{rates[w]:,.0f} = {1e6 / rates[w]:.0f} us each" for w in whos)
          + " | 30 us each |")
    if args.json:
        args.json.write_text(json.dumps({"numpy_import": numpy_s, "commands": figures,
                                         "impacts_per_second": rates}, indent=1))


if __name__ == "__main__":
    main()
