"""The laminated tube of the finite-element check (scripts/fe_laminate_tube.py, recorded in
data/fe_laminate_tube.json) as batcert's shell of revolution: a uniform tube whose wall is the
recorded layup of the recorded ply (plane stress: E1, E2, G12, nu12), for the tube cases of
``tube_cases`` (which read ``outer_diameter``, ``length`` and ``shell(ends, elements)``)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from batcert.physics.laminate import Layer, OrthotropicPly, WallStack
from batcert.physics.shell_element import ShellOfRevolution

DATA = json.loads((Path(__file__).resolve().parent / "data" / "fe_laminate_tube.json")
                  .read_text())


def ply() -> OrthotropicPly:
    p = DATA["ply_material"]
    return OrthotropicPly("fe-check", p["E1"], p["E2"], p["G12"], p["nu12"], p["rho"])


def angles(layup: str) -> list[float]:
    """The layup's ply angles [deg] from the inner surface outward."""
    return [float(a) for a in DATA["layups"][layup]["angles_deg_inner_to_outer"]]


class LaminatedTube:
    """A uniform tube of the recorded geometry with the recorded layup as its wall."""

    def __init__(self, layup: str):
        thickness = DATA["layups"][layup]["ply_thickness_m"]
        self.outer_diameter = DATA["tube"]["outer_diameter_m"]
        self.length = DATA["tube"]["length_m"]
        self.stack = WallStack((tuple(Layer(ply(), np.radians(a), t) for a, t in
                                      zip(angles(layup), thickness, strict=True)),))
        self.wall = self.stack.thickness

    @property
    def mean_radius(self) -> float:
        return 0.5 * (self.outer_diameter - self.wall)

    def shell(self, ends: tuple[str, str], elements: int = 120) -> ShellOfRevolution:
        z = np.linspace(0.0, self.length, elements + 1)
        ones = np.ones(elements)
        rho = self.stack.areal_density / self.wall
        law = np.repeat(self.stack.law()[None], elements, axis=0)
        return ShellOfRevolution(z, np.full(z.size, self.mean_radius), self.wall * ones,
                                 rho * ones, ones, 0.3, ends, law)
