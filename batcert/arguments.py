"""The arguments of batcert's commands, read and checked in one place, for the command line and
the library alike: the same value is refused by both, with the same words.

Each reader takes what a caller may give (a string with its unit, ``"85 mph"``, or an SI float;
an engine's name; a worker count) and returns the SI value, or raises :class:`ArgumentError`
naming the argument. The command line turns that into click's "Invalid value for '--pitch'"
(exit 2); :mod:`batcert.api` lets it go to the caller (a :class:`batcert.errors.UsageProblem`,
so a :class:`batcert.errors.BatcertError`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from numbers import Integral, Real
from pathlib import Path
from typing import Any

from batcert.errors import UsageProblem

__all__ = ["ArgumentError", "BOUNDS", "UNCERTAINTY_METHODS", "choice", "elevation",
           "launch_angle", "name_or_path", "names_or_paths", "pitch_speed", "positive", "spin",
           "temperature", "whole", "workers"]


# The ranges the commands accept (SI; angles in degrees, spins in rpm, temperatures in C):
# beyond any field or test, so that only a typo or a hostile value is refused.
BOUNDS = {
    "pitch_speed": (0.0, 60.0),  # m/s (about 134 mph)
    "elevation": (-500.0, 5000.0),  # m
    "launch_angle": (-10.0, 60.0),  # deg
    "backspin": (-5000.0, 6000.0),  # rpm
    "sidespin": (-5000.0, 5000.0),  # rpm
    "temperature": (-43.0, 57.0),  # C (the coldest and hottest air a game was played in, rounded out)
    "workers": (1, 256),
    "points": (3, 1001),  # of a design's margin curve
    "uncertainty": (2, 1_000_000),  # Monte Carlo draws of run --uncertainty
    "seed": (0, 2**63 - 1),  # their random seed
}
# how run --uncertainty finds the draws' results (docs/uncertainty.md): a response surface
# checked on a sample of the draws, or every draw solved by the engine
UNCERTAINTY_METHODS = ("surrogate", "full")

_TEMPERATURE = {"f": lambda t: (t - 32) * 5 / 9 + 273.15, "c": lambda t: t + 273.15,
                "k": lambda t: t}


class ArgumentError(UsageProblem):
    """An argument that cannot mean anything: its name and what is wrong."""

    def __init__(self, name: str, message: str):
        super().__init__(f"{name}: {message}")
        self.name, self.reason = name, message


def _number(name: str, value: Any) -> float:
    """A finite real number (a bool is not one)."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ArgumentError(name, f"expected a number, got {type(value).__name__} {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ArgumentError(name, f"must be a finite number, got {value!r}")
    return v


def _within(name: str, v: float, shown: str, unit: str) -> float:
    lo, hi = BOUNDS[name]
    if not lo <= v <= hi:
        raise ArgumentError(name, f"{shown} is outside {lo:g} to {hi:g} {unit}")
    return v


def _quantity(name: str, value: Any, dimension: str, unit: str) -> float:
    """A quantity given as a string with its unit or as an SI float, within its bounds."""
    if isinstance(value, str):
        from batcert.units import UnitError, parse_quantity
        lo, hi = BOUNDS[name]
        try:
            v = parse_quantity(value, dimension, largest=max(abs(lo), abs(hi)))
        except UnitError as exc:
            raise ArgumentError(name, str(exc)) from None
        return _within(name, v, value, f"{unit} (SI)")
    v = _number(name, value)
    return _within(name, v, f"{v:g} {unit}", unit)


def pitch_speed(value: Any) -> float | None:
    """A pitch speed [m/s]: ``"85 mph"`` or m/s; None keeps the batter profile's."""
    return None if value is None else _quantity("pitch_speed", value, "speed", "m/s")


def elevation(value: Any) -> float:
    """A field's elevation [m]: ``"5280 ft"`` or m."""
    return _quantity("elevation", value, "length", "m")


def temperature(value: Any) -> float:
    """An air temperature [K]: ``"70F"``, ``"21 C"``, ``"294 K"`` or kelvin; -43 to 57 C, both
    ends included."""
    if isinstance(value, str):
        text = value.strip().replace("\u00b0", "").replace(" ", "").lower()
        try:
            kelvin = _TEMPERATURE[text[-1]](float(text[:-1]))
        except (KeyError, ValueError, IndexError):
            raise ArgumentError("temperature", f"cannot read {value!r}: give a number with F, "
                                "C or K, e.g. 70F or 21C") from None
        shown = value
    else:
        kelvin = _number("temperature", value)
        shown = f"{kelvin:g} K"
    if not math.isfinite(kelvin):
        raise ArgumentError("temperature", f"must be finite, got {value!r}")
    lo, hi = BOUNDS["temperature"]
    # compared in C with 1e-9 of rounding, so that the ends themselves are accepted
    if not lo - 1e-9 <= kelvin - 273.15 <= hi + 1e-9:
        raise ArgumentError("temperature", f"{shown} is outside {lo:g} to {hi:g} C")
    return kelvin


def launch_angle(value: Any) -> float:
    """A launch angle [deg]."""
    return _within("launch_angle", _number("launch_angle", value), f"{value!r}", "deg")


def spin(name: str, value: Any) -> float | None:
    """A backspin or sidespin [rpm]; None: the trajectory calculator's."""
    if value is None:
        return None
    return _within(name, _number(name, value), f"{value!r}", "rpm")


def whole(name: str, value: Any) -> int:
    """A whole number within the argument's bounds (a bool or a float is not one)."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise ArgumentError(name, f"expected a whole number, got {type(value).__name__} "
                            f"{value!r}")
    lo, hi = BOUNDS[name]
    if not lo <= int(value) <= hi:
        raise ArgumentError(name, f"{value} is outside {lo} to {hi}")
    return int(value)


def positive(name: str, value: Any) -> float:
    """A finite number above 0 (the surrogate's bound, in the metric's unit)."""
    v = _number(name, value)
    if not v > 0:
        raise ArgumentError(name, f"must be above 0, got {value!r}")
    return v


def workers(value: Any) -> int:
    """A number of worker processes, 1 to 256."""
    return whole("workers", value)


def choice(name: str, value: Any, options: Sequence[str]) -> str:
    """One of ``options``."""
    if not isinstance(value, str) or value not in options:
        raise ArgumentError(name, f"expected one of {', '.join(map(repr, options))}, got "
                            f"{value!r}")
    return value


def name_or_path(name: str, value: Any, kind: str, loaded: type | None = None) -> Any:
    """A shipped name or a path (returned as a string), or an object of type ``loaded`` (the
    loaded input itself, returned as it is); anything else is refused, naming the argument."""
    if loaded is not None and isinstance(value, loaded):
        return value
    if isinstance(value, (str, Path)) and str(value).strip():
        return str(value)
    also = ", or what batcert.load_" + kind + " returned" if loaded is not None else ""
    raise ArgumentError(name, f"expected a shipped {kind} name or a path{also}, got "
                        f"{type(value).__name__} {value!r}"[:300])


def names_or_paths(name: str, values: Any, kind: str, at_least: int = 1) -> list[Any]:
    """A list of :func:`name_or_path` values (a single string is refused: it is not a list of
    names, and would be read letter by letter)."""
    if isinstance(values, (str, Path)) or not isinstance(values, Sequence):
        raise ArgumentError(name, f"expected a list of {kind} names or paths, got "
                            f"{type(values).__name__} {values!r}"[:300])
    if len(values) < at_least:
        raise ArgumentError(name, f"needs at least {at_least} {kind}"
                            f"{'s' if at_least > 1 else ''}, got {len(values)}")
    return [name_or_path(f"{name}[{i}]", v, kind) for i, v in enumerate(values)]
