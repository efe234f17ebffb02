"""The work a ball fit (:mod:`batcert.physics.balls.fit`) may do: a count of test evaluations
(one test's impact integrated, or its compression computed, for one law), so that a fit to many
tests that contradict one another ends, whatever the machine's speed, instead of refitting for
minutes. Counted, not timed: the same file stops at the same point on every machine."""

from __future__ import annotations

# test evaluations a fit may make, its search for a test at fault included: the shipped balls'
# fits take about a thousand, a refused fit of the collegiate ball's seven tests about fifteen
# thousand (its leave-one-out refits); 40 contradictory tests took 530,000 (five minutes)
MAX_EVALUATIONS = 60_000


class Exhausted(Exception):
    """The fit's budget is spent (not a ValueError: the least-squares solver must not take it
    for a failed start)."""


class Budget:
    """Test evaluations a fit may still make (:data:`MAX_EVALUATIONS` unless given)."""

    def __init__(self, limit: int | None = None) -> None:
        self.limit = MAX_EVALUATIONS if limit is None else int(limit)
        if self.limit < 1:
            raise ValueError(f"a fit's budget is at least one test evaluation, got {limit!r}")
        self.used = 0

    def spend(self, n: int) -> None:
        """Count ``n`` evaluations about to be made; :class:`Exhausted` when they would pass
        the limit."""
        if self.used + n > self.limit:
            raise Exhausted(f"{self.used + n} test evaluations asked, {self.limit} allowed")
        self.used += n
