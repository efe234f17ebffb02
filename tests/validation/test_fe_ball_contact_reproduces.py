"""The independent 3-D finite-element reference for the ball's contact footprint on a barrel
still reproduces its recorded numbers.

The reference (``scripts/fe_ball_contact.py``, recorded in ``data/fe_ball_contact.json``):
- a linear-elastic sphere, R_b = 36.9 mm, pushed by a uniform body force (the quasi-static
  analogue of an impact's deceleration) onto a rigid cylinder (2 5/8 in and 2 1/4 in barrels) or
  a rigid flat; the compression is the sphere's centre-of-mass approach;
- frictionless node-to-surface contact, solved by an active-set (Signorini) iteration;
- 27-node isoparametric hexahedra, graded toward the contact, quarter model, meshes M1 and M2;
- the footprint's equivalent semi-axes from the contact pressure's second moments
  (``sqrt(5 <x^2>)`` along the bat, ``sqrt(5 <s^2>)`` around it), with Hertz's ellipse beside
  them, and the pressure's marginals.
It uses nothing of batcert, so it can check batcert's footprint rule
(``batcert/physics/balls/footprint.py``).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

DATA = json.loads((Path(__file__).resolve().parent / "data" / "fe_ball_contact.json").read_text())


@pytest.mark.slow
def test_the_fe_reference_reproduces(tmp_path):
    # Re-run the coarse mesh of --quick (the 2 5/8 in barrel, u/R_b = 0.02 and 0.07, nu = 0.3;
    # ~15 s) and check it still gives the recorded numbers. Same mesh, same direct solver, and the
    # contact's active set is a discrete fixed point, so only rounding separates the runs (the
    # order of sums in BLAS and SuperLU, the number of processes): 1e-12 or so. A change to the
    # model (mesh, material, contact or its solution, the measures of the footprint) moves these
    # numbers by 1e-4 or more (the coarse mesh differs from M1 by 1e-3), so 1e-6 relative tells
    # the two apart. The contact-node counts must agree exactly.
    run = _rerun(tmp_path, "fe_ball_contact.py", "--quick")["quick"]["rows"]
    rec = DATA["quick"]["rows"]
    assert [r["u_over_R"] for r in run] == [r["u_over_R"] for r in rec]
    _same_rows(run, rec, ("F_N", "a_eq_mm", "b_eq_mm", "x_max_mm", "s_max_mm"), 1e-6)


@pytest.mark.slow
def test_the_finite_strain_fe_reference_reproduces(tmp_path):
    # Re-run the first two load steps (u/R_b = 0.01, 0.02) of the recorded finite-strain run on
    # mesh Q3, 2 5/8 in barrel, nu = 0.3 (scripts/fe_ball_contact_finite.py --smoke, about a
    # minute): the same mesh, steps and Newton path, so only rounding separates the runs, and
    # the Newton tolerance (1e-7 of the load) bounds what a different path could move: 1e-5
    # relative tells a rerun from a change of the model (the Q3 and quick meshes differ by
    # 1e-3 or more). The contact-node counts must agree exactly.
    run = _rerun(tmp_path, "fe_ball_contact_finite.py", "--smoke")["rows"]
    rec = DATA["finite_strain"]["results"]["Q3"]["nu=0.30"]["cyl_2.625in"][:len(run)]
    assert [r["u_over_R"] for r in run] == [r["u_over_R"] for r in rec] == [0.01, 0.02]
    _same_rows(run, rec, ("F_N", "a_eq_mm", "b_eq_mm", "a_eq_undeformed_mm",
                          "b_eq_undeformed_mm"), 1e-5)


def _rerun(tmp_path, script: str, level: str) -> dict:
    """The FE script ``scripts/SCRIPT`` run at ``level`` into a scratch file, its record."""
    pytest.importorskip("skfem")
    import subprocess

    out = tmp_path / "rerun.json"
    path = Path(__file__).resolve().parents[2] / "scripts" / script
    subprocess.run([sys.executable, str(path), level, "--out", str(out)],
                   check=True, capture_output=True, timeout=600)
    return json.loads(out.read_text())


def _same_rows(run: list[dict], rec: list[dict], names: tuple[str, ...], rel: float) -> None:
    """Each rerun row against its recorded one: the contact-node count exactly, the named
    quantities to ``rel`` (each test says why)."""
    for r, ref in zip(run, rec, strict=True):
        assert r["n_contact_nodes_quarter"] == ref["n_contact_nodes_quarter"], r["u_over_R"]
        for name in names:
            assert r[name] == pytest.approx(ref[name], rel=rel), (r["u_over_R"], name)
