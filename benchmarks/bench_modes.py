"""Time the beam modes: R161 (84 slices) and an 86-slice hollow bat, free and pinned.

Run from the repository root:  python benchmarks/bench_modes.py
Prints figures only; nothing is asserted. "first" is the very first call of a case (cache
empty); "cold" is the median of fresh computations (cache cleared before each); "cached" is a
cache hit (content hash + dictionary lookup).
"""

from __future__ import annotations

import dataclasses
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from r161 import r161_bat, solid_bat  # noqa: E402

from batcert import workspace  # noqa: E402
from batcert.physics.batmodel import Material  # noqa: E402
from batcert.physics.modes import cached_modes  # noqa: E402
from batcert.physics.residual import residual_compliance  # noqa: E402

PIVOT = 0.1524  # [m]
N_MODES = 24
REPEAT = 15


def hollow_86() -> object:
    """A 34 in aluminium-like bat in 86 slices: tapered handle, 2 5/8 in barrel, 2.5 mm wall."""
    al = Material("aluminium-7050", 2830.0, 71.7e9, 26.9e9, 0.33)
    z = np.linspace(0.0, 0.8636, 87)
    mid = 0.5 * (z[1:] + z[:-1])
    d = np.interp(mid, [0.0, 0.02, 0.03, 0.30, 0.55, 0.8636],
                  [0.050, 0.050, 0.025, 0.024, 0.06668, 0.06668])
    bat = solid_bat("hollow-86", z, d, al, kappa=0.5)
    inner = d - 2 * 2.5e-3
    area = np.pi * (d**2 - inner**2) / 4
    i_area = np.pi * (d**4 - inner**4) / 64
    return dataclasses.replace(bat, construction="hollow", inner_diameter=inner,
                               linear_density=al.density * area, rotary_inertia=al.density * i_area,
                               bending_stiffness=al.youngs_modulus * i_area,
                               shear_stiffness=0.5 * al.shear_modulus * area,
                               point_masses=((0.0, 0.02), (0.8636, 0.03)))


def ms(f) -> float:
    t = time.perf_counter()
    f()
    return 1e3 * (time.perf_counter() - t)


def main() -> None:
    bats = {"R161 (84 slices)": r161_bat(), "hollow (86 slices)": hollow_86()}
    print(f"modes: {N_MODES} bending modes, pivot {PIVOT} m; times in ms "
          f"(median of {REPEAT} for cold and cached)")
    print(f"{'bat':20s} {'support':8s} {'refine':>6s} {'dofs':>5s} {'first':>8s} {'cold':>8s} "
          f"{'cached':>8s}  f1 [Hz]")
    for name, bat in bats.items():
        for support in ("free", "pinned"):
            for refine in (1, 2, 4):
                def solve(bat=bat, support=support, refine=refine):
                    return cached_modes(bat, support, PIVOT, N_MODES, refine)

                workspace.current().clear("modes")
                first = ms(solve)
                cold = []
                for _ in range(REPEAT):
                    workspace.current().clear("modes")
                    cold.append(ms(solve))
                hit = [ms(solve) for _ in range(REPEAT)]
                modes = cached_modes(bat, support, PIVOT, N_MODES, refine)
                print(f"{name:20s} {support:8s} {refine:6d} {2 * modes.z.size:5d} "
                      f"{first:8.2f} {np.median(cold):8.2f} {np.median(hit):8.3f}  "
                      f"{modes.frequencies_hz[0]:.1f}")
    bat = bats["R161 (84 slices)"]
    modes = cached_modes(bat, "free", PIVOT, 18)
    z = np.linspace(0.5, 0.83, 34)
    t = np.median([ms(lambda: residual_compliance(bat, modes, z)) for _ in range(REPEAT)])
    print(f"residual_compliance, R161 free, 18 modes, {z.size} impact points: {t:.2f} ms")


if __name__ == "__main__":
    main()
