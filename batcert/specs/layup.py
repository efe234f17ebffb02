"""The ``layup`` field of a bat file: laminated (composite) and multi-wall parts of a hollow bat,
as spans along the bat, each a stack of concentric walls of plies (no physics: the stiffness is
:mod:`batcert.physics.laminate`'s).

    layup:
      - span: [21.5 in, 34 in]          # from the knob; omitted: the whole bat
        walls:                           # innermost first; two or more walls slide on each other
          - plies:                       # from the wall's inner surface outward
              - [t700-epoxy, 90 deg, 0.4 mm]
              - [t700-epoxy, ±30 deg, 1.2 mm]   # ± : both angles interlaced in one layer
              - [t700-epoxy, 0 deg, 0.8 mm]

A ply's material is a ply of the library (:data:`batcert.specs.materials.PLIES`), a material of
the bat library (a metal wall: ``[aluminium-7050, 0 deg, 1.4 mm]``), or an inline ply mapping.
"""

from __future__ import annotations

import math
import re
from typing import Any

from batcert.errors import Collector
from batcert.physics.laminate import Layer, OrthotropicPly, WallStack, laminate
from batcert.specs.materials import LIBRARY, PLIES
from batcert.specs.schema import (
    Field,
    FieldError,
    Kind,
    Schema,
    label,
    list_of,
    lookup,
    number,
    quantity,
    section,
    validate,
)
from batcert.specs.yamlio import Located, LocatedList
from batcert.units import UnitError, parse_quantity

PLY_SCHEMA = Schema("inline ply", (
    Field("name", label(), "Label shown in reports.",
          default="custom ply"),
    Field("e1", quantity("modulus", minimum=1e8, maximum=1e12), "Young's modulus along the "
          "fibres.", required=True),
    Field("e2", quantity("modulus", minimum=1e8, maximum=1e12), "Young's modulus across the "
          "fibres.", required=True),
    Field("g12", quantity("modulus", minimum=1e7, maximum=1e12), "In-plane shear modulus.",
          required=True),
    Field("nu12", number(minimum=0.0, maximum=0.6), "Major Poisson's ratio.", required=True),
    Field("density", quantity("density", minimum=100.0, maximum=20000.0), "Density.",
          required=True),
    Field("loss_factor", number(minimum=0.0, maximum=0.5), "Structural loss factor.",
          default=0.0),
))

_ANGLE = re.compile(r"^\s*(±|\+/-|\+-)?\s*([-+]?\d+(?:\.\d*)?|\.\d+)\s*(deg|degrees?|°)\s*$")


def _angle(value: Any) -> tuple[float, bool]:
    """A ply angle from the bat's axis: ``'30 deg'``, or ``'±30 deg'`` (also ``'+-30 deg'``)
    for a balanced layer; returns radians and whether balanced."""
    match = _ANGLE.match(value) if isinstance(value, str) else None
    if not match:
        raise FieldError(f"a ply angle is written like '0 deg', '90 deg' or '±45 deg' "
                         f"(degrees from the bat's axis), got {value!r}")
    degrees = float(match.group(2))
    if not -90.0 <= degrees <= 90.0:
        raise FieldError(f"a ply angle lies between -90 and 90 deg, got {value!r}")
    return math.radians(degrees), match.group(1) is not None


def _ply(value: Any, errors: Collector, path: str) -> OrthotropicPly | None:
    if isinstance(value, str):
        if value in PLIES:
            return PLIES[value][0]
        if value in LIBRARY:
            m = LIBRARY[value][0]
            return OrthotropicPly.isotropic(m.name, m.youngs_modulus, m.poisson_ratio, m.density,
                                            m.loss_factor)
        import difflib
        names = list(PLIES) + list(LIBRARY)
        close = difflib.get_close_matches(value, names, n=1, cutoff=0.5)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise FieldError(f"unknown ply material {value!r} (plies: {', '.join(PLIES)}; "
                         f"materials: {', '.join(LIBRARY)}){hint}")
    if isinstance(value, Located):
        v = validate(value, PLY_SCHEMA, errors, path)
        if v is None or any(v[k] is None for k in ("e1", "e2", "g12", "nu12", "density")):
            return None
        try:
            return OrthotropicPly(v["name"], v["e1"], v["e2"], v["g12"], v["nu12"], v["density"],
                                  v["loss_factor"])
        except ValueError as exc:
            raise FieldError(str(exc)) from None
    raise FieldError("expected a ply or material name, or an inline ply mapping")


def _plies_kind() -> Kind:
    def parse(value: Any, errors: Collector, path: str):
        if not isinstance(value, LocatedList) or not value:
            raise FieldError("expected a list of plies [material, angle, thickness], e.g. "
                             "[[t700-epoxy, ±30 deg, 1.2 mm]]")
        layers: list[Layer] | None = []
        for i, item in enumerate(value):
            line, col = value.item_pos[i]
            sub = f"{path}[{i}]"
            try:
                if not isinstance(item, LocatedList) or len(item) != 3:
                    raise FieldError("expected a ply [material, angle, thickness], e.g. "
                                     "[t700-epoxy, ±30 deg, 1.2 mm]")
                ply = _ply(item[0], errors, f"{sub}[0]")
                angle, balanced = _angle(item[1])
                thickness = parse_quantity(item[2], "length")
                if not 1e-5 <= thickness <= 0.02:
                    raise FieldError(f"a ply's thickness must be 0.01-20 mm, got {item[2]}")
            except (FieldError, UnitError) as exc:
                errors.add(line, sub, str(exc), col)
                layers = None
                continue
            if ply is None:
                layers = None
            elif layers is not None:
                layers.append(Layer(ply, angle, thickness, balanced))
        return None if layers is None else tuple(layers)

    return Kind("list of plies [material, angle, thickness] from the wall's inner surface "
                "outward; angle from the bat's axis, '±30 deg' for a balanced layer", parse)


def _span_kind() -> Kind:
    def parse(value: Any, errors: Collector, path: str):
        if not isinstance(value, LocatedList) or len(value) != 2:
            raise FieldError("expected [start, end] from the knob, e.g. [21.5 in, 34 in]")
        try:
            start, end = (parse_quantity(v, "length") for v in value)
        except UnitError as exc:
            raise FieldError(str(exc)) from None
        if not 0.0 <= start < end:
            raise FieldError(f"a span's start must be at least 0 and below its end, got "
                             f"{value[0]} to {value[1]}")
        return start, end

    return Kind("[start, end] from the knob", parse)


WALL_SCHEMA = Schema("wall of a layup", (
    Field("plies", _plies_kind(), "The wall's plies from its inner surface outward: "
          "[material, angle, thickness].", required=True),
))

SPAN_SCHEMA = Schema("layup span", (
    Field("span", _span_kind(), "Where along the bat this wall holds, from the knob "
          "([start, end]; the slices whose centre lies within). Omitted: the whole bat."),
    Field("walls", list_of(section(WALL_SCHEMA), min_items=1, max_items=4),
          "The concentric walls, innermost first: one for a single (laminated or metal) wall, "
          "two or more for a multi-wall barrel whose walls slide on each other.",
          required=True),
))

LAYUP_KIND = list_of(section(SPAN_SCHEMA), min_items=1,
                     describe="list of spans, each with `walls` (and `span`)")


def spans_of(layup: list[dict], length: float) -> tuple[tuple[float, float, WallStack], ...]:
    """The parsed ``layup`` field as ``(start, end, stack)`` spans (a missing span is the
    whole bat)."""
    out = []
    for entry in layup:
        start, end = entry["span"] if entry["span"] is not None else (0.0, length)
        out.append((start, end, WallStack(tuple(w["plies"] for w in entry["walls"]))))
    return tuple(out)


def check_layup(v: dict, data: Located, errors: Collector, length_blamed: bool = False) -> None:
    """Cross-field checks of ``layup``: hollow bats only, spans on the bat and apart, walls the
    shell of revolution can carry (no shear coupling), and ``wall`` / ``material`` where the
    spans leave part of the bat to them. ``length_blamed``: spans beyond the tip are already
    the length's problem (an implausibly short bat)."""
    layup = v["layup"]
    if layup is None:
        return
    line = lookup(data, "layup")[0]
    if v["construction"] != "hollow":
        errors.add(line, "layup", "only a hollow bat has a wall to lay up; set "
                   "`construction: hollow` or remove `layup`")
        return
    length = v["length"]
    spans = spans_of(layup, length)
    if len(spans) > 1 and any(entry["span"] is None for entry in layup):
        errors.add(line, "layup", "with more than one entry, each needs its `span`")
        return
    order = sorted(range(len(spans)), key=lambda i: spans[i][0])
    for i, (_start, end, stack) in enumerate(spans):
        at = lookup(data, "layup", i)[0]
        if end > length * (1 + 1e-9) and not length_blamed:
            errors.add(at, f"layup[{i}].span", f"the span ends beyond the tip ({length:.4f} m)")
        for w, wall in enumerate(stack.walls):
            if laminate(wall).couples_shear():
                errors.add(lookup(data, "layup", i, "walls", w, "plies")[0],
                           f"layup[{i}].walls[{w}].plies",
                           "this wall couples stretching or bending with shear or twist "
                           "(A16, A26, B16, B26, D16 or D26 not zero: an off-axis ply that no "
                           "opposite ply balances at the same depth), which the shell of "
                           "revolution cannot carry (docs/physics.md); write an angle pair "
                           "as one balanced layer, e.g. [t700-epoxy, ±30 deg, 1.2 mm]")
    for a, b in zip(order, order[1:], strict=False):
        if spans[b][0] < spans[a][1] - 1e-12:
            errors.add(lookup(data, "layup", b)[0], f"layup[{b}].span",
                       f"overlaps span {a} (spans must not overlap)")
    covered = _covers(spans, length)
    if not covered and v["wall"] is None:
        errors.add(lookup(data, "construction")[0], "wall", "the layup does not cover the "
                   "whole bat: give `wall` (and `material`) for the rest")
    if not covered and v["material"] is None:
        errors.add(data.line, "material", "the layup does not cover the whole bat: give "
                   "`material` for the rest")


def _covers(spans, length: float) -> bool:
    ends = sorted((s, e) for s, e, _ in spans)
    reach = 0.0
    for s, e in ends:
        if s > reach + 1e-9:
            return False
        reach = max(reach, e)
    return reach >= length * (1 - 1e-9)


__all__ = ["LAYUP_KIND", "check_layup", "spans_of"]
