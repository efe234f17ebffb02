"""From a bat spec to the bat model every engine reads: geometry, reconciliation, calibration.

:func:`build_bat` slices the profile into a beam (:mod:`batcert.model.geometry`), reconciles it to
the measured mass properties (:mod:`batcert.model.reconcile`) and, when a first bending frequency
was measured, calibrates its stiffness (:mod:`batcert.model.calibrate`). A bat that cannot be
modelled is reported against the line of the spec field at fault.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from batcert.conventions import STANDARD_GRAVITY
from batcert.errors import ModelError
from batcert.model.calibrate import calibrate_barrel, calibrate_stiffness
from batcert.model.geometry import build_geometry, stack_material
from batcert.model.reconcile import MeasuredMassProperties, Reconciliation, reconcile
from batcert.physics.batmodel import BatModel, Material
from batcert.specs.bat import BatSpec, MeasuredSpec


@dataclass(frozen=True)
class BuiltBat:
    """A bat spec with its models: geometry only, and reconciled (what the engines use)."""

    spec: BatSpec
    geometry: BatModel  # profile x material, before reconciliation
    model: BatModel  # reconciled (and calibrated)
    reconciliation: Reconciliation
    measured: MeasuredMassProperties | None
    first_bending_frequency: float | None  # measured, free-free [Hz]


def measured_properties(m: MeasuredSpec) -> MeasuredMassProperties:
    """Mass, balance point and MOI about the pivot from whichever form the file gives: the MOI
    itself, a radius of gyration about the CG, or an ASTM F2398 pendulum period
    (``I = M g (BP - pivot) T^2 / (4 pi^2)``)."""
    p = m.pivot
    bp = m.balance_point if m.balance_point is not None else (
        p + m.cg if m.cg is not None else None)
    moi = m.moi
    if m.radius_of_gyration is not None and bp is not None:
        moi = m.mass * (m.radius_of_gyration ** 2 + (bp - p) ** 2)
    if m.pendulum_period is not None and bp is not None:
        moi = m.mass * STANDARD_GRAVITY * (bp - p) * m.pendulum_period ** 2 / (4 * math.pi**2)
    return MeasuredMassProperties(m.mass, bp, moi, p)


def _barrel_text(corr: dict[str, float]) -> str:
    text = f"; barrel wall stiffness x {corr['barrel_stiffness_scale']:.3f}"
    if corr["barrel_mass_scale"] != 1.0:
        text += f" and mass x {corr['barrel_mass_scale']:.3f}"
    sources = []
    if "measured_compression_stiffness" in corr:
        sources.append(f"the measured compression stiffness "
                       f"{corr['measured_compression_stiffness']:.4g} N/m (model "
                       f"{corr['model_compression_stiffness']:.4g} N/m)")
    if "measured_hoop_frequency_hz" in corr:
        sources.append(f"the measured {corr['measured_hoop_frequency_hz']:.0f} Hz hoop frequency "
                       f"(model {corr['model_hoop_frequency_hz']:.0f} Hz)")
    return text + " to match " + " and ".join(sources)


def _material(spec: BatSpec) -> Material:
    """The bat's material; where a layup covers the whole bat and none is given, that of the
    span holding the barrel's middle (:func:`stack_material`)."""
    if spec.material is not None:
        return spec.material
    i = spec.layup_span_at(spec.barrel_middle)
    return stack_material(spec.layup[-1 if i is None else i][2])


def _wall_stations(spec: BatSpec):
    if spec.construction != "hollow" or spec.wall is None:
        return None, None
    if isinstance(spec.wall, tuple):
        return spec.wall
    return (0.0,), (spec.wall,)


def build_bat(spec: BatSpec) -> BuiltBat:
    """Geometry, reconciliation and calibration; model errors name the spec file's line."""
    try:
        wall_z, wall_t = _wall_stations(spec)
        geometry = build_geometry(
            spec.name, spec.construction, spec.length, spec.profile[0], spec.profile[1],
            _material(spec), wall_z, wall_t, spec.knob_mass, spec.end_cap_mass,
            spec.shear_correction, spec.slice_length, spec.barrel_end, spec.layup)
        meas = measured_properties(spec.measured) if spec.measured else None
        model, rec = reconcile(geometry, meas, spec.reconcile)
        freq = spec.measured.first_bending_frequency if spec.measured else None
        if freq is not None and meas is not None:
            model, corr = calibrate_stiffness(model, freq, meas.pivot)
            rec = Reconciliation(
                rec.method, rec.description + f"; stiffness x {corr['stiffness_scale']:.3f} to "
                f"match the measured {freq:.0f} Hz fundamental (model "
                f"{corr['model_first_frequency_hz']:.0f} Hz)", {**rec.corrections, **corr})
        m = spec.measured
        if m is not None and (m.hoop_frequency is not None or m.barrel_compression is not None):
            model, corr = calibrate_barrel(model, m.hoop_frequency, m.barrel_compression)
            rec = Reconciliation(rec.method, rec.description + _barrel_text(corr),
                                 {**rec.corrections, **corr})
    except ModelError as exc:
        raise spec.source.problem(exc.field, str(exc)) from None
    return BuiltBat(spec, geometry, model, rec, meas, freq)
