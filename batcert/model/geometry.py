"""The bat's geometry: slices, section properties and the beam properties they give.

:func:`build_geometry` turns a profile, a wall and a material into a :class:`BatModel` before any
reconciliation to measured values (:mod:`batcert.model.reconcile`).
"""

from __future__ import annotations

import numpy as np

from batcert.errors import ModelError
from batcert.physics.batmodel import BatModel, Layup, Material
from batcert.physics.laminate import WallStack


def section_properties(outer_diameter, inner_diameter):
    """Area [m^2] and second moment of area [m^4] of solid or annular circular sections."""
    do = np.asarray(outer_diameter, float)
    di = np.asarray(inner_diameter, float)
    area = np.pi / 4 * (do**2 - di**2)
    second_moment = np.pi / 64 * (do**4 - di**4)
    return area, second_moment


def stack_section(stack: WallStack, outer_diameter, damage: float = 0.0) -> dict[str, np.ndarray]:
    """The beam's section properties of slices whose wall is ``stack`` (walls innermost
    first, the outermost at ``outer_diameter`` [m]), after break-in ``damage``: per wall its
    annulus, its axial modulus ``1 / (a11 t)`` and shear modulus ``1 / (a66 t)`` (``a`` the
    inverse of the wall's ``A``: the wall stretched or sheared alone, the other resultants
    free) and its mean density; summed over the walls (concentric tubes bend about the same
    axis, so sliding walls add as bonded ones would). Keys ``area``, ``second_moment``,
    ``linear_density``, ``rotary_inertia``, ``bending_stiffness``, ``shear_area_modulus`` (G A,
    without the shear coefficient) and ``poisson_ratio`` (the stack's ``-a12 / a11``)."""
    outer = np.asarray(outer_diameter, dtype=float)
    keys = ("area", "second_moment", "linear_density", "rotary_inertia", "bending_stiffness",
            "shear_area_modulus")
    out = {k: np.zeros_like(outer) for k in keys}
    d_out = outer.copy()
    a_total = np.zeros((3, 3))
    for lam in reversed(stack.laminates(damage)):  # from the outermost wall inward
        d_in = d_out - 2 * lam.thickness
        area, second = section_properties(d_out, d_in)
        compliance = np.linalg.inv(lam.a)
        e_x = 1.0 / (compliance[0, 0] * lam.thickness)
        g_xy = 1.0 / (compliance[2, 2] * lam.thickness)
        rho = lam.areal_density / lam.thickness
        for key, value in (("area", area), ("second_moment", second),
                           ("linear_density", rho * area), ("rotary_inertia", rho * second),
                           ("bending_stiffness", e_x * second),
                           ("shear_area_modulus", g_xy * area)):
            out[key] += value
        a_total += lam.a
        d_out = d_in
    a_inv = np.linalg.inv(a_total)
    out["poisson_ratio"] = np.full_like(outer, -a_inv[0, 1] / a_inv[0, 0])
    return out


def stack_material(stack: WallStack) -> Material:
    """A bat's material where its layup covers the whole bat: the stack's effective axial
    modulus, shear modulus, Poisson's ratio and mean density (:func:`stack_section` of a thin
    wall), and the thickness-weighted mean of its plies' loss factors; named after its plies.
    The engines read it for the beam's damping only (the walls come from the layup)."""
    inv = np.linalg.inv(stack.law()[:3, :3])
    t = stack.thickness
    layers = [layer for wall in stack.walls for layer in wall]
    names = list(dict.fromkeys(layer.ply.name for layer in layers))
    eta = sum(layer.ply.loss_factor * layer.thickness for layer in layers) / t
    rho = stack.areal_density / t
    return Material(" + ".join(names) + " layup", rho, 1.0 / (inv[0, 0] * t),
                    1.0 / (inv[2, 2] * t), float(-inv[0, 1] / inv[0, 0]), float(eta))


def default_shear_correction(construction: str, poisson_ratio: float) -> float:
    """Timoshenko shear coefficient: solid circle 6(1+nu)/(7+6nu); thin tube 2(1+nu)/(4+3nu)
    (Cowper 1966)."""
    nu = poisson_ratio
    if construction == "solid":
        return 6 * (1 + nu) / (7 + 6 * nu)
    return 2 * (1 + nu) / (4 + 3 * nu)


def _span_index(spans: tuple[tuple[float, float, WallStack], ...], mid: np.ndarray,
                length: float, slice_length: float) -> np.ndarray:
    """The span of each slice (the one that holds its centre ``mid``), -1 for none; ModelError
    at a span that holds no slice's centre (narrower than a slice: its wall would not be in
    the model)."""
    index = np.full(mid.size, -1)
    for k, (start, end, _) in enumerate(spans):
        at = (mid >= start) & ((mid < end) | (end >= length))
        if not np.any(at):
            raise ModelError(f"layup[{k}].span", f"the span ({1e3 * (end - start):.3g} mm, "
                             f"{100 * start:.2f} to {100 * end:.2f} cm from the knob) holds no "
                             f"slice's centre: the model slices the bat every "
                             f"{1e3 * slice_length:.1f} mm and gives each slice the wall of the "
                             "span that holds its centre, so this span's wall would not be in "
                             "the model; widen it to a slice or more, or join it to its "
                             "neighbour")
        index[at] = k
    return index


def build_geometry(name: str, construction: str, length: float, profile_z, profile_d,
                   material: Material, wall_z=None, wall_t=None, knob_mass: float = 0.0,
                   end_cap_mass: float = 0.0, shear_correction: float | None = None,
                   slice_length: float = 0.01, barrel_end: str = "closed",
                   spans: tuple[tuple[float, float, WallStack], ...] = ()) -> BatModel:
    """Slice the bat (slices of at most ``slice_length`` [m]) and compute section properties.

    The profile (outer diameter [m] at stations ``profile_z`` [m from knob]) and the wall
    thickness are interpolated linearly, held constant beyond the first and last station.
    A hollow bat's ``spans`` ``(start, end, stack)`` [m from knob] give the slices whose centre
    lies in ``[start, end)`` (the last span's end included) a laminated or multi-wall wall
    (:func:`stack_section`); the other slices have ``wall_t`` of ``material``.
    """
    n = max(int(np.ceil(length / slice_length - 1e-9)), 4)
    edges = np.linspace(0.0, length, n + 1)
    mid = 0.5 * (edges[1:] + edges[:-1])
    outer = np.interp(mid, profile_z, profile_d)
    index = _span_index(spans, mid, length, edges[1] - edges[0])
    if construction == "hollow":
        wall = np.interp(mid, wall_z, wall_t) if wall_z is not None else np.zeros(n)
        for k, (_, _, stack) in enumerate(spans):
            wall[index == k] = stack.thickness
        inner = outer - 2 * wall
        if np.any(inner <= 0):
            i = int(np.argmax(inner <= 0))
            raise ModelError("layup" if index[i] >= 0 else "wall",
                             f"the wall ({wall[i] * 1e3:.{1 if index[i] < 0 else 2}f} mm) "
                             f"fills the section at "
                             f"{mid[i] * 100:.1f} cm from the knob (outer diameter "
                             f"{outer[i] * 1e3:.1f} mm)")
    else:
        inner = np.zeros_like(outer)
    area, i_area = section_properties(outer, inner)
    kappa = shear_correction if shear_correction is not None else default_shear_correction(
        construction, material.poisson_ratio)
    beam = {"linear_density": material.density * area, "rotary_inertia": material.density * i_area,
            "bending_stiffness": material.youngs_modulus * i_area,
            "shear_stiffness": kappa * material.shear_modulus * area}
    for k, (_, _, stack) in enumerate(spans):
        at = index == k
        sec = stack_section(stack, outer[at])
        kap = shear_correction if shear_correction is not None else default_shear_correction(
            "hollow", float(sec["poisson_ratio"][0]))
        for key in ("linear_density", "rotary_inertia", "bending_stiffness"):
            beam[key][at] = sec[key]
        beam["shear_stiffness"][at] = kap * sec["shear_area_modulus"]
    points = []
    if knob_mass > 0:
        points.append((0.0, knob_mass))
    if end_cap_mass > 0:
        points.append((length, end_cap_mass))
    return BatModel(
        name=name, construction=construction, length=length, z_edges=edges,
        outer_diameter=outer, inner_diameter=inner, **beam,
        point_masses=tuple(points), material=material,
        barrel_end=barrel_end,
        extras={"shear_correction": kappa},
        layup=Layup(tuple(stack for _, _, stack in spans), index) if spans else None,
    )
