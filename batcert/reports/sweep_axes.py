"""A sweep's parameters as the reports show them: units, values, labels."""

from __future__ import annotations

from batcert.reports import format as fmt
from batcert.results.sweep import SweepAxis
from batcert.units import Display


def display_unit(axis: SweepAxis) -> tuple[str, float]:
    """The unit a parameter is shown in and its SI factor: moduli in GPa, walls and
    diameters in mm, the rest in their SI unit."""
    if axis.dimension == "modulus":
        return "GPa", 1e9
    if axis.dimension == "length":
        return "mm", 1e-3
    return axis.unit, 1.0


def axis_value(axis: SweepAxis, value: float) -> Display:
    """A parameter value in its display unit, with its percent of nominal (or US units)."""
    pct = f"{value / axis.nominal * 100:.4g} % of nominal" if axis.nominal else None
    unit, factor = display_unit(axis)
    us = None
    if axis.dimension in ("length", "mass", "moi", "speed", "angular_speed"):
        us = fmt.quantity(value, axis.dimension, 4).us
    return Display(f"{value / factor:.4g} {unit}" if unit != "-" else f"{value:.4g}", pct or us)


def words(axis: SweepAxis) -> str:
    """The parameter in words ("bat angular speed"; its name where a saved 0.2 document has
    none)."""
    return axis.label or axis.name.replace("_", " ")


def column_label(axis: SweepAxis) -> str:
    """A table's column: the parameter's name as typed on the command line, with its unit
    (``bat_angular_speed [rad/s]``)."""
    return f"{axis.name} [{display_unit(axis)[0]}]"


def axis_label(axis: SweepAxis) -> str:
    """A figure's axis title: "Bat angular speed [rad/s]"."""
    text = words(axis)
    return f"{text[:1].upper()}{text[1:]} [{display_unit(axis)[0]}]"


def x_values(axis: SweepAxis, values: list[float]) -> list[float]:
    """Values of ``axis`` in its display unit (a figure's x)."""
    factor = display_unit(axis)[1]
    return [v / factor for v in values]
