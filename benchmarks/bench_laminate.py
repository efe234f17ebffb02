"""A laminated barrel against an alloy one: the wall time of a ``run`` of the shipped composite
and alloy BBCOR bats under a protocol without break-in (astm-bpf: the impacts only, a cold
process each), and under ncaa-bbcor (the composite's emulated ABI runs the test twice and reads
its compression every pass), against ``python -c "import numpy"``. Issue 26's target: a
laminate hollow run within 1.5x of an alloy one. Prints figures; asserts nothing.

    python benchmarks/bench_laminate.py [--repeat N]
"""

from __future__ import annotations

import argparse

from alternating import median_times, print_ratios

RUN = ("import batcert.api as api\n"
       "api.run(api.load_bat({bat!r}), api.load_protocol({protocol!r}))\n")
CASES = {f"{bat} / {protocol}": RUN.format(bat=bat, protocol=protocol)
         for protocol in ("astm-bpf", "ncaa-bbcor")
         for bat in ("bbcor-alloy-34", "composite-bbcor-34")}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    medians = median_times(CASES, args.repeat)
    print_ratios(medians, width=36)
    for protocol in ("astm-bpf", "ncaa-bbcor"):
        ratio = (medians[f"composite-bbcor-34 / {protocol}"]
                 / medians[f"bbcor-alloy-34 / {protocol}"])
        print(f"composite / alloy under {protocol}: x{ratio:.2f} (target 1.5 without break-in)")


if __name__ == "__main__":
    main()
