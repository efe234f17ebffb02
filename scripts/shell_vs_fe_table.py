"""batcert's shell of revolution against the independent 3-D finite-element reference, as the
Markdown tables of docs/validation.md (section 3).

    python scripts/shell_vs_fe_table.py

Reads tests/validation/data/fe_tube_reference.json (written by scripts/fe_tube_reference.py)
and computes the same cases with tests/validation/tube_cases.py.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "validation"))
from tube_cases import Tube, frequencies, squeeze, squeeze_pulse  # noqa: E402

DATA = json.loads((ROOT / "tests" / "validation" / "data" / "fe_tube_reference.json").read_text())


def main() -> None:
    t, load = DATA["tube"], DATA["load"]
    walls = sorted(DATA["walls"], key=float)
    print("Frequencies [Hz]: shell / 3-D FE (finest mesh) and the difference.\n")
    print("| wall | mesh | free n=2 (1st) | free n=2 (2nd) | free n=3 (1st) | free n=3 (2nd) "
          "| s.s. n=2 m=1 | s.s. n=2 m=2 | s.s. n=3 m=1 | s.s. n=3 m=2 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows_static = []
    for wall in walls:
        tube = Tube(t["outer_diameter_m"], float(wall) * 1e-3, t["length_m"],
                    t["youngs_modulus_Pa"], t["poisson_ratio"], t["density_kg_m3"])
        levels = DATA["walls"][wall]
        mesh = "M2" if "M2" in levels else "M1"
        fe = levels[mesh]
        free = [f for n in (2, 3) for f in frequencies(tube, n, ("open", "open"), 2)]
        ss = [f for n in (2, 3) for f in frequencies(tube, n, ("closed", "closed"), 2)]
        ref = ([fe["free_free_hz"][k] for k in ("n2_axial0", "n2_axial1", "n3_axial0",
                                                "n3_axial1")]
               + [fe["shear_diaphragm_hz"][k] for k in ("n2_m1", "n2_m2", "n3_m1", "n3_m2")])
        cells = [f"{m:.0f} / {r:.0f} ({100 * (m / r - 1):+.2f} %)"
                 for m, r in zip(free + ss, ref, strict=True)]
        print(f"| {wall} mm | {mesh} | " + " | ".join(cells) + " |")
        length = t["length_m"]
        mid = squeeze(tube, 0.5 * length, load["patch_length_m"], load["patch_arc_m"])
        end = squeeze(tube, length - load["end_patch_from_end_m"], load["patch_length_m"],
                      load["patch_arc_m"])
        pulse = squeeze_pulse(tube, 0.5 * length, load["patch_length_m"], load["patch_arc_m"],
                              load["pulse_peak_force_N"], load["pulse_duration_s"],
                              load["pulse_until_s"])
        f = load["static_force_N"]
        model = [mid["centre_approach_per_newton"] * f * 1e3,
                 mid["average_approach_per_newton"] / 2 * f * 1e3,
                 end["centre_approach_per_newton"] * f * 1e3,
                 end["average_approach_per_newton"] / 2 * f * 1e3,
                 pulse["max_centre_approach"] * 1e3, pulse["max_average_approach"] / 2 * 1e3]
        ref = [fe["squeeze_mid_mm"]["centre_approach"], fe["squeeze_mid_mm"]["patch_average_inward"],
               fe["squeeze_end_mm"]["centre_approach"], fe["squeeze_end_mm"]["patch_average_inward"],
               fe["pulse_mid_max_mm"]["centre_approach"],
               fe["pulse_mid_max_mm"]["patch_average_inward"]]
        rows_static.append(f"| {wall} mm | {mesh} | " + " | ".join(
            f"{m:.4g} / {r:.4g} ({100 * (m / r - 1):+.2f} %)"
            for m, r in zip(model, ref, strict=True)) + " |")
    print(f"\nSqueeze by two opposite {load['patch_length_m'] * 1e3:.0f} x "
          f"{load['patch_arc_m'] * 1e3:.0f} mm patches, {load['static_force_N']:.0f} N each "
          f"(static), and the {load['pulse_peak_force_N'] / 1e3:.0f} kN, "
          f"{load['pulse_duration_s'] * 1e3:.0f} ms half-sine pulse [mm]: shell / 3-D FE.\n")
    print("| wall | mesh | mid: approach | mid: patch average | 50 mm from end: approach "
          "| 50 mm from end: patch average | pulse: max approach | pulse: max patch average |")
    print("|---|---|---|---|---|---|---|---|")
    print("\n".join(rows_static))


if __name__ == "__main__":
    main()
