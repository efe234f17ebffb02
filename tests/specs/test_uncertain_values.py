"""Values that carry an uncertainty (batcert.units): ``863 g +/- 1 g`` (normal: the +/- is the
standard uncertainty u) and ``863 g +/- 0.5 g (uniform)`` (rectangular: the +/- is the
half-width a, and u = a / sqrt 3, JCGM 100 4.3.7), read by parse_uncertain into an Uncertain
float in SI; parse_quantity (fields that take no uncertainty) refuses them.

The SI factors below are exact (1 g = 1e-3 kg, 1 mm = 1e-3 m, 1 in = 0.0254 m, 1 oz =
0.028349523125 kg, batcert.units.FAST_UNITS), so values are compared to rel 1e-12: only the
float rounding of a product or a division by sqrt 3 is left.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle
from pathlib import Path

import numpy as np
import pytest

from batcert.units import OUNCE, Uncertain, UnitError, parse_quantity, parse_uncertain, show

REPO = Path(__file__).resolve().parents[2]
SQRT3 = math.sqrt(3.0)
REL = 1e-12  # exact unit factors: only float rounding remains


# ---------------------------------------------------------------- reading


@pytest.mark.parametrize("text, dimension, value, u, distribution", [
    ("863 g +/- 1 g", "mass", 0.863, 0.001, "normal"),  # the +/- is u itself
    ("863 g +/- 1 g (normal)", "mass", 0.863, 0.001, "normal"),  # the default, named
    ("863 g +/- 0.5 g (uniform)", "mass", 0.863, 0.0005 / SQRT3, "uniform"),  # a = 0.5 g
    ("863 g +/- 1", "mass", 0.863, 0.001, "normal"),  # a bare number takes the value's unit (g)
    ("863 g +/- 1 (uniform)", "mass", 0.863, 0.001 / SQRT3, "uniform"),  # bare, and uniform
    ("863 g ± 1 g", "mass", 0.863, 0.001, "normal"),  # the sign itself
    ("863 g +- 1 g", "mass", 0.863, 0.001, "normal"),
    ("863 g+/-1 g(uniform)", "mass", 0.863, 0.001 / SQRT3, "uniform"),  # spaces are optional
    ("34 in +/- 1 mm", "length", 34 * 0.0254, 0.001, "normal"),  # u in its own unit
    ("5.125 oz +/- 0.125 oz (uniform)", "mass", 5.125 * OUNCE, 0.125 * OUNCE / SQRT3, "uniform"),
    ("0.209 kg*m^2 +/- 0.0005 (uniform)", "moi", 0.209, 0.0005 / SQRT3, "uniform"),
    ("165 Hz +/- 2 Hz", "frequency", 165.0, 2.0, "normal"),
    ("863 g +/- 0 g", "mass", 0.863, 0.0, "normal"),  # zero is allowed (stated, no spread)
])
def test_reads_the_value_and_its_standard_uncertainty_in_si(text, dimension, value, u,
                                                             distribution):
    v = parse_uncertain(text, dimension)
    assert type(v) is Uncertain
    assert float(v) == pytest.approx(value, rel=REL)
    assert v.u == pytest.approx(u, rel=REL, abs=0.0)
    assert v.distribution == distribution
    # half_width gives back the stated +/- (in SI): u for normal, u sqrt 3 for uniform
    stated = u * SQRT3 if distribution == "uniform" else u
    assert v.half_width == pytest.approx(stated, rel=REL, abs=0.0)


def test_without_plus_minus_it_is_a_plain_float():
    v = parse_uncertain("863 g", "mass")
    assert type(v) is float and v == pytest.approx(0.863, rel=REL)


@pytest.mark.parametrize("text, message", [
    ("863 g +/- -1 g", "cannot read '863 g +/- -1 g': the uncertainty must not be negative"),
    ("863 g +/- -1 g (uniform)", "the uncertainty must not be negative"),
    ("863 g +/- -1", "the uncertainty must not be negative"),  # bare number, same rule
    ("863 g +/- 1 g (triangular)", "cannot read '863 g +/- 1 g (triangular)': unknown "
                                   "distribution 'triangular' (choose normal or uniform)"),
    ("863 g +/- ", "cannot read '863 g +/- ': give a value and its standard uncertainty, "
                   "e.g. '863 g +/- 1 g'"),
    ("+/- 1 g", "cannot read '+/- 1 g': give a value and its standard uncertainty"),
    ("863 g +/- 1 g +/- 2 g", "give a value and its standard uncertainty"),
    ("863 g +/- 1 m", "'1 m' is not a mass"),  # the uncertainty has the value's dimension
    ("863 +/- 1 g", "a unit is required"),  # the value still needs its unit
])
def test_malformed_uncertainties_are_refused_with_a_clear_message(text, message):
    with pytest.raises(UnitError) as exc:
        parse_uncertain(text, "mass")
    assert message in str(exc.value)


def test_a_distribution_without_its_spread_is_refused_naming_the_input():
    with pytest.raises(UnitError) as exc:
        parse_uncertain("863 g +/- (uniform)", "mass")
    assert "'863 g +/- (uniform)'" in str(exc.value)


@pytest.mark.parametrize("text", ["863 g +/- 1 g", "863 g ± 1 g", "863 g +- 1 g",
                                  "863 g +/- 0.5 g (uniform)"])
def test_parse_quantity_refuses_an_uncertainty_naming_the_docs(text):
    with pytest.raises(UnitError) as exc:
        parse_quantity(text, "mass")
    message = str(exc.value)
    assert f"cannot read {text!r}: this field cannot carry an uncertainty" in message
    assert "docs/uncertainty.md" in message


def test_the_page_the_refusal_names_exists_and_lists_the_syntax():
    page = (REPO / "docs" / "uncertainty.md").read_text(encoding="utf-8")
    assert "+/-" in page and "(uniform)" in page


# ---------------------------------------------------------------- the Uncertain float


def test_survives_pickle_and_deepcopy():
    """Worker processes receive specs by pickle: u and the distribution must come along."""
    v = parse_uncertain("863 g +/- 0.5 g (uniform)", "mass")
    for back in (pickle.loads(pickle.dumps(v)), copy.deepcopy(v)):
        assert type(back) is Uncertain
        assert float(back) == float(v) and back.u == v.u and back.distribution == "uniform"


def test_survives_dataclasses_replace_of_another_field():
    @dataclasses.dataclass(frozen=True)
    class Measured:
        mass: float
        pivot: float

    m = Measured(parse_uncertain("906 g +/- 2 g", "mass"), 0.15)
    moved = dataclasses.replace(m, pivot=0.2)
    assert type(moved.mass) is Uncertain and moved.mass.u == 0.002
    assert moved.mass.distribution == "normal"


def test_behaves_as_its_float():
    v = Uncertain(0.863, 0.001)
    assert v == 0.863 and hash(v) == hash(0.863)
    assert {0.863: "x"}[v] == "x"  # usable where the plain value is a key
    assert Uncertain(0.863, 0.001) == Uncertain(0.863, 0.5, "uniform")  # u is not compared
    assert v < 0.864 and v > 0.862
    # arithmetic gives plain floats (the uncertainty does not propagate by arithmetic)
    for result, expected in ((v + 1.0, 1.863), (v * 2, 1.726), (v - v, 0.0), (v / 2, 0.4315),
                             (-v, -0.863), (v**2, 0.863**2)):
        assert type(result) is float and result == pytest.approx(expected, rel=REL)
    assert math.sqrt(v) == pytest.approx(math.sqrt(0.863), rel=REL)
    assert np.asarray([v]).dtype == np.float64 and float(np.asarray([v])[0]) == 0.863
    assert f"{v:.3f}" == "0.863"  # formatting with a spec (reports) shows the value alone
    assert str(show(v, "mass")) == str(show(0.863, "mass"))


def test_repr_shows_the_stated_plus_minus_and_distribution():
    assert repr(Uncertain(0.863, 0.001)) == "0.863 +/- 0.001 (normal)"
    # uniform: the repr shows the half-width a = u sqrt 3 as written in the file
    assert repr(parse_uncertain("863 g +/- 0.5 g (uniform)", "mass")) == \
        "0.863 +/- 0.0005 (uniform)"
