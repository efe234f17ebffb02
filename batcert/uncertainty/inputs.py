"""The inputs whose uncertainty a bat or ball file states, and bats and balls drawn from them.

An input carries its uncertainty in the file (``mass: 863 g +/- 1 g``; the inputs that may are
listed in :data:`BAT_FIELDS`, the ``wall`` and the ball's ``mass`` and ``cor``), read as an
:class:`~batcert.units.Uncertain`. Each stated input is one independent source, normal (JCGM
101, 6.4.7: a value known by its best estimate and standard uncertainty) or, with
``(uniform)``, rectangular (6.4.2: a value known only to lie within bounds, such as a rounded
published value). A wall given station by station, or a ball's COR given at several speeds, is
one source: every station (point) moves together by the same number of its own standard
uncertainties (a drawn tube's wall gauge, a ball lot's liveliness).
"""

from __future__ import annotations

import functools
import math
import os
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from batcert.errors import InputError, Problem
from batcert.physics.balls import LAWS
from batcert.specs.ball import BallSpec
from batcert.specs.bat import BatSpec
from batcert.units import si_unit

# the measured-block fields that may carry an uncertainty, with their dimension
BAT_FIELDS = {"mass": "mass", "balance_point": "length", "cg": "length", "moi": "moi",
              "radius_of_gyration": "length", "pendulum_period": "time",
              "first_bending_frequency": "frequency", "hoop_frequency": "frequency"}


@dataclass(frozen=True)
class StatedInput:
    """One input with a stated standard uncertainty."""

    file: str  # "bat" | "ball"
    path: str  # the file
    field: str  # dotted field in the file: "measured.mass", "wall", "cor"
    line: int | None
    dimension: str | None  # a batcert.units dimension; None for the COR
    nominal: tuple[float, ...]  # [SI]: one value, or one per wall station or COR point
    u: tuple[float, ...]  # standard uncertainties [SI], the same shape (0 where none stated)
    distribution: str = "normal"  # normal | uniform

    @property
    def label(self) -> str:
        return f"{self.file} {self.field}"


def _u(x: object) -> float:
    return float(getattr(x, "u", 0.0))


def _distribution(values, path: str, line: int | None, field: str) -> str:
    kinds = {getattr(v, "distribution", "normal") for v in values if _u(v) > 0}
    if len(kinds) > 1:
        raise InputError([Problem(path, line, field, "the stations' uncertainties move together, "
                                  "so they must share one distribution (all normal or all "
                                  "uniform)")])
    return kinds.pop()


def stated_inputs(bat: BatSpec, balls: list[BallSpec]) -> list[StatedInput]:
    """Every input of ``bat`` and ``balls`` (each ball once) that states an uncertainty."""
    out: list[StatedInput] = []
    m = bat.measured
    for name, dim in BAT_FIELDS.items():
        value = getattr(m, name) if m is not None else None
        if value is not None and _u(value) > 0:
            out.append(StatedInput("bat", bat.path, f"measured.{name}",
                                   bat.source.line("measured", name), dim, (float(value),),
                                   (_u(value),), value.distribution))
    if bat.wall is not None:
        walls = bat.wall[1] if isinstance(bat.wall, tuple) else (bat.wall,)
        if any(_u(t) > 0 for t in walls):
            line = bat.source.line("wall")
            out.append(StatedInput("bat", bat.path, "wall", line, "length",
                                   tuple(float(t) for t in walls), tuple(_u(t) for t in walls),
                                   _distribution(walls, bat.path, line, "wall")))
    seen: set[str] = set()
    for ball in balls:
        if _same_file(ball.path) in seen:  # one ball file, however its path is spelled
            continue
        seen.add(_same_file(ball.path))
        b = ball.model
        if _u(b.mass) > 0:
            out.append(StatedInput("ball", ball.path, "mass", ball.source.line("mass"), "mass",
                                   (float(b.mass),), (_u(b.mass),),
                                   getattr(b.mass, "distribution", "normal")))
        cors = [p.value for key, p in ball.tests if key == "cor"]
        if any(_u(e) > 0 for e in cors):
            line = ball.source.line("cor")
            if ball.fit is None and not LAWS[b.law.name].cor_parameters:
                raise InputError([Problem(ball.path, line, "cor", "the COR's uncertainty moves "
                                          "Nathan's law or a fitted viscoelastic ball; this "
                                          "ball's law is stated by its parameters, which the "
                                          "COR does not move: state no uncertainty on it")])
            out.append(StatedInput("ball", ball.path, "cor", line, None,
                                   tuple(float(e) for e in cors), tuple(_u(e) for e in cors),
                                   _distribution(cors, ball.path, line, "cor")))
    return out


def draw(inputs: list[StatedInput], samples: int, seed: int) -> np.ndarray:
    """Each input's move in each draw, in units of its standard uncertainty (mean 0, variance
    1), shape (samples, inputs): standard normal, or for a uniform input ``sqrt(3) (2 Phi(z)
    - 1)`` of a standard normal ``z``; the same seed gives the same draws. Refuses an
    uncertainty that reaches impossible values (a mass, length, MOI or frequency <= 0, a COR
    above 1) in any draw: an :class:`InputError` at the input's line."""
    z = np.random.default_rng(seed).standard_normal((samples, len(inputs)))
    for j, s in enumerate(inputs):
        if s.distribution == "uniform":
            z[:, j] = np.sqrt(3.0) * np.array([math.erf(x / math.sqrt(2.0)) for x in z[:, j]])
    problems = []
    for j, s in enumerate(inputs):
        values = np.asarray(s.nominal)[None, :] + z[:, j:j + 1] * np.asarray(s.u)[None, :]
        low, high = float(values.min()), float(values.max())
        if low <= 0 or (s.dimension is None and high > 1):
            worst = low if low <= 0 else high
            unit = f" {si_unit(s.dimension)}" if s.dimension else ""
            problems.append(Problem(s.path, s.line, s.field, f"the stated uncertainty draws "
                                    f"{worst:.4g}{unit} in {samples} draws (seed {seed}), "
                                    "which is not a possible value: state a smaller "
                                    "uncertainty"))
    if problems:
        raise InputError(problems)
    return z


def sampled(bat: BatSpec, balls: list[BallSpec], inputs: list[StatedInput], z: np.ndarray
            ) -> tuple[BatSpec, list[BallSpec]]:
    """``bat`` and ``balls`` with each input moved by ``z[j]`` of its standard uncertainties
    (``z``: one row of :func:`draw`); inputs without an uncertainty keep their values."""
    measured = bat.measured
    wall = bat.wall
    models = {_same_file(b.path): b.model for b in balls}
    for s, k in zip(inputs, z, strict=True):
        values = tuple(float(v + k * u) for v, u in zip(s.nominal, s.u, strict=True))
        if s.file == "bat" and s.field == "wall":
            wall = (bat.wall[0], values) if isinstance(bat.wall, tuple) else values[0]
        elif s.file == "bat":
            assert measured is not None
            changes: dict[str, Any] = {s.field.split(".", 1)[1]: values[0]}
            measured = replace(measured, **changes)
        elif s.field == "mass":
            key = _same_file(s.path)
            models[key] = replace(models[key], mass=values[0])
        else:  # the COR: Nathan's law takes the drawn points; a fitted law moves along its fit
            key = _same_file(s.path)
            spec = next(b for b in balls if _same_file(b.path) == key)
            law: Any = models[key].law  # Nathan's law (cor_values) or a fitted one
            law = spec.fit.moved(float(k)) if spec.fit is not None else replace(
                law, cor_values=values)
            models[key] = replace(models[key], law=law)
    return (replace(bat, measured=measured, wall=wall),
            [replace(b, model=models[_same_file(b.path)]) for b in balls])


@functools.lru_cache(maxsize=64)
def _same_file(path: str) -> str:
    """One key per file, however its path is spelled (relative, ``..``, links); kept per
    spelling (a Monte Carlo asks five times per draw: 0.1 s of a thousand draws)."""
    return os.path.realpath(path)
