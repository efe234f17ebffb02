"""End-to-end timing of `batcert run` (start-up, specs, engine, reports), printed, not asserted.

Target (issue 3): `batcert run bats/ash-34.yaml --protocol proposed` within 2 s end to end.
Run from the repository root: `python benchmarks/bench_run.py`.
"""

from __future__ import annotations

import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def time_command(args: list[str], repeats: int = 3) -> list[float]:
    times = []
    for _ in range(repeats):
        out = tempfile.mkdtemp()
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "batcert.cli", *args, "--out", out],
                              cwd=ROOT, capture_output=True, text=True)
        times.append(time.perf_counter() - t0)
        shutil.rmtree(out, ignore_errors=True)
        if proc.returncode not in (0, 1):
            print(proc.stderr)
            raise SystemExit(f"command failed with exit code {proc.returncode}")
    return times


def main() -> None:
    print("batcert end-to-end (python -m batcert.cli ...; start-up and reports included)")
    for engine in ("flexible", "rigid"):
        for bat in ("bats/ash-34.yaml", "bats/aluminium-34.yaml"):
            t = time_command(["run", bat, "--protocol", "proposed", "--engine", engine])
            print(f"  run {bat:<24} --protocol proposed --engine {engine:<8}: "
                  f"median {statistics.median(t):.2f} s (min {min(t):.2f} s, {len(t)} runs; "
                  "target 2 s)")
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import batcert.cli"], cwd=ROOT, check=True)
    print(f"  python start-up + import batcert.cli: {time.perf_counter() - t0:.2f} s")


if __name__ == "__main__":
    main()
