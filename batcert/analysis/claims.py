"""Findings and claim checks of a bat comparison: what the numbers show, in words.

:func:`findings` states per protocol the mean, spread and sign pattern of the relative
performance P, and what the engine cannot show. :func:`evaluate_claim` tests one claim of a
study file with the check registered for it in :data:`CHECKS`, keyed by the names of
:data:`batcert.specs.kinds.CLAIM_CHECKS` (their meanings, which the study schema reads). A check
returns ``supported``, ``not-supported`` or ``not-testable`` (e.g. the sweet spot lies on the
search window's edge) with the evidence; nothing is ever assumed supported.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from batcert.reports.format import percent
from batcert.results.compare import ClaimResult, ComparisonResult

if TYPE_CHECKING:
    from batcert.specs.study import ClaimSpec


def _sign(p: float, tol: float) -> int:
    return 1 if p > tol else -1 if p < -tol else 0


def findings(result: ComparisonResult, tol: float = 0.005) -> list[str]:
    """Plain statements of what the numbers show, per protocol and across protocols."""
    out = []
    ref = result.reference
    signs: dict[str, set[int]] = {lab: set() for lab in result.compared}
    for p in result.protocols:
        for lab in result.compared:
            s = p.relative_spread[lab]
            if s.mean is None:
                out.append(f"{p.protocol}: P of {lab} against {ref} is undefined (a reference "
                           "value is zero).")
                continue
            ps = [c.bats[lab].relative for c in p.conditions]
            kinds = {_sign(v, tol) for v in ps if v is not None}
            signs[lab] |= kinds
            if kinds == {0}:
                shape = f"no difference beyond ±{tol * 100:g} % in any condition"
            elif len(kinds - {0}) == 2:
                shape = "the sign changes between conditions"
            elif 0 in kinds:
                shape = f"some conditions show no difference beyond ±{tol * 100:g} %"
            else:
                shape = "the same sign in every condition"
            spread = (f"; std {(s.std or 0.0) * 100:.2f} %, range {percent(s.min)} to "
                      f"{percent(s.max)} over {len(ps)} conditions" if len(ps) > 1 else "")
            out.append(f"{p.protocol} ({p.metric}, {p.impact_rule}): P of {lab} against {ref} "
                       f"has mean {percent(s.mean)}{spread}: {shape}.")
    for lab, kinds in signs.items():
        if {1, -1} <= kinds:
            out.append(f"Across the protocols and conditions, P of {lab} takes both signs: the "
                       "methods disagree on which bat performs better.")
        elif kinds == {0}:
            out.append(f"No protocol separates {lab} from {ref} by more than ±{tol * 100:g} %.")
    edges = [b for p in result.protocols for c in p.conditions for b in c.bats.values()]
    n_edge = sum(b.sweet_spot_at_edge for b in edges)
    if n_edge:
        out.append(f"In {n_edge} of {len(edges)} bat-conditions the exit-speed maximum lies on "
                   "the search window's edge: the sweet spot there is not located, and protocols "
                   "that strike the sweet spot strike the window's edge instead.")
    if result.engine == "rigid":
        out.append("Engine: rigid. The ball-bat COR is the ball's own COR at the relative speed, "
                   "so BPF stays close to 1 for every bat (it moves only with the ball's lower loss "
                   "when it compresses less against a recoiling bat) and P under a BPF protocol "
                   "is small, and "
                   "the sweet spot follows the rigid formula (Eq. 7). Differences between bats "
                   "come from mass properties only (MOI, CG); barrel flexing (the trampoline "
                   "effect) and vibration losses are not modelled by this engine, so a claim "
                   "that a hollow bat's advantage is shown cannot be supported, and one that it "
                   "is hidden is supported only trivially.")
    return out


def _entries(result: ComparisonResult, pids: Sequence[str], labels: Sequence[str] | None = None):
    labels = result.compared if labels is None else labels
    for pid in pids:
        p = result.protocol(pid)
        for c in p.conditions:
            for lab in labels:
                yield p, c, lab, c.bats[lab]


def _defined(values: Sequence[float | None]) -> list[float] | None:
    """The values, or None when any is undefined."""
    out = [v for v in values if v is not None]
    return out if len(out) == len(values) else None


def _check_sign_disagreement(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    tol = claim.tolerance
    vals = [(b.relative, f"{lab}, {p.protocol}/{c.name}")
            for p, c, lab, b in _entries(result, claim.protocols)]
    if any(v is None for v, _ in vals):
        return "not-testable", "P is undefined in at least one condition."
    lo, hi = min(vals, key=lambda t: t[0]), max(vals, key=lambda t: t[0])
    n_pos = sum(v > tol for v, _ in vals)
    n_neg = sum(v < -tol for v, _ in vals)
    text = (f"P ranges from {percent(lo[0])} ({lo[1]}) to {percent(hi[0])} ({hi[1]}); {n_pos} of "
            f"{len(vals)} values above +{tol * 100:g} %, {n_neg} below -{tol * 100:g} %.")
    return ("supported" if n_pos and n_neg else "not-supported"), text


def _check_consistent(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    tol, ok, parts = claim.tolerance, True, []
    yard = None
    if claim.compare_with:
        ys = _defined([b.relative for _, _, _, b in _entries(result, claim.compare_with)])
        if ys is None:
            return "not-testable", "P is undefined in a yardstick protocol."
        yard = max(ys) - min(ys)
    for pid in claim.protocols:
        p = result.protocol(pid)
        for lab in result.compared:
            ps = _defined([c.bats[lab].relative for c in p.conditions])
            if ps is None:
                return "not-testable", f"P is undefined in {pid}."
            kinds = {_sign(v, tol) for v in ps}
            rng = max(ps) - min(ps)
            same = len(kinds) == 1 and 0 not in kinds
            smaller = yard is None or rng < yard
            ok &= same and smaller
            parts.append(f"{pid}, {lab}: P from {percent(min(ps))} to {percent(max(ps))} (range "
                         f"{rng * 100:.2f} %), "
                         + ("one sign throughout" if same else
                            f"not one sign beyond ±{tol * 100:g} %"))
    text = "; ".join(parts) + "."
    if yard is not None:
        text += (f" Range over {', '.join(claim.compare_with or [])}: {yard * 100:.2f} %.")
    return ("supported" if ok else "not-supported"), text


def _check_advantage(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    tol, shown, parts = claim.tolerance, [], []
    for pid in claim.protocols:
        for lab in result.compared:
            m = result.protocol(pid).relative_spread[lab].mean
            if m is None:
                return "not-testable", f"P is undefined in {pid}."
            shown.append(m > tol)
            parts.append(f"{pid}: mean P of {lab} {percent(m)}")
    ok = all(shown) if claim.expected == "shown" else not any(shown)
    return ("supported" if ok else "not-supported"), "; ".join(parts) + "."


def _check_lower_than(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    low, high = claim.protocols
    tol, ok, parts = claim.tolerance, True, []
    for lab in result.compared:
        a = result.protocol(low).relative_spread[lab].mean
        b = result.protocol(high).relative_spread[lab].mean
        if a is None or b is None:
            return "not-testable", "P is undefined."
        ok &= a < b - tol
        moi = result.protocol(low).mass
        parts.append(f"{lab} (MOI {moi[lab].moi_pivot:.4f} kg m², reference "
                     f"{moi[result.reference].moi_pivot:.4f}): mean P {percent(a)} under {low}, "
                     f"{percent(b)} under {high}")
    return ("supported" if ok else "not-supported"), "; ".join(parts) + "."


def _located(result: ComparisonResult, claim: ClaimSpec, labels: Sequence[str]):
    entries = list(_entries(result, claim.protocols, labels))
    good = [e for e in entries if not e[3].sweet_spot_at_edge]
    note = (f" {len(entries) - len(good)} of {len(entries)} bat-conditions left out: their "
            "sweet spot lies on the search window's edge (the true maximum is outside it)."
            if len(good) < len(entries) else "")
    return good, note


def _check_cop_not_sweet(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    tol = claim.location_tolerance
    good, note = _located(result, claim, [b.label for b in result.bats])
    if not good:
        return "not-testable", "No sweet spot was located inside the search window." + note
    offsets = [e[3].sweet_spot_minus_cop for e in good]
    far = sum(abs(o) > tol for o in offsets)
    text = (f"Sweet spot minus COP from {min(offsets) * 100:+.1f} to {max(offsets) * 100:+.1f} cm; "
            f"{far} of {len(offsets)} beyond ±{tol * 100:g} cm.{note}")
    return ("supported" if far == len(offsets) else "not-supported"), text


def _check_offset_differs(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    tol = claim.location_tolerance
    good, note = _located(result, claim, [b.label for b in result.bats])
    means = {}
    for lab in [b.label for b in result.bats]:
        o = [e[3].sweet_spot_minus_cop for e in good if e[2] == lab]
        if not o:
            return "not-testable", f"No located sweet spot for {lab}." + note
        means[lab] = sum(o) / len(o)
    ref = means[result.reference]
    ok = all(abs(means[lab] - ref) > tol for lab in result.compared)
    text = "; ".join(f"{lab}: mean offset {m * 100:+.1f} cm" for lab, m in means.items()) + "."
    return ("supported" if ok else "not-supported"), text + note


def _movements(pts: Sequence[tuple[float, float]]) -> tuple[float, float]:
    """How far the sweet spot and Eq. 7's rigid sweet spot move over (model, rigid) pairs."""
    model = max(s for s, _ in pts) - min(s for s, _ in pts)
    rigid = max(r for _, r in pts) - min(r for _, r in pts)
    return model, rigid


def _check_sweet_spot_moves(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    parts, ok, tested = [], True, 0
    for pid in claim.protocols:
        p = result.protocol(pid)
        for b in result.bats:
            pts: list[tuple[float, float]] = []
            for c in p.conditions:
                bc = c.bats[b.label]
                if bc.rigid_sweet_spot is not None and not bc.sweet_spot_at_edge:
                    pts.append((bc.sweet_spot, bc.rigid_sweet_spot))
            if len(pts) < 2:
                continue
            tested += 1
            model, rigid = _movements(pts)
            ok &= model <= claim.factor * rigid
            parts.append(f"{pid}, {b.label}: sweet spot moves {model * 100:.1f} cm, Eq. 7 "
                         f"{rigid * 100:.1f} cm")
    if not tested:
        return "not-testable", ("Fewer than two fixed-speed conditions with a sweet spot located "
                                "inside the search window (Eq. 7 needs w1 > 0).")
    return ("supported" if ok else "not-supported"), "; ".join(parts) + "."


def _figure(result: ComparisonResult, claim: ClaimSpec):
    return next((f for f in result.figures if f.id == claim.figure), None)


def _not_computed(claim: ClaimSpec) -> str:
    return (f"The study figure {claim.figure!r} was not computed in this comparison: a study's "
            "figures are computed when asked for (batcert compare --study-figures or --figures "
            "DIR; figures=True in the library).")


def _trend(values: list[float | None], xs: list[float], nominal: float | None) -> float | None:
    """Change of a quantity from the nominal value of the parameter down to its smallest value
    (the thin-wall side): value at the smallest x minus value at the x nearest nominal."""
    pts = [(x, v) for x, v in zip(xs, values, strict=True) if v is not None]
    if len(pts) < 2 or nominal is None:
        return None
    low = min(pts)
    near = min(pts, key=lambda t: abs(t[0] - nominal))
    return None if low[0] >= near[0] else low[1] - near[1]


def _check_opposite_trends(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    fig = _figure(result, claim)
    if fig is None:
        return "not-testable", _not_computed(claim)
    a, b = claim.metrics or ["", ""]
    parts, ok, tested = [], True, 0
    for bat in fig.bats:
        da = _trend(bat.series[a], bat.values, bat.nominal)
        db = _trend(bat.series[b], bat.values, bat.nominal)
        if da is None or db is None:
            continue
        tested += 1
        ok &= (da > claim.tolerance and db < -claim.tolerance) or \
            (da < -claim.tolerance and db > claim.tolerance)
        parts.append(f"{bat.label}: from the nominal {fig.parameter} to the thinnest, {a} "
                     f"changes by {da:+.4f} and {b} by {db:+.4f}")
    if not tested:
        return "not-testable", f"The figure has no values below the nominal {fig.parameter}."
    return ("supported" if ok else "not-supported"), "; ".join(parts) + "."


def _check_figure_sweet_spot(result: ComparisonResult, claim: ClaimSpec) -> tuple[str, str]:
    fig = _figure(result, claim)
    if fig is None:
        return "not-testable", _not_computed(claim)
    parts, ok, tested = [], True, 0
    for bat in fig.bats:
        spots = bat.series.get("sweet_spot", [])
        edges = bat.series.get("at_window_edge") or [False] * len(spots)
        pts = [(s, r) for s, r, edge in zip(spots, bat.series.get("rigid_sweet_spot", []),
                                            edges, strict=True)
               if s is not None and r is not None and not edge]
        if len(pts) < 2:
            continue
        tested += 1
        model, rigid = _movements(pts)
        ok &= model <= claim.factor * rigid
        parts.append(f"{bat.label}: over {len(pts)} speeds where Eq. 7 is defined and the sweet "
                     f"spot lies inside the search window, the sweet spot moves "
                     f"{model * 100:.1f} cm, Eq. 7 {rigid * 100:.1f} cm")
    if not tested:
        return "not-testable", ("The figure has fewer than two speeds where Eq. 7 is defined and "
                                "the sweet spot lies inside the search window.")
    return ("supported" if ok else "not-supported"), "; ".join(parts) + "."


# how each claim check (:data:`batcert.specs.kinds.CLAIM_CHECKS`: its name and meaning) tests a
# comparison: (status, evidence)
CHECKS: dict[str, Callable[[ComparisonResult, ClaimSpec], tuple[str, str]]] = {
    "sign-disagreement": _check_sign_disagreement,
    "consistent-across-conditions": _check_consistent,
    "advantage": _check_advantage,
    "lower-than": _check_lower_than,
    "cop-not-sweet-spot": _check_cop_not_sweet,
    "cop-offset-differs": _check_offset_differs,
    "sweet-spot-moves-less-than-rigid": _check_sweet_spot_moves,
    "opposite-trends": _check_opposite_trends,
    "figure-sweet-spot-less-than-rigid": _check_figure_sweet_spot,
}


def evaluate_claim(result: ComparisonResult, claim: ClaimSpec) -> ClaimResult:
    """Test one study claim against the comparison; the status never defaults to supported."""
    wanted = [*claim.protocols, *(claim.compare_with or [])]
    if claim.figure is not None and _figure(result, claim) is None:
        status, text = "not-testable", _not_computed(claim)
        return ClaimResult(claim.id, claim.statement, claim.source or "", claim.check, status,
                           text)
    missing = [p for p in wanted if p not in {x.protocol for x in result.protocols}]
    if missing:
        status, text = "not-testable", f"Protocols not in this comparison: {', '.join(missing)}."
    else:
        status, text = CHECKS[claim.check](result, claim)
    return ClaimResult(claim.id, claim.statement, claim.source or "", claim.check, status, text)
