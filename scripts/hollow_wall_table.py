"""The barrel wall's effect on a hollow bat, as a table for docs/validation.md.

For barrel walls from 1.6 to 4.0 mm in the shipped ``bbcor-alloy-34`` (34 in, 2 5/8 in 7050
barrel, 1.6 mm handle, 20 g knob, 40 g end cap; the bat file's other values kept, and no
reconciliation: the bat's weight and MOI follow the wall, as they would for a maker) it prints
the bat's weight and MOI about the 6 in pivot, the bat's hoop frequency (shell model, as an
impact-hammer test on the free bat measures it), the thin-ring estimate, the free 0.3 m tube's
n = 2 frequency from the shell model and from the independent 3-D finite-element reference (recorded in
tests/validation/data/fe_tube_reference.json where that wall was computed), and BBCOR and BESR
under the shipped protocols with the flexible engine, with the wall's deflection under the
BBCOR impact's peak force in wall thicknesses (where the linear wall ends, docs/physics.md).

    python scripts/hollow_wall_table.py            # walls 1.6 2.0 2.3 2.6 2.85 3.2 3.6 4.0 mm
    python scripts/hollow_wall_table.py 2.2 2.8    # chosen walls [mm]
"""

from __future__ import annotations

import json
import re
import sys
import tempfile
from pathlib import Path

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.engines import get_engine
from batcert.model.mass import mass_properties
from batcert.physics import barrel
from batcert.physics.shell import ring_frequency
from batcert.runner.runner import run_protocol
from batcert.units import INCH, OUNCE

ROOT = Path(__file__).resolve().parents[1]
FE = ROOT / "tests" / "validation" / "data" / "fe_tube_reference.json"
sys.path.insert(0, str(ROOT / "tests" / "validation"))
from tube_cases import Tube, frequencies  # noqa: E402

OUTER = 2.625 * INCH
PIVOT = 6 * INCH
AL7050 = dict(youngs_modulus=71.7e9, poisson_ratio=0.33, density=2830.0)


def bat_with_wall(wall_mm: float, folder: Path) -> Path:
    """bbcor-alloy-34 with its barrel wall (the last two wall points) set to ``wall_mm`` and
    its measured block (the weight it is reconciled to) removed."""
    text = (ROOT / "bats" / "bbcor-alloy-34.yaml").read_text()
    text = re.sub(r"\[(22|34) in, 2\.85 mm\]", rf"[\1 in, {wall_mm} mm]", text)
    text = text[:text.index("measured:")]
    path = folder / f"alloy-34-wall-{wall_mm}.yaml"
    path.write_text(text)
    return path


def main(walls: list[float]) -> None:
    fe = json.loads(FE.read_text())["walls"] if FE.exists() else {}
    protocols = [load_protocol_any(p) for p in ("ncaa-bbcor", "ncaa-besr")]
    engine = get_engine("flexible")
    print("| barrel wall [mm] | weight [oz] | MOI at 6 in [oz in^2] | bat hoop (shell) [Hz] "
          "| thin ring [Hz] | tube n=2: shell [Hz] | tube n=2: 3-D FE [Hz] | BBCOR | BESR "
          "| BESR exit speed [mph] | wall deflection / thickness (BBCOR) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for wall in walls:
            t = wall * 1e-3
            bat = load_bat_any(str(bat_with_wall(wall, Path(tmp)))).built
            mp = mass_properties(bat, PIVOT)
            hoop = barrel.hoop_frequency(bat.model)
            ring = float(ring_frequency(0.5 * (OUTER - t), t, AL7050["youngs_modulus"],
                                        AL7050["density"], AL7050["poisson_ratio"]))
            tube = Tube(OUTER, t, 0.300, **AL7050)
            shell_tube = float(frequencies(tube, 2, ("open", "open"), count=1)[0])
            rec = fe.get(f"{wall:.1f}", {})
            fe_tube = rec.get("M2", rec.get("M1", {})).get("free_free_hz", {}).get("n2_axial0")
            runs = [run_protocol(bat, p.protocol, p.ball, engine) for p in protocols]
            values = [r.value for r in runs]
            ratio = runs[0].conditions[0].diagnostics.get("barrel_deflection_ratio")
            besr_mph = values[1] * 136.0 - 2.0  # 70 mph ball, 66 mph bat: Eq. 2 for v_b
            print(f"| {wall:g} | {mp.mass / OUNCE:.1f} | {mp.moi_pivot / (OUNCE * INCH**2):.0f} "
                  f"| {hoop:.0f} | {ring:.0f} | {shell_tube:.0f} | "
                  f"{'-' if fe_tube is None else f'{fe_tube:.0f}'} | {values[0]:.3f} | "
                  f"{values[1]:.3f} | {besr_mph:.1f} | "
                  f"{'-' if ratio is None else f'{ratio:.2f}'} |")


if __name__ == "__main__":
    main([float(a) for a in sys.argv[1:]] or [1.6, 2.0, 2.3, 2.6, 2.85, 3.2, 3.6, 4.0])
