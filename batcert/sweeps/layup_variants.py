"""The sweep parameters of a bat's layup (:mod:`batcert.specs.layup`), all of its barrel: the
span that holds the barrel's middle (``BatSpec.barrel_middle``).

- ``ply_angle``: the angle [deg] of every balanced (``±``) layer of the barrel's walls;
- ``ply_count``: the barrel wall's thickness in plies of its thinnest layer (a 4.2 mm wall whose
  thinnest layer is 0.3 mm holds 14); every layer scales in proportion, so the stacking
  sequence's shares are kept and a fractional count is a proportional thickness;
- ``wall_split``: the outer wall's share of a multi-wall barrel's thickness (the others keep
  their proportions among themselves).

A variant is the bat as its geometry gives it (:func:`~batcert.sweeps.cases.geometry_only`).
"""

from __future__ import annotations

import math
from dataclasses import replace

from batcert.model.build import BuiltBat
from batcert.physics.laminate import Layer, WallStack
from batcert.specs.bat import BatSpec
from batcert.sweeps.cases import Case, Parameter, ParameterError, geometry_only


def _barrel(spec: BatSpec) -> int:
    """The index of the layup span holding the barrel's middle."""
    if not spec.layup:
        raise ParameterError(f"{spec.name!r} has no layup: the ply parameters vary a layup's "
                             "barrel (give the bat a `layup`, or vary `wall`)")
    i = spec.layup_span_at(spec.barrel_middle)
    if i is None:
        raise ParameterError(f"{spec.name!r}'s layup does not cover its barrel's middle "
                             f"({spec.barrel_middle * 100:.1f} cm from the knob)")
    return i


def _with_stack(case: Case, stack: WallStack) -> Case:
    i = _barrel(case.bat)
    start, end, _ = case.bat.layup[i]
    layup = case.bat.layup[:i] + ((start, end, stack),) + case.bat.layup[i + 1:]
    return replace(case, bat=geometry_only(replace(case.bat, layup=layup)))


def _stack(case: Case) -> WallStack:
    return case.bat.layup[_barrel(case.bat)][2]


def _scaled(wall: tuple[Layer, ...], factor: float) -> tuple[Layer, ...]:
    return tuple(replace(layer, thickness=layer.thickness * factor) for layer in wall)


def _angle_nominal(case: Case, built: BuiltBat) -> float:
    for wall in _stack(case).walls:
        for layer in wall:
            if layer.balanced:
                return math.degrees(layer.angle)
    raise ParameterError(f"{case.bat.name!r}'s barrel has no balanced (±) layer whose angle "
                         "could vary")


def _angle_apply(case: Case, built: BuiltBat, value: float) -> Case:
    _angle_nominal(case, built)
    stack = WallStack(tuple(tuple(replace(layer, angle=math.radians(value)) if layer.balanced
                                  else layer for layer in wall) for wall in _stack(case).walls))
    return _with_stack(case, stack)


def _ply(stack: WallStack) -> float:
    return min(layer.thickness for wall in stack.walls for layer in wall)


def _count_nominal(case: Case, built: BuiltBat) -> float:
    stack = _stack(case)
    return stack.thickness / _ply(stack)


def _count_apply(case: Case, built: BuiltBat, value: float) -> Case:
    factor = value / _count_nominal(case, built)
    return _with_stack(case, WallStack(tuple(_scaled(w, factor) for w in _stack(case).walls)))


def _split_nominal(case: Case, built: BuiltBat) -> float:
    stack = _stack(case)
    if len(stack.walls) < 2:
        raise ParameterError(f"{case.bat.name!r}'s barrel has one wall: wall_split needs two "
                             "or more")
    return sum(layer.thickness for layer in stack.walls[-1]) / stack.thickness


def _split_apply(case: Case, built: BuiltBat, value: float) -> Case:
    share = _split_nominal(case, built)
    walls = _stack(case).walls
    inner = tuple(_scaled(w, (1.0 - value) / (1.0 - share)) for w in walls[:-1])
    return _with_stack(case, WallStack(inner + (_scaled(walls[-1], value / share),)))


LAYUP_PARAMETERS = (
    Parameter("ply_angle", "ply angle", None, "geometry", "The angle [deg, from the bat's "
              "axis] of every balanced (±) layer of the barrel's layup (the span holding the "
              "barrel's middle).", _angle_nominal,
              _angle_apply, (0.0, 90.0), 0.01, unit="deg"),
    Parameter("ply_count", "barrel plies", None, "geometry", "The barrel wall's thickness in "
              "plies of its thinnest layer; every layer scales in proportion (a fractional "
              "count is a proportional thickness).", _count_nominal,
              _count_apply, (1.0, 200.0), 0.01),
    Parameter("wall_split", "outer wall share", None, "geometry", "A multi-wall barrel: the "
              "outer wall's share of the wall thickness (the inner walls share the rest in "
              "their proportions).", _split_nominal, _split_apply, (0.05, 0.95), 1e-4),
)
