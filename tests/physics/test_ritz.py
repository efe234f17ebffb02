"""Rayleigh-Ritz modes of drawn bats on the nominal bat's modes (batcert.physics.ritz), against
new modes of the drawn bat (batcert.physics.modes.compute_modes).

The drawn bats are the shipped ash-34 (solid, density-profile reconciliation) and aluminium-34
(hollow, point-mass reconciliation) with their measured mass, CG and MOI moved by three of their
stated standard uncertainties (as a Monte Carlo draw does, in the four sign patterns that pull
the mass distribution different ways), and aluminium-34 with its wall 5 % thicker or thinner
(a draw that changes the beam's stiffness). The basis is the nominal bat's 48 bending modes, 16
are kept, as in batcert.uncertainty.propagate.

The tolerances are a few times the errors measured on these bats (stated at each); they are
set per bat because the two bats' errors differ by up to two orders of magnitude.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from batcert.model.build import build_bat
from batcert.physics.modes import compute_modes
from batcert.physics.residual import nodal_flexibility, residual_compliance
from batcert.physics.ritz import reduced_modes, reduced_modes_many, ritz_basis, ritz_modes
from batcert.specs.bat import load_bat
from batcert.uncertainty.propagate import BASIS_MODES

REPO = Path(__file__).resolve().parents[2]

KEPT = 16  # the flexible engine's default number of bending modes
PIVOTS = {"pinned": 0.1524, "free": 0.15}  # 6 in pin (ncaa-bbcor); the study's 150 mm [m]
BARREL = np.linspace(0.45, 0.82, 12)  # impact points along the barrel [m from knob]
# Monte Carlo-like draws: (mass, CG, MOI) moved by these multiples of their standard uncertainty
PATTERNS = [(3, 3, 3), (3, -3, 3), (-3, 3, -3), (-3, -3, -3)]

# Tolerances for the mass-property draws, per bat: (bending frequencies, first five bending
# shapes, nodal flexibility, residual compliance), each relative. Measured worst cases over
# PATTERNS and both supports: ash-34 6.8e-8, 3.2e-6, 5.6e-8, 6.1e-5; aluminium-34 1.2e-5,
# 2.5e-4, 2.5e-6, 3.2e-4. About 3-5 times those.
TOLERANCE = {"ash-34": (3e-7, 1e-5, 2e-7, 2e-4),
             "aluminium-34": (5e-5, 1e-3, 1e-5, 1e-3)}


@pytest.fixture(scope="module")
def bats():
    out = {}
    for name in TOLERANCE:
        spec = load_bat(REPO / "bats" / f"{name}.yaml")
        out[name] = (spec, build_bat(spec).model)
    return out


@pytest.fixture(scope="module")
def bases(bats):
    """(RitzBasis, basis Modes) of each nominal bat and support."""
    return {(name, support): ritz_basis(model, support, PIVOTS[support], BASIS_MODES)
            for name, (_, model) in bats.items() for support in PIVOTS}


def drawn(spec, pattern):
    """The bat with its measured mass, CG and MOI moved by ``pattern`` standard uncertainties,
    rebuilt (reconciled) as the Monte Carlo rebuilds a draw."""
    m = spec.measured
    moved = {name: float(getattr(m, name)) + k * getattr(m, name).u
             for name, k in zip(("mass", "cg", "moi"), pattern, strict=True)}
    return build_bat(dataclasses.replace(spec, measured=dataclasses.replace(m, **moved))).model


def relative(a, b):
    """Largest difference relative to the largest magnitude of the reference ``b``."""
    return float(np.abs(np.asarray(a) - np.asarray(b)).max() / np.abs(b).max())


def thicker_wall(spec, factor):
    z, t = spec.wall
    return build_bat(dataclasses.replace(spec, wall=(z, tuple(w * factor for w in t)))).model


# --- the nominal bat on its own basis ---------------------------------------------------------
@pytest.mark.parametrize("support", PIVOTS)
@pytest.mark.parametrize("name", TOLERANCE)
def test_ritz_of_the_nominal_bat_reproduces_its_modes(bats, bases, name, support):
    # The basis spans the nominal bat's own modes, so Ritz gives them back to rounding: both
    # paths (assembly-free and general), and the carried flexibility is the nominal one (the
    # 16 replaced modes' sum phi phi^T / omega^2 is put back). Measured: frequencies 4.3e-11,
    # shapes 6.0e-11, rotations 6.3e-12, flexibility 6.5e-11; 5e-10 allows for rounding.
    _, model = bats[name]
    rb, basis = bases[name, support]
    exact = compute_modes(model, support, PIVOTS[support], KEPT)
    for modes in (reduced_modes(rb, model, KEPT), ritz_modes(model, basis, rb.flexibility, KEPT)):
        assert modes.n_rigid == exact.n_rigid and modes.omega.size == exact.omega.size
        np.testing.assert_array_equal(modes.omega[:exact.n_rigid], 0.0)
        np.testing.assert_allclose(modes.omega[exact.n_rigid:], exact.omega[exact.n_rigid:],
                                   rtol=5e-10)
        assert relative(modes.shapes, exact.shapes) < 5e-10  # also the sign convention
        assert relative(modes.rotations, exact.rotations) < 5e-10
        assert relative(modes.flexibility, rb.flexibility) < 5e-10
        np.testing.assert_array_equal(modes.z, exact.z)


# --- drawn mass properties: the fast path -------------------------------------------------------
@pytest.mark.parametrize("pattern", PATTERNS, ids=str)
@pytest.mark.parametrize("support", PIVOTS)
@pytest.mark.parametrize("name", TOLERANCE)
def test_drawn_mass_properties_match_new_modes(bats, bases, name, support, pattern):
    spec, nominal = bats[name]
    model = drawn(spec, pattern)
    # the draw only redistributes mass: same stiffness and point-mass positions as the nominal
    np.testing.assert_array_equal(model.bending_stiffness, nominal.bending_stiffness)
    assert not np.array_equal(model.linear_density, nominal.linear_density)
    rb, _ = bases[name, support]
    ritz = reduced_modes(rb, model, KEPT)
    exact = compute_modes(model, support, PIVOTS[support], KEPT)
    assert ritz.flexibility is not None  # the fast path carries the flexibility along
    f_tol, shape_tol, flex_tol, res_tol = TOLERANCE[name]
    nr = exact.n_rigid
    error = ritz.omega[nr:] / exact.omega[nr:] - 1
    assert np.abs(error).max() < f_tol
    # Ritz frequencies bound the exact ones from above; to rounding, as the error itself is
    # down to 1e-11 for the lowest modes (measured: -7.5e-11 at worst)
    assert error.min() > -1e-9
    # rigid modes are built exactly (beam.rigid_modes), not by Ritz: measured 1e-15
    assert relative(ritz.shapes[:nr], exact.shapes[:nr]) < 1e-12
    assert relative(ritz.rotations[:nr], exact.rotations[:nr]) < 1e-12
    assert relative(ritz.shapes[nr:nr + 5], exact.shapes[nr:nr + 5]) < shape_tol
    assert relative(ritz.flexibility, nodal_flexibility(model, exact)) < flex_tol
    np.testing.assert_allclose(residual_compliance(model, ritz, BARREL),
                               residual_compliance(model, exact, BARREL), rtol=res_tol)


@pytest.mark.parametrize("pattern", PATTERNS, ids=str)
@pytest.mark.parametrize("support", PIVOTS)
@pytest.mark.parametrize("name", TOLERANCE)
def test_fast_path_equals_the_general_path(bats, bases, name, support, pattern):
    # reduced_modes' assembly-free projections against ritz_modes' assembly of K and M of the
    # drawn bat: the same Ritz problem, so the same answer to rounding. Measured: frequencies
    # 6.4e-12, shapes 5.1e-12, rotations 4.1e-13, flexibility 1.4e-11; 1e-10 allows for it.
    spec, _ = bats[name]
    model = drawn(spec, pattern)
    rb, basis = bases[name, support]
    fast = reduced_modes(rb, model, KEPT)
    general = ritz_modes(model, basis, rb.flexibility, KEPT)
    np.testing.assert_array_equal(fast.omega[:fast.n_rigid], 0.0)
    np.testing.assert_allclose(fast.omega[fast.n_rigid:], general.omega[general.n_rigid:],
                               rtol=1e-10)
    assert relative(fast.shapes, general.shapes) < 1e-10
    assert relative(fast.rotations, general.rotations) < 1e-10
    assert relative(fast.flexibility, general.flexibility) < 1e-10


@pytest.mark.parametrize("support", PIVOTS)
def test_many_draws_solved_together_are_each_draw_alone(bats, bases, support):
    # reduced_modes_many stacks the draws' eigenproblems (and takes a drawn wall, which needs
    # its own assembly, aside): each draw's modes are what it gets alone, to rounding (the
    # stacked products round differently: measured 1.9e-12 on a frequency), in the order
    # given; 1e-10 is far below Ritz's own error (1e-5, TOLERANCE)
    spec, _ = bats["aluminium-34"]
    models = [drawn(spec, pattern) for pattern in PATTERNS] + [thicker_wall(spec, 1.05)]
    rb, _ = bases["aluminium-34", support]
    together = reduced_modes_many(rb, models, KEPT)
    for model, got in zip(models, together, strict=True):
        alone = reduced_modes_many(rb, [model], KEPT)[0]
        np.testing.assert_allclose(got.omega, alone.omega, rtol=1e-10)
        assert relative(got.shapes, alone.shapes) < 1e-10
        assert (got.flexibility is None) == (alone.flexibility is None)
    assert together[-1].flexibility is None  # the drawn wall: the general path
    assert len({m.omega[-1] for m in together}) == len(models)  # not one draw's modes twice


# --- a drawn wall: the general path ---------------------------------------------------------------
@pytest.mark.parametrize("factor", [1.05, 0.95])
@pytest.mark.parametrize("support", PIVOTS)
def test_a_drawn_wall_takes_the_general_path(bats, bases, support, factor):
    spec, nominal = bats["aluminium-34"]
    model = thicker_wall(spec, factor)
    assert not np.array_equal(model.bending_stiffness, nominal.bending_stiffness)
    rb, basis = bases["aluminium-34", support]
    ritz = reduced_modes(rb, model, KEPT)
    # the stiffness changed: no flexibility is carried (the residual compliance solves for it)
    assert ritz.flexibility is None
    general = ritz_modes(model, basis, None, KEPT)
    np.testing.assert_array_equal(ritz.omega, general.omega)  # it is that computation
    exact = compute_modes(model, support, PIVOTS[support], KEPT)
    old = compute_modes(nominal, support, PIVOTS[support], KEPT)
    nr = exact.n_rigid
    error = np.abs(ritz.omega[nr:] / exact.omega[nr:] - 1)
    # measured 3.4e-6 at worst (the frequencies themselves move by 1.9-2.2 %): 1.5e-5
    assert error.max() < 1.5e-5
    assert error.max() < 1e-3 * np.abs(exact.omega[nr:] / old.omega[nr:] - 1).min()
    assert relative(ritz.shapes[:nr], exact.shapes[:nr]) < 1e-12  # measured 0
    assert relative(ritz.shapes[nr:nr + 5], exact.shapes[nr:nr + 5]) < 1e-4  # measured 2.7e-5
    # the residual compliance from the drawn bat's own flexibility minus the Ritz modes:
    # measured 4.0e-4 at worst; 2e-3
    exact_residual = residual_compliance(model, exact, BARREL)
    np.testing.assert_allclose(residual_compliance(model, ritz, BARREL), exact_residual,
                               rtol=2e-3)
    # why a stiffness change must not carry the nominal flexibility: it would be off by
    # 1.5-1.6 % (measured), ten times more than the tolerance above
    carried = ritz_modes(model, basis, rb.flexibility, KEPT)
    off = np.abs(residual_compliance(model, carried, BARREL) / exact_residual - 1).max()
    assert off > 1e-2


def test_the_general_path_works_with_a_refined_mesh(bats):
    spec, nominal = bats["aluminium-34"]
    model = thicker_wall(spec, 1.05)
    rb, _ = ritz_basis(nominal, "pinned", PIVOTS["pinned"], BASIS_MODES, refine=2)
    ritz = reduced_modes(rb, model, KEPT)
    exact = compute_modes(model, "pinned", PIVOTS["pinned"], KEPT, refine=2)
    np.testing.assert_allclose(ritz.omega[1:], exact.omega[1:], rtol=1.5e-5)
