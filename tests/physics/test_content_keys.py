"""What a kept computation is keyed on is what it reads (batcert.workspace): the beam's modes
are computed from ``beam_of(bat)`` and the barrel's wall from ``wall_of(bat)``, which set the
fields the computation does not read to neutral values. If a computation came to read one of
them, the cached result would differ from the direct one; these tests hold them equal, exactly,
on the shipped bats."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from batcert import workspace
from batcert.commands.inputs import load_bat_any
from batcert.physics import barrel
from batcert.physics.modes import beam_of, compute_modes

PIVOT = 0.1524  # [m from knob]


@pytest.mark.parametrize("name", ["ash-34", "aluminium-34", "bbcor-alloy-34"])
def test_the_beam_modes_read_nothing_beam_of_sets_aside(name):
    bat = load_bat_any(name).built.model
    for support in ("free", "pinned"):
        direct = compute_modes(bat, support, PIVOT, 12)
        kept = compute_modes(beam_of(bat), support, PIVOT, 12)
        for f in ("z", "omega", "shapes", "rotations"):
            np.testing.assert_array_equal(getattr(kept, f), getattr(direct, f), err_msg=f)


@pytest.mark.parametrize("name", ["aluminium-34", "bbcor-alloy-34"])
def test_the_wall_reads_nothing_wall_of_sets_aside(name):
    bat = load_bat_any(name).built.model
    direct, kept = barrel.barrel_shell(bat), barrel.barrel_shell(barrel.wall_of(bat))
    for f in dataclasses.fields(direct):
        np.testing.assert_array_equal(getattr(kept, f.name), getattr(direct, f.name),
                                      err_msg=f.name)


def test_bats_that_differ_only_in_what_is_set_aside_share_and_others_do_not():
    bat = load_bat_any("aluminium-34").built.model
    m = bat.material
    other = dataclasses.replace(bat, name="another", bending_stiffness=bat.bending_stiffness * 2,
                                material=dataclasses.replace(m, name="x", loss_factor=0.05))
    key = workspace.content_key(barrel.wall_of(bat))
    assert workspace.content_key(barrel.wall_of(other)) == key
    stiffer = dataclasses.replace(bat, material=dataclasses.replace(
        m, youngs_modulus=m.youngs_modulus * 1.01))
    assert workspace.content_key(barrel.wall_of(stiffer)) != key
    assert workspace.content_key(beam_of(other)) != workspace.content_key(beam_of(bat))
