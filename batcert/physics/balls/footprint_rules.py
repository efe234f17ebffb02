"""How the ball's footprint departs from Hertz's at large compression: a registry of rules.

:mod:`batcert.physics.balls.footprint` computes Hertz's elliptical footprint of the ball on a
barrel and the barrel's stiffness factor (the force on the barrel over that on a flat at the
same compression). Hertz's theory is the small-compression limit; a rule here multiplies its
semi-axes and its stiffness factor by factors of the compression over the ball's radius
``x = u / R_b`` and of the ball-to-barrel radius ratio ``rho = R_b / R_c`` (0 on a flat):

* ``hertz``: the factors are 1 (Hertz's rule, batcert 0.2's; old results are reproduced with it);
* ``fe-finite-strain`` (the engine's default): the factors of the independent 3-D finite-element
  sphere at finite strain (``scripts/fe_ball_contact_finite.py``: a compressible neo-Hookean
  sphere of the ball's radius, small-strain Poisson's ratio 0.30, frictionless contact on the
  deformed positions, recorded in ``tests/validation/data/fe_ball_contact.json`` under
  ``finite_strain``), fitted as ``f = 1 + c1 sqrt(x) + c2 x`` by least squares over its
  compressions ``x`` = 0.01-0.40 for each counterface (a flat, the 2 5/8 in and 2 1/4 in
  barrels); between them the coefficients are interpolated linearly in ``rho`` and held
  beyond the 2 1/4 in barrel; beyond ``x`` = 0.40 the factors are held at their value there.
  Each factor is 1 at ``x = 0``, so the rule is Hertz's in the small-compression limit.

The fit's residuals against the FE and the FE's own limits (a homogeneous elastic sphere, not a
wound core in a cover; no rate effects) are in docs/validation.md, "The ball's footprint".
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

# ``fe-finite-strain``: rho = R_b / R_c of the FE's counterfaces (36.9 mm ball; a flat,
# 33.3375 mm and 28.575 mm barrels) and, at each, (c1, c2) of f = 1 + c1 sqrt(x) + c2 x for
# the footprint along the bat (a), around it (b) and the barrel's stiffness factor (stiffness;
# 0 on the flat by definition). Source: scripts/fe_ball_contact_finite.py --record, the
# "fit" entry of fe_ball_contact.json's "finite_strain" (nu = 0.30, mesh Q3);
# tests/validation/test_footprint_against_fe.py checks these numbers against it.
FE_RHO = (0.0, 36.9 / 33.3375, 36.9 / 28.575)
FE_FIT = {
    "a": ((0.194406, 0.209687), (0.163672, 0.0693614), (0.157356, 0.0642583)),
    "b": ((0.194406, 0.209687), (0.0917604, 0.45438), (0.0934, 0.441589)),
    "stiffness": ((0, 0), (-0.0394546, -0.395215), (-0.0430846, -0.433536)),
}
FE_X_MAX = 0.40  # the largest compression over the ball's radius of the FE [-]


@dataclass(frozen=True)
class FootprintRule:
    """One footprint rule: its name (the engine's ``footprint`` setting), a display word, a line
    of documentation, and its factors on Hertz's semi-axes (``size``: ``(f_a, f_b)``) and on
    Hertz's stiffness factor (``stiffness``), functions of ``x = u / R_b`` and ``rho = R_b /
    R_c`` (arrays broadcasting together) [-]."""

    name: str
    title: str
    doc: str
    size: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]
    stiffness: Callable[[np.ndarray, np.ndarray], np.ndarray]


def _ones(x, rho) -> np.ndarray:
    return np.ones(np.broadcast(np.asarray(x, dtype=float), np.asarray(rho, dtype=float)).shape)


def _fe_factor(kind: str, x, rho) -> np.ndarray:
    """``1 + c1 sqrt(x) + c2 x`` with the FE fit's coefficients at ``rho`` (module notes)."""
    x = np.clip(np.asarray(x, dtype=float), 0.0, FE_X_MAX)
    rho = np.asarray(rho, dtype=float)
    c1 = np.interp(rho, FE_RHO, [c[0] for c in FE_FIT[kind]])
    c2 = np.interp(rho, FE_RHO, [c[1] for c in FE_FIT[kind]])
    return 1.0 + c1 * np.sqrt(x) + c2 * x


RULES: dict[str, FootprintRule] = {
    "hertz": FootprintRule(
        "hertz", "Hertz's footprint",
        "Hertz's elliptical contact at every compression (the small-compression limit; "
        "batcert 0.2's rule)",
        lambda x, rho: (_ones(x, rho), _ones(x, rho)), _ones),
    "fe-finite-strain": FootprintRule(
        "fe-finite-strain", "Hertz's footprint corrected by the finite-strain FE sphere",
        "Hertz's ellipse and barrel factor times the factors of a 3-D finite-strain "
        "(neo-Hookean) sphere, fitted over u / R_b = 0.01-0.40 (docs/validation.md)",
        lambda x, rho: (_fe_factor("a", x, rho), _fe_factor("b", x, rho)),
        lambda x, rho: _fe_factor("stiffness", x, rho)),
}
DEFAULT_RULE = "fe-finite-strain"


def rule(name: str) -> FootprintRule:
    """The rule called ``name`` (:data:`RULES`); ValueError naming the known ones if none."""
    try:
        return RULES[name]
    except KeyError:
        raise ValueError(f"footprint must be one of {tuple(RULES)}, got {name!r}") from None
