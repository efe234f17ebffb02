"""Bat specification: the YAML fields of a bat file and their validation (no physics).

The bat model is built from a :class:`BatSpec` by :func:`batcert.model.build.build_bat`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from batcert.conventions import BODIES, DEFAULT_PIVOT
from batcert.errors import Collector
from batcert.physics.batmodel import Material
from batcert.specs.common import HEADER_FIELDS, Source, load_checked, pairs, spec_from
from batcert.specs.layup import LAYUP_KIND, check_layup, spans_of
from batcert.specs.materials import LIBRARY
from batcert.specs.schema import (
    Field,
    FieldError,
    Kind,
    Schema,
    choice,
    label,
    lookup,
    number,
    one_of,
    quantity,
    section,
    validate,
)
from batcert.specs.yamlio import Located, load_yaml
from batcert.units import to_us

MATERIAL_SCHEMA = Schema("inline material", (
    Field("name", label(), "Label shown in reports.", default="custom"),
    Field("density", quantity("density", minimum=100.0, maximum=20000.0), "Density "
          "(100-20,000 kg/m^3: balsa to tungsten).", required=True),
    Field("youngs_modulus", quantity("modulus", minimum=1e8, maximum=1e12), "Young's modulus "
          "along the bat (0.1-1000 GPa).", required=True),
    Field("shear_modulus", quantity("modulus", minimum=1e7, maximum=1e12), "Shear modulus "
          "(transverse shear; 0.01-1000 GPa).", required=True),
    Field("poisson_ratio", number(minimum=0.0, maximum=0.5), "Poisson's ratio (hoop stiffness of "
          "hollow barrels).", default=0.3),
    Field("loss_factor", number(minimum=0.0, maximum=0.5), "Structural loss factor eta; modal "
          "damping ratio eta/2.", default=0.0),
))


def _material_kind() -> Kind:
    def parse(value: Any, errors: Collector, path: str):
        if isinstance(value, str):
            if value not in LIBRARY:
                import difflib
                close = difflib.get_close_matches(value, list(LIBRARY), n=1, cutoff=0.5)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                raise FieldError(f"unknown material {value!r} (library: {', '.join(LIBRARY)}){hint}")
            return LIBRARY[value][0]
        if isinstance(value, Located):
            v = validate(value, MATERIAL_SCHEMA, errors, path)
            if v is None or any(v[k] is None for k in ("density", "youngs_modulus", "shear_modulus")):
                return None
            return Material(v["name"], v["density"], v["youngs_modulus"], v["shear_modulus"],
                            v["poisson_ratio"], v["loss_factor"])
        raise FieldError(f"expected a library name ({', '.join(LIBRARY)}) or a mapping")

    return Kind("library name (" + ", ".join(f"`{k}`" for k in LIBRARY) + ") or inline mapping "
                "(density, youngs_modulus, shear_modulus, poisson_ratio, loss_factor)", parse,
                schema=MATERIAL_SCHEMA)


def _check_measured(v: dict, data: Located, errors: Collector, path: str) -> None:
    line = data.line
    if v["balance_point"] is not None and v["cg"] is not None:
        errors.add(lookup(data, "cg")[0], f"{path}.cg", "give either balance_point (from the knob) "
                   "or cg (from the pivot), not both")
    given = [k for k in ("moi", "radius_of_gyration", "pendulum_period") if v[k] is not None]
    if len(given) > 1:
        errors.add(lookup(data, given[1])[0], f"{path}.{given[1]}",
                   f"give only one of moi, radius_of_gyration, pendulum_period (got {', '.join(given)})")
    if given and v["balance_point"] is None and v["cg"] is None:
        errors.add(line, path, f"{given[0]} needs the CG: add balance_point or cg")
    del line


COMPRESSION_SCHEMA = Schema("barrel compression test", (
    Field("force", quantity("force", positive=True), "Force on one platen at the deflection.",
          required=True),
    Field("deflection", quantity("length", positive=True), "Approach of the two platens "
          "(change of the barrel's diameter between them).", required=True),
    Field("position", quantity("length", positive=True), "Centre of the platens, from the "
          "tip.", required=True),
    Field("platen_width", quantity("length", positive=True), "Length of barrel each flat "
          "platen touches (along the bat).", required=True),
))

MEASURED_SCHEMA = Schema("measured properties", (
    Field("pivot", quantity("length", minimum=0.0), "Pivot of the MOI (and origin of `cg`), "
          "from the knob end.", default=DEFAULT_PIVOT),
    Field("mass", quantity("mass", minimum=0.1, maximum=3.0, uncertain=True), "Measured mass (0.1-3 kg).",
          required=True),
    Field("balance_point", quantity("length", positive=True, uncertain=True), "CG from the knob end (F2398 "
          "balance point)."),
    Field("cg", quantity("length", positive=True, uncertain=True), "CG from the pivot (alternative to "
          "balance_point)."),
    Field("moi", quantity("moi", positive=True, uncertain=True), "Moment of inertia about the pivot."),
    Field("radius_of_gyration", quantity("length", positive=True, uncertain=True), "Radius of gyration about the "
          "CG (Nathan 2000 Table I form); alternative to moi."),
    Field("pendulum_period", quantity("time", positive=True, uncertain=True), "ASTM F2398 pendulum period about "
          "the pivot; I = M g (BP - pivot) T^2 / (4 pi^2). Alternative to moi."),
    Field("first_bending_frequency", quantity("frequency", positive=True, uncertain=True), "Measured free-free "
          "first bending frequency; EI and kappa G A are scaled together so the model matches it."),
    Field("hoop_frequency", quantity("frequency", positive=True, uncertain=True), "Hollow bats: the barrel's "
          "lowest hoop (n = 2) frequency measured on the free bat (impact hammer and "
          "accelerometer on the barrel); the barrel shell is calibrated to it "
          "(docs/physics.md)."),
    Field("barrel_compression", section(COMPRESSION_SCHEMA), "Hollow bats: a barrel "
          "compression test; with hoop_frequency it sets the shell's stiffness, and the "
          "frequency then its mass."),
), checks=(_check_measured,))


def _check_bat(v: dict, data: Located, errors: Collector, path: str) -> None:
    check_layup(v, data, errors, length_blamed=_check_stations(v, data, errors))
    if v["layup"] is None and v["material"] is None:
        errors.add(data.line, "material", "required field is missing")
    if v["construction"] == "hollow" and v["wall"] is None and v["layup"] is None:
        errors.add(lookup(data, "construction")[0], "wall", "hollow bats need a wall thickness "
                   "(`wall: 2.5 mm` or a list of [position, thickness] pairs)")
    if v["construction"] == "solid" and v["wall"] is not None:
        errors.add(lookup(data, "wall")[0], "wall", "a solid bat has no wall; remove `wall` or set "
                   "`construction: hollow`")
    measured = v["measured"] or {}
    for key in ("hoop_frequency", "barrel_compression"):
        if v["construction"] == "solid" and measured.get(key) is not None:
            errors.add(lookup(data, "measured", key)[0], f"measured.{key}", "only a hollow bat "
                       "has a barrel to measure")


# Shorter than any bat a league or a test covers (tee-ball bats start at about 24 in): a bat
# file's length below this, shorter than its own profile, is the length's mistake (a unit)
SHORTEST_BAT = 0.5  # [m]


def _check_stations(v: dict, data: Located, errors: Collector) -> bool:
    """The profile's and the wall's stations lie on the bat, from the knob (0) to the tip (the
    length). Stations (or layup spans) beyond an implausibly short length
    (:data:`SHORTEST_BAT`) are the length's problem, at its line ("34 cm" for 34 in; returns
    True); otherwise each list's, naming the length's line."""
    length = v["length"]
    lists = {"profile": v["profile"][0]}
    if isinstance(v["wall"], tuple):
        lists["wall"] = v["wall"][0]
    if v["layup"]:
        lists["layup"] = [max(end for _, end, _ in spans_of(v["layup"], length))]
    beyond = {k: z[-1] for k, z in lists.items() if z[-1] > length * (1 + 1e-9)}
    length_line = lookup(data, "length")[0]
    blame_length = bool(beyond) and length < SHORTEST_BAT
    if blame_length:
        reach = max(beyond.values())
        errors.add(length_line, "length", f"{to_us(length, 'length'):.2f} in is shorter than "
                   f"any bat ({to_us(SHORTEST_BAT, 'length'):.0f} in) and than the "
                   f"{' and the '.join(beyond)}, which reach{'es' if len(beyond) == 1 else ''} "
                   f"{to_us(reach, 'length'):.2f} in from the knob: is the length's unit right?")
    on_bat = (f"stations must lie between the knob (0) and the tip (the length, "
              f"{to_us(length, 'length'):.2f} in" + (f", line {length_line})" if length_line
                                                      else ")"))
    for key in ("profile", "wall"):
        z = lists.get(key)
        if z is not None and (z[0] < 0 or (key in beyond and not blame_length)):
            errors.add(lookup(data, key)[0], key, on_bat)
    return blame_length


IDENTIFICATION_SCHEMA = Schema("bat identification", (
    Field("maker", label(), "Who made the bat."),
    Field("model", label(), "The maker's model name or number."),
    Field("serial", label(), "The bat's serial number (one physical bat)."),
    Field("lot", label(), "The production lot or batch."),
))

BAT_SCHEMA = Schema("bat", (
    Field("name", label(), "Bat name shown in reports.", required=True),
    *HEADER_FIELDS,
    Field("body", choice(*BODIES), "The game the bat is made for (its ball): a run under a "
          "protocol whose ball is the other game's warns."),
    Field("construction", choice("solid", "hollow"), "Solid (wood) or hollow (metal, composite) "
          "barrel.", required=True),
    Field("length", quantity("length", minimum=0.3, maximum=1.5), "Overall length, knob end "
          "to tip (0.3-1.5 m).", required=True),
    Field("profile", pairs("length", "length", "position from knob", "outer diameter", min_items=2,
                           second_range=(0.005, 0.15)),
          "Outer diameter at stations from the knob end, interpolated linearly; held constant "
          "beyond the first and last station (5-150 mm).", required=True),
    Field("wall", one_of(quantity("length", minimum=1e-4, maximum=0.02, uncertain=True),
                         pairs("length", "length", "position from knob", "wall thickness",
                               second_range=(1e-4, 0.02), second_uncertain=True),
                         describe="a thickness or a list of [position, thickness] pairs"),
          "Wall thickness of a hollow bat: constant, or per station (interpolated; "
          "0.1-20 mm)."),
    Field("material", _material_kind(), "Material: library name or inline properties. With "
          "a `layup` that covers the whole bat it may be left out (the layup's own then)."),
    Field("layup", LAYUP_KIND, "Hollow bats: laminated (composite) or multi-wall walls, as "
          "spans along the bat, each a stack of walls of plies [material, angle, thickness] "
          "(docs/inputs.md, 'Layups'); where given, it replaces `wall` and `material`."),
    Field("knob_mass", quantity("mass", minimum=0.0, maximum=1.0), "Extra mass at the knob end "
          "(at most 1 kg).", default=0.0),
    Field("end_cap_mass", quantity("mass", minimum=0.0, maximum=1.0), "Extra mass at the tip "
          "(end cap; at most 1 kg).", default=0.0),
    Field("shear_correction", number(minimum=0.1, maximum=1.5), "Timoshenko shear "
          "coefficient kappa; default 6(1+nu)/(7+6nu) solid, 2(1+nu)/(4+3nu) hollow."),
    Field("barrel_end", choice("closed", "open"), "Hollow bats: the barrel's tip end is held "
          "round by its end cap (closed) or free to oval (open).", default="closed"),
    Field("slice_length", quantity("length", minimum=0.0025, maximum=0.02), "Beam slice "
          "length. Finer than 2.5 mm is refused: results are converged at the default 10 mm "
          "(docs/validation.md) and the cost grows with the square of the slice count.",
          default=0.01),
    Field("measured", section(MEASURED_SCHEMA), "What a lab measured: mass properties (the "
          "model is reconciled to match them exactly), frequencies and barrel compression (the "
          "model is calibrated to them)."),
    Field("reconcile", choice("density-profile", "point-masses", "none"), "How the model is "
          "corrected to the measured values (docs/reconciliation.md).", default="density-profile"),
    Field("identification", section(IDENTIFICATION_SCHEMA), "Which bat this file describes: "
          "maker, model, serial number, lot (text, each optional); shown on every report."),
), checks=(_check_bat,))


@dataclass(frozen=True)
class MeasuredSpec:
    """The ``measured:`` block: what a lab measured on the bat (SI; None where not given)."""

    pivot: float  # pivot of the MOI and origin of `cg` [m from knob]
    mass: float  # [kg]
    balance_point: float | None  # CG [m from knob]
    cg: float | None  # CG [m from pivot]
    moi: float | None  # about the pivot [kg m^2]
    radius_of_gyration: float | None  # about the CG [m]
    pendulum_period: float | None  # ASTM F2398 period about the pivot [s]
    first_bending_frequency: float | None  # free-free [Hz]
    hoop_frequency: float | None  # barrel, lowest n = 2, free bat [Hz]
    barrel_compression: dict | None  # force [N], deflection [m], position [m from tip],
    # platen_width [m]


@dataclass(frozen=True)
class BatSpec:
    """A validated bat file (SI values, field names as in the file)."""

    source: Source
    name: str
    description: str | None
    reference: str | None
    version: str | None
    construction: str  # solid | hollow
    length: float  # [m]
    profile: tuple[tuple[float, ...], tuple[float, ...]]  # stations [m from knob], diameters [m]
    wall: float | tuple[tuple[float, ...], tuple[float, ...]] | None  # [m] or stations, walls
    material: Material | None  # None: a layup covers the whole bat
    knob_mass: float  # [kg]
    end_cap_mass: float  # [kg]
    shear_correction: float | None  # [-]
    barrel_end: str  # closed | open
    slice_length: float  # [m]
    measured: MeasuredSpec | None
    reconcile: str  # density-profile | point-masses | none
    identification: dict | None = None  # maker, model, serial, lot (text; those given)
    layup: tuple = ()  # (start [m from knob], end [m], WallStack) spans; () for none
    body: str | None = None  # baseball | softball; None when the file does not say

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def barrel_middle(self) -> float:
        """The middle of the barrel [m from knob]: halfway between the first and the last
        profile station at the largest diameter."""
        z, d = self.profile
        top = [zi for zi, di in zip(z, d, strict=True) if di >= max(d)]
        return 0.5 * (top[0] + top[-1])

    def layup_span_at(self, z: float) -> int | None:
        """The index of the ``layup`` span holding ``z`` [m from knob], or None."""
        for i, (start, end, _) in enumerate(self.layup):
            if start <= z <= end:
                return i
        return None

    @property
    def sha256(self) -> str:
        return self.source.sha256


def load_bat(path: str | Path) -> BatSpec:
    """Read and validate a bat file; raise InputError with every problem of the file."""
    data = load_yaml(path)
    values = load_checked(path, BAT_SCHEMA, data)
    measured: Any = values["measured"]
    if measured is not None:
        values["measured"] = spec_from(MeasuredSpec, measured)
    values["layup"] = () if values["layup"] is None else spans_of(values["layup"],
                                                                    values["length"])
    return spec_from(BatSpec, values, source=Source.of(path, data))
