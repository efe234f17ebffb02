"""A bat after break-in: its layup's plies softened (:func:`batcert.physics.laminate.broken_in`)
in the barrel shell and in the beam.

The shell reads the damage directly (``BatModel.wall_damage``); the beam's bending and shear
stiffness of every laminated slice are scaled by the ratio of the damaged section's to the new
one's (:func:`batcert.model.geometry.stack_section`), so that a calibration of the new bat (a
measured bending or hoop frequency) is kept and the damage acts on top of it.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from batcert.model.geometry import stack_section
from batcert.physics.batmodel import BatModel


def breaks_in(model: BatModel, z: float) -> bool:
    """Whether the wall at ``z`` [m from knob] has plies that soften with use (a composite
    barrel there; a hybrid's composite handle does not make its alloy barrel break in)."""
    if model.layup is None:
        return False
    stack = model.layup.stack_of(int(model.slice_at(z)))
    return stack is not None and stack.breaks_in


def broken_in_model(model: BatModel, damage: float) -> BatModel:
    """``model`` (new: ``wall_damage`` 0) with its layup's plies at break-in ``damage``."""
    if model.wall_damage != 0.0:
        raise ValueError("break-in is applied to the new bat (wall_damage 0)")
    if model.layup is None or damage == 0.0:
        return model
    bending = np.array(model.bending_stiffness, dtype=float)
    shear = np.array(model.shear_stiffness, dtype=float)
    index = np.asarray(model.layup.index)
    for k, stack in enumerate(model.layup.stacks):
        at = index == k
        if not np.any(at):
            continue
        new = stack_section(stack, model.outer_diameter[at])
        worn = stack_section(stack, model.outer_diameter[at], damage)
        bending[at] *= worn["bending_stiffness"] / new["bending_stiffness"]
        shear[at] *= worn["shear_area_modulus"] / new["shear_area_modulus"]
    return replace(model, wall_damage=float(damage), bending_stiffness=bending,
                   shear_stiffness=shear)
