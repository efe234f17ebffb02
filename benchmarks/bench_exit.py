"""Why the command line leaves through ``os._exit`` (batcert.cli.base._exit_now): the wall time
of a process that has done what a ``run`` does (the library's run of a shipped bat, numpy and
scipy loaded) and then exits through the interpreter's shutdown (``sys.exit``) or without it
(``os._exit``, after flushing and the exit handlers), against ``python -c "import numpy"``.
Prints figures; asserts nothing.

    python benchmarks/bench_exit.py [--repeat N]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

WORK = """
import os, sys
import batcert.api as api
api.run(api.load_bat("ash-34"), api.load_protocol("ncaa-bbcor"), engine="rigid")
import scipy.linalg, scipy.optimize
"""
WAYS = {"numpy import (baseline)": "import numpy",
        "run, then sys.exit": WORK + "sys.exit(0)",
        "run, then os._exit": WORK + "sys.stdout.flush(); os._exit(0)"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    times: dict[str, list[float]] = {k: [] for k in WAYS}
    for _ in range(args.repeat):  # alternating, so that a drifting machine loads all alike
        for name, code in WAYS.items():
            t = time.perf_counter()
            subprocess.run([sys.executable, "-c", code], check=True)
            times[name].append(time.perf_counter() - t)
    base = statistics.median(times["numpy import (baseline)"])
    for name, ts in times.items():
        med = statistics.median(ts)
        print(f"{name:26s} {med * 1e3:7.0f} ms  x{med / base:5.2f} numpy import")
    saved = statistics.median(times["run, then sys.exit"]) - statistics.median(
        times["run, then os._exit"])
    print(f"os._exit saves {saved * 1e3:.0f} ms ({saved / base:.2f} numpy imports) per command")


if __name__ == "__main__":
    main()
