"""The coordinates a fit moves a viscoelastic law's parameters in
(:mod:`batcert.physics.balls.fit`): each law class names its ``PARAMETERS`` and, per parameter,
a ``COORDINATES`` entry: ``"log"`` for a positive scale (a stiffness, a time), ``"logit"`` for a
fraction in (0, 1), ``""`` for the number itself (an exponent). A fit in these coordinates
cannot leave a parameter's domain, and steps of equal size are changes of equal relative size.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

_TO: dict[str, Callable[[Any], Any]] = {"log": np.log, "logit": lambda p: np.log(p / (1 - p)), "": lambda x: x}
_FROM: dict[str, Callable[[Any], Any]] = {"log": np.exp, "logit": lambda y: 1.0 / (1.0 + np.exp(-y)), "": lambda y: y}
# d(parameter) / d(coordinate), at the parameter's value
SLOPE: dict[str, Callable[[Any], Any]] = {"log": lambda x: x, "logit": lambda p: p * (1 - p), "": lambda x: 1.0}


def theta_of(law) -> np.ndarray:
    """The fit's coordinates of ``law`` (its class's ``COORDINATES``)."""
    return np.array([_TO[c](getattr(law, p)) for p, c in zip(law.PARAMETERS, law.COORDINATES,
                                                             strict=True)], dtype=float)


def law_of(theta, cls):
    """The law of class ``cls`` at coordinates ``theta``."""
    return cls(*(float(_FROM[c](x)) for c, x in zip(cls.COORDINATES, theta, strict=True)))


def bounds(cls, limits: dict[str, tuple[float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """The plausible ranges ``limits`` (by parameter name, SI) of ``cls``'s parameters, in
    its coordinates: (lower, upper)."""
    lo = [_TO[c](limits[p][0]) for p, c in zip(cls.PARAMETERS, cls.COORDINATES, strict=True)]
    hi = [_TO[c](limits[p][1]) for p, c in zip(cls.PARAMETERS, cls.COORDINATES, strict=True)]
    return np.array(lo, dtype=float), np.array(hi, dtype=float)
