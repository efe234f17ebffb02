"""Variants of a bat or a protocol: the parameters a sweep or a design study may vary.

:data:`PARAMETERS` is the one registry of what can be varied: each :class:`Parameter` holds its
name (the one used on the command line and in the results), its dimension (for units), what it
changes (``geometry``: the bat's shape or material; ``measured``: a property a lab measured;
``protocol``: a test speed), how to read its nominal value and how to apply a value.

When a geometric or material parameter varies, the variant's mass properties come from its
geometry: the nominal bat's measurements (mass, CG, MOI, frequencies, barrel compression) were
made on the nominal bat and do not apply to the variant, so a variant is built without them
(:func:`geometry_only`). A measured parameter keeps the others measured and replaces one.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from batcert.model.build import BuiltBat, measured_properties
from batcert.model.mass import mass_properties
from batcert.specs.bat import BatSpec, MeasuredSpec
from batcert.specs.protocol import ConditionSpec, ProtocolSpec
from batcert.sweeps.cases import Case, Parameter, ParameterError, geometry_only, hollow
from batcert.sweeps.layup_variants import LAYUP_PARAMETERS


def _walls(spec: BatSpec) -> tuple[tuple[float, ...], tuple[float, ...]]:
    if isinstance(spec.wall, tuple):
        return spec.wall
    if spec.wall is None:
        raise ParameterError(f"{spec.name!r} gives its walls as a layup, not a wall thickness "
                             "(vary its plies instead: ply_angle, ply_count, wall_split)")
    return (0.0,), (float(spec.wall),)


def _wall_nominal(case: Case, built: BuiltBat) -> float:
    hollow(case, "wall")
    return max(_walls(case.bat)[1])


def _wall_apply(case: Case, built: BuiltBat, value: float) -> Case:
    z, t = _walls(case.bat)
    s = value / max(t)
    scaled = tuple(x * s for x in t)
    wall: float | tuple[tuple[float, ...], tuple[float, ...]] = \
        (z, scaled) if isinstance(case.bat.wall, tuple) else scaled[0]
    return replace(case, bat=geometry_only(replace(case.bat, wall=wall)))


def _material(case: Case):
    m = case.bat.material
    if m is None:
        raise ParameterError(f"{case.bat.name!r} has no material of its own: its walls are a "
                             "layup (vary its plies instead: ply_angle, ply_count, wall_split)")
    return m


def _material_apply(**scale_of: str):
    def apply(case: Case, built: BuiltBat, value: float) -> Case:
        m = _material(case)
        field = next(iter(scale_of))
        s = value / getattr(m, field)
        changes = {f: getattr(m, f) * s for f in scale_of.values()}
        material = replace(m, name=f"{m.name} ({field} x {s:.3g})", **changes)
        return replace(case, bat=geometry_only(replace(case.bat, material=material)))
    return apply


def _barrel_nominal(case: Case, built: BuiltBat) -> float:
    z, d = case.bat.profile
    return max(d[int(np.argmin(d)):])


def _barrel_apply(case: Case, built: BuiltBat, value: float) -> Case:
    """Barrel diameter ``value``: beyond the handle's thinnest station each diameter d becomes
    h + (d - h) (value - h) / (D - h) (h the handle, D the nominal barrel), so the barrel takes
    the new diameter, the taper is stretched in proportion and the handle and knob keep theirs."""
    z, d = case.bat.profile
    i = int(np.argmin(d))
    h, big = d[i], _barrel_nominal(case, built)
    if value <= h:
        raise ParameterError(f"a barrel diameter of {value * 1000:.1f} mm is not larger than the "
                             f"handle ({h * 1000:.1f} mm)")
    s = (value - h) / (big - h)
    new = tuple(x if j <= i else h + (x - h) * s for j, x in enumerate(d))
    return replace(case, bat=geometry_only(replace(case.bat, profile=(z, new))))


# ---- measured properties ------------------------------------------------------------------

def _explicit(case: Case, built: BuiltBat) -> MeasuredSpec:
    """The bat's measured block with mass, balance point and MOI given directly; a bat without
    one gets its geometry's values (at the protocol's pivot)."""
    m = case.bat.measured
    if m is None:
        mp = mass_properties(built, case.protocol.pivot)
        return MeasuredSpec(case.protocol.pivot, mp.geometry_mass, case.protocol.pivot
                            + mp.geometry_cg, None, mp.geometry_moi_pivot, None, None, None,
                            None, None)
    mm = measured_properties(m)
    if mm.balance_point is None or mm.moi is None:
        raise ParameterError(f"{case.bat.name!r} gives a measured mass without its CG and MOI: "
                             "a mass-property sweep needs all three")
    return replace(m, mass=mm.mass, balance_point=mm.balance_point, cg=None, moi=mm.moi,
                   radius_of_gyration=None, pendulum_period=None)


def _measured(field: str):
    def nominal(case: Case, built: BuiltBat) -> float | None:
        if field == "hoop_frequency":
            hollow(case, field)
            m = case.bat.measured
            return None if m is None or m.hoop_frequency is None else m.hoop_frequency
        return float(getattr(_explicit(case, built), field))

    def apply(case: Case, built: BuiltBat, value: float) -> Case:
        changes: dict[str, Any] = {field: value}
        m = case.bat.measured
        if field == "hoop_frequency" and m is not None:  # the mass properties stay as given
            return replace(case, bat=replace(case.bat, measured=replace(m, **changes)))
        return replace(case, bat=replace(case.bat, measured=replace(_explicit(case, built),
                                                                   **changes)))
    return nominal, apply


# ---- test speeds --------------------------------------------------------------------------

def _uses(c: ConditionSpec, field: str) -> bool:
    """The condition sets this speed and its body moves: a stationary set-up stays
    stationary (a sweep of the pitch speed does not pitch at a stationary-ball test)."""
    if field == "relative_speed":
        return c.relative_speed is not None
    if field == "bat_angular_speed":
        return c.relative_speed is None and ((c.bat_angular_speed or 0) > 0
                                              or (c.bat_speed or 0) > 0)
    return c.pitch_speed is not None and c.pitch_speed > 0  # pitch_speed


def _settable(c: ConditionSpec, field: str) -> bool:
    """The condition has this speed among its explicit fields (moving or at rest)."""
    if field == "relative_speed":
        return c.relative_speed is not None
    return c.relative_speed is None  # pitch_speed and bat_angular_speed of explicit set-ups


def _conditions(case: Case, field: str) -> list[ConditionSpec]:
    """The conditions a speed parameter sets: those whose body moves; when none does (a
    stationary-bat test swept in swing speed), every condition with explicit speeds."""
    used = [c for c in case.protocol.conditions if _uses(c, field)] or \
        [c for c in case.protocol.conditions if _settable(c, field)]
    if not used:
        why = {"relative_speed": "sets explicit speeds, not a matched relative speed",
               "bat_angular_speed": "matches a relative speed (vary relative_speed)",
               "pitch_speed": "matches a relative speed with a stationary ball or bat (vary "
                              "relative_speed)"}
        raise ParameterError(f"protocol {case.protocol.id!r} {why[field]}: {field} does not "
                             "apply to it")
    return used


def _speed_nominal(field: str):
    def nominal(case: Case, built: BuiltBat) -> float:
        c = _conditions(case, field)[0]
        if field == "bat_angular_speed" and c.bat_angular_speed is None:
            from batcert.runner.conditions import conditions_from_spec
            p = case.protocol
            return float(conditions_from_spec([c], built.model, p.pivot)[0]
                         .bat_angular_speed or 0.0)
        return float(getattr(c, field))
    return nominal


def _speed_apply(field: str):
    def apply(case: Case, built: BuiltBat, value: float) -> Case:
        used = {c.name for c in _conditions(case, field)}
        conds = []
        for c in case.protocol.conditions:
            if c.name in used:
                changes: dict[str, Any] = {field: value}
                if field == "bat_angular_speed":
                    changes.update(bat_speed=None, bat_speed_from_tip=None)
                c = replace(c, **changes)
                _check_speeds(case.protocol, c)
            conds.append(c)
        return replace(case, protocol=replace(case.protocol, conditions=tuple(conds)))
    return apply


def _check_speeds(p: ProtocolSpec, c: ConditionSpec) -> None:
    if c.relative_speed is not None and c.pitch_speed is not None \
            and c.pitch_speed >= c.relative_speed:
        raise ParameterError(f"protocol {p.id!r}, condition {c.name!r}: the pitch speed "
                             f"({c.pitch_speed:g} m/s) must stay below the relative speed "
                             f"({c.relative_speed:g} m/s)")
    if c.relative_speed is None and c.pitch_speed == 0 and (c.bat_angular_speed or 0) == 0 \
            and c.bat_speed is None:
        raise ParameterError(f"protocol {p.id!r}, condition {c.name!r}: with the pitch and bat "
                             "speeds both zero the ball and the bat never meet")


def _param(name: str, label: str, dimension: str | None, changes: str, doc: str, nominal,
           apply, bounds: tuple[float, float], tolerance: float) -> Parameter:
    return Parameter(name, label, dimension, changes, doc, nominal, apply, bounds, tolerance)


_mass, _moi, _hoop = _measured("mass"), _measured("moi"), _measured("hoop_frequency")

PARAMETERS: dict[str, Parameter] = {p.name: p for p in (
    _param("wall", "wall thickness", "length", "geometry", "Wall thickness of a hollow bat: "
           "the thickest wall station (the barrel) takes the value; every station scales in "
           "proportion.",
           _wall_nominal, _wall_apply, (1e-4, 0.02), 1e-6),
    _param("youngs_modulus", "Young's modulus", "modulus", "geometry", "The material's "
           "Young's modulus; the shear modulus scales with it.", lambda c, b: _material(c).youngs_modulus,
           _material_apply(youngs_modulus="youngs_modulus", shear_modulus="shear_modulus"),
           (1e8, 1e12), 1e6),
    _param("density", "density", "density", "geometry", "The material's density.",
           lambda c, b: _material(c).density, _material_apply(density="density"),
           (100.0, 20000.0), 0.1),
    _param("barrel_diameter", "barrel diameter", "length", "geometry", "The barrel takes the value; beyond "
           "the handle's thinnest station each diameter `d` becomes `h + (d - h)(D' - h)/(D - h)` "
           "(`h` handle, `D` nominal barrel), so the taper stretches and the handle and knob keep "
           "theirs.", _barrel_nominal, _barrel_apply,
           (0.005, 0.15), 1e-5),
    _param("mass", "mass", "mass", "measured", "The measured mass; CG and MOI stay as measured.",
           _mass[0], _mass[1], (0.1, 3.0), 1e-4),
    _param("moi", "MOI about the pivot", "moi", "measured", "The measured MOI about the measured pivot; "
           "mass and CG stay.", _moi[0], _moi[1], (1e-4, 10.0), 1e-6),
    _param("hoop_frequency", "hoop frequency", "frequency", "measured", "The measured barrel hoop (n = 2) "
           "frequency of a hollow bat; the barrel is calibrated to it.", _hoop[0], _hoop[1],
           (100.0, 20000.0), 0.5),
    *LAYUP_PARAMETERS,
    _param("pitch_speed", "pitch speed", "speed", "protocol", "Ball speed toward the bat, in every condition "
           "that pitches the ball (a stationary-ball set-up stays at rest, unless no condition "
           "pitches: then every condition with explicit speeds).", _speed_nominal("pitch_speed"),
           _speed_apply("pitch_speed"), (0.0, 300.0), 0.01),
    _param("bat_angular_speed", "bat angular speed", "angular_speed", "protocol", "Bat angular speed about the "
           "pivot, in every condition that swings the bat at explicit speeds (replaces a "
           "linear `bat_speed`; a stationary-bat set-up stays at rest, unless no condition "
           "swings, as in `ncaa-bbcor`).",
           _speed_nominal("bat_angular_speed"), _speed_apply("bat_angular_speed"),
           (0.0, 2000.0), 0.01),
    _param("relative_speed", "relative speed", "speed", "protocol", "Matched relative normal speed, in every "
           "matched condition.", _speed_nominal("relative_speed"),
           _speed_apply("relative_speed"), (0.1, 300.0), 0.01),
)}


# ---- values on the command line -------------------------------------------------------------

@dataclass(frozen=True)
class Axis:
    """One varied parameter and its values (SI), with the nominal value they relate to."""

    parameter: Parameter
    values: tuple[float, ...]  # [SI]
    nominal: float | None  # [SI], None when the bat file does not give it
    percent: bool  # the values were given as percent of nominal

    @property
    def name(self) -> str:
        return self.parameter.name


_RANGE = re.compile(r"^\s*([^:]+?)\s*:\s*([^:]+?)\s*(?::\s*(\d+)\s*)?$")
MAX_POINTS = 100_000


def parse_vary(text: str) -> tuple[str, str]:
    """``PARAM=START:STOP:N`` as (parameter name, range text); unknown names get a suggestion."""
    if "=" not in text:
        raise ParameterError(f"--vary {text!r}: give PARAM=START:STOP:N, e.g. wall=60%:140%:9")
    name, spec = (s.strip() for s in text.split("=", 1))
    lookup_parameter(name)
    return name, spec


def lookup_parameter(name: str) -> Parameter:
    if name not in PARAMETERS:
        import difflib
        close = difflib.get_close_matches(name, list(PARAMETERS), n=1, cutoff=0.5)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ParameterError(f"unknown parameter {name!r} (choose from "
                             f"{', '.join(PARAMETERS)}){hint}")
    return PARAMETERS[name]


def read_value(text: str, parameter: Parameter, nominal: float | None) -> tuple[float, bool]:
    """One value: ``NN%`` of the nominal, or a quantity with its unit (a plain number for a
    dimensionless parameter). Returns (SI value, given as percent)."""
    from batcert.units import UnitError, parse_quantity
    t = text.strip()
    if t.endswith("%"):
        try:
            pct = float(t[:-1].replace("_", "?"))  # no digit-group underscores
        except ValueError:
            raise ParameterError(f"{parameter.name}: {text!r} is not a percentage") from None
        if not math.isfinite(pct):
            raise ParameterError(f"{parameter.name}: {text!r} is not a finite percentage")
        if nominal is None or nominal == 0:
            what = "is zero" if nominal == 0 else "is not given by the bat file"
            raise ParameterError(f"{parameter.name}: the nominal value {what}, so a percentage "
                                 "of it means nothing; give absolute values with units")
        return nominal * (pct / 100.0), True
    if parameter.dimension is None:
        try:
            value = float(t.replace("_", "?"))  # no digit-group underscores
        except ValueError:
            raise ParameterError(f"{parameter.name}: {text!r} is not a number") from None
        if not math.isfinite(value):
            raise ParameterError(f"{parameter.name}: {text!r} is not a finite number")
        return value, False
    try:
        return parse_quantity(t, parameter.dimension), False
    except UnitError as exc:
        raise ParameterError(f"{parameter.name}: {exc}") from None


def read_range(name: str, spec: str, nominal: float | None, points: int | None = None,
               check_bounds: bool = True) -> Axis:
    """``START:STOP:N`` (N evenly spaced values, both ends included), ``START:STOP`` (with
    ``points``) or one value; each end ``NN%`` or a quantity."""
    parameter = lookup_parameter(name)
    m = _RANGE.match(spec)
    if m is None:
        v, pct = read_value(spec, parameter, nominal)
        values: tuple[float, ...] = (v,)
    else:
        first, last = m.group(1), m.group(2)
        if _plain(first) and not _plain(last) and not last.endswith("%"):
            first += " " + _NUMBER.sub("", last, count=1).strip()  # 50:70m/s reads as 50m/s:70m/s
        start, pct = read_value(first, parameter, nominal)
        stop, pct2 = read_value(last, parameter, nominal)
        count = (m.group(3) or "").lstrip("0") or "0"  # N, read only if short enough to be valid
        if len(count) > len(str(MAX_POINTS)) or int(count) > MAX_POINTS:
            raise ParameterError(f"{name}: at most {MAX_POINTS} values per parameter")
        n = int(count) if m.group(3) else (points or 0)
        if pct != pct2:
            raise ParameterError(f"{name}: give both ends as percentages or both as quantities")
        if n < 1 or (n == 1 and start != stop):
            raise ParameterError(f"{name}={spec}: give the number of values, START:STOP:N with "
                                 "N >= 2")
        values = tuple(float(x) for x in np.linspace(start, stop, n))
    lo, hi = parameter.bounds if check_bounds else (-np.inf, np.inf)
    bad = [v for v in values if not (np.isfinite(v) and lo <= v <= hi)]
    if bad:
        from batcert.units import show
        where = (f" ({show(lo, parameter.dimension, 4).si} to {show(hi, parameter.dimension, 4).si})"
                 if parameter.dimension else f" ({lo:g} to {hi:g})")
        raise ParameterError(f"{name}: {bad[0]:.6g} (SI) is outside the accepted range{where}")
    return Axis(parameter, values, nominal, pct)


_NUMBER = re.compile(r"^\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _plain(text: str) -> bool:
    """A bare number, without a unit or a percent sign."""
    m = _NUMBER.match(text)
    return m is not None and not text[m.end():].strip()
