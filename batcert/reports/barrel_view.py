"""A run's barrel tests, formatted: the barrel compression test and the accelerated break-in
with its compression history and the result before and after it."""

from __future__ import annotations

from typing import Any

from batcert.reports import format as fmt
from batcert.reports.table import Table
from batcert.results.run import BreakInResult, RunResult


def compression_table(result: RunResult) -> Table | None:
    """The compression test's conventions and the force it reads (None without one)."""
    c = result.compression
    if c is None:
        return None
    rows: list[list[Any]] = [["Platens' centre from the tip", fmt.quantity(c.position, "length")],
            ["Platen width along the bat", fmt.quantity(c.platen_width, "length")],
            ["Approach of the platens", fmt.quantity(c.deflection, "length", 6)],
            ["Force on one platen (model)", fmt.quantity(c.force, "force", 0)],
            ["Stiffness (force per approach)", f"{c.stiffness / 1e3:.4g} N/mm"]]
    if c.min is not None:
        rows += [["Smallest passing force", fmt.quantity(c.min, "force", 0)],
                 ["Verdict", f"{(c.verdict or '').upper()} (margin {c.margin:+.4g} N)"]]
    if c.source:
        rows.append(["Conventions", c.source])
    return Table(["Item", "Value"], rows)


def break_in_view(result: RunResult) -> dict[str, Any] | None:
    """The break-in's outcome, the metric before and after it, and its compression history
    (None without a break-in)."""
    b = result.break_in
    if b is None:
        return None
    history = history_table(b)
    name = fmt.metric_name(result.metric)
    compare = None
    if b.value_before is not None:
        compare = Table(["", name, "Verdict"], [
            ["Before break-in", fmt.metric_value(b.value_before, result.metric),
             (b.verdict_before or fmt.DASH).upper()],
            ["After break-in", fmt.metric_value(result.value, result.metric),
             (result.verdict or fmt.DASH).upper()]])
    basis = ("measured readings" if b.measured else
             f"emulated: each rolling pass adds {100 * b.damage_per_pass:g} % damage (assumed)")
    return {"outcome": b.outcome, "basis": basis, "history": history, "compare": compare,
            "source": b.source}


def history_table(b: BreakInResult) -> Table:
    """A break-in's compression readings, pass by pass (a long history shortened)."""
    head = ["Passes", "Damage (E2, G12 lost)", "Compression", "Drop from initial"]
    if b.measured:
        head.pop(1)
    rows = []
    for s in _shown(b.steps):
        row = [str(s.passes), fmt.DASH if s.damage is None else f"{100 * s.damage:.1f} %",
               fmt.quantity(s.force, "force", 0), f"{100 * s.drop:.2f} %"]
        if b.measured:
            row.pop(1)
        rows.append(row)
    return Table(head, rows, numeric=[True] * len(head))


def _shown(steps: list) -> list:
    """Every reading of a short history; of a long one the first three, every tenth and the
    last three."""
    if len(steps) <= 15:
        return steps
    keep = {0, 1, 2, len(steps) - 3, len(steps) - 2, len(steps) - 1}
    keep |= set(range(0, len(steps), 10))
    return [s for i, s in enumerate(steps) if i in keep]
