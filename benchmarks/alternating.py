"""Wall times of short Python programs, each a fresh process, run in turns and compared with
``python -c "import numpy"`` (the benchmarks' yardstick): the measuring loop of
bench_exit.py and bench_laminate.py; and the installed ``batcert`` command that the command
benchmarks time (bench_cli.py, bench_commands.py, bench_field.py, bench_scaling.py,
bench_uncertainty.py), one run at a time (:func:`timed_command`)."""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

BASELINE = "numpy import (baseline)"


def installed_batcert() -> tuple[str, str]:
    """The ``batcert`` on PATH and the Python it is installed in (this one if none beside it);
    exits with a message when batcert is not installed."""
    exe = shutil.which("batcert")
    if exe is None:
        raise SystemExit("no `batcert` on PATH: install the package first (pip install .)")
    python = Path(exe).with_name("python")
    return exe, str(python) if python.exists() else sys.executable


def timed_command(args: list[str], cwd: Path, env: dict[str, str],
                  allowed: tuple[int, ...] = (0, 1)) -> float:
    """Wall time [s] of one run of ``args`` (a fresh process) in ``cwd`` with ``env``; exits
    with the command's error output when its exit code is not among ``allowed`` (1: a verdict
    of fail, which is a result)."""
    t0 = time.perf_counter()
    proc = subprocess.run(args, cwd=cwd, capture_output=True, text=True, env=env)
    elapsed = time.perf_counter() - t0
    if proc.returncode not in allowed:
        raise SystemExit(f"{' '.join(map(str, args))} failed ({proc.returncode}):\n"
                         f"{proc.stderr}")
    return elapsed


def median_times(cases: dict[str, str], repeat: int) -> dict[str, float]:
    """The median wall time [s] of ``python -c CODE`` for each named case, the baseline
    (``import numpy``) added; the cases run in turns, so that a drifting machine loads all
    alike."""
    programs = {BASELINE: "import numpy", **cases}
    times: dict[str, list[float]] = {k: [] for k in programs}
    for _ in range(repeat):
        for name, code in programs.items():
            t = time.perf_counter()
            subprocess.run([sys.executable, "-c", code], check=True)
            times[name].append(time.perf_counter() - t)
    return {name: statistics.median(ts) for name, ts in times.items()}


def print_ratios(medians: dict[str, float], width: int = 26) -> None:
    """Each case's median and its ratio to the baseline's."""
    base = medians[BASELINE]
    for name, med in medians.items():
        print(f"{name:{width}s} {med * 1e3:7.0f} ms  x{med / base:5.2f} numpy import")
