"""`batcert field` as a user runs it: every shipped bat under every batter profile, one command
each (`batcert field BAT --batter PROFILE --no-reports -q`), warm (the cache directory filled
by a first pass), against `python -c "import numpy"` in the same run. Prints figures; asserts
nothing.

    python benchmarks/bench_field.py [--repeat N] [--quick] [--json FILE]

Uses the `batcert` on PATH from a scratch directory. Each command runs `--repeat` times (default
1) alternating with the numpy baseline. Target (issue 28, 2-core machine): every bat and profile
under 1 s warm. ``--quick`` (as CI runs it): three bats, a solid, an alloy and a composite, under
every profile (36 commands instead of 120, about 45 s).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import tempfile
from pathlib import Path

from alternating import installed_batcert, timed_command

TARGET = 1.0  # [s], warm, each bat and profile
QUICK_BATS = ("ash-34", "aluminium-34", "composite-bbcor-34")  # a solid, an alloy, a composite


def wall(args: list[str], cwd: Path, env: dict[str, str]) -> float:
    return timed_command(args, cwd, env, allowed=(0,))


def shipped(python: str, kind: str) -> list[str]:
    code = f"from batcert.specs.resolve import shipped_names; print(*shipped_names({kind!r}))"
    return subprocess.run([python, "-c", code], capture_output=True, text=True,
                          check=True).stdout.split()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    parser.add_argument("--quick", action="store_true", help="three bats, not every shipped one")
    args = parser.parse_args()
    exe, python = installed_batcert()
    bats, batters = shipped(python, "bat"), shipped(python, "batter")
    if args.quick:
        bats = [b for b in bats if b in QUICK_BATS]
    times: dict[str, list[float]] = {}
    base: list[float] = []
    with tempfile.TemporaryDirectory() as tmp:
        cwd = Path(tmp)
        env = dict(os.environ, BATCERT_CACHE_DIR=str(cwd / "cache"), OPENBLAS_NUM_THREADS="1",
                   OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
        for bat in bats:  # fill the cache (barrel shells, modes): the warm runs follow
            wall([exe, "field", bat, "--batter", "all", "--no-reports", "-q"], cwd, env)
        for _ in range(args.repeat):
            for bat in bats:
                for who in batters:
                    base.append(wall([python, "-c", "import numpy"], cwd, env))
                    times.setdefault(f"{bat} / {who}", []).append(wall(
                        [exe, "field", bat, "--batter", who, "--no-reports", "-q"], cwd, env))
    numpy_s = statistics.median(base)
    medians = {k: statistics.median(v) for k, v in times.items()}
    worst = max(medians, key=medians.__getitem__)
    print(f"python -c 'import numpy': median {numpy_s:.3f} s over {len(base)} runs")
    print(f"{'bat / batter':48s} {'median s':>9s} {'x numpy':>8s}")
    for k, v in medians.items():
        print(f"{k:48s} {v:9.3f} {v / numpy_s:8.1f}")
    print(f"slowest: {worst}, {medians[worst]:.3f} s ({medians[worst] / numpy_s:.1f}x numpy); "
          f"median of all {statistics.median(medians.values()):.3f} s; target {TARGET:.1f} s "
          f"each: {'met' if medians[worst] <= TARGET else 'NOT met'}")
    if args.json:
        args.json.write_text(json.dumps({"numpy_s": numpy_s, "median_s": medians}, indent=2))


if __name__ == "__main__":
    main()
