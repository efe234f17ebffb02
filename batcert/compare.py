"""Side-by-side comparison of bats under several protocols (pure: results in, results out).

:func:`compare` takes the :class:`~batcert.results.RunResult` of every bat under every protocol
and returns a :class:`ComparisonResult`: per protocol and condition the metric of each bat and its
relative performance against the reference bat, P = (P_bat - P_ref) / P_ref (Smith 2001, Eq. 6),
the mean and spread of P across conditions, the centre of percussion against the sweet spot, and
the study's claims tested against these numbers (checks registered in :data:`CLAIM_CHECKS`). It
computes no physics; reports only read the result, which round-trips through JSON.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, fields
from typing import Any

from batcert import __version__
from batcert.compare_claims import evaluate_claim, findings, percent
from batcert.results import RunResult

__all__ = ["BatCondition", "BatEntry", "BatMass", "ClaimResult", "ComparisonResult",
           "ConditionComparison", "ProtocolComparison", "Spread", "bat_labels", "compare",
           "evaluate_claim", "findings", "percent", "relative_performance"]


def relative_performance(value: float, reference: float) -> float | None:
    """P = (P_a - P_w) / P_w of bat a over the reference bat w [-] (Smith 2001, Eq. 6).

    None when the reference value is zero or either value is not finite (P undefined).
    """
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0:
        return None
    return (value - reference) / reference


@dataclass
class Spread:
    """Mean and spread of P across a protocol's conditions [-]; None when any P is undefined."""

    mean: float | None
    std: float | None  # population standard deviation (ddof = 0): the conditions are all of them
    min: float | None
    max: float | None
    range: float | None  # max - min

    @classmethod
    def of(cls, values: Sequence[float | None]) -> Spread:
        if not values or any(v is None for v in values):
            return cls(None, None, None, None, None)
        vals = [float(v) for v in values if v is not None]
        mean = sum(vals) / len(vals)
        std = math.sqrt(sum((v - mean) ** 2 for v in vals) / len(vals))
        return cls(mean, std, min(vals), max(vals), max(vals) - min(vals))


@dataclass
class BatCondition:
    """One bat in one condition of one protocol. Positions are from the protocol's pivot [m]."""

    value: float  # the protocol metric
    relative: float | None  # P against the reference bat, Eq. 6 [-]
    exit_speed: float  # [m/s]
    pitch_speed: float  # [m/s], negative toward the bat
    bat_angular_speed: float  # [rad/s]
    relative_speed: float  # at the impact location [m/s]
    impact_location: float  # [m from pivot]
    cop: float  # centre of percussion, Eq. 4 [m from pivot]
    sweet_spot: float  # maximum exit speed in the window [m from pivot]
    sweet_spot_minus_cop: float  # [m]
    sweet_spot_at_edge: bool  # the exit-speed maximum lies on the search window's edge
    rigid_sweet_spot: float | None  # Eq. 7 [m from pivot]; None when w1 = 0 or speeds matched


@dataclass
class ConditionComparison:
    name: str
    setup: str
    bats: dict[str, BatCondition]  # by bat label


@dataclass
class BatMass:
    """Mass properties of one bat about one protocol's pivot."""

    mass: float  # [kg]
    cg: float  # [m from pivot]
    moi_pivot: float  # [kg m^2]
    cop: float  # [m from pivot]


@dataclass
class ProtocolComparison:
    protocol: str
    title: str
    reference: str
    version: str
    metric: str
    impact_rule: str
    aggregate: str
    pivot: float  # [m from knob]
    ball: str
    limit: float | None
    conditions: list[ConditionComparison]
    aggregate_value: dict[str, float]  # the run's aggregated metric, by bat label
    aggregate_relative: dict[str, float | None]  # P of the aggregated values
    relative_spread: dict[str, Spread]  # P across conditions, by bat label
    verdicts: dict[str, str | None]
    mass: dict[str, BatMass]


@dataclass
class BatEntry:
    label: str  # unique key used in every per-bat mapping
    name: str
    path: str
    sha256: str
    length: float  # [m]
    construction: str | None = None
    material: str | None = None


@dataclass
class ClaimResult:
    id: str
    statement: str
    source: str
    check: str
    status: str  # supported | not-supported | not-testable
    evidence: str  # what the model's numbers show, in one or two sentences


@dataclass
class ComparisonResult:
    title: str
    study: str | None
    study_reference: str
    study_notes: str
    reference: str  # label of the reference bat
    bats: list[BatEntry]
    protocols: list[ProtocolComparison]
    claims: list[ClaimResult]
    findings: list[str]
    warnings: list[str]
    engine: str
    engine_settings: dict[str, Any]
    inputs: list[dict[str, str]]  # role, name, path, sha256 of every input file
    batcert_version: str
    created: str

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2, allow_nan=False)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ComparisonResult:
        kw = {f.name: data[f.name] for f in fields(cls)}
        kw["bats"] = [BatEntry(**b) for b in data["bats"]]
        kw["claims"] = [ClaimResult(**c) for c in data["claims"]]
        protos = []
        for p in data["protocols"]:
            p = dict(p)
            p["conditions"] = [ConditionComparison(c["name"], c["setup"], {
                k: BatCondition(**v) for k, v in c["bats"].items()}) for c in p["conditions"]]
            p["relative_spread"] = {k: Spread(**v) for k, v in p["relative_spread"].items()}
            p["mass"] = {k: BatMass(**v) for k, v in p["mass"].items()}
            protos.append(ProtocolComparison(**p))
        kw["protocols"] = protos
        return cls(**kw)

    def protocol(self, pid: str) -> ProtocolComparison:
        return next(p for p in self.protocols if p.protocol == pid)

    @property
    def compared(self) -> list[str]:
        """Labels of the bats compared with the reference."""
        return [b.label for b in self.bats if b.label != self.reference]


# ---------------------------------------------------------------- building the comparison


def bat_labels(names: Sequence[str], paths: Sequence[str]) -> list[str]:
    """Unique labels: the bat's name, with its file name added where two names coincide."""
    out = []
    for i, (n, p) in enumerate(zip(names, paths)):
        label = n if list(names).count(n) == 1 else f"{n} [{p.rsplit('/', 1)[-1]}]"
        while label in out:
            label = f"{label} #{i + 1}"
        out.append(label)
    return out


def _sweet_spot_at_edge(c) -> bool:
    speeds = c.sweep.exit_speed
    if not speeds:
        return c.at_window_edge
    i = max(range(len(speeds)), key=lambda k: speeds[k])
    return i in (0, len(speeds) - 1)


def _protocol_comparison(runs: list[RunResult], labels: list[str], ref: int
                         ) -> ProtocolComparison:
    first = runs[0]
    names = [c.name for c in first.conditions]
    for r in runs[1:]:
        if [c.name for c in r.conditions] != names or r.protocol != first.protocol:
            raise ValueError(f"runs of protocol {first.protocol!r} differ in their conditions")
    conds = []
    per_bat_p: dict[str, list[float | None]] = {lab: [] for lab in labels}
    for k, name in enumerate(names):
        ref_value = runs[ref].conditions[k].metric_value
        bats = {}
        for lab, r in zip(labels, runs):
            c = r.conditions[k]
            p = relative_performance(c.metric_value, ref_value)
            per_bat_p[lab].append(p)
            bats[lab] = BatCondition(
                value=c.metric_value, relative=p, exit_speed=c.exit_speed,
                pitch_speed=c.pitch_speed, bat_angular_speed=c.bat_angular_speed,
                relative_speed=c.relative_speed, impact_location=c.impact_location, cop=c.cop,
                sweet_spot=c.sweet_spot, sweet_spot_minus_cop=c.sweet_spot - c.cop,
                sweet_spot_at_edge=_sweet_spot_at_edge(c), rigid_sweet_spot=c.rigid_sweet_spot)
        conds.append(ConditionComparison(name, first.conditions[k].setup, bats))
    return ProtocolComparison(
        protocol=first.protocol, title=first.protocol_title, reference=first.protocol_reference,
        version=first.protocol_version, metric=first.metric, impact_rule=first.impact_rule,
        aggregate=first.aggregate, pivot=first.mass_properties.pivot, ball=first.ball,
        limit=first.limit, conditions=conds,
        aggregate_value={lab: r.value for lab, r in zip(labels, runs)},
        aggregate_relative={lab: relative_performance(r.value, runs[ref].value)
                            for lab, r in zip(labels, runs)},
        relative_spread={lab: Spread.of(ps) for lab, ps in per_bat_p.items()},
        verdicts={lab: r.verdict for lab, r in zip(labels, runs)},
        mass={lab: BatMass(r.mass_properties.mass, r.mass_properties.cg,
                           r.mass_properties.moi_pivot, r.mass_properties.cop)
              for lab, r in zip(labels, runs)})


def compare(runs: Sequence[Sequence[RunResult]], reference: int = 0, *,
            bats: Sequence[BatEntry] | None = None, title: str = "", study: str | None = None,
            study_reference: str = "", study_notes: str = "", claims: Sequence[dict] = (),
            created: str | None = None) -> ComparisonResult:
    """Compare bats under protocols. ``runs[i][j]`` is bat ``i`` under protocol ``j``; every bat
    must have been run under the same protocols, in the same order, with one engine.

    ``reference`` is the index of the reference bat (default the first). ``claims`` are a study's
    claim entries (see :mod:`batcert.specs.study`), each tested by its check.
    """
    if len(runs) < 2:
        raise ValueError("a comparison needs at least two bats")
    n_proto = len(runs[0])
    if n_proto == 0 or any(len(r) != n_proto for r in runs):
        raise ValueError("every bat needs a result under every protocol")
    if not 0 <= reference < len(runs):
        raise ValueError(f"reference index {reference} is not one of the {len(runs)} bats")
    for j in range(n_proto):
        ids = {r[j].protocol for r in runs}
        if len(ids) != 1:
            raise ValueError(f"protocol {j + 1} differs between bats: {', '.join(sorted(ids))}")
    engines = {r.engine for row in runs for r in row}
    if len(engines) != 1:
        raise ValueError(f"all runs must use one engine, got {', '.join(sorted(engines))}")
    if bats is None:
        names = [row[0].bat for row in runs]
        paths = [next((i.path for i in row[0].inputs if i.role == "bat"), n)
                 for row, n in zip(runs, names)]
        labels = bat_labels(names, paths)
        bats = [BatEntry(lab, row[0].bat, p, next((i.sha256 for i in row[0].inputs
                                                   if i.role == "bat"), ""),
                         row[0].mass_properties.length)
                for lab, row, p in zip(labels, runs, paths)]
    labels = [b.label for b in bats]
    if len(set(labels)) != len(labels):
        raise ValueError("bat labels must be unique")
    protocols = [_protocol_comparison([row[j] for row in runs], labels, reference)
                 for j in range(n_proto)]
    inputs: dict[tuple[str, str], dict[str, str]] = {}
    raised: dict[str, list[str]] = {}  # warning text -> bats whose runs raised it
    for row, lab in zip(runs, labels):
        for r in row:
            for i in r.inputs:
                inputs.setdefault((i.path, i.sha256), asdict(i))
            for w in r.warnings:
                raised.setdefault(f"{r.protocol}: {w}", []).append(lab)
    warnings = [f"{text} ({'all bats' if len(labs) == len(labels) else ', '.join(labs)})"
                for text, labs in raised.items()]
    first = runs[0][0]
    result = ComparisonResult(
        title=title or f"Comparison of {', '.join(labels)}", study=study,
        study_reference=study_reference, study_notes=study_notes, reference=labels[reference],
        bats=list(bats), protocols=protocols, claims=[], findings=[], warnings=warnings,
        engine=first.engine, engine_settings=first.engine_settings, inputs=list(inputs.values()),
        batcert_version=__version__,
        created=created or _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"))
    result.claims = [evaluate_claim(result, c) for c in claims]
    result.findings = findings(result)
    return result
