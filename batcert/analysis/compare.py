"""Side-by-side comparison of bats under several protocols (pure: results in, results out).

:func:`compare` takes the :class:`~batcert.results.run.RunResult` of every bat under every
protocol and returns a :class:`~batcert.results.compare.ComparisonResult`: per protocol and
condition the metric of each bat and its relative performance against the reference bat,
P = (P_bat - P_ref) / P_ref (Smith 2001, Eq. 6), the mean and spread of P across conditions, the
centre of percussion against the sweet spot, and the study's claims tested against these numbers
(:mod:`batcert.analysis.claims`). It computes no physics.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict
from typing import TYPE_CHECKING

from batcert.analysis.claims import evaluate_claim, findings
from batcert.results.compare import (
    BatCondition,
    BatEntry,
    BatMass,
    ComparisonResult,
    ConditionComparison,
    ProtocolComparison,
    Spread,
    StudyFigure,
)
from batcert.results.run import RunResult
from batcert.results.serialise import utc_now
from batcert.version import __version__

if TYPE_CHECKING:
    from batcert.specs.study import ClaimSpec


def relative_performance(value: float, reference: float) -> float | None:
    """P = (P_a - P_w) / P_w of bat a over the reference bat w [-] (Smith 2001, Eq. 6).

    None when the reference value is zero or either value is not finite (P undefined).
    """
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0:
        return None
    return (value - reference) / reference


# ---------------------------------------------------------------- building the comparison


def bat_labels(names: Sequence[str], paths: Sequence[str]) -> list[str]:
    """Unique labels: the bat's name, with its file name added where two names coincide."""
    out = []
    for i, (n, p) in enumerate(zip(names, paths, strict=True)):
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
        for lab, r in zip(labels, runs, strict=True):
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
        aggregate_value={lab: r.value for lab, r in zip(labels, runs, strict=True)},
        aggregate_relative={lab: relative_performance(r.value, runs[ref].value)
                            for lab, r in zip(labels, runs, strict=True)},
        relative_spread={lab: Spread.of(ps) for lab, ps in per_bat_p.items()},
        verdicts={lab: r.verdict for lab, r in zip(labels, runs, strict=True)},
        mass={lab: BatMass(r.mass_properties.mass, r.mass_properties.cg,
                           r.mass_properties.moi_pivot, r.mass_properties.cop)
              for lab, r in zip(labels, runs, strict=True)})


def compare(runs: Sequence[Sequence[RunResult]], reference: int = 0, *,
            bats: Sequence[BatEntry] | None = None, title: str = "", study: str | None = None,
            study_reference: str = "", study_notes: str = "", claims: Sequence[ClaimSpec] = (),
            created: str | None = None, figures: Sequence[StudyFigure] = ()) -> ComparisonResult:
    """Compare bats under protocols. ``runs[i][j]`` is bat ``i`` under protocol ``j``; every bat
    must have been run under the same protocols, in the same order, with one engine.

    ``reference`` is the index of the reference bat (default the first). ``claims`` are a study's
    claims (:class:`~batcert.specs.study.ClaimSpec`), each tested by its check.
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
                 for row, n in zip(runs, names, strict=True)]
        labels = bat_labels(names, paths)
        bats = [BatEntry(lab, row[0].bat, p, next((i.sha256 for i in row[0].inputs
                                                   if i.role == "bat"), ""),
                         row[0].mass_properties.length)
                for lab, row, p in zip(labels, runs, paths, strict=True)]
    labels = [b.label for b in bats]
    if len(set(labels)) != len(labels):
        raise ValueError("bat labels must be unique")
    protocols = [_protocol_comparison([row[j] for row in runs], labels, reference)
                 for j in range(n_proto)]
    inputs: dict[tuple[str, str], dict[str, str]] = {}
    raised: dict[str, list[str]] = {}  # warning text -> bats whose runs raised it
    for row, lab in zip(runs, labels, strict=True):
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
        created=created or utc_now())
    result.figures = list(figures)
    result.claims = [evaluate_claim(result, c) for c in claims]
    result.findings = findings(result)
    return result
