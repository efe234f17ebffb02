"""The league report: everything its Markdown and HTML show, formatted once."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from batcert.reports import format as fmt
from batcert.reports.compare_view import PREDICTED_BADGES, VERDICT_BADGES, badge
from batcert.reports.table import Badge, Table
from batcert.results.league import LeagueResult, RuleResult
from batcert.units import Display

VERDICT_WORDS = {"pass": "pass", "fail": "FAIL", "not-applicable": "not applicable",
                 "not-modelled": "NOT MODELLED"}


def predicted(rules: Sequence[RuleResult]) -> bool:
    """Whether a verdict over ``rules`` rests on the model: a performance rule (one that runs a
    protocol) was judged. Length, drop and barrel rules read the bat file's numbers."""
    return any(r.protocol and r.verdict in ("pass", "fail") for r in rules)


def rests_on_model(rules: Sequence[RuleResult], verdict: str | None) -> bool:
    """Whether a bat's ``verdict`` over ``rules`` is the model's: a FAIL is "predicted" only
    when every rule that fails is a performance rule (a bat too long fails outright); a PASS
    (or an incomplete verdict) when a performance rule was judged."""
    if verdict == "fail":
        failing = [r for r in rules if r.verdict == "fail"]
        return bool(failing) and all(r.protocol for r in failing)
    return predicted(rules)


def offsets(rules: Sequence[RuleResult]) -> list[str]:
    """The model's known offsets of the performance rules judged (each once, by metric)."""
    out: dict[str, str] = {}
    for r in rules:
        if r.protocol and r.verdict in ("pass", "fail") and r.model_offset:
            out.setdefault(r.metric or "", r.model_offset)
    return [f"{fmt.metric_word(m)}: {text}" for m, text in out.items()]


def _badge(verdict: str | None, by_model: bool) -> Badge:
    return badge(PREDICTED_BADGES if by_model else VERDICT_BADGES, verdict)


def overall(bats: Sequence[Any]) -> tuple[Badge, str]:
    """The headline badge and sentence (the worst bat verdict decides; "predicted" when a
    performance rule of any bat was judged by the model)."""
    counts = {v: sum(b.verdict == v for b in bats) for v in ("pass", "fail", "incomplete")}
    n = len(bats)
    worst = "fail" if counts["fail"] else "incomplete" if counts["incomplete"] else "pass"
    parts = [f"{counts['pass']} pass", f"{counts['fail']} fail"]
    if counts["incomplete"]:
        parts.append(f"{counts['incomplete']} incomplete (a rule is not modelled, none fails)")
    if n == 1:
        sentence = {"pass": "The bat passes every rule that applies to it.",
                    "fail": "The bat fails at least one rule.",
                    "incomplete": "The bat fails no rule, but at least one rule is not "
                                  "modelled, so it is not shown to pass."}[worst]
    else:
        sentence = f"Of {n} bats, " + ", ".join(parts) + "."
    by_model = any(rests_on_model(b.rules, b.verdict) for b in bats if b.verdict == worst)
    if any(predicted(b.rules) for b in bats):
        sentence += (" Performance rules are the model's prediction from the bat file, not a "
                     "measurement.")
    return _badge(worst, by_model), sentence


def rule_row(r: RuleResult) -> dict[str, Any]:
    """One rule's cells: value, limit and margin formatted in the rule's unit."""
    judged = r.verdict in ("pass", "fail")
    return {"id": r.rule, "title": r.title, "applies_to": r.applies_to, "kind": r.kind,
            "protocol": r.protocol, "value": fmt.rule_value(r.value, r.unit),
            "limit": fmt.rule_limit(r.limit, r.unit, r.tolerance),
            "badge": _badge(r.verdict, predicted([r])), "verdict": r.verdict,
            "verdict_text": VERDICT_WORDS.get(r.verdict, r.verdict),
            "margin": fmt.rule_margin(r.margin if judged else None, r.unit),
            "source": r.source, "confidence": r.confidence, "note": r.note}


def brief_rows(result: LeagueResult) -> list[tuple[str, Badge, str]]:
    """One row per bat for the terminal's summary (issue 40): its short name (the bat file's
    name, or the bat's when two files share one), its verdict, and in a few words why: the rules
    it fails, else those not modelled."""
    from pathlib import PurePosixPath
    stems = [PurePosixPath(b.path.replace("\\", "/")).stem for b in result.bats]
    rows = []
    for b, stem in zip(result.bats, stems, strict=True):
        failed = [r.rule for r in b.rules if r.verdict == "fail"]
        open_ = [r.rule for r in b.rules if r.verdict == "not-modelled"]
        why = (", ".join(failed) if failed
               else "not modelled: " + ", ".join(open_) if open_ else fmt.DASH)
        rows.append((stem if stem and stems.count(stem) == 1 else b.bat,
                     _badge(b.verdict, rests_on_model(b.rules, b.verdict)), why))
    return rows


def league_view(result: LeagueResult) -> dict[str, Any]:
    """Everything the league report shows, formatted; the templates only arrange it."""
    head_badge, sentence = overall(result.bats)
    verdicts = ("pass", "fail", "not-modelled", "not-applicable")
    summary: list[dict[str, Any]] = []
    bats: list[dict[str, Any]] = []
    for i, b in enumerate(result.bats):
        anchor = f"bat-{i + 1}"
        counts = {v: sum(r.verdict == v for r in b.rules) for v in verdicts}
        summary.append({"bat": b.bat, "anchor": anchor,
                        "badge": _badge(b.verdict, rests_on_model(b.rules, b.verdict)),
                        "counts": [counts[v] for v in verdicts]})
        f = b.facts
        cls = f.get("material_class") or "class unknown"
        facts = [("Length", fmt.quantity(f["length"], "length")),
                 ("Mass", fmt.quantity(f["mass"], "mass")),
                 ("Drop (length in \u2212 weight oz)", Display(f"{f['drop']:.2f}", None)),
                 ("Barrel diameter", fmt.quantity(f["barrel_diameter"], "length", 4)),
                 ("Smallest diameter", fmt.quantity(f["min_diameter"], "length", 4)),
                 ("Construction", Display(str(f["construction"]), None)),
                 ("Material", Display(f"{f['material']} ({cls})", None))]
        bats.append({"bat": b.bat, "anchor": anchor,
                     "badge": _badge(b.verdict, rests_on_model(b.rules, b.verdict)),
                     "path": b.path, "sha256": b.sha256, "facts": facts,
                     "rules": [rule_row(r) for r in b.rules],
                     "not_modelled": [(r.rule, r.note or "no reason given")
                                      for r in b.rules if r.verdict == "not-modelled"],
                     "warnings": list(b.warnings)})
    inputs = [{"role": "league", "name": result.league, "path": result.path,
               "sha256": result.sha256}]
    inputs += [{"role": "bat", "name": b.bat, "path": b.path, "sha256": b.sha256}
               for b in result.bats]
    summary_table = Table(["Bat", "Verdict", "Passed", "Failed", "Not modelled",
                           "Not applicable"],
                          [[s["bat"], s["badge"], *map(str, s["counts"])] for s in summary],
                          [False, False, True, True, True, True])
    return {
        "result": result, "page_title": f"League rules: {result.title} \u2014 batcert",
        "badge": head_badge, "sentence": sentence,
        "offsets": offsets([r for b in result.bats for r in b.rules]),
        "facts": [("League", f"{result.league} (version {result.version})"),
                  ("Rule book", result.reference or fmt.DASH),
                  ("Engine (performance rules)", result.engine),
                  ("Date", fmt.created(result.created)),
                  ("batcert version", result.batcert_version)],
        "inputs": inputs, "summary": summary, "summary_table": summary_table, "bats": bats,
        "description": fmt.paragraphs(result.description), "notes": fmt.paragraphs(result.notes),
        "date": fmt.created(result.created),
    }
