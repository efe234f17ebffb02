"""Ball specification: mass, radius, speed-dependent rigid-wall COR, contact law."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from batcert.errors import Collector
from batcert.physics.ball import BallModel
from batcert.specs.common import HEADER_FIELDS, Source, load_checked
from batcert.specs.schema import Field, FieldError, Kind, Schema, choice, number, quantity, section, text
from batcert.specs.yamlio import LocatedList, load_yaml
from batcert.units import UnitError, parse_quantity, read_spread, split_uncertainty, uncertain


def _cor_points() -> Kind:
    def parse(value: Any, errors: Collector, path: str):
        if not isinstance(value, LocatedList) or not value:
            raise FieldError("expected a list of [impact speed, COR] pairs, e.g. [[85 ft/s, 0.546]]")
        speeds: list[float] = []
        cors: list[float] = []
        ok = True
        for i, item in enumerate(value):
            line, col = value.item_pos[i]
            sub = f"{path}[{i}]"
            if not isinstance(item, LocatedList) or len(item) != 2:
                errors.add(line, sub, "expected a pair [impact speed, COR], e.g. [85 ft/s, 0.546]", col)
                ok = False
                continue
            try:
                v = parse_quantity(item[0], "speed")
            except UnitError as exc:
                errors.add(line, sub, str(exc), col)
                ok = False
                continue
            try:
                e = _cor_value(item[1])
            except ValueError as exc:
                errors.add(line, sub, str(exc), col)
                ok = False
                continue
            if v <= 0 or (speeds and v <= speeds[-1]):
                errors.add(line, sub, "impact speeds must be positive and increasing", col)
                ok = False
                continue
            speeds.append(v)
            cors.append(e)
        return (tuple(speeds), tuple(cors)) if ok else None

    return Kind("list of [impact speed, COR] pairs; each COR may carry `+/- u` (the ball "
                "lot's spread)", parse, "m/s")


def _cor_value(value: Any) -> float:
    """A COR in (0, 1], or ``0.546 +/- 0.008`` (an :class:`Uncertain`)."""
    text, u_text = split_uncertainty(value)
    distribution = "normal"
    try:
        if u_text is not None:
            u_text, distribution = read_spread(value, u_text)
        e = float(text) if u_text is not None else text  # type: ignore[arg-type]
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


CONTACT_SCHEMA = Schema("contact law", (
    Field("model", choice("power-law-hysteresis"), "Contact law (Nathan 2000): compression "
          "F = k1 u^alpha, restitution F = k2 u^beta, beta = (1 + alpha)/e^2 - 1.",
          default="power-law-hysteresis"),
    Field("k1", number(minimum=1e3, maximum=1e12), "Compression stiffness [N/m^alpha].",
          required=True),
    Field("alpha", number(minimum=1.0, maximum=3.0), "Compression exponent.", required=True),
))

BALL_SCHEMA = Schema("ball", (
    Field("name", text(), "Ball name shown in reports.", required=True),
    *HEADER_FIELDS,
    Field("mass", quantity("mass", minimum=0.02, maximum=1.0, uncertain=True), "Ball mass "
          "(20-1000 g).",
          required=True),
    Field("radius", quantity("length", minimum=0.02, maximum=0.1), "Ball radius (20-100 mm).",
          required=True),
    Field("cor", _cor_points(), "Rigid-wall COR at one or more impact speeds; piecewise linear "
          "in speed between points, constant beyond the first and last.", required=True),
    Field("contact", section(CONTACT_SCHEMA), "Contact law parameters.", required=True),
))


@dataclass(frozen=True)
class BallSpec:
    """A validated ball file and the ball model it defines."""

    source: Source
    name: str
    model: BallModel

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def sha256(self) -> str:
        return self.source.sha256


def load_ball(path: str | Path) -> BallSpec:
    """Read and validate a ball file; raise InputError with every problem of the file."""
    data = load_yaml(path)
    v = load_checked(path, BALL_SCHEMA, data)
    c = v["contact"]
    model = BallModel(v["name"], v["mass"], v["radius"], v["cor"][0], v["cor"][1],
                      c["model"], c["k1"], c["alpha"])
    return BallSpec(Source.of(path, data), v["name"], model)
