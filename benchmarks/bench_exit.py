"""Why the command line leaves through ``os._exit`` (batcert.cli.base._exit_now): the wall time
of a process that has done what a ``run`` does (the library's run of a shipped bat, numpy and
scipy loaded) and then exits through the interpreter's shutdown (``sys.exit``) or without it
(``os._exit``, after flushing and the exit handlers), against ``python -c "import numpy"``.
Prints figures; asserts nothing.

    python benchmarks/bench_exit.py [--repeat N]
"""

from __future__ import annotations

import argparse

from alternating import BASELINE, median_times, print_ratios

WORK = """
import os, sys
import batcert.api as api
api.run(api.load_bat("ash-34"), api.load_protocol("ncaa-bbcor"), engine="rigid")
import scipy.linalg, scipy.optimize
"""
WAYS = {"run, then sys.exit": WORK + "sys.exit(0)",
        "run, then os._exit": WORK + "sys.stdout.flush(); os._exit(0)"}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    medians = median_times(WAYS, args.repeat)
    print_ratios(medians)
    saved = medians["run, then sys.exit"] - medians["run, then os._exit"]
    print(f"os._exit saves {saved * 1e3:.0f} ms ({saved / medians[BASELINE]:.2f} numpy imports) "
          "per command")


if __name__ == "__main__":
    main()
