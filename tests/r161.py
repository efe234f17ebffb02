"""Test helper: the R161 wood bat of Nathan, Am. J. Phys. 68 (2000) 979, built slice by slice.

Built directly from the published profile (not through the YAML specs) so that the beam tests do
not depend on the spec and reconciliation layers: solid, 84 slices of 1 cm, density 649 kg/m^3,
E = 1.814e10 Pa, G = 1.05e9 Pa with no shear correction factor (kappa = 1), Table I.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from batcert.physics.batmodel import BatModel, Material

# the published profile as the project ships it (the same file as the development reference
# data's shared/data/r161-profile.csv), so that the tests need nothing beside the clone
PROFILE = Path(__file__).resolve().parents[1] / "bats" / "r161-profile.csv"

R161_WOOD = Material(name="r161-wood", density=649.0, youngs_modulus=1.814e10,
                     shear_modulus=1.05e9, poisson_ratio=0.3)  # Poisson ratio unused by the beam


def r161_profile() -> tuple[np.ndarray, np.ndarray]:
    """Slice far edges [m] and outer diameters [m] from the CSV (columns: cm, mm)."""
    data = np.loadtxt(PROFILE, delimiter=",", comments="#", skiprows=6)
    return data[:, 0] / 100.0, data[:, 1] / 1000.0


def solid_bat(name: str, z_edges, diameter, material: Material, kappa: float = 1.0,
              point_masses: tuple[tuple[float, float], ...] = ()) -> BatModel:
    """A solid bat from slice edges [m] and per-slice outer diameters [m]."""
    z_edges = np.asarray(z_edges, dtype=float)
    d = np.asarray(diameter, dtype=float)
    area = np.pi * d**2 / 4.0
    second_moment = np.pi * d**4 / 64.0
    return BatModel(
        name=name, construction="solid", length=float(z_edges[-1] - z_edges[0]), z_edges=z_edges,
        outer_diameter=d, inner_diameter=np.zeros_like(d),
        linear_density=material.density * area,
        rotary_inertia=material.density * second_moment,
        bending_stiffness=material.youngs_modulus * second_moment,
        shear_stiffness=kappa * material.shear_modulus * area,
        point_masses=point_masses, material=material)


def r161_bat() -> BatModel:
    """The R161 as Nathan (2000) modelled it: 84 solid 1 cm slices, Table I material."""
    far_edge, d = r161_profile()
    z_edges = np.concatenate([[0.0], far_edge])
    return solid_bat("R161", z_edges, d, R161_WOOD)
