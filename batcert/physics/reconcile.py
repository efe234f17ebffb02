"""Build a :class:`BatModel` from geometry and material, then reconcile it to measured mass
properties (mass, CG, MOI about a pivot) exactly.

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

from batcert.physics.batmodel import BatModel, Material

WEIGHT_BOUNDS = (0.5, 2.0)
MAX_POINT_MASS_FRACTION = 0.25
POINT_MASS_ROUNDING = 1e-6  # [kg]; smaller negative point masses are rounding


class ModelError(ValueError):
    """A bat that cannot be modelled; ``field`` names the offending spec field."""

    def __init__(self, field_: str, message: str):
        super().__init__(message)
        self.field = field_


@dataclass(frozen=True)
class MeasuredMassProperties:
    mass: float  # [kg]
    balance_point: float | None = None  # CG from the knob [m]
    moi: float | None = None  # about `pivot` [kg m^2]
    pivot: float = 0.1524  # [m from knob]


@dataclass(frozen=True)
class Reconciliation:
    method: str
    description: str
    corrections: dict[str, float] = field(default_factory=dict)


def section_properties(outer_diameter, inner_diameter):
    """Area [m^2] and second moment of area [m^4] of solid or annular circular sections."""
    do = np.asarray(outer_diameter, float)
    di = np.asarray(inner_diameter, float)
    area = np.pi / 4 * (do**2 - di**2)
    second_moment = np.pi / 64 * (do**4 - di**4)
    return area, second_moment


def default_shear_correction(construction: str, poisson_ratio: float) -> float:
    """Timoshenko shear coefficient: solid circle 6(1+nu)/(7+6nu); thin tube 2(1+nu)/(4+3nu)
    (Cowper 1966)."""
    nu = poisson_ratio
    if construction == "solid":
        return 6 * (1 + nu) / (7 + 6 * nu)
    return 2 * (1 + nu) / (4 + 3 * nu)


def build_geometry(name: str, construction: str, length: float, profile_z, profile_d,
                   material: Material, wall_z=None, wall_t=None, knob_mass: float = 0.0,
                   end_cap_mass: float = 0.0, shear_correction: float | None = None,
                   slice_length: float = 0.01, barrel_effective_width: float | None = None
                   ) -> BatModel:
    """Slice the bat (slices of at most ``slice_length`` [m]) and compute section properties.

    The profile (outer diameter [m] at stations ``profile_z`` [m from knob]) and the wall
    thickness are interpolated linearly, held constant beyond the first and last station.
    """
    n = max(int(np.ceil(length / slice_length - 1e-9)), 4)
    edges = np.linspace(0.0, length, n + 1)
    mid = 0.5 * (edges[1:] + edges[:-1])
    outer = np.interp(mid, profile_z, profile_d)
    if construction == "hollow":
        wall = np.interp(mid, wall_z, wall_t)
        inner = outer - 2 * wall
        if np.any(inner <= 0):
            zbad = mid[np.argmax(inner <= 0)]
            raise ModelError("wall", f"the wall ({np.interp(zbad, wall_z, wall_t) * 1e3:.1f} mm) "
                             f"fills the section at {zbad * 100:.1f} cm from the knob "
                             f"(outer diameter {np.interp(zbad, profile_z, profile_d) * 1e3:.1f} mm)")
    else:
        inner = np.zeros_like(outer)
    area, i_area = section_properties(outer, inner)
    kappa = shear_correction if shear_correction is not None else default_shear_correction(
        construction, material.poisson_ratio)
    points = []
    if knob_mass > 0:
        points.append((0.0, knob_mass))
    if end_cap_mass > 0:
        points.append((length, end_cap_mass))
    return BatModel(
        name=name, construction=construction, length=length, z_edges=edges,
        outer_diameter=outer, inner_diameter=inner,
        linear_density=material.density * area,
        rotary_inertia=material.density * i_area,
        bending_stiffness=material.youngs_modulus * i_area,
        shear_stiffness=kappa * material.shear_modulus * area,
        point_masses=tuple(points), material=material,
        barrel_effective_width=barrel_effective_width if construction == "hollow" else None,
        extras={"shear_correction": kappa},
    )


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
    weight = sum(c * b for c, b in zip(coef, basis))
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
