"""Units at the edges: parse lab-style quantities to SI floats once, format SI + US for display.

Everything inside batcert (physics, results) is SI floats. This module is the only place that
knows unit strings. Parsing uses pint; the registry is created lazily on first use.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache

# Dimension name -> (pint dimensionality text, SI unit, US customary display unit, example)
DIMENSIONS: dict[str, tuple[str, str, str | None, str]] = {
    "length": ("[length]", "m", "in", "34 in"),
    "mass": ("[mass]", "kg", "oz", "31 oz"),
    "moi": ("[mass] * [length] ** 2", "kg*m^2", "oz*in^2", "12000 oz*in^2"),
    "speed": ("[length] / [time]", "m/s", "mph", "70 mph"),
    "angular_speed": ("1 / [time]", "rad/s", "rpm", "53 rad/s"),
    "density": ("[mass] / [length] ** 3", "kg/m^3", "lb/in^3", "649 kg/m^3"),
    "modulus": ("[mass] / [length] / [time] ** 2", "Pa", "psi", "71.7 GPa"),
    "time": ("[time]", "s", None, "0.5 s"),
    "frequency": ("1 / [time]", "Hz", None, "165 Hz"),
    "force": ("[mass] * [length] / [time] ** 2", "N", "lbf", "220 lbf"),
}


_BARE_NUMBER = re.compile(r"^\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*$")
_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d.+-].*)?$")


# Exact SI factors of the units lab files use most, so that reading the shipped files does not
# need pint's registry (about 0.4 s of start-up). Every entry is checked against pint in
# tests/test_units.py; anything not listed here goes through pint.
INCH, OUNCE, FOOT, MPH = 0.0254, 0.028349523125, 0.3048, 0.44704  # [m], [kg], [m], [m/s]
POUND_FORCE = 4.4482216152605  # [N]
FAST_UNITS: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": INCH, "ft": FOOT},
    "mass": {"kg": 1.0, "g": 0.001, "oz": OUNCE, "lb": 0.45359237},
    "moi": {"kg*m^2": 1.0, "kg*m**2": 1.0, "oz*in^2": OUNCE * INCH**2, "oz*in**2": OUNCE * INCH**2,
            "g*cm^2": 1e-7},
    "speed": {"m/s": 1.0, "mph": MPH, "ft/s": FOOT, "km/h": 1 / 3.6},
    "angular_speed": {"rad/s": 1.0, "rpm": 2 * 3.141592653589793 / 60, "deg/s":
                      3.141592653589793 / 180},
    "density": {"kg/m^3": 1.0, "kg/m**3": 1.0, "g/cm^3": 1000.0},
    "modulus": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9},
    "time": {"s": 1.0, "ms": 1e-3},
    "frequency": {"Hz": 1.0, "kHz": 1e3},
    "force": {"N": 1.0, "kN": 1e3, "lbf": POUND_FORCE},
}


# The largest magnitude (SI) accepted for each dimension: far beyond any bat, ball or test, so
# that only a typo or a hostile value (1e308 mph, inf) is refused. Documented in docs/inputs.md.
PLAUSIBLE: dict[str, float] = {
    "length": 10.0,  # m
    "mass": 100.0,  # kg
    "moi": 100.0,  # kg*m^2
    "speed": 300.0,  # m/s (about 670 mph)
    "angular_speed": 2000.0,  # rad/s
    "density": 30000.0,  # kg/m^3 (osmium is 22,600)
    "modulus": 2e12,  # Pa (diamond is about 1.2e12)
    "time": 3600.0,  # s
    "frequency": 1e6,  # Hz
    "force": 1e7,  # N
}


class UnitError(ValueError):
    """A quantity that could not be parsed or has the wrong dimension."""


DISTRIBUTIONS = ("normal", "uniform")


class Uncertain(float):
    """A value [SI] that carries its uncertainty, read from an input written ``863 g +/- 1 g``
    (``u`` = 1 g, the standard uncertainty of a normal distribution) or ``863 g +/- 0.5 g
    (uniform)`` (0.5 g, the half-width of a rectangular distribution; ``u`` = 0.5 g / sqrt 3,
    JCGM 100 4.3.7): a float everywhere (arithmetic drops the rest), so the value flows
    through specs and models unchanged, and :mod:`batcert.uncertainty` finds what was stated."""

    u: float  # standard uncertainty [same unit]
    distribution: str  # normal | uniform

    def __new__(cls, value: float, u: float, distribution: str = "normal") -> Uncertain:
        out = super().__new__(cls, value)
        out.u, out.distribution = float(u), distribution
        return out

    @property
    def half_width(self) -> float:
        """The stated ``+/-``: u for a normal distribution, the half-width for a uniform one."""
        return self.u * math.sqrt(3.0) if self.distribution == "uniform" else self.u

    def __reduce__(self):  # keep u through pickling (worker processes)
        return (Uncertain, (float(self), self.u, self.distribution))

    def __repr__(self) -> str:
        return f"{float(self)!r} +/- {self.half_width!r} ({self.distribution})"


_PLUS_MINUS = re.compile(r"\s*(?:\+/-|\+-|±)\s*")
_DISTRIBUTION = re.compile(r"^(.*?)\s*\(\s*(\w+)\s*\)\s*$")
UNCERTAIN_EXAMPLE = "863 g +/- 1 g"


def split_uncertainty(value: object) -> tuple[object, str | None]:
    """``"863 g +/- 1 g"`` -> (``"863 g"``, ``"1 g"``); anything else -> (value, None)."""
    if not isinstance(value, str):
        return value, None
    parts = _PLUS_MINUS.split(value)
    if len(parts) == 1:
        return value, None
    if len(parts) != 2 or not parts[0].strip() or not parts[1].strip():
        raise UnitError(f"cannot read {value!r}: give a value and its standard uncertainty, "
                        f"e.g. '{UNCERTAIN_EXAMPLE}'")
    return parts[0].strip(), parts[1].strip()


def read_spread(value: object, u_text: str) -> tuple[str, str]:
    """``"0.5 g (uniform)"`` -> (``"0.5 g"``, ``"uniform"``); without a distribution, normal."""
    m = _DISTRIBUTION.match(u_text)
    if m is None:
        return u_text, "normal"
    if m.group(2) not in DISTRIBUTIONS:
        raise UnitError(f"cannot read {value!r}: unknown distribution {m.group(2)!r} (choose "
                        f"{' or '.join(DISTRIBUTIONS)})")
    return m.group(1), m.group(2)


def uncertain(v: float, spread: float, distribution: str, value: object) -> Uncertain:
    """The :class:`Uncertain` of ``v`` with the stated ``+/-`` ``spread`` (both SI)."""
    if not spread >= 0:
        raise UnitError(f"cannot read {value!r}: the uncertainty must not be negative")
    u = spread / math.sqrt(3.0) if distribution == "uniform" else spread
    return Uncertain(v, u, distribution)


def parse_uncertain(value: object, dimension: str) -> float:
    """:func:`parse_quantity`, also reading ``VALUE +/- U`` (or ``±``), optionally followed by
    ``(normal)`` (the default: U is the standard uncertainty, k = 1) or ``(uniform)`` (U is the
    half-width of a rectangular distribution): then an :class:`Uncertain`. U takes the value's
    unit when given as a bare number and must be >= 0."""
    nominal, u_text = split_uncertainty(value)
    v = parse_quantity(nominal, dimension)
    if u_text is None:
        return v
    u_text, distribution = read_spread(value, u_text)
    if not u_text.strip():
        raise UnitError(f"cannot read {value!r}: give the uncertainty before its distribution, "
                        f"e.g. '863 g +/- 0.5 g ({distribution})'")
    unit = (_NUMBER_UNIT.match(str(nominal)).group(2) or "").strip()  # type: ignore[union-attr]
    if _BARE_NUMBER.match(u_text):
        u_text = f"{u_text} {unit}"
    return uncertain(v, parse_quantity(u_text, dimension), distribution, value)



@lru_cache(maxsize=1)
def registry():
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    # the ASCII spellings of the micro- units that labs type (issue 40: "um" was refused)
    ureg.define("um = micrometer")
    ureg.define("us = microsecond")
    return ureg


def parse_quantity(value: object, dimension: str, largest: float | None = None) -> float:
    """Convert ``value`` (e.g. ``"34 in"``) to a float in the SI unit of ``dimension``.

    Bare numbers are refused for dimensioned quantities: a lab file must say its unit. A value
    larger in size than :data:`PLAUSIBLE` (or than ``largest`` [SI], for a quantity that is not
    a bat's or a ball's, such as a field's elevation) is refused.
    """
    dim_text, si_unit, _, example = DIMENSIONS[dimension]
    if isinstance(value, bool) or value is None:
        raise UnitError(f"expected a {dimension.replace('_', ' ')} with a unit, e.g. '{example}'")
    if isinstance(value, (int, float)):
        raise UnitError(f"a unit is required (e.g. '{example}'), got the bare number {value}")
    if not isinstance(value, str):
        raise UnitError(f"expected a {dimension.replace('_', ' ')} with a unit, e.g. '{example}'")
    if split_uncertainty(value)[1] is not None:
        raise UnitError(f"cannot read {value!r}: this field cannot carry an uncertainty "
                        "('+/-'); the inputs that can are listed in docs/uncertainty.md")
    match = _NUMBER_UNIT.match(value)
    if not match:
        raise UnitError(f"cannot read {value!r}: expected a number then a unit, e.g. '{example}'")
    number, unit_text = float(match.group(1)), (match.group(2) or "").strip()
    if not unit_text:
        raise UnitError(f"a unit is required (e.g. '{example}'), got {value!r}")
    fast = FAST_UNITS.get(dimension, {}).get(unit_text.replace(" ", ""))
    if fast is not None:  # the units of the shipped files, without starting pint (~0.4 s)
        return _plausible(number * fast, value, dimension, largest)
    import pint

    ureg = registry()
    try:
        unit = ureg.parse_units(unit_text)
    except pint.errors.UndefinedUnitError as exc:
        raise UnitError(f"cannot read {value!r}: unknown unit {exc.unit_names[0]!r} "
                        f"(e.g. '{example}')") from None
    except Exception:  # pint's parser raises many types (e.g. tokenize.TokenError for "in)")
        raise UnitError(f"cannot read {value!r}: not a unit expression (e.g. '{example}')") from None
    _check_spelling(value, unit_text, ureg, example)
    # pint treats radian as dimensionless, so rad/s, rpm, Hz and 1/s all match 1/[time]; the
    # angle check below keeps angular speeds (rad/s, rpm) and frequencies (Hz) apart
    try:
        si = float(ureg.Quantity(number, unit).to(si_unit).magnitude)
    except pint.errors.DimensionalityError:
        raise UnitError(
            f"{value!r} is not a {dimension.replace('_', ' ')} (expected units like '{example}')"
        ) from None
    except Exception:  # pint cannot convert it: a logarithmic unit (dB, neper), an exponent
        # whose factor overflows ("degree ** 1e9")
        raise UnitError(f"cannot read {value!r}: not a unit that converts to {si_unit} "
                        f"(e.g. '{example}')") from None
    _check_angle(value, unit, dimension, example)
    return _plausible(si, value, dimension, largest)


def _check_spelling(value: str, unit_text: str, ureg, example: str) -> None:
    """Refuse unit words that pint reads only by guessing: it strips any trailing "s", so
    "36.9 inchs" would silently be 36.9 in. A word must be a unit's name, symbol or alias, or
    its regular English plural ("inches", "meters", "grams")."""
    for word in re.findall(r"[A-Za-z_]+", unit_text):
        try:
            name = ureg.get_name(word)
            if not name:  # "dimensionless": a pure number, which the dimension check refuses
                continue
            symbol = ureg.get_symbol(word)
        except Exception:  # a word pint's parser passed but cannot name ("per"): not a unit
            raise UnitError(f"cannot read {value!r}: unknown unit {word!r} "
                            f"(e.g. '{example}')") from None
        unit = ureg._units.get(name)
        spelled = {name, symbol, *(unit.aliases if unit is not None else ())}
        plurals = {w + ("es" if w.endswith(("s", "sh", "ch", "x", "z")) else "s")
                   for w in spelled}
        if word not in spelled | plurals:
            raise UnitError(f"cannot read {value!r}: unknown unit {word!r} (e.g. '{example}')")


def _plausible(si: float, value: str, dimension: str, largest: float | None = None) -> float:
    """``si`` if it is finite and within :data:`PLAUSIBLE` (or ``largest``); otherwise a
    :class:`UnitError`."""
    bound = PLAUSIBLE[dimension] if largest is None else largest
    if not math.isfinite(si) or abs(si) > bound:
        raise UnitError(f"{value!r} is outside the range accepted for a "
                        f"{dimension.replace('_', ' ')} (at most {bound:g} {DIMENSIONS[dimension][1]} "
                        "in size)")
    return si


def _check_angle(value: str, unit, dimension: str, example: str) -> None:
    """Refuse the rotation/cycle mix-ups that pint's dimensionless radian lets through.

    pint converts "1 Hz" to 1 rad/s and "165 rad/s" to 165 Hz; for a bat both are off by 2 pi.
    """
    if dimension not in ("angular_speed", "frequency"):
        return
    has_angle = "radian" in str(registry().get_root_units(unit)[1])
    if dimension == "angular_speed" and not has_angle:
        raise UnitError(f"{value!r} is ambiguous as an angular speed: give an angle per time, "
                        f"e.g. '{example}' or '2500 rpm'")
    if dimension == "frequency" and has_angle:
        raise UnitError(f"{value!r} is an angular speed; give a frequency in cycles per time, "
                        f"e.g. '{example}'")


# Conversion factors for display, so reports need not import pint (computed from Units section
# of docs/references.md: 1 in = 0.0254 m, 1 mph = 0.44704 m/s, 1 oz = 28.3495 g).
_US: dict[str, tuple[str, float]] = {
    "length": ("in", 1 / INCH),
    "mass": ("oz", 1 / OUNCE),
    "moi": ("oz*in^2", 1 / (OUNCE * INCH**2)),
    "speed": ("mph", 1 / MPH),
    "angular_speed": ("rpm", 60 / (2 * 3.141592653589793)),
    "force": ("lbf", 1 / POUND_FORCE),
}
DASH = "\u2014"  # how an empty or undefined value is shown, everywhere
_SI_LABEL = {"length": "m", "mass": "kg", "moi": "kg m²", "speed": "m/s", "angular_speed": "rad/s",
             "force": "N", "frequency": "Hz", "density": "kg/m³", "modulus": "Pa", "time": "s"}


@dataclass(frozen=True)
class Display:
    si: str
    us: str | None

    def __str__(self) -> str:
        return f"{self.si} ({self.us})" if self.us else self.si


def to_us(value_si: float, dimension: str) -> float:
    """SI value -> US customary value for display."""
    return value_si * _US[dimension][1]


def us_unit(dimension: str) -> str:
    return _US[dimension][0]


def si_unit(dimension: str) -> str:
    return _SI_LABEL[dimension]


def show(value_si: float | None, dimension: str, digits: int = 3) -> Display:
    """Format an SI value with its US customary equivalent, e.g. ``0.860 m (33.86 in)``."""
    if value_si is None:
        return Display(DASH, None)
    si = f"{value_si:.{digits}f} {_SI_LABEL[dimension]}"
    if dimension in _US:
        unit, factor = _US[dimension]
        us_digits = 0 if dimension == "moi" else 2 if dimension in ("length", "mass") else 1
        return Display(si, f"{value_si * factor:,.{us_digits}f} {unit}")
    return Display(si, None)
