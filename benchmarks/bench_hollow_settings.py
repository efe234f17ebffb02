"""What a hollow bat's speed costs in accuracy: the engine's defaults against fewer bending
modes and a longer step. Prints figures; asserts nothing.

    python benchmarks/bench_hollow_settings.py [--variants] [--json FILE]

For each setting: impacts per second on 20,000 random aluminium-34 impacts (bench_kernel.py's
batch; the best of 3), and the largest relative difference from the converged engine (48 modes,
2.5 us, shell modes to 16 kHz) of every exit speed and metric of the shipped protocols, on
aluminium-34 and on its wall made 1.8 mm (the worst case of tests/engines/test_convergence.py).
``--variants`` (about 5 minutes) adds bbcor-alloy-34 and 20 variants of the two hollow bats:
walls of 1.6-3.4 mm, Young's modulus x 0.8 and x 1.2, barrels of 63.5 and 70 mm. The
settings: the defaults (16 bending modes, 12.5 us); the 11 bending modes below the 10 kHz shell
cut; a 16 us step; both; both with 10 bending modes. docs/performance.md ("A longer hollow
step, fewer bending modes") keeps the defaults from these figures. Target (issue 9): 50,000
impacts per second, within 2e-4 of converged.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "tests" / "engines"))

from bench_engine import (  # noqa: E402
    CONVERGED,
    SHIPPED_PROTOCOLS,
    clear_engine_caches,
    largest_difference,
    protocol_values,
)
from bench_kernel import random_batch  # noqa: E402

from batcert.commands.inputs import load_bat_any, load_protocol_any  # noqa: E402
from batcert.engines.flexible import FlexibleEngine  # noqa: E402

SETTINGS = {"defaults": {}, "11 bending modes": dict(n_modes=11),
            "16 us step": dict(time_step=16e-6), "both": dict(n_modes=11, time_step=16e-6),
            "both, 10 modes": dict(n_modes=10, time_step=16e-6)}
IMPACTS = 20_000


def variant(name: str, parameter: str, value: float):
    """The shipped bat ``name`` with one sweep parameter set to ``value`` (SI)."""
    from batcert.model.build import build_bat
    from batcert.sweeps.variants import Case, lookup_parameter

    nominal = load_bat_any(name).built
    protocol = load_protocol_any(SHIPPED_PROTOCOLS[0]).protocol
    case = lookup_parameter(parameter).apply(Case(nominal.spec, protocol), nominal, value)
    return build_bat(case.bat)


def hollow_bats(variants: bool) -> dict:
    """The bats the settings are checked on, by name."""
    bats = {"aluminium-34": load_bat_any("aluminium-34").built,
            "aluminium-34, 1.8 mm wall": variant("aluminium-34", "wall", 1.8e-3)}
    if not variants:
        return bats
    for name in ("aluminium-34", "bbcor-alloy-34"):
        built = bats.setdefault(name, load_bat_any(name).built)
        for wall in (1.6e-3, 2.0e-3, 2.4e-3, 2.8e-3, 3.4e-3):
            bats[f"{name}, {wall * 1e3:.1f} mm wall"] = variant(name, "wall", wall)
        modulus = built.model.material.youngs_modulus
        for scale in (0.8, 1.2):
            bats[f"{name}, E x {scale}"] = variant(name, "youngs_modulus", modulus * scale)
        for diameter in (0.0635, 0.070):
            bats[f"{name}, {diameter * 1e3:.1f} mm barrel"] = variant(name, "barrel_diameter",
                                                                       diameter)
    return bats


def rate(engine: FlexibleEngine) -> float:
    """Impacts per second of ``engine`` on the random aluminium-34 batch (best of 3)."""
    bat = load_bat_any("aluminium-34").built.model
    ball = load_protocol_any("proposed").ball.model
    batch = random_batch(bat, IMPACTS)
    engine.solve(bat, ball, 0.1524, random_batch(bat, 5))
    times = []
    for _ in range(3):
        clear_engine_caches()
        t0 = time.perf_counter()
        engine.solve(bat, ball, 0.1524, batch)
        times.append(time.perf_counter() - t0)
    return IMPACTS / min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", action="store_true",
                        help="also bbcor-alloy-34 and 20 variants of the hollow bats (minutes)")
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    args = parser.parse_args()
    bats = hollow_bats(args.variants)
    protocols = [load_protocol_any(p) for p in SHIPPED_PROTOCOLS]
    jobs = [(b, p.protocol, p.ball) for b in bats.values() for p in protocols]
    converged = protocol_values(jobs, FlexibleEngine(**CONVERGED))
    figures: dict[str, float] = {}
    print(f"{'hollow setting':<16} {'impacts/s':>10}   largest difference from converged over "
          f"{len(bats)} bats (which; the median bat's)")
    for label, settings in SETTINGS.items():
        engine = FlexibleEngine(**settings)
        values = protocol_values(jobs, engine)
        errors = [largest_difference(values, converged,
                                     range(i * len(protocols), (i + 1) * len(protocols)))
                  for i in range(len(bats))]
        speed = rate(engine)
        worst = int(np.argmax(errors))
        key = label.replace(",", "").replace(" ", "_")
        figures[f"impacts_per_s_{key}"], figures[f"error_{key}"] = speed, errors[worst]
        print(f"{label:<16} {speed:10.0f}   {errors[worst]:.1e} ({list(bats)[worst]}; "
              f"{np.median(errors):.1e})  [target 50,000 and 2e-4]")
    if args.json:
        args.json.write_text(json.dumps(figures, indent=1) + "\n")
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
