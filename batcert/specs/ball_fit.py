"""A ball file's tests as the fit takes them, the fit of a law to them and the check of a law
given whole against them, each refusal an input error at the test or the field at fault
(:mod:`batcert.specs.ball` reads the file)."""

from __future__ import annotations

from batcert.errors import InputError, Problem
from batcert.physics.balls import Viscoelastic
from batcert.physics.balls.fit import BallFit, BallTest, FitError, check_given
from batcert.physics.balls.fit_kept import cached_fit

# the file's test keys and the fit's test kinds (the same names)
_KIND = {"cor": "cor", "cylinder_cor": "cylinder_cor", "peak_force": "peak_force",
         "collision_time": "collision_time", "contact_time": "contact_time",
         "compression": "compression"}


def ball_tests(tests: tuple) -> tuple[BallTest, ...]:
    """The points as the fit takes them (each with its standard uncertainty)."""
    return tuple(BallTest(_KIND[key], p.condition, float(p.value), float(getattr(p.value, "u", 0)),
                          p.surface_diameter) for key, p in tests)


def judge_given(path, tests, mass: float, radius: float, law) -> None:
    """A law given whole is checked against the file's own tests (:func:`check_given`): one
    it misses by many standard uncertainties is an input error at that test."""
    try:
        check_given(law, ball_tests(tests), mass, radius)
    except FitError as exc:
        key, p = tests[exc.test]
        raise InputError([Problem(str(path), p.line, key, str(exc))]) from None


def fitted(path, data, tests, mass: float, radius: float, held=(),
            law: str = Viscoelastic.name) -> BallFit:
    """:func:`cached_fit` of the file's tests; its refusal as an input error at the test."""
    problems = []
    for key, p in tests:
        if not getattr(p.value, "u", 0) > 0:
            problems.append(Problem(str(path), p.line, key, "a fitted viscoelastic ball needs "
                                    "every test's standard uncertainty ('0.546 +/- 0.018')"))
    if problems:
        raise InputError(problems)
    try:
        return cached_fit(ball_tests(tests), mass, radius, held, law)
    except FitError as exc:
        if exc.test is not None:
            key, p = tests[exc.test]
            raise InputError([Problem(str(path), p.line, key, str(exc))]) from None
        if exc.parameter is not None:
            line = data["contact"].key_pos.get(exc.parameter, (data.line, None))[0]
            raise InputError([Problem(str(path), line, f"contact.{exc.parameter}",
                                      str(exc))]) from None
        line = data["contact"].key_pos.get("model", (data.line, None))[0]
        message = str(exc) if exc.converged else f"{exc} ({_lines_of(tests)})"
        raise InputError([Problem(str(path), line, "contact.model", message)]) from None


def _lines_of(tests) -> str:
    """Where the file's tests are, by key: ``cor at lines 6-9, collision_time at line 12``."""
    where: dict[str, list[int]] = {}
    for key, p in tests:
        where.setdefault(key, []).extend([p.line] if p.line else [])
    return ", ".join(f"{k} at line{'s' if min(v) < max(v) else ''} "
                     f"{'-'.join(str(x) for x in sorted({min(v), max(v)}))}" if v else k
                     for k, v in where.items())
