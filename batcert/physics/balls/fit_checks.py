"""What a ball fit (:mod:`batcert.physics.balls.fit`) refuses before it fits: too few tests for
the free parameters, no COR or no stiffness-bearing test, a test without its uncertainty, a held
fraction the fit's coordinates cannot take; and the error a refusal raises."""

from __future__ import annotations

from typing import Any

import numpy as np

COR_KINDS = ("cor", "cylinder_cor")  # what a livelier or deader lot moves
STIFFNESS_KINDS = ("peak_force", "collision_time", "contact_time", "compression")


class FitError(ValueError):
    """The tests cannot give a trustworthy law; ``test`` is the index of the test at fault
    (None when the fit as a whole is), so that the message can point at its line."""

    def __init__(self, message: str, test: int | None = None, converged: bool = True,
                 parameter: str | None = None) -> None:
        super().__init__(message)
        self.test = test
        self.converged = converged  # False: no law was found (within the fit's budget)
        self.parameter = parameter  # a held parameter at fault


def check_tests(tests: tuple[Any, ...], fixed: tuple[tuple[str, float], ...], cls: Any) -> None:
    """FitError when ``tests`` cannot hold the free parameters of ``cls`` (too few, no COR or
    no stiffness-bearing test, a test without its uncertainty), or a held fraction is not one
    the fit can move from (``relaxed_fraction`` 1: no loss, a COR of 1 at every speed)."""
    for name, x in fixed:
        if dict(zip(cls.PARAMETERS, cls.COORDINATES, strict=True)).get(name) == "logit" \
                and not 0.0 < x < 1.0:
            raise FitError(f"{name} held at {x:g}: the fit needs it strictly between 0 and 1 "
                           "(a relaxed fraction of 1 is a ball that loses no energy, a COR of 1 "
                           "at every speed, which no COR test fits); omit it to have it fitted",
                           parameter=name)
    kinds = {t.kind for t in tests}
    n_free = len(cls.PARAMETERS) - len(fixed)
    if len(tests) < n_free:
        held = f" ({len(fixed)} held)" if fixed else ""
        raise FitError(f"the {cls.name} ball has {n_free} parameters to fit{held} and the "
                       f"file gives {len(tests)} ball tests: give at least {n_free} (COR at "
                       "several speeds and a contact time, peak force or compression), or "
                       "hold more of the law's parameters")
    if not kinds & set(COR_KINDS) or not kinds & set(STIFFNESS_KINDS):
        raise FitError("the viscoelastic ball needs the COR at two or more speeds and at least "
                       "one test that measures its stiffness (collision_time, contact_time, "
                       "peak_force or compression)")
    sigma = np.array([t.uncertainty for t in tests])
    if not np.all(sigma > 0):
        raise FitError("every ball test of a fit needs its standard uncertainty",
                       int(np.argmin(sigma > 0)))
