"""Inverse design: the value of one parameter at which a protocol's metric meets its limit.

The margin (limit + tolerance - value) is first swept over the range (the margin curve, a
:mod:`~batcert.sweeps.sweep` of ``points`` variants); every sign change between neighbours
brackets a root, which Brent's method (:func:`batcert.numerics.brent_root`) then locates on the engine
to within the parameter's tolerance. The margin need not be monotonic: every root in the range
is found, between points of the curve, and the passing intervals are stated. A root between two
points of the curve that both pass (or both fail) is missed, so the curve should be fine enough
for the margin's shape; the report shows it.
"""

from __future__ import annotations

from batcert.numerics import brent_root
from batcert.results.sweep import DesignResult, DesignRoot, SweepResult
from batcert.sweeps.sweep import Chunk, Plan, evaluate_chunk
from batcert.sweeps.variants import ParameterError


def margin_at(plan: Plan, value: float) -> float:
    """The margin of one variant (the engine solves it now)."""
    return float(_row_at(plan, value)["margin"])


def _row_at(plan: Plan, value: float) -> dict:
    chunk = Chunk(0, plan.base, plan.built, plan.ball, plan.engine, (plan.axes[0].name,),
                  ((0, (value,)),), plan.created)
    row = evaluate_chunk(chunk)[0]
    if row["error"] is not None:
        raise ParameterError(f"{plan.axes[0].name} = {value:.6g}: the model has no result "
                             f"({row['error']})")
    return row


ROUNDING = 1e-12  # a margin this close to zero is taken as zero (it passes): rounding, not a root


def _passes(margin: float) -> bool:
    return margin >= -ROUNDING


def solve(plan: Plan, curve: SweepResult, tolerance: float) -> DesignResult:
    """Every root of the margin in the range of ``curve`` (the margin swept over ``plan``'s
    axis), located to ``tolerance`` [SI]."""
    if curve.limit is None:
        raise ParameterError(f"protocol {curve.protocol!r} sets no limit: there is nothing to "
                             "design to")
    xs = [p[0] for p in curve.points]
    ms = curve.series["margin"]
    roots = []
    for (x0, m0), (x1, m1) in zip(zip(xs, ms, strict=True), zip(xs[1:], ms[1:], strict=True),
                                  strict=False):
        if m0 is None or m1 is None or _passes(m0) == _passes(m1):
            continue
        found = brent_root(lambda x: margin_at(plan, x), x0, x1, xtol=tolerance, rtol=1e-12,
                           maxiter=100)
        root = found.x
        at = _row_at(plan, root)  # the bat there: its mass and length (the drop)
        roots.append(DesignRoot(root, [x0, x1], found.calls, passes_above=_passes(m1),
                                mass=at.get("mass"), length=at.get("length")))
    return DesignResult(plan.axes[0].name, tolerance, roots, [xs[0], xs[-1]])
