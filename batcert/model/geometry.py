"""The bat's geometry: slices, section properties and the beam properties they give.

:func:`build_geometry` turns a profile, a wall and a material into a :class:`BatModel` before any
reconciliation to measured values (:mod:`batcert.model.reconcile`).
"""

from __future__ import annotations

import numpy as np

from batcert.errors import ModelError
from batcert.physics.batmodel import BatModel, Material


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
                   slice_length: float = 0.01, barrel_end: str = "closed") -> BatModel:
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
        barrel_end=barrel_end,
        extras={"shear_correction": kappa},
    )
