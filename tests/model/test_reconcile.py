"""Reconciliation of the geometry-derived bat to measured mass properties
(batcert.model.reconcile and the bat spec's `measured` block, batcert.model.build)."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from batcert.conventions import STANDARD_GRAVITY
from batcert.errors import ModelError
from batcert.model.build import build_bat, measured_properties
from batcert.model.geometry import build_geometry
from batcert.model.reconcile import MeasuredMassProperties, reconcile
from batcert.specs.bat import MeasuredSpec, load_bat
from batcert.specs.materials import LIBRARY

REPO = Path(__file__).resolve().parents[2]
BATS = REPO / "bats"
EXACT = 1e-9  # reconciliation solves 3 linear equations: "exactly" = to rounding


def _built(name):
    return build_bat(load_bat(BATS / name))


@pytest.mark.parametrize("name, pivot, mass, cg, moi", [
    # Smith 2001: measured about a pivot 150 mm from the knob (DESIGN.md section 1)
    ("ash-34.yaml", 0.150, 0.906, 0.429, 0.209),
    ("aluminium-34.yaml", 0.150, 0.863, 0.418, 0.198),
    # Nathan 2000 Table I: M 0.885 kg, CG 0.564 m from the knob, radius of gyration about the CG
    # 0.23 m; about the default 6 in pivot: I = M (k^2 + rbar^2)
    ("r161.yaml", 0.1524, 0.885, 0.564 - 0.1524, 0.885 * (0.23**2 + (0.564 - 0.1524) ** 2)),
])
def test_shipped_bats_reconcile_exactly(name, pivot, mass, cg, moi):
    model = _built(name).model
    assert model.mass == pytest.approx(mass, rel=EXACT)
    assert model.cg_from(pivot) == pytest.approx(cg, rel=EXACT)
    assert model.moi_about(pivot) == pytest.approx(moi, rel=EXACT)


def test_shipped_corrections_are_modest():
    """The corrections the shipped bats need (docs/reconciliation.md quotes them)."""
    ash = _built("ash-34.yaml").reconciliation
    assert ash.method == "density-profile"
    c = ash.corrections
    assert 0.80 < c["density_weight_min"] < c["density_weight_max"] < 1.12
    alu = _built("aluminium-34.yaml").reconciliation
    assert alu.method == "point-masses"
    assert alu.corrections["density_scale"] == pytest.approx(0.993, abs=5e-4)
    assert alu.corrections["added_knob_mass"] == pytest.approx(0.0092, abs=5e-5)
    assert alu.corrections["added_end_cap_mass"] == pytest.approx(0.0540, abs=5e-5)


def test_r161_geometry_before_reconciliation():
    """REFERENCE-DATA "R161" (D): integrating the profile at 649 kg/m^3 gives M = 0.869 kg and
    CG 0.561 m from the knob. Both are quoted to 3 decimals, so the tolerance is half a unit in
    the last place (0.5 g, 0.5 mm); the profile is given at the 1 cm slice centres, so the
    sliced model integrates it exactly as the reference did."""
    geometry = _built("r161.yaml").geometry
    assert geometry.mass == pytest.approx(0.869, abs=5e-4)
    assert geometry.balance_point == pytest.approx(0.561, abs=5e-4)


def _rod(length=0.84, d_handle=0.025, d_barrel=0.065, material="ash", **kw):
    z = [0.0, 0.30, 0.55, length]
    d = [d_handle, d_handle, d_barrel, d_barrel]
    return build_geometry("test", "solid", length, z, d, LIBRARY[material][0], **kw)


def test_none_keeps_geometry():
    bat = _rod()
    model, rec = reconcile(bat, MeasuredMassProperties(1.0, 0.5, 0.2, 0.1524), "none")
    assert model is bat and rec.method == "none"


@pytest.mark.parametrize("given", ["mass", "mass+cg", "mass+cg+moi"])
def test_density_profile_uses_as_many_terms_as_measured(given):
    bat = _rod()
    p = 0.1524
    mass = bat.mass * 1.02
    bp = bat.balance_point + 0.003 if "cg" in given else None
    moi = bat.moi_about(p) * 1.02 if "moi" in given else None
    model, rec = reconcile(bat, MeasuredMassProperties(mass, bp, moi, p))
    assert model.mass == pytest.approx(mass, rel=EXACT)
    if bp is not None:
        assert model.balance_point == pytest.approx(bp, rel=EXACT)
    if moi is not None:
        assert model.moi_about(p) == pytest.approx(moi, rel=EXACT)
    if given == "mass":  # one equation: a uniform scale
        assert rec.corrections["density_weight_min"] == pytest.approx(1.02)
        assert rec.corrections["density_weight_max"] == pytest.approx(1.02)


def test_density_profile_refusal_message():
    bat = _rod()
    with pytest.raises(ModelError) as exc:
        reconcile(bat, MeasuredMassProperties(bat.mass * 2.5))
    assert exc.value.field == "measured"
    assert str(exc.value).startswith("cannot reconcile: matching the measured mass properties "
                                     "needs the density scaled by 2.50 to 2.50 along the bat "
                                     "(allowed 0.5-2.0)")


def _measured_from(bat, p=0.1524, scale=1.0, knob=0.0, cap=0.0):
    """Mass properties of ``bat`` with its density scaled and end masses added [SI]."""
    target = replace(bat, linear_density=bat.linear_density * scale,
                     rotary_inertia=bat.rotary_inertia * scale,
                     point_masses=((0.0, knob), (bat.length, cap)))
    return MeasuredMassProperties(target.mass, target.balance_point, target.moi_about(p), p)


def test_point_masses_exact_and_added_at_the_ends():
    """A 20 g knob and a 30 g cap on a 1 % denser bat: the fit finds them again."""
    bat = _rod()
    model, rec = reconcile(bat, _measured_from(bat, scale=1.01, knob=0.020, cap=0.030),
                           "point-masses")
    assert rec.corrections["density_scale"] == pytest.approx(1.01, rel=1e-9)
    assert rec.corrections["added_knob_mass"] == pytest.approx(0.020, rel=1e-9)
    assert rec.corrections["added_end_cap_mass"] == pytest.approx(0.030, rel=1e-9)
    (z0, m0), (z1, m1) = model.point_masses
    assert (z0, z1) == (0.0, bat.length)
    assert (m0, m1) == pytest.approx((0.020, 0.030), rel=1e-9)


@pytest.mark.parametrize("target, message", [
    # more compact about the CG than the profile: negative end masses
    (dict(scale=1.0, knob=-0.016, cap=-0.036), r"it would need a negative knob mass \(-16 g\) "
                                               r"and a negative end-cap mass \(-36 g\)"),
    (dict(scale=1.0, cap=0.400), r"it would need an end-cap mass of 400 g \(over 25% of the bat\)"),
    (dict(scale=2.5), r"it would need density scale 2.50 \(allowed 0.5-2.0\)"),
])
def test_point_masses_refusals(target, message):
    bat = _rod()
    with pytest.raises(ModelError, match="^cannot reconcile with point masses: " + message) as exc:
        reconcile(bat, _measured_from(bat, **target), "point-masses")
    assert exc.value.field == "measured"
    assert "try `reconcile: density-profile`" in str(exc.value)


def test_impossible_measurements_refused():
    bat = _rod()
    p = 0.1524
    with pytest.raises(ModelError, match="lies outside the bat") as exc:
        reconcile(bat, MeasuredMassProperties(0.9, 0.95, 0.2, p))
    assert exc.value.field == "measured"
    with pytest.raises(ModelError, match=r"below M rbar\^2") as exc:
        reconcile(bat, MeasuredMassProperties(0.9, 0.60, 0.9 * (0.60 - p) ** 2 * 0.99, p))
    assert exc.value.field == "measured.moi"
    # radius of gyration about the CG larger than a uniform rod's L / sqrt(12) (+5 %)
    with pytest.raises(ModelError, match="exceeds that of a uniform rod"):
        reconcile(bat, MeasuredMassProperties(0.9, 0.55, 0.9 * (0.40**2 + 0.30**2), p))


def _values(**measured) -> MeasuredSpec:
    base = dict(pivot=0.1524, mass=None, balance_point=None, cg=None, moi=None,
                radius_of_gyration=None, pendulum_period=None, first_bending_frequency=None,
                hoop_frequency=None, barrel_compression=None)
    base.update(measured)
    return MeasuredSpec(**base)


def test_pendulum_period_formula():
    """ASTM F2398: I = M g (BP - pivot) T^2 / (4 pi^2) about the pivot, g = 9.80665 m/s^2."""
    mass, bp, pivot, period = 0.906, 0.579, 0.150, 1.6
    meas = measured_properties(_values(pivot=pivot, mass=mass, balance_point=bp,
                                       pendulum_period=period))
    expected = mass * 9.80665 * (bp - pivot) * period**2 / (4 * math.pi**2)
    assert STANDARD_GRAVITY == 9.80665
    assert meas.moi == pytest.approx(expected, rel=1e-15)
    assert (meas.mass, meas.balance_point, meas.pivot) == (mass, bp, pivot)


def test_pendulum_period_spec_reconciles(tmp_path):
    """A bat given by F2398 pendulum data reconciles to the MOI the period implies, and its COP
    is g T^2 / (4 pi^2) from the pivot (REFERENCE-DATA, Standards)."""
    mass, cg, moi, pivot = 0.906, 0.429, 0.209, 0.150
    period = 2 * math.pi * math.sqrt(moi / (mass * 9.80665 * cg))
    text = (BATS / "ash-34.yaml").read_text().replace(
        "moi: 0.209 kg*m^2 +/- 0.0005 kg*m^2 (uniform) # about the pivot",
        f"pendulum_period: {period:.12f} s")
    path = tmp_path / "ash-pendulum.yaml"
    path.write_text(text)
    model = build_bat(load_bat(path)).model
    assert model.moi_about(pivot) == pytest.approx(moi, rel=1e-9)
    cop = model.moi_about(pivot) / (model.mass * model.cg_from(pivot))
    assert cop == pytest.approx(9.80665 * period**2 / (4 * math.pi**2), rel=1e-9)


def test_radius_of_gyration_path():
    """Nathan 2000 Table I form: I_pivot = M (k^2 + (BP - pivot)^2)."""
    meas = measured_properties(_values(mass=0.885, balance_point=0.564, radius_of_gyration=0.23))
    assert meas.moi == pytest.approx(0.885 * (0.23**2 + (0.564 - 0.1524) ** 2), rel=1e-15)


def test_cg_from_pivot_is_converted_to_balance_point():
    meas = measured_properties(_values(pivot=0.150, mass=0.906, cg=0.429, moi=0.209))
    assert meas.balance_point == pytest.approx(0.579)


def test_reconciled_weight_stays_smooth_and_positive():
    built = _built("ash-34.yaml")
    w = built.model.linear_density / built.geometry.linear_density
    assert np.all(w > 0.5) and np.all(w < 2.0)
    # a quadratic in z: its third differences vanish on the uniform slice grid
    assert np.max(np.abs(np.diff(w, 3))) < 1e-9
    c = built.reconciliation.corrections
    assert (c["density_weight_knob"], c["density_weight_tip"]) == pytest.approx((w[0], w[-1]))
