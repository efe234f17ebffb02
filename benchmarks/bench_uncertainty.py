"""`batcert run BAT -p ncaa-bbcor --uncertainty N` as a user runs it, for every shipped bat:
wall time of the whole command (imports, nominal run, N Monte Carlo draws, reports) and the
pass probability it reports. Prints figures; asserts nothing.

    python benchmarks/bench_uncertainty.py [--draws N] [--repeat R] [--json FILE]

Uses the `batcert` on PATH (the installed package, as CI does), from a scratch directory.
Target (issue 12, 2-core machine): under 5 s with N = 1000 for each shipped bat.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

from alternating import installed_batcert

BATS = ("ash-34", "aluminium-34", "bbcor-alloy-34", "r161")
TARGET_S = 5.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    args = parser.parse_args()
    exe, _ = installed_batcert()
    figures: dict[str, dict[str, float]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for bat in BATS:
            cmd = [exe, "run", bat, "-p", "ncaa-bbcor", "--uncertainty", str(args.draws),
                   "--out", str(Path(tmp) / "reports")]
            times, report = [], {}
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                proc = subprocess.run(cmd + ["--json"], cwd=tmp, capture_output=True, text=True)
                times.append(time.perf_counter() - t0)
                if proc.returncode not in (0, 1):
                    raise SystemExit(f"{' '.join(cmd)} failed ({proc.returncode}):\n{proc.stderr}")
                report = json.loads(proc.stdout)["results"][0]
            u = report["uncertainty"]
            med = statistics.median(times)
            figures[bat] = {"median_s": med, "min_s": min(times), "value": report["value"],
                            "mean": u["mean"], "standard_deviation": u["standard_deviation"],
                            "pass_probability": u["pass_probability"],
                            "full_run_difference": u["full_run_difference"]}
            print(f"run {bat:<15} -p ncaa-bbcor --uncertainty {args.draws}: median {med:5.2f} s "
                  f"(min {min(times):5.2f}) [target {TARGET_S} s]; BBCOR {u['mean']:.4f} "
                  f"+/- {u['standard_deviation']:.4f}, P(pass) {u['pass_probability']:.3f}, "
                  f"full-run check {u['full_run_difference']:.1e}")
    if args.json:
        args.json.write_text(json.dumps({"batcert": exe, "draws": args.draws,
                                         "figures": figures}, indent=1) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
