"""A laminated barrel against an alloy one: the wall time of a ``run`` of the shipped composite
and alloy BBCOR bats under a protocol without break-in (astm-bpf: the impacts only, a cold
process each), and under ncaa-bbcor (the composite's emulated ABI runs the test twice and reads
its compression every pass), against ``python -c "import numpy"``. Issue 26's target: a
laminate hollow run within 1.5x of an alloy one. Prints figures; asserts nothing.

    python benchmarks/bench_laminate.py [--repeat N]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

RUN = ("import batcert.api as api\n"
       "api.run(api.load_bat({bat!r}), api.load_protocol({protocol!r}))\n")
CASES = {"numpy import (baseline)": "import numpy"}
for _protocol in ("astm-bpf", "ncaa-bbcor"):
    for _bat in ("bbcor-alloy-34", "composite-bbcor-34"):
        CASES[f"{_bat} / {_protocol}"] = RUN.format(bat=_bat, protocol=_protocol)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    times: dict[str, list[float]] = {k: [] for k in CASES}
    for _ in range(args.repeat):  # alternating, so that a drifting machine loads all alike
        for name, code in CASES.items():
            t = time.perf_counter()
            subprocess.run([sys.executable, "-c", code], check=True)
            times[name].append(time.perf_counter() - t)
    base = statistics.median(times["numpy import (baseline)"])
    for name, ts in times.items():
        med = statistics.median(ts)
        print(f"{name:36s} {med * 1e3:7.0f} ms  x{med / base:5.2f} numpy import")
    for protocol in ("astm-bpf", "ncaa-bbcor"):
        ratio = (statistics.median(times[f"composite-bbcor-34 / {protocol}"])
                 / statistics.median(times[f"bbcor-alloy-34 / {protocol}"]))
        print(f"composite / alloy under {protocol}: x{ratio:.2f} (target 1.5 without break-in)")


if __name__ == "__main__":
    main()
