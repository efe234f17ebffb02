"""batcert's thin shell of revolution against an independent 3-D finite-element model of the
same tube, and against the exact thin-shell solution of a simply supported tube.

The reference (``scripts/fe_tube_reference.py``, recorded in ``data/fe_tube_reference.json``):
- the geometry is a free 7050 tube, 2 5/8 in outer diameter, 0.3 m long, walls of 2-4 mm;
- 3-D linear elasticity on 27-node isoparametric hexahedra (scikit-fem), no shell theory;
- two mesh levels, M1 and M2; the comparisons use M2 where it was run;
- the loads are two opposite 40 x 40 mm pressure patches (1000 N each, static), at mid-length
  and 50 mm from an end, and a 10 kN, 1 ms half-sine pulse at mid-length.
The same cases on batcert's side are in ``tube_cases.py``.

Why the two differ, and so the tolerances (set from theory, before comparing):
- **Thin-shell theory** (Kirchhoff-Love, which Sanders-Koiter is) leaves out the wall's
  transverse shear and rotary inertia. For a flexural wave of wavenumber ``k`` in a wall of
  thickness ``t`` this lowers the frequency by about
  ``(k t)^2 (1 + E / (kappa G)) / 24``, the Timoshenko correction of a plate strip
  (``kappa = 5/6``, ``E / G = 2 (1 + nu)``). For order ``n`` the wavenumber is ``n / R``. The
  estimate is 0.27 / 0.62 / 1.14 % at n = 2 and 0.60 / 1.40 / 2.56 % at n = 3, for 2 / 3 / 4 mm.
  The shell should come out *above* the 3-D model by up to that.
- **Static compliance under a patch of size ``l``**: shear adds about
  ``(pi t / l)^2 E / (12 kappa G)`` to the bending compliance: 0.7 / 1.5 / 2.6 %. The shell
  should come out *stiffer*. The through-thickness squeeze of the wall under the 0.66 MPa pressure
  is 1e-3 of the deflection and is ignored.
- **Finite-element error**: up to 0.1 % (frequencies) and 0.3 % (displacements) between M1 and M2.
  That is added to each tolerance.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from tube_cases import Tube, frequencies, squeeze, squeeze_pulse  # noqa: E402

DATA = json.loads((Path(__file__).resolve().parent / "data" / "fe_tube_reference.json")
                  .read_text())
WALLS = sorted(DATA["walls"], key=float)
SHEAR_FACTOR = 5.0 / 6.0
FE_FREQUENCY, FE_DISPLACEMENT = 0.001, 0.003


def tube(wall: str) -> Tube:
    t = DATA["tube"]
    return Tube(t["outer_diameter_m"], float(wall) * 1e-3, t["length_m"], t["youngs_modulus_Pa"],
                t["poisson_ratio"], t["density_kg_m3"])


def fe(wall: str) -> dict:
    """The finest mesh computed for this wall."""
    levels = DATA["walls"][wall]
    return levels["M2"] if "M2" in levels else levels["M1"]


def e_over_kappa_g() -> float:
    return 2 * (1 + DATA["tube"]["poisson_ratio"]) / SHEAR_FACTOR


def shell_theory_error(n: int, wall: str) -> float:
    """Timoshenko estimate of what thin-shell theory leaves out at order ``n`` [-]."""
    t = float(wall) * 1e-3
    radius = 0.5 * (DATA["tube"]["outer_diameter_m"] - t)
    return (n * t / radius) ** 2 * (1 + e_over_kappa_g()) / 24


def static_shear_error(wall: str) -> float:
    t = float(wall) * 1e-3
    return (np.pi * t / DATA["load"]["patch_length_m"]) ** 2 * e_over_kappa_g() / 12


@pytest.mark.parametrize("wall", WALLS)
@pytest.mark.parametrize("ends, key", [(("open", "open"), "free_free_hz"),
                                        (("closed", "closed"), "shear_diaphragm_hz")])
def test_hoop_frequencies(wall, ends, key):
    # n = 2 and 3, the first two axial orders. Free-free: the names are the FE's axial
    # symmetric/antisymmetric pair; shear diaphragm ("closed" ends: V = W = 0, U free): m = 1, 2.
    ref = fe(wall)[key]
    names = (["n2_axial0", "n2_axial1", "n3_axial0", "n3_axial1"] if key == "free_free_hz"
             else ["n2_m1", "n2_m2", "n3_m1", "n3_m2"])
    model = np.concatenate([frequencies(tube(wall), n, ends, count=2) for n in (2, 3)])
    for name, f in zip(names, model, strict=True):
        n = int(name[1])
        diff = f / ref[name] - 1
        assert -FE_FREQUENCY <= diff <= shell_theory_error(n, wall) + FE_FREQUENCY, (name, diff)


@pytest.mark.parametrize("wall", WALLS)
def test_shear_diaphragm_matches_the_exact_sanders_solution(wall):
    # The simply supported tube has exact mode shapes (sin/cos in z); the recorded closed-form
    # Sanders frequencies (the FE script's own 3 x 3 eigenproblem) are the exact answer of the
    # theory batcert implements, so only batcert's axial discretisation (120 elements) is left:
    # 0.05 % (measured <= 0.007 %, the m = 2 modes).
    exact = DATA["walls"][wall]["thin_shell_theory_hz"]
    model = {f"n{n}_m{m}": f for n in (2, 3)
             for m, f in zip((1, 2), frequencies(tube(wall), n, ("closed", "closed"), count=2),
                             strict=True)}
    for name, f in model.items():
        assert f == pytest.approx(exact[name]["sanders"], rel=5e-4), name


@pytest.mark.parametrize("wall", WALLS)
@pytest.mark.parametrize("case", ["squeeze_mid_mm", "squeeze_end_mm"])
def test_static_squeeze(wall, case):
    # Displacements per the recorded force; the shell is expected stiffer by up to the shear
    # estimate.
    load = DATA["load"]
    length = DATA["tube"]["length_m"]
    centre = 0.5 * length if case == "squeeze_mid_mm" else length - load["end_patch_from_end_m"]
    out = squeeze(tube(wall), centre, load["patch_length_m"], load["patch_arc_m"])
    force = load["static_force_N"]
    ref = fe(wall)[case]
    model = {"centre_approach": out["centre_approach_per_newton"] * force * 1e3,
             "patch_average_inward": out["average_approach_per_newton"] / 2 * force * 1e3}
    for name, value in model.items():
        diff = value / ref[name] - 1
        assert -(static_shear_error(wall) + FE_DISPLACEMENT) <= diff <= FE_DISPLACEMENT, (name,
                                                                                        diff)


@pytest.mark.parametrize("wall", WALLS)
def test_pulse(wall):
    # The largest approach under the half-sine pulse: dynamic compliance, the modes up to 60 kHz
    # plus the static correction on batcert's side. Same tolerance as the static squeeze: the
    # response is carried by the same n = 2 ovalling and the local bending under the patch.
    load = DATA["load"]
    out = squeeze_pulse(tube(wall), 0.5 * DATA["tube"]["length_m"], load["patch_length_m"],
                        load["patch_arc_m"], load["pulse_peak_force_N"], load["pulse_duration_s"],
                        load["pulse_until_s"])
    ref = fe(wall)["pulse_mid_max_mm"]
    model = {"centre_approach": out["max_centre_approach"] * 1e3,
             "patch_average_inward": out["max_average_approach"] / 2 * 1e3}
    for name, value in model.items():
        diff = value / ref[name] - 1
        assert abs(diff) <= static_shear_error(wall) + FE_DISPLACEMENT, (name, diff)


@pytest.mark.slow
def test_the_fe_reference_reproduces(tmp_path):
    # Re-run the independent model on its coarse mesh (cases A and C, 3 mm wall; ~15 s) and
    # check it still gives the recorded numbers: the same mesh and solver settings, so only the
    # eigensolver's tolerance (1e-10) and the sparse solver separate them: 1e-6 relative. The
    # coarse mesh is 0.07-0.3 % off the fine one, so the shell agrees with it as with M2.
    pytest.importorskip("skfem")
    import subprocess

    out = tmp_path / "quick.json"
    script = Path(__file__).resolve().parents[2] / "scripts" / "fe_tube_reference.py"
    subprocess.run([sys.executable, str(script), "--quick", "--wall", "3.0", "--out", str(out)],
                   check=True, capture_output=True, timeout=600)
    run = json.loads(out.read_text())["3.0"]["quick"]
    rec = DATA["quick"]["3.0"]
    for name, f in rec["free_free_hz"].items():
        assert run["A"][name]["f_Hz"] == pytest.approx(f, rel=1e-6), name
    assert run["C"]["approach_mm"] == pytest.approx(rec["squeeze_mid_mm"]["centre_approach"],
                                                    rel=1e-6)
    assert run["C"]["patch_avg_inward_mm"] == pytest.approx(
        rec["squeeze_mid_mm"]["patch_average_inward"], rel=1e-6)
