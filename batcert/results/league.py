"""Results of checking bats against a league's rules (SI units).

Built by :func:`batcert.analysis.league.evaluate_league`; reports only read them and a saved
league JSON re-renders through :meth:`LeagueResult.from_dict`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from batcert.results.serialise import Serialisable


@dataclass
class RuleResult:
    rule: str  # rule id
    title: str
    kind: str
    value: Any  # measured value (SI for lengths; drop as a plain number) or None
    limit: Any  # the rule's limit (SI), required construction, allowed materials, or text
    verdict: str  # pass | fail | not-applicable | not-modelled
    unit: str = ""  # unit of value and limit: m, kg, N, m/s, in - oz, or "" (dimensionless / text)
    tolerance: float = 0.0
    margin: float | None = None  # limit (+ tolerance) - value, positive passes
    protocol: str | None = None
    metric: str | None = None
    applies_to: str = "all"
    source: str = ""
    confidence: str = ""
    note: str = ""  # why not modelled / not applicable, and assumptions
    model_offset: str = ""  # a performance rule's: the model's known offset for its metric


@dataclass
class BatLeagueResult:
    bat: str
    path: str
    sha256: str
    facts: dict[str, Any]  # length, mass, drop, barrel_diameter, ... (SI)
    rules: list[RuleResult]
    warnings: list[str] = field(default_factory=list)

    @property
    def verdict(self) -> str:
        """fail if a rule fails; otherwise incomplete if a rule is not modelled; else pass."""
        verdicts = {r.verdict for r in self.rules}
        if "fail" in verdicts:
            return "fail"
        return "incomplete" if "not-modelled" in verdicts else "pass"


@dataclass(repr=False)
class LeagueResult(Serialisable):
    KIND = "league"
    SUMMARY = ("league", "bats", "engine")

    league: str
    title: str
    reference: str
    version: str
    description: str
    notes: str
    path: str
    sha256: str
    engine: str
    bats: list[BatLeagueResult]
    batcert_version: str
    created: str

    def return_code(self, allow_not_modelled: bool = False) -> int:
        """0 only when every bat passes every rule that applies to it (a rule not modelled
        passes only with ``allow_not_modelled``), else 1."""
        return 0 if self.passed(allow_not_modelled) else 1

    def passed(self, allow_not_modelled: bool = False) -> bool:
        ok = {"pass", "incomplete"} if allow_not_modelled else {"pass"}
        return all(b.verdict in ok for b in self.bats)

    def _document(self) -> dict[str, Any]:
        d = asdict(self)  # with each bat's verdict, a property, added
        for b, out in zip(self.bats, d["bats"], strict=True):
            out["verdict"] = b.verdict
        return d
