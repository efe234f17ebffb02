"""Units at the edges (batcert.units): lab-style quantities to SI, and SI to US for display.

Conversion factors are those of REFERENCE-DATA.md, Units: 1 in = 0.0254 m, 1 mph = 0.44704 m/s,
1 oz = 28.3495 g, 1 oz*in^2 = 1.8290e-5 kg*m^2.
"""

from __future__ import annotations

import math

import pytest

from batcert.units import DIMENSIONS, UnitError, parse_quantity, show, to_us


@pytest.mark.parametrize("dimension", sorted(DIMENSIONS))
def test_every_example_parses(dimension):
    example = DIMENSIONS[dimension][3]
    value = parse_quantity(example, dimension)
    assert math.isfinite(value) and value > 0


@pytest.mark.parametrize("text, dimension, si, rel", [
    ("2500 rpm", "angular_speed", 261.799, 2e-6),  # 2500 * 2 pi / 60, given to 3 decimals
    ("53 rad/s", "angular_speed", 53.0, 1e-12),
    # REFERENCE-DATA gives 1 oz*in^2 = 1.8290e-5 kg m^2 (5 figures): 12000 x = 0.21948
    ("12000 oz*in^2", "moi", 0.21948, 2e-5),
    ("0.209 kg*m^2", "moi", 0.209, 1e-12),
    ("34 in", "length", 0.8636, 1e-12),
    ("860 mm", "length", 0.860, 1e-12),
    ("31 oz", "mass", 31 * 0.028349523125, 1e-12),
    ("906 g", "mass", 0.906, 1e-12),
    ("70 mph", "speed", 31.2928, 1e-12),
    ("85 ft/s", "speed", 25.908, 1e-12),
    ("649 kg/m^3", "density", 649.0, 1e-12),
    ("71.7 GPa", "modulus", 71.7e9, 1e-12),
    ("165 Hz", "frequency", 165.0, 1e-12),
    ("2.2 kHz", "frequency", 2200.0, 1e-12),
    ("0.5 s", "time", 0.5, 1e-12),
    ("1.2e3 mm", "length", 1.2, 1e-12),
    # the ASCII micro- spellings labs type (issue 40: "um" was an unknown unit)
    ("250 um", "length", 250e-6, 1e-12),
    ("30 us", "time", 30e-6, 1e-12),
])
def test_conversions(text, dimension, si, rel):
    assert parse_quantity(text, dimension) == pytest.approx(si, rel=rel)


@pytest.mark.parametrize("value, dimension, message", [
    (34, "length", "a unit is required (e.g. '34 in'), got the bare number 34"),
    ("34", "length", "a unit is required"),
    ("34 kg", "length", "'34 kg' is not a length"),
    ("34 inchez", "length", "unknown unit 'inchez'"),
    ("in 34", "length", "expected a number then a unit"),
    ("34 in)", "length", "not a unit expression"),  # pint's tokenizer error is caught
    (None, "length", "expected a length with a unit"),
    (True, "mass", "expected a mass with a unit"),
    ([1, 2], "mass", "expected a mass with a unit"),
    # pint treats the radian as dimensionless; batcert keeps rotation and cycles apart
    ("8 Hz", "angular_speed", "ambiguous as an angular speed"),
    ("53 1/s", "angular_speed", "ambiguous as an angular speed"),
    ("1100 rad/s", "frequency", "is an angular speed; give a frequency"),
    ("2500 rpm", "frequency", "is an angular speed"),
    # pint's oddities: each a UnitError, never pint's own exception (issue 24)
    ("0.5 dimensionless", "length", "'0.5 dimensionless' is not a length"),
    ("5 dimensionless", "speed", "'5 dimensionless' is not a speed"),
    ("1 percent", "length", "'1 percent' is not a length"),
    ("5 meter ** 2", "length", "'5 meter ** 2' is not a length"),
    ("1e400 m", "length", "outside the range accepted for a length"),
    ("nan m", "length", "expected a number then a unit"),
    ("0x10 m", "length", "unknown unit 'x10'"),
    ("5 Δm", "length", "unknown unit 'Δm'"),
    ("5 neper cycle", "length", "not a unit that converts to m"),  # pint: AssertionError
    ("5 dB", "length", "not a length"),
    ("5 degree ** 1e9 lbf", "force", "not a unit that converts to N"),  # pint: OverflowError
])
def test_refused(value, dimension, message):
    with pytest.raises(UnitError) as exc:
        parse_quantity(value, dimension)
    assert message in str(exc.value)


def test_display_side_by_side():
    assert str(show(0.8636, "length")) == "0.864 m (34.00 in)"
    assert str(show(31.2928, "speed", 2)) == "31.29 m/s (70.0 mph)"
    assert to_us(0.21948, "moi") == pytest.approx(12000, rel=2e-5)
    assert to_us(261.79938779914943, "angular_speed") == pytest.approx(2500)
    assert str(show(None, "mass")) == "—"


def test_fast_units_agree_with_pint():
    # units.FAST_UNITS skips pint for common units; each factor must equal pint's conversion
    # (tolerance: floating-point rounding only).
    import pint

    from batcert.units import DIMENSIONS, FAST_UNITS
    ureg = pint.UnitRegistry()
    for dimension, units in FAST_UNITS.items():
        si = DIMENSIONS[dimension][1]
        for unit, factor in units.items():
            expected = ureg.Quantity(1.0, ureg.parse_units(unit)).to(si).magnitude
            assert factor == pytest.approx(expected, rel=1e-12), (dimension, unit)


def test_a_word_pint_parses_but_cannot_name_is_an_unknown_unit():
    """pint's parser passes "per" ("3 furlongs per fortnight"), then cannot name it: a clear
    UnitError, not pint's UndefinedUnitError (found by the robustness corpus's hits files)."""
    import pytest

    from batcert.units import UnitError, parse_quantity
    with pytest.raises(UnitError, match="unknown unit 'per'"):
        parse_quantity("3 furlongs per fortnight", "speed")


def test_a_caller_may_widen_the_plausible_size():
    """A field's elevation is no bat length: 5280 ft is refused as a length (10 m at most) but
    read with the caller's own bound, and that bound still refuses what lies beyond it."""
    with pytest.raises(UnitError, match="at most 10 m"):
        parse_quantity("5280 ft", "length")
    assert parse_quantity("5280 ft", "length", largest=5000.0) == pytest.approx(1609.344)
    with pytest.raises(UnitError, match="at most 5000 m"):
        parse_quantity("6 km", "length", largest=5000.0)
