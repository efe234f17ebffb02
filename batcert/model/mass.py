"""Mass properties of a built bat about a pivot: model, geometry and measured, side by side."""

from __future__ import annotations

from batcert.model.build import BuiltBat
from batcert.physics import rigid
from batcert.results.run import MassProperties

CLEARANCE = 0.01  # [m] the pivot, the CG, impacts and bat-speed stations keep this far apart


def pivot_problem(model, pivot: float) -> str | None:
    """Why ``pivot`` [m from the knob] cannot be a test pivot of ``model``, or None. A pivot
    must lie on the bat, on the handle side of the CG and :data:`CLEARANCE` from it: at the
    CG the centre of percussion (Smith 2001 Eq. 4) is at infinity, beyond it the bat recoils
    the wrong way."""
    if 0 <= pivot < model.balance_point - CLEARANCE:
        return None
    return (f"the pivot ({pivot * 100:.1f} cm from the knob) must lie on the bat on the handle "
            f"side of its CG ({model.balance_point * 100:.1f} cm from the knob), at least "
            f"{CLEARANCE * 100:.0f} cm from it")


def mass_properties(built: BuiltBat, pivot: float) -> MassProperties:
    """Mass, CG, MOI and centre of percussion (Smith 2001 Eq. 4) about ``pivot`` [m from knob]
    of the reconciled model, of the geometry before reconciliation and of the measured values
    (the measured MOI moved to ``pivot`` by the parallel-axis theorem)."""
    g, m, meas = built.geometry, built.model, built.measured
    moi = m.moi_about(pivot)
    meas_moi = meas_cg = meas_cop = None
    if meas is not None and meas.balance_point is not None:
        meas_cg = meas.balance_point - pivot
        if meas.moi is not None:
            moi_cg = meas.moi - meas.mass * (meas.balance_point - meas.pivot) ** 2
            meas_moi = moi_cg + meas.mass * meas_cg ** 2
            meas_cop = float(rigid.centre_of_percussion(meas_moi, meas.mass, meas_cg))
    return MassProperties(
        length=m.length, pivot=pivot, mass=m.mass, cg=m.cg_from(pivot), moi_pivot=moi,
        cop=rigid.centre_of_percussion(moi, m.mass, m.cg_from(pivot)),
        geometry_mass=g.mass, geometry_cg=g.cg_from(pivot), geometry_moi_pivot=g.moi_about(pivot),
        measured_mass=meas.mass if meas else None, measured_cg=meas_cg,
        measured_moi_pivot=meas_moi, reconciliation=built.reconciliation.description,
        corrections=dict(built.reconciliation.corrections),
        geometry_cop=float(rigid.centre_of_percussion(g.moi_about(pivot), g.mass,
                                                      g.cg_from(pivot))),
        measured_cop=meas_cop)
