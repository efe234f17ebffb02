"""Compare two runs of a benchmark: the figures two ``--json FILE`` outputs share, side by side.

    python benchmarks/compare_figures.py BEFORE.json AFTER.json

Every number in either file (nested entries joined with ``/``) is listed with its value before,
after, and the ratio after / before; figures only one file has are listed apart. Whether a
ratio above 1 is better depends on the figure (a time or an error: lower is better; impacts per
second: higher), so the ratio is printed, not judged. Exits 2 if a file cannot be read.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path


def numbers(data, prefix: str = "") -> dict[str, float]:
    """Every number in ``data`` (dicts and lists nested), keyed by its path."""
    out: dict[str, float] = {}
    if isinstance(data, dict):
        for key, value in data.items():
            out.update(numbers(value, f"{prefix}/{key}" if prefix else str(key)))
    elif isinstance(data, list):
        for i, value in enumerate(data):
            out.update(numbers(value, f"{prefix}/{i}" if prefix else str(i)))
    elif isinstance(data, (int, float)) and not isinstance(data, bool):
        out[prefix] = float(data)
    return out


def compare(before: dict[str, float], after: dict[str, float]) -> list[str]:
    """The lines of the comparison table."""
    width = max((len(k) for k in before.keys() | after.keys()), default=6)
    lines = [f"{'figure':<{width}}  {'before':>12}  {'after':>12}  {'after/before':>12}"]
    for key in sorted(before.keys() & after.keys()):
        b, a = before[key], after[key]
        ratio = f"{a / b:12.3f}" if b != 0 else f"{'-':>12}"
        lines.append(f"{key:<{width}}  {b:12.6g}  {a:12.6g}  {ratio}")
    for name, only in (("before", before.keys() - after.keys()),
                       ("after", after.keys() - before.keys())):
        for key in sorted(only):
            value = before[key] if name == "before" else after[key]
            lines.append(f"{key:<{width}}  only {name}: {value:.6g}")
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path)
    parser.add_argument("after", type=Path)
    args = parser.parse_args()
    loaded = []
    for path in (args.before, args.after):
        try:
            loaded.append(numbers(json.loads(path.read_text())))
        except (OSError, ValueError) as exc:
            print(f"compare_figures: cannot read {path}: {exc}", file=sys.stderr)
            raise SystemExit(2) from None
    print("\n".join(compare(*loaded)))


if __name__ == "__main__":
    main()
