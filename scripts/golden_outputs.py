"""Capture, or compare against a capture, the JSON output of every command on the shipped inputs.

A behaviour-preserving change (a refactor, a speed-up) must leave every number the same. This
script runs every command that prints JSON (``run`` of each shipped bat under each shipped
protocol with both engines, ``inspect`` of each bat and ball, ``protocols``, ``compare --study``
with both engines, ``league`` of each shipped league) and either saves the outputs or compares
them with a saved set, number by number, to a relative tolerance.

    python scripts/golden_outputs.py save DIR          # before the change
    python scripts/golden_outputs.py check DIR         # after it: exit 1 on any difference

Fields that legitimately change between runs (creation time, batcert version, absolute paths) are
ignored. Fields present only in the new output are listed as added, not counted as differences: a
refactor may add information but must not change what was there. Run it with the package installed
(``pip install -e .``)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IGNORED = {"created", "batcert_version", "path", "file"}


def _names(folder: str) -> list[str]:
    return sorted(p.stem for p in (ROOT / folder).glob("*.yaml"))


def commands() -> dict[str, list[str]]:
    bats, protocols = _names("bats"), _names("protocols")
    out: dict[str, list[str]] = {}
    for engine in ("flexible", "rigid"):
        for bat in bats:
            for p in protocols:
                out[f"run--{bat}--{p}--{engine}"] = ["run", bat, "-p", p, "--engine", engine,
                                                     "--json", "--no-reports"]
        out[f"compare--smith2001--{engine}"] = ["compare", "--study", "smith2001", "--engine",
                                                engine, "--json", "--no-reports"]
    for bat in bats:
        out[f"inspect--{bat}"] = ["inspect", bat, "--json"]
    for ball in _names("protocols/balls"):
        out[f"inspect--{ball}"] = ["inspect", str(ROOT / "protocols" / "balls" / f"{ball}.yaml"),
                                   "--json"]
    out["protocols"] = ["protocols", "--json"]
    for league in _names("protocols/leagues"):
        out[f"league--{league}"] = ["league", league, *bats, "--json", "--no-reports"]
    return out


def capture(args: list[str]) -> object:
    proc = subprocess.run([sys.executable, "-m", "batcert", *args], capture_output=True,
                          text=True, cwd=ROOT)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"batcert {' '.join(args)} exited {proc.returncode}:\n{proc.stderr}")
    return {"exit": proc.returncode, "output": json.loads(proc.stdout)}


def differences(a: object, b: object, rtol: float, where: str = "") -> list[str]:
    """Every place where ``a`` and ``b`` differ (numbers beyond ``rtol`` relative)."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            if k in IGNORED:
                continue
            if k not in a:
                out.append(f"{where}.{k}: ADDED (only in the new output)")
                continue
            if k not in b:
                out.append(f"{where}.{k}: only in the saved output")
                continue
            out += differences(a[k], b[k], rtol, f"{where}.{k}")
        return out
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items saved, {len(b)} now"]
        return [d for i, (x, y) in enumerate(zip(a, b, strict=True)) for d in differences(x, y, rtol,
                                                                              f"{where}[{i}]")]
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if math.isclose(a, b, rel_tol=rtol, abs_tol=rtol * 1e-3):
            return []
        return [f"{where}: {a!r} saved, {b!r} now"]
    if a != b and not (isinstance(a, str) and isinstance(b, str) and where.endswith("path")):
        return [f"{where}: {a!r} saved, {b!r} now"]
    return []


def main(argv: list[str]) -> int:
    if len(argv) != 2 or argv[0] not in ("save", "check"):
        print(__doc__)
        return 2
    mode, folder = argv[0], Path(argv[1])
    folder.mkdir(parents=True, exist_ok=True)
    failed = new = 0
    for name, args in commands().items():
        path = folder / f"{name}.json"
        if mode == "check" and not path.exists():  # an input added since the capture
            print(f"{name}: new (not in the saved set; not compared)")
            new += 1
            continue
        got = capture(args)
        if mode == "save":
            path.write_text(json.dumps(got, indent=1, sort_keys=True))
            continue
        saved = json.loads(path.read_text())
        found = differences(saved, got, 1e-9)
        added = [d for d in found if d.endswith("ADDED (only in the new output)")]
        diffs = [d for d in found if d not in added]
        status = "same" if not diffs else f"{len(diffs)} differences"
        print(f"{name}: {status}" + (f" ({len(added)} fields added)" if added else ""))
        for d in diffs[:10] + added[:2]:
            print(f"    {d}")
        failed += bool(diffs)
    if mode == "check":
        print(f"{failed} of {len(commands()) - new} outputs differ ({new} new, not compared)")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
