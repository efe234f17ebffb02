"""Reconcile a geometry-derived :class:`BatModel` to measured mass properties (mass, CG, MOI
about a pivot) exactly.

Two correction models, chosen by the bat spec (`reconcile:`):

``density-profile`` (default; suits wood and composite bats)
    The distributed mass (and rotary inertia) of every slice is multiplied by a smooth weight
    ``w(z) = a + b s + c s^2`` with ``s = z / L``. Mass, first moment and second moment about the
    pivot are linear in (a, b, c): three equations, three unknowns, solved exactly. A weight that
    leaves [0.5, 2.0] anywhere along the bat is refused as absurd (the profile, material or
    measured values are then inconsistent). With fewer measured values, fewer terms are used
    (mass only: uniform scale; mass and CG: linear weight).

``point-masses`` (suits hollow bats with a knob and an end cap)
    Uniform density scale plus two point masses at the knob end and at the tip (end cap).
    Refused when a point mass comes out negative, above 25 % of the bat's mass, or when the
    density scale leaves [0.5, 2.0].

``none``
    Keep the geometry-derived model (measured values are only reported).

The bat in Smith 2001 (ash, 906 g, CG 429 mm and MOI 0.209 kg m^2 about a pivot 150 mm from
the knob) is more compact about its CG than a profile with end masses can reach (that would need a
negative cap mass), which is why the default redistributes density smoothly instead.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from batcert.conventions import DEFAULT_PIVOT
from batcert.errors import ModelError
from batcert.physics.batmodel import BatModel

WEIGHT_BOUNDS = (0.5, 2.0)
MAX_POINT_MASS_FRACTION = 0.25
POINT_MASS_ROUNDING = 1e-6  # [kg]; smaller negative point masses are rounding


@dataclass(frozen=True)
class MeasuredMassProperties:
    mass: float  # [kg]
    balance_point: float | None = None  # CG from the knob [m]
    moi: float | None = None  # about `pivot` [kg m^2]
    pivot: float = DEFAULT_PIVOT  # [m from knob]


@dataclass(frozen=True)
class Reconciliation:
    method: str
    description: str
    corrections: dict[str, float] = field(default_factory=dict)


def _moments(bat: BatModel, weight: np.ndarray, pivot: float) -> np.ndarray:
    """Mass, first moment about the knob and MOI about the pivot of the distributed part."""
    m = bat.slice_masses * weight
    own = (bat.slice_masses * bat.dz**2 / 12 + bat.rotary_inertia * bat.dz) * weight
    return np.array([m.sum(), (m * bat.z_mid).sum(), (m * (bat.z_mid - pivot) ** 2 + own).sum()])


def _targets(bat: BatModel, meas: MeasuredMassProperties, n_eq: int) -> np.ndarray:
    t = np.array([meas.mass, meas.mass * (meas.balance_point or 0.0), meas.moi or 0.0])
    for z, mp in bat.point_masses:  # existing point masses stay as specified
        t -= np.array([mp, mp * z, mp * (z - meas.pivot) ** 2])
    return t[:n_eq]


def _check_measured(bat: BatModel, meas: MeasuredMassProperties) -> None:
    if meas.balance_point is not None and not 0 < meas.balance_point < bat.length:
        raise ModelError("measured", f"the CG ({meas.balance_point * 100:.1f} cm from the knob) "
                         f"lies outside the bat (length {bat.length * 100:.1f} cm)")
    if meas.moi is not None and meas.balance_point is not None:
        rbar = meas.balance_point - meas.pivot
        moi_cg = meas.moi - meas.mass * rbar**2
        if moi_cg <= 0:
            raise ModelError("measured.moi", f"MOI {meas.moi:.4f} kg m^2 about the pivot is below "
                             f"M rbar^2 = {meas.mass * rbar**2:.4f} kg m^2: no real bat has that "
                             "(check the pivot, the CG and the MOI)")
        gyration = np.sqrt(moi_cg / meas.mass)
        if gyration > bat.length / np.sqrt(12) * 1.05:
            raise ModelError("measured.moi", f"radius of gyration about the CG {gyration * 100:.1f} "
                             f"cm exceeds that of a uniform rod of the bat's length "
                             f"({bat.length / np.sqrt(12) * 100:.1f} cm): check the MOI and pivot")


def reconcile(bat: BatModel, meas: MeasuredMassProperties | None, method: str = "density-profile"
              ) -> tuple[BatModel, Reconciliation]:
    """Return a model matching the measured mass properties exactly, and what was changed."""
    if meas is None or method == "none":
        return bat, Reconciliation("none", "none: geometry-derived model used as is")
    _check_measured(bat, meas)
    n_eq = 1 + (meas.balance_point is not None) + (meas.moi is not None and meas.balance_point is not None)
    target = _targets(bat, meas, n_eq)
    if method == "point-masses" and n_eq == 3:
        return _point_masses(bat, meas, target)
    s = bat.z_mid / bat.length
    basis = [np.ones_like(s), s, s**2][:n_eq]
    a = np.stack([_moments(bat, b, meas.pivot)[:n_eq] for b in basis], axis=1)
    coef = np.linalg.solve(a, target)
    weight = sum(c * b for c, b in zip(coef, basis, strict=True))
    lo, hi = float(weight.min()), float(weight.max())
    if lo < WEIGHT_BOUNDS[0] or hi > WEIGHT_BOUNDS[1]:
        raise ModelError("measured", f"cannot reconcile: matching the measured mass properties "
                         f"needs the density scaled by {lo:.2f} to {hi:.2f} along the bat "
                         f"(allowed {WEIGHT_BOUNDS[0]}-{WEIGHT_BOUNDS[1]}); check the profile, "
                         "the material density, the wall and the measured values")
    model = replace(bat, linear_density=bat.linear_density * weight,
                    rotary_inertia=bat.rotary_inertia * weight)
    # knob and tip weights at the end slices' centres, the points the bounds were checked at
    corr = {"density_weight_knob": float(weight[0]), "density_weight_tip": float(weight[-1]),
            "density_weight_min": lo, "density_weight_max": hi,
            "mass_change": model.mass - bat.mass}
    desc = (f"density-profile: slice density x {lo:.3f}-{hi:.3f} (smooth quadratic weight, "
            f"knob {corr['density_weight_knob']:.3f}, tip {corr['density_weight_tip']:.3f}); "
            f"mass change {corr['mass_change'] * 1e3:+.1f} g")
    return model, Reconciliation("density-profile", desc, corr)


def _point_masses(bat: BatModel, meas: MeasuredMassProperties, target: np.ndarray):
    dist = _moments(bat, np.ones_like(bat.z_mid), meas.pivot)
    p = meas.pivot
    a = np.array([[dist[0], 1.0, 1.0], [dist[1], 0.0, bat.length], [dist[2], p**2, (bat.length - p) ** 2]])
    scale, m_knob, m_cap = np.linalg.solve(a, target)
    problems = []
    if not WEIGHT_BOUNDS[0] <= scale <= WEIGHT_BOUNDS[1]:
        problems.append(f"density scale {scale:.2f} (allowed {WEIGHT_BOUNDS[0]}-{WEIGHT_BOUNDS[1]})")
    for label, m in (("knob", m_knob), ("end-cap", m_cap)):
        if m < -POINT_MASS_ROUNDING:  # a zero mass may come out as -1e-17 from the solve
            problems.append(f"a negative {label} mass ({m * 1e3:.0f} g)")
        elif m > MAX_POINT_MASS_FRACTION * meas.mass:
            problems.append(f"{'an' if label[0] in 'aeiou' else 'a'} {label} mass of "
                            f"{m * 1e3:.0f} g (over {MAX_POINT_MASS_FRACTION:.0%} of the bat)")
    if problems:
        raise ModelError("measured", "cannot reconcile with point masses: it would need "
                         + " and ".join(problems) + "; try `reconcile: density-profile` or check "
                         "the profile, wall, material and measured values")
    points = tuple(bat.point_masses) + ((0.0, float(m_knob)), (bat.length, float(m_cap)))
    model = replace(bat, linear_density=bat.linear_density * scale,
                    rotary_inertia=bat.rotary_inertia * scale, point_masses=points)
    corr = {"density_scale": float(scale), "added_knob_mass": float(m_knob),
            "added_end_cap_mass": float(m_cap), "mass_change": model.mass - bat.mass}
    desc = (f"point-masses: density x {scale:.3f}, knob +{m_knob * 1e3:.1f} g, "
            f"end cap +{m_cap * 1e3:.1f} g")
    return model, Reconciliation("point-masses", desc, corr)
