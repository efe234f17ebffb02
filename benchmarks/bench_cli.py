"""The installed `batcert` command as a user runs it: wall time of whole commands against
`python -c "import numpy"` on the same machine. Prints figures; asserts nothing.

    python benchmarks/bench_cli.py [--repeat N] [--json FILE]

Uses the `batcert` on PATH (the installed package, with its compiled bytecode: run it after
`pip install .`, as CI does), from a scratch directory so that shipped names resolve from the
installation. Each command runs `--repeat` times (default 7), alternating with the numpy
baseline so that a drifting machine loads both alike; figures are the minimum and median wall
time and the ratio of medians to the baseline. batcert's cache directory (batcert.cache:
compiled templates, hollow bats' barrels) is a scratch one, warm as for a user's second run;
the commands on hollow bats run again with an empty cache each time, as a first run does.
Targets (issue 9, 2-core machine): `run ash-34 --protocol proposed` <= 0.25 s, `--engine
rigid` <= 0.2 s, the study replay (the 2001 study's five protocols on its two bats) <= 0.4 s.
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

COMMANDS = {
    "run ash-34 proposed": ["run", "ash-34", "--protocol", "proposed"],
    "run ash-34 proposed --engine rigid": ["run", "ash-34", "--protocol", "proposed",
                                           "--engine", "rigid"],
    "run ash-34 proposed --json": ["run", "ash-34", "--protocol", "proposed", "--json"],
    "run aluminium-34 proposed": ["run", "aluminium-34", "--protocol", "proposed"],
    "run aluminium-34 ncaa-bbcor": ["run", "aluminium-34", "--protocol", "ncaa-bbcor"],
    "compare smith2001 replay": ["compare", "ash-34", "aluminium-34", *[
        a for p in ("{studies}/smith2001-bpf-cop.yaml", "{studies}/smith2001-besr-sweet-spot.yaml",
                    "{studies}/smith2001-bpf-sweet-spot.yaml", "proposed",
                    "{studies}/smith2001-besr-matched.yaml") for a in ("-p", p)]],
    "compare --study smith2001": ["compare", "--study", "smith2001"],
    "inspect ash-34": ["inspect", "ash-34"],
}
# hollow bats' barrels are kept in the cache directory (batcert.cache): these run also with
# an empty cache each time, as a first run does
COLD = ("run aluminium-34 proposed", "compare smith2001 replay", "compare --study smith2001")
TARGETS = {"run ash-34 proposed": 0.25, "run ash-34 proposed --engine rigid": 0.2,
           "compare smith2001 replay": 0.4}


def wall(args: list[str], cwd: Path, cache: Path) -> float:
    return timed_command(args, cwd, dict(os.environ, BATCERT_CACHE_DIR=str(cache)))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    args = parser.parse_args()
    exe, python = installed_batcert()
    figures: dict[str, dict[str, float]] = {}
    studies = subprocess.run(
        [python, "-c", "from batcert.specs.resolve import resolve; "
         "print(resolve('study', 'smith2001').parent)"],
        capture_output=True, text=True, check=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        cwd = Path(tmp)
        runs = [(name, cmd, False) for name, cmd in COMMANDS.items()]
        runs += [(name, COMMANDS[name], True) for name in COLD]
        for name, cmd, cold in runs:
            cmd = [a.format(studies=studies) for a in cmd]
            writes = cmd[0] in ("run", "compare", "league") and "--json" not in cmd
            full = [exe, *cmd] + (["--out", str(cwd / "reports")] if writes else [])
            warm = cwd / "cache"
            wall(full, cwd, warm)  # warm the file cache (and batcert's, for the warm figures)
            times, base = [], []
            for i in range(args.repeat):
                base.append(wall([python, "-c", "import numpy"], cwd, warm))
                times.append(wall(full, cwd, cwd / f"cold-{name}-{i}" if cold else warm))
            med, med_base = statistics.median(times), statistics.median(base)
            label = name + (" (empty cache)" if cold else "")
            figures[label] = {"min_s": min(times), "median_s": med,
                              "numpy_import_s": med_base, "ratio_to_numpy_import": med / med_base}
            target = None if cold else TARGETS.get(name)
            print(f"{label:<42} median {med:5.2f} s (min {min(times):5.2f}); "
                  f"{med / med_base:4.1f}x `import numpy` ({med_base:.3f} s)"
                  + (f"  [target {target} s]" if target else ""))
    if args.json:
        args.json.write_text(json.dumps({"batcert": exe, "repeat": args.repeat,
                                         "figures": figures}, indent=1) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
