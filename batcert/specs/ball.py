"""Ball specification: mass, radius, what ball tests measured, and the contact law.

A ball file states what a ball lab measures, each test a list of points with their
conditions (and, for a fit, their uncertainties, ``0.546 +/- 0.018``): the COR against a rigid
flat wall at several speeds (``cor``; ASTM F1887 at 60 mph, cannon tests), against a rigid
cylinder (``cylinder_cor``; ASTM F2845), peak forces, collision and contact times, and the
quasi-static compression (ASTM F1888). The ``contact`` section names the law
(:data:`batcert.physics.balls.LAWS`): Nathan's power-law hysteresis takes its ``k1`` and
``alpha`` and reads its loss off the ``cor`` points; the viscoelastic law takes its four
parameters, or (without them) has them fitted to the tests (:mod:`batcert.physics.balls.fit`;
a fit that cannot be trusted is an input error at the test at fault).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from batcert.conventions import SOFTBALL_RADIUS
from batcert.errors import Collector, InputError, Problem
from batcert.physics.ball import BallModel
from batcert.physics.balls import LAWS, ContactLaw, PowerLawHysteresis, TwoTimeViscoelastic
from batcert.physics.balls.fit import BallFit
from batcert.specs.ball_fit import ball_tests, fitted, judge_given
from batcert.specs.common import HEADER_FIELDS, Source, load_checked
from batcert.specs.schema import (
    Field,
    FieldError,
    Kind,
    Schema,
    choice,
    label,
    number,
    quantity,
    section,
    text,
)
from batcert.specs.yamlio import LocatedList, load_yaml
from batcert.units import DIMENSIONS, UnitError, parse_quantity, read_spread, split_uncertainty, uncertain

__all__ = ["BALL_SCHEMA", "BallSpec", "ReferenceBat", "ball_tests", "load_ball"]


@dataclass(frozen=True)
class TestPoint:
    """One measured point of a ball test: its condition (speed [m/s], or displacement [m] for
    ``compression``), value (SI; an :class:`~batcert.units.Uncertain` when stated with one),
    rigid surface's diameter [m] (``inf``: flat) and the point's 1-based line in the file."""

    condition: float
    value: float
    surface_diameter: float
    line: int | None


def _cor_value(value: Any) -> float:
    """A COR in (0, 1], or ``0.546 +/- 0.008`` (an :class:`Uncertain`)."""
    text_, u_text = split_uncertainty(value)
    distribution = "normal"
    try:
        if u_text is not None:
            u_text, distribution = read_spread(value, u_text)
        e = float(text_) if u_text is not None else text_  # type: ignore[arg-type]
        u = None if u_text is None else float(u_text)
    except UnitError as exc:
        raise ValueError(str(exc)) from None
    except ValueError:
        raise ValueError(f"COR must be a number in (0, 1], or one with its standard "
                         f"uncertainty ('0.546 +/- 0.008'), got {value!r}") from None
    if isinstance(e, bool) or not isinstance(e, (int, float)) or not 0 < e <= 1:
        raise ValueError(f"COR must be a number in (0, 1], got {value!r}")
    if u is None:
        return float(e)
    if not 0 <= u < 1:
        raise ValueError(f"the COR's uncertainty must lie in [0, 1), got {value!r}")
    return uncertain(float(e), u, distribution, value)


def _quantity_value(dimension: str):
    def read(value: Any) -> float:
        from batcert.units import parse_uncertain

        try:
            v = parse_uncertain(value, dimension)
        except UnitError as exc:
            raise ValueError(str(exc)) from None
        if not v > 0:
            raise ValueError(f"must be positive, got {value!r}")
        return v
    return read


def _points(condition: str, condition_name: str, value_name: str, example: str, read_value,
            *, surface: bool = False, increasing: bool = False) -> Kind:
    """A list of ``[condition, value]`` points (``[condition, value, cylinder diameter]``
    with ``surface``); each value may carry its uncertainty (``+/- u``)."""
    shape = f"[{condition_name}, {value_name}" + (", surface diameter or flat]" if surface else "]")

    def parse(value: Any, errors: Collector, path: str):
        if not isinstance(value, LocatedList) or not value:
            raise FieldError(f"expected a list of {shape} points, e.g. [{example}]")
        out: list[TestPoint] = []
        ok = True
        for i, item in enumerate(value):
            line, col = value.item_pos[i]
            sub = f"{path}[{i}]"
            size = 3 if surface else 2
            if not isinstance(item, LocatedList) or len(item) != size:
                errors.add(line, sub, f"expected {shape}, e.g. {example}", col)
                ok = False
                continue
            try:
                c = parse_quantity(item[0], condition)
                if not c > 0:
                    raise UnitError(f"{condition_name} must be positive, got {item[0]!r}")
                v = read_value(item[1])
                d = math.inf
                if surface:
                    d = _read_flat(item[2])
                    if not (d == math.inf or 0.01 <= d <= 1.0):
                        raise UnitError(f"the cylinder's diameter must be 10-1000 mm (or "
                                        f"`flat`), got {item[2]!r}")
            except (UnitError, ValueError) as exc:
                errors.add(line, sub, str(exc), col)
                ok = False
                continue
            if increasing and out and not c > out[-1].condition:
                errors.add(line, sub, f"{condition_name}s must increase; {item[0]} follows "
                           f"{value[i - 1][0]}", col)
                ok = False
                continue
            out.append(TestPoint(c, v, d, line))
        return tuple(out) if ok else None

    return Kind(f"list of {shape} points; each {value_name} may carry `+/- u`", parse,
                DIMENSIONS[condition][1])


# every ball test: the file's key, its kind in the fit, and how it is read
TESTS: dict[str, tuple[Kind, str]] = {
    "cor": (_points("speed", "impact speed", "COR", "[85 ft/s, 0.546 +/- 0.018]", _cor_value,
                    increasing=True),
            "Rigid-wall COR at impact speeds (ASTM F1887: 60 mph into a rigid flat wall; cannon "
            "tests). Nathan's law reads its loss off these points (linear in speed between "
            "them, constant beyond); the viscoelastic law is fitted to them. Required."),
    "cylinder_cor": (_points("speed", "impact speed", "COR", "[60 mph, 0.50 +/- 0.01, 2.25 in]",
                             _cor_value, surface=True),
                     "COR against a rigid cylinder of the stated diameter (ASTM F2845's CCOR)."),
    "peak_force": (_points("speed", "impact speed", "peak force",
                           "[60 mph, 3000 lbf +/- 100 lbf, flat]", _quantity_value("force"),
                           surface=True),
                   "Largest force of an impact on a rigid flat wall (diameter `flat`) or "
                   "cylinder, by load cells."),
    "collision_time": (_points("speed", "impact speed", "time", "[45 m/s, 0.7 ms +/- 0.04 ms]",
                               _quantity_value("time")),
                       "Time over which the central 99 % of the impulse acts against a rigid "
                       "wall (Nathan 2000's collision time)."),
    "contact_time": (_points("speed", "impact speed", "time", "[26.8 m/s, 0.95 ms +/- 0.05 ms]",
                             _quantity_value("time")),
                     "First touch to separation against a rigid wall."),
    "compression": (_points("length", "diametral displacement", "force",
                            "[0.25 in, 250 lbf +/- 10 lbf]", _quantity_value("force")),
                    "Quasi-static force squeezing the ball between flat platens by a diametral "
                    "displacement (ASTM F1888: 0.25 in, slowly)."),
}


def _read_flat(value: Any) -> float:
    return math.inf if str(value).strip().lower() == "flat" else parse_quantity(value, "length")


_HYSTERESIS = ("k1", "alpha")
_VISCOELASTIC = TwoTimeViscoelastic.PARAMETERS  # every viscoelastic law's parameters


def _own(model: str) -> tuple[str, ...]:
    law: Any = LAWS[model].law  # a viscoelastic law's class lists its parameters
    return _HYSTERESIS if model == "power-law-hysteresis" else tuple(law.PARAMETERS)


def _contact_check(values: dict, data, errors: Collector, path: str) -> None:
    """Each law's own parameters: Nathan's needs ``k1`` and ``alpha``; a viscoelastic law
    takes any of its parameters (four, or six with two relaxation times; those not given are
    fitted to the tests, the given ones held: a ball known only by its marks)."""
    model = values["model"]
    own = _own(model)
    for name in _HYSTERESIS + _VISCOELASTIC:
        if name not in own and values.get(name) is not None:
            errors.add(data.key_pos[name][0], f"{path}.{name}",
                       f"not a parameter of the {model} law (its parameters: {', '.join(own)})")
    given = [n for n in own if values.get(n) is not None]
    if model == "power-law-hysteresis" and len(given) < 2:
        for name in own:
            if values.get(name) is None:
                errors.add(data.line, f"{path}.{name}", "required by the power-law-hysteresis law")


CONTACT_SCHEMA = Schema("contact law", (
    Field("model", choice(*LAWS), "Contact law: " + "; ".join(
        f"`{e.name}`, {e.title}: {e.doc}" for e in LAWS.values()) + ".",
          default="power-law-hysteresis"),
    Field("k1", number(minimum=1e3, maximum=1e12), "power-law-hysteresis: compression "
          "stiffness [N/m^alpha]."),
    Field("alpha", number(minimum=1.0, maximum=3.0), "power-law-hysteresis: compression "
          "exponent."),
    Field("stiffness", number(minimum=1e3, maximum=1e13), "viscoelastic: instantaneous "
          "stiffness k0 [N/m^exponent]. Any of the four parameters omitted is fitted to the "
          "ball tests; those given are held (a ball known only by its marks)."),
    Field("exponent", number(minimum=1.0, maximum=3.0), "viscoelastic: exponent a of u^a."),
    Field("relaxed_fraction", number(exclusive_minimum=0.0, maximum=1.0), "viscoelastic: "
          "relaxed over instantaneous stiffness."),
    Field("relaxation_time", quantity("time", positive=True), "viscoelastic: relaxation time "
          "tau (viscoelastic-2: the slow branch's)."),
    Field("fast_share", number(exclusive_minimum=0.0, maximum=0.99), "viscoelastic-2: "
          "the fast branch's share of the relaxing stiffness k0 - k_inf."),
    Field("fast_relaxation_time", quantity("time", positive=True), "viscoelastic-2: the fast "
          "branch's relaxation time tau_f."),
), checks=(_contact_check,))


def _cor_kind() -> Kind:
    def parse(value: Any, errors: Collector, path: str):
        try:
            return _cor_value(value)
        except ValueError as exc:
            raise FieldError(str(exc)) from None
    return Kind("number in (0, 1], may carry `+/- u`", parse)


def _reference_check(values: dict, data, errors: Collector, path: str) -> None:
    if not getattr(values.get("value"), "u", 0) > 0:
        errors.add(data.key_pos.get("value", (data.line, None))[0], f"{path}.value",
                   "a reference bat's value needs its standard uncertainty ('0.490 +/- 0.010')")


REFERENCE_SCHEMA = Schema("reference bat", (
    Field("bat", label(), "The reference bat: a shipped name (`ash-34`) or a bat file's path "
          "(relative to this file).", required=True),
    Field("protocol", label(), "The protocol it was measured under: a shipped id "
          "(`ncaa-bbcor`) or a path (relative to this file). Its own ball is not used.",
          required=True),
    Field("value", _cor_kind(), "The protocol's metric measured on the reference bat with this "
          "ball lot, with its standard uncertainty.", required=True),
    Field("source", text(), "Where the value comes from."),
), doc="A reference bat's measurement with this ball lot: the lot is calibrated on it (a lab "
       "checks its lots this way), by moving every COR test together (the fit's lot direction) "
       "until the model's metric for the reference bat equals the value. A CALIBRATION: the "
       "reference bat is then no longer a validation.", checks=(_reference_check,))

BALL_SCHEMA = Schema("ball", (
    Field("name", label(), "Ball name shown in reports.", required=True),
    *HEADER_FIELDS,
    Field("mass", quantity("mass", minimum=0.02, maximum=1.0, uncertain=True), "Ball mass "
          "(20-1000 g).",
          required=True),
    Field("radius", quantity("length", minimum=0.02, maximum=0.1), "Ball radius (20-100 mm).",
          required=True),
    *(Field(name, kind, doc, required=name == "cor") for name, (kind, doc) in TESTS.items()),
    Field("contact", section(CONTACT_SCHEMA), "Contact law and its parameters.", required=True),
    Field("reference_bat", section(REFERENCE_SCHEMA), "A reference bat's measurement that "
          "calibrates the ball lot (fitted viscoelastic balls only)."),
))


@dataclass(frozen=True)
class ReferenceBat:
    """A reference bat's measurement with the ball lot (the ball file's ``reference_bat``):
    the resolved bat and protocol files, the measured value and its standard uncertainty."""

    bat: str  # the resolved bat file
    protocol: str  # the resolved protocol file
    value: float
    uncertainty: float
    source: str
    line: int | None  # the value's line
    path: str | None = None  # the file of that line, when not the ball file (a lab session)
    field: str = "reference_bat"  # the field at that line


@dataclass(frozen=True)
class BallSpec:
    """A validated ball file, the ball model it defines and, for a fitted law, the fit."""

    source: Source
    name: str
    model: BallModel
    tests: tuple[tuple[str, TestPoint], ...] = ()  # (file key, point) of every test point
    fit: BallFit | None = None
    reference: ReferenceBat | None = None  # a reference bat that calibrates the lot
    # the calibration applied (batcert.runner.lot.LotCalibration: the lot's shift along the
    # fit's lot direction and the model's value for the reference bat), None before
    lot: Any = None

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def sha256(self) -> str:
        return self.source.sha256

    @property
    def body(self) -> str:
        """The game the ball is for, by its size (:data:`SOFTBALL_RADIUS`)."""
        return "softball" if self.model.radius > SOFTBALL_RADIUS else "baseball"


def load_ball(path: str | Path) -> BallSpec:
    """Read and validate a ball file; raise InputError with every problem of the file (a
    viscoelastic fit that cannot be trusted included)."""
    data = load_yaml(path)
    v = load_checked(path, BALL_SCHEMA, data)
    c = v["contact"]
    tests = tuple((key, p) for key in TESTS for p in (v[key] or ()))
    mass, radius = v["mass"], v["radius"]
    fit = None
    if c["model"] == "power-law-hysteresis":
        cor = v["cor"]
        law: ContactLaw = PowerLawHysteresis(
            c["k1"], c["alpha"], tuple(p.condition for p in cor), tuple(p.value for p in cor))
    elif all(c[n] is not None for n in _own(c["model"])):
        law = LAWS[c["model"]].law(*(c[n] for n in _own(c["model"])))
        judge_given(path, tests, float(mass), radius, law)
    else:
        held = tuple((n, float(c[n])) for n in _own(c["model"]) if c[n] is not None)
        fit = fitted(path, data, tests, float(mass), radius, held, c["model"])
        law = fit.law
    model = BallModel(v["name"], mass, radius, law)
    reference = _reference(path, data, v["reference_bat"], fit) if v["reference_bat"] else None
    return BallSpec(Source.of(path, data), v["name"], model, tests, fit, reference)


def _reference(path, data, r: dict, fit: BallFit | None) -> ReferenceBat:
    """The ``reference_bat`` section with its files resolved (an input error at the line of
    one that does not resolve, or where the law is not a fitted one)."""
    from batcert.specs.resolve import NotFound, resolve

    node = data["reference_bat"]
    if fit is None:
        raise InputError([Problem(str(path), data.key_pos["reference_bat"][0], "reference_bat",
                                  "a reference bat calibrates a ball lot along its fit: only a "
                                  "viscoelastic law fitted to ball tests takes one")])
    found, problems = {}, []
    for key in ("bat", "protocol"):
        try:
            found[key] = resolve(key, r[key], relative_to=Path(path))
        except NotFound as exc:
            problems.append(Problem(str(path), node.key_pos[key][0], f"reference_bat.{key}",
                                    str(exc)))
    if problems:
        raise InputError(problems)
    return ReferenceBat(str(found["bat"]), str(found["protocol"]), float(r["value"]),
                        float(r["value"].u), r["source"] or "", node.key_pos["value"][0])
