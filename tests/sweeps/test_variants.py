"""batcert.sweeps.variants: reading ``--vary`` ranges and building the variants of a bat or a
protocol (no engine runs: every expected number follows from the inputs by arithmetic).

Tolerances: where a variant's value is made by a scale factor (``value / nominal``) applied to
the nominal, the result carries one or two roundings, so it is compared with ``rel=1e-15``
(a few units in the last place of a double); everything else is compared exactly.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.commands.sweep import plan_sweep
from batcert.model.build import measured_properties
from batcert.sweeps.variants import (
    PARAMETERS,
    Case,
    ParameterError,
    parse_vary,
    read_range,
)

MM = 1e-3  # [m]
MPH = 0.44704  # [m/s], exact by definition
ULPS = 1e-15  # relative: a value made by one scale factor and one product (see the docstring)


def case_of(bat: str, protocol: str) -> tuple[Case, object]:
    built = load_bat_any(bat).built
    return Case(built.spec, load_protocol_any(protocol).protocol), built


def vary(case_built, name: str, value: float) -> Case:
    case, built = case_built
    return PARAMETERS[name].apply(case, built, value)


@pytest.fixture(scope="module")
def alu():
    """aluminium-34 (hollow; measured mass 863 g, CG 418 mm and MOI 0.198 kg m^2 about a pivot
    150 mm from the knob) under ncaa-bbcor."""
    return case_of("aluminium-34", "ncaa-bbcor")


@pytest.fixture(scope="module")
def ash():
    """ash-34 (solid; measured 906 g, CG 429 mm, MOI 0.209 kg m^2) under ncaa-bbcor."""
    return case_of("ash-34", "ncaa-bbcor")


# ---- ranges ---------------------------------------------------------------------------------
def test_registry_names_follow_the_glossary():
    assert list(PARAMETERS) == ["wall", "youngs_modulus", "density", "barrel_diameter", "mass",
                                "moi", "hoop_frequency", "ply_angle", "ply_count",
                                "wall_split", "pitch_speed", "bat_angular_speed",
                                "relative_speed"]
    for name, p in PARAMETERS.items():
        assert p.name == name and p.changes in ("geometry", "measured", "protocol")
        assert p.bounds[0] < p.bounds[1] and p.tolerance > 0


def test_percent_of_nominal():
    axis = read_range("wall", "60%:140%:5", 2.7 * MM)
    assert axis.name == "wall" and axis.percent and axis.nominal == 2.7 * MM
    # each end is nominal x percent / 100, then evenly spaced (np.linspace): a few ulps
    assert axis.values == pytest.approx([x * 2.7 * MM for x in (0.6, 0.8, 1.0, 1.2, 1.4)],
                                        rel=ULPS)


def test_quantities_with_units():
    axis = read_range("pitch_speed", "100 mph:136mph:2", 60.0)
    assert not axis.percent
    # the ends are the quantities themselves (linspace keeps both ends exactly)
    assert axis.values == (100 * MPH, 136 * MPH)
    axis = read_range("wall", "2mm:3.5mm:7", 2.7 * MM)
    assert len(axis.values) == 7 and axis.values[0] == 2 * MM and axis.values[-1] == 3.5 * MM
    assert np.diff(axis.values) == pytest.approx([0.25 * MM] * 6, rel=1e-12)  # linspace steps


def test_number_of_values():
    assert len(read_range("wall", "2mm:3mm:2", 2.7 * MM).values) == 2
    assert len(read_range("wall", "2mm:3mm", 2.7 * MM, points=9).values) == 9  # design's --points
    assert read_range("wall", "2.5mm", 2.7 * MM).values == (2.5 * MM,)  # one value
    for bad in ("2mm:3mm:1", "2mm:3mm:0", "2mm:3mm"):  # N < 2, or no N and no points
        with pytest.raises(ParameterError, match="N >= 2"):
            read_range("wall", bad, 2.7 * MM)


def test_unknown_parameter_suggests_the_nearest_name():
    with pytest.raises(ParameterError, match=r"unknown parameter 'wal'.*did you mean 'wall'\?"):
        parse_vary("wal=60%:140%:5")
    with pytest.raises(ParameterError, match="did you mean 'bat_angular_speed'"):
        parse_vary("bat_angular_sped=1rad/s:2rad/s:2")
    with pytest.raises(ParameterError, match="give PARAM=START:STOP:N"):
        parse_vary("wall")
    assert parse_vary(" wall = 60%:140%:5 ") == ("wall", "60%:140%:5")


def test_percent_and_units_cannot_mix():
    with pytest.raises(ParameterError, match="both ends as percentages or both as quantities"):
        read_range("wall", "60%:3mm:5", 2.7 * MM)


def test_values_outside_the_accepted_range():
    with pytest.raises(ParameterError, match=r"wall: 0\.025 \(SI\) is outside the accepted range"):
        read_range("wall", "2mm:25mm:3", 2.7 * MM)  # wall accepts 0.1 mm to 20 mm
    with pytest.raises(ParameterError, match="outside the accepted range"):
        read_range("wall", "0%:100%:3", 2.7 * MM)  # a zero wall


def test_units_of_the_wrong_kind_or_missing():
    with pytest.raises(ParameterError, match="^wall: "):
        read_range("wall", "2kg:3kg:2", 2.7 * MM)
    with pytest.raises(ParameterError, match="a unit is required"):
        read_range("wall", "2:3:2", 2.7 * MM)
    with pytest.raises(ParameterError, match="not a percentage"):
        read_range("wall", "x%:140%:2", 2.7 * MM)


def test_percent_of_a_zero_nominal_is_refused():
    # ncaa-bbcor's bat is at rest: its nominal bat_angular_speed is 0 rad/s
    case, built = case_of("ash-34", "ncaa-bbcor")
    assert PARAMETERS["bat_angular_speed"].nominal(case, built) == 0.0
    with pytest.raises(ParameterError, match="nominal value is zero"):
        plan_sweep("ash-34", "ncaa-bbcor", ["bat_angular_speed=50%:150%:3"], engine="rigid")
    # absolute values are fine
    plan = plan_sweep("ash-34", "ncaa-bbcor", ["bat_angular_speed=0rad/s:20rad/s:3"],
                      engine="rigid")
    assert plan.axes[0].values == (0.0, 10.0, 20.0)


def test_hundred_percent_is_the_nominal_exactly():
    nominal = 136 * MPH  # ncaa-bbcor's pitch speed
    assert read_range("pitch_speed", "100%:120%:2", nominal).values[0] == nominal


# ---- geometry and material ------------------------------------------------------------------
def test_wall_thickest_station_takes_the_value(alu):
    case, _ = alu
    z, t = case.bat.wall
    assert max(t) == 2.7 * MM  # aluminium-34: 1.8 mm handle, 2.2 mm taper, 2.7 mm barrel
    assert PARAMETERS["wall"].nominal(*alu) == 2.7 * MM
    new = vary(alu, "wall", 3.0 * MM).bat
    z2, t2 = new.wall
    assert z2 == z
    assert max(t2) == pytest.approx(3.0 * MM, rel=ULPS)
    # every station in proportion: the ratios to the thickest stay
    assert [x / max(t2) for x in t2] == pytest.approx([x / max(t) for x in t], rel=ULPS)
    assert new.measured is None  # the measurements belong to the nominal bat
    assert case.bat.measured is not None  # and the nominal bat keeps them


def test_uniform_wall(alu):
    case, built = alu
    uniform = replace(case, bat=replace(case.bat, wall=2.5 * MM))
    assert PARAMETERS["wall"].nominal(uniform, built) == 2.5 * MM
    assert PARAMETERS["wall"].apply(uniform, built, 3.0 * MM).bat.wall == pytest.approx(3.0 * MM,
                                                                                        rel=ULPS)


def test_wall_needs_a_hollow_bat():
    with pytest.raises(ParameterError, match="wall needs a hollow bat; 'Ash 34 in"):
        plan_sweep("ash-34", "ncaa-bbcor", ["wall=2mm:3mm:2"], engine="rigid")


def test_barrel_diameter_keeps_handle_and_knob(alu):
    case, _ = alu
    z, d = case.bat.profile
    i = int(np.argmin(d))  # the thinnest handle station (0.95 in at 9 in)
    h, big = d[i], max(d)
    assert (z[i], h, big) == pytest.approx((9 * 0.0254, 0.95 * 0.0254, 2.625 * 0.0254), rel=ULPS)
    assert PARAMETERS["barrel_diameter"].nominal(*alu) == big
    new = vary(alu, "barrel_diameter", 70 * MM).bat
    z2, d2 = new.profile
    assert z2 == z
    assert d2[: i + 1] == d[: i + 1]  # knob and handle unchanged, exactly
    barrel = [j for j, x in enumerate(d) if x == big]
    assert [d2[j] for j in barrel] == pytest.approx([70 * MM] * len(barrel), rel=ULPS)
    # the taper in proportion: (d' - h) / (d - h) is one factor beyond the handle
    s = (70 * MM - h) / (big - h)
    assert [(d2[j] - h) / (d[j] - h) for j in range(i + 1, len(d))] == pytest.approx(
        [s] * (len(d) - i - 1), rel=1e-12)  # a difference of near-equal diameters: 1e-12
    assert new.measured is None


def test_barrel_no_larger_than_the_handle(alu):
    with pytest.raises(ParameterError, match="not larger than the handle"):
        vary(alu, "barrel_diameter", 20 * MM)  # the handle is 0.95 in = 24.1 mm


def test_youngs_modulus_scales_the_shear_modulus(alu):
    m = alu[0].bat.material
    new = vary(alu, "youngs_modulus", 2 * m.youngs_modulus).bat
    assert new.material.youngs_modulus == pytest.approx(2 * m.youngs_modulus, rel=ULPS)
    assert new.material.shear_modulus == pytest.approx(2 * m.shear_modulus, rel=ULPS)
    assert (new.material.density, new.material.poisson_ratio, new.material.loss_factor) == (
        m.density, m.poisson_ratio, m.loss_factor)
    assert new.measured is None


def test_density_changes_only_the_density(alu):
    m = alu[0].bat.material
    new = vary(alu, "density", 1.1 * m.density).bat.material
    assert new.density == pytest.approx(1.1 * m.density, rel=ULPS)
    assert (new.youngs_modulus, new.shear_modulus) == (m.youngs_modulus, m.shear_modulus)


# ---- measured properties --------------------------------------------------------------------

@pytest.mark.parametrize("bat", ["ash-34", "aluminium-34"])
def test_measured_mass_keeps_cg_and_moi(bat):
    cb = case_of(bat, "ncaa-bbcor")
    before = measured_properties(cb[0].bat.measured)
    assert PARAMETERS["mass"].nominal(*cb) == before.mass
    after = measured_properties(vary(cb, "mass", 0.95).bat.measured)
    assert after.mass == 0.95
    assert (after.balance_point, after.moi, after.pivot) == (before.balance_point, before.moi,
                                                             before.pivot)


def test_measured_moi_keeps_mass_and_cg(ash):
    before = measured_properties(ash[0].bat.measured)
    after = measured_properties(vary(ash, "moi", 0.2).bat.measured)
    assert after.moi == 0.2
    assert (after.mass, after.balance_point) == (before.mass, before.balance_point)


def test_mass_without_cg_and_moi_is_refused():
    # bbcor-alloy-34 gives its measured mass (31 oz) only
    with pytest.raises(ParameterError, match="without its CG and MOI"):
        plan_sweep("bbcor-alloy-34", "ncaa-bbcor", ["mass=95%:105%:3"], engine="rigid")


def test_hoop_frequency_with_absolute_values():
    plan = plan_sweep("aluminium-34", "ncaa-bbcor", ["hoop_frequency=1500Hz:2500Hz:3"],
                      engine="rigid")
    assert plan.axes[0].values == (1500.0, 2000.0, 2500.0)


def test_hoop_frequency_on_a_bat_with_a_measured_mass_only():
    plan_sweep("bbcor-alloy-34", "ncaa-bbcor", ["hoop_frequency=1200Hz:3000Hz:9"],
               engine="rigid")


# ---- test speeds ----------------------------------------------------------------------------
def test_pitch_speed_must_stay_below_the_relative_speed():
    # proposed: pitched-and-swung pitches at 31 m/s into a matched 60 m/s
    with pytest.raises(ParameterError, match=r"pitch speed \(60 m/s\) must stay below the "
                                             r"relative speed \(60 m/s\)"):
        plan_sweep("ash-34", "proposed", ["pitch_speed=40m/s:60m/s:3"], engine="rigid")
    with pytest.raises(ParameterError, match="must stay below the relative speed"):
        plan_sweep("ash-34", "proposed", ["relative_speed=20m/s:60m/s:3"], engine="rigid")
    plan = plan_sweep("ash-34", "proposed", ["pitch_speed=20m/s:40m/s:3"], engine="rigid")
    assert plan.axes[0].nominal == 31.0


def test_speeds_that_do_not_apply_to_the_protocol():
    with pytest.raises(ParameterError, match="matches a relative speed"):
        plan_sweep("ash-34", "proposed", ["bat_angular_speed=40rad/s:60rad/s:3"],
                   engine="rigid")
    with pytest.raises(ParameterError, match="sets explicit speeds"):
        plan_sweep("ash-34", "ncaa-bbcor", ["relative_speed=50m/s:60m/s:3"], engine="rigid")


def test_bat_angular_speed_replaces_a_linear_bat_speed():
    # ncaa-besr: 66 mph at 6 in from the tip, pivot 6 in: w1 = v / (L - 12 in)
    cb = case_of("ash-34", "ncaa-besr")
    w1 = 66 * MPH / (0.860 - 12 * 0.0254)
    assert PARAMETERS["bat_angular_speed"].nominal(*cb) == pytest.approx(w1, rel=ULPS)
    (c,) = vary(cb, "bat_angular_speed", 50.0).protocol.conditions
    assert (c.bat_angular_speed, c.bat_speed, c.bat_speed_from_tip) == (50.0, None, None)
    assert c.pitch_speed == 70 * MPH


# ---- combinations ---------------------------------------------------------------------------
def test_geometry_and_measured_cannot_vary_together():
    with pytest.raises(ParameterError, match="cannot vary together"):
        plan_sweep("aluminium-34", "ncaa-bbcor", ["wall=90%:110%:3", "mass=95%:105%:3"],
                   engine="rigid")


def test_each_parameter_once_and_at_most_two():
    with pytest.raises(ParameterError, match="varied once"):
        plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2",
                                             "pitch_speed=55m/s:65m/s:2"], engine="rigid")
    with pytest.raises(ParameterError, match="at most 2"):
        plan_sweep("ash-34", "ncaa-bbcor", ["pitch_speed=50m/s:60m/s:2", "moi=95%:105%:2",
                                             "mass=95%:105%:2"], engine="rigid")
    with pytest.raises(ParameterError, match="give a parameter to vary"):
        plan_sweep("ash-34", "ncaa-bbcor", [], engine="rigid")
