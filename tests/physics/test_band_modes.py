"""The banded count and Lanczos (batcert.physics.band_modes) against the dense generalized
eigen-solve they replace, on every shipped hollow bat's wall and on aluminium-34's wall from
60 to 140 % of its thickness (the span of a wall sweep), every order the engine keeps.

Tolerances. Both are exact methods; the banded one stops when each Ritz pair's residual is
below 1e-12 of its value, so frequencies agree to about that (measured: 3.5e-12 at most) and
mode shapes to about the residual over the gap to the next mode (measured 2.4e-12); 1e-9 and
1e-7 leave room for rounding on other machines and are far below anything the engine resolves
(its step changes exit speeds by 1e-5). A missed or extra mode fails the count check outright.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any
from batcert.model.build import build_bat
from batcert.physics import barrel
from batcert.physics.band_modes import count_below, lowest_modes
from batcert.physics.barrel.wall import NOMINAL_CUT, _orders
from batcert.physics.shell import Assembler, dense_modes_below

HOLLOW = ("aluminium-34", "bbcor-alloy-34", "composite-bbcor-34", "double-wall-alloy-34",
          "fastpitch-alloy-33", "slowpitch-composite-34", "youth-alloy-30", "hybrid-34")

WALLS = [(name, 1.0) for name in HOLLOW] + [("aluminium-34", 0.6), ("aluminium-34", 1.4)]


def wall(name: str, factor: float):
    """The bat with its wall thickness times ``factor``, rebuilt from its file."""
    loaded = load_bat_any(name)
    if factor == 1.0:
        return loaded.built.model
    spec = loaded.built.spec
    z, t = spec.wall
    return build_bat(dataclasses.replace(spec, wall=(z, tuple(w * factor for w in t)))).model


@pytest.mark.parametrize("name,factor", WALLS)
def test_banded_modes_are_the_dense_modes(name, factor):
    label = f"{name} wall x{factor}"
    shell = barrel.barrel_shell(wall(name, factor))
    if shell is None:
        pytest.skip(f"{label}: no hollow wall")
    assembler = Assembler(shell)
    for cut_hz in (NOMINAL_CUT, 10_000.0):
        cut = (2 * np.pi * cut_hz) ** 2
        for n in _orders(6):
            system = assembler.system(n)
            k, m = system.stiffness, system.mass
            lam_d, vec_d = dense_modes_below(system, cut)
            count = count_below(k - cut * m, system.free, system.node_dofs, shell.z.size)
            assert count == lam_d.size, (label, n, cut_hz)
            if lam_d.size == 0:
                continue
            found = lowest_modes(k, m, cut, 2 * system.node_dofs - 1, lam_d.size)
            assert found is not None, (label, n, cut_hz)
            lam, vec = found
            elastic = lam_d > 1.0  # order 0's rigid translation: 0 to rounding in both
            np.testing.assert_allclose(lam[elastic], lam_d[elastic], rtol=1e-9)
            sign = np.sign(np.einsum("ij,ij->j", vec_d, m @ vec))  # a mode's sign is free
            scale = np.abs(vec_d[:, elastic]).max()
            assert np.abs(vec[:, elastic] * sign[elastic] - vec_d[:, elastic]).max() < 1e-7 * scale


def test_count_below_counts_the_eigenvalues():
    # a diagonal pencil of ten nodes of one unknown: eigenvalues 1 .. 10, in blocks of four
    k, m = np.diag(np.arange(1.0, 11.0)), np.eye(10)
    free = np.arange(10)
    for lam, expected in ((0.5, 0), (2.5, 2), (6.5, 6), (9.5, 9), (20.0, 10)):
        assert count_below(k - lam * m, free, 1, 10) == expected
    # the cut on an eigenvalue inside the first block: a singular pivot block, no count
    assert count_below(k - 2.0 * m, free, 1, 10) is None


def test_lowest_modes_gives_up_rather_than_miss_one():
    # asked for more modes than lie below the cut: None (the caller solves densely)
    k, m = np.diag(np.arange(1.0, 41.0)), np.eye(40)
    assert lowest_modes(k, m, 5.5, 1, 6) is None
    lam, vec = lowest_modes(k, m, 5.5, 1, 5)
    np.testing.assert_allclose(lam, [1, 2, 3, 4, 5], rtol=1e-10)
    np.testing.assert_allclose(np.abs(vec.T @ vec), np.eye(5), atol=1e-10)
