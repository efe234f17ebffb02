"""Comparison and league reports as Markdown.

Each report is first laid out as a list of neutral blocks (headings, paragraphs, lists, tables,
charts) by :func:`comparison_blocks` / :func:`league_blocks`; :func:`blocks_to_markdown` renders
them. Rendering reads the result dataclasses and never computes physics; a saved JSON re-renders
through ``from_dict``. The text helpers here are shared with the terminal (console.py).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from batcert.compare import ComparisonResult, ProtocolComparison, percent
from batcert.league import LeagueResult, RuleResult
from batcert.reports import DASH, IMPACT_RULES, METRIC_NAMES
from batcert.units import INCH, Display, show



# ---------------------------------------------------------------- blocks


@dataclass
class Heading:
    level: int
    text: str


@dataclass
class Para:
    text: str


@dataclass
class Bullets:
    items: list[str]


@dataclass
class Grid:
    headers: list[str]
    rows: list[list[str]]
    numeric: list[bool] = field(default_factory=list)


@dataclass
class Chart:
    svg: str


Block = Heading | Para | Bullets | Grid | Chart


# ---------------------------------------------------------------- value formatting


def metric_display(value: float | None, metric: str) -> Any:
    """The protocol metric: exit speed in m/s with mph, any other metric to 4 decimals."""
    if value is None:
        return DASH
    if metric == "exit-speed":
        return show(value, "speed", 2)
    return Display(f"{value:.4f}", None)


def location_display(r: float | None, pivot: float, length: float) -> Any:
    """A position on the bat: metres from the pivot, with inches from the tip."""
    if r is None:
        return DASH
    from_tip = length - pivot - r
    where = "from tip" if from_tip >= 0 else "beyond tip"
    return Display(f"{r:.3f} m", f"{abs(from_tip) / INCH:.2f} in {where}")


def rule_value_display(value: Any, unit: str) -> Any:
    """A league rule's value or limit as a display cell (lengths in mm with inches)."""
    if value is None:
        return DASH
    if isinstance(value, (list, tuple)):
        return ", ".join(str(v) for v in value)
    if isinstance(value, str):
        return value
    if unit == "m":
        return Display(f"{value * 1000:.1f} mm", f"{value / INCH:.3f} in")
    if unit == "m/s":
        return show(value, "speed", 2)
    if unit == "in - oz":
        return Display(f"{value:.2f}", None)
    return Display(f"{value:.4f}", None)


# Plain-text forms for Markdown and the terminal: the display cells above, "SI (US)".
def metric_text(value: float | None, metric: str) -> str:
    return str(metric_display(value, metric))


def location_text(r: float | None, pivot: float, length: float) -> str:
    return str(location_display(r, pivot, length))


def rule_value_text(value: Any, unit: str) -> str:
    return str(rule_value_display(value, unit))


def limit_text(r: RuleResult) -> str:
    return rule_value_text(r.limit, r.unit) + (f" + {r.tolerance:g}" if r.tolerance else "")


def margin_text(r: RuleResult) -> str:
    if r.margin is None or r.verdict not in ("pass", "fail"):
        return DASH
    if r.unit == "m":
        return f"{r.margin * 1000:+.1f} mm ({r.margin / INCH:+.3f} in)"
    return f"{r.margin:+.4f}" if r.unit != "in - oz" else f"{r.margin:+.2f}"


def created_text(stamp: str) -> str:
    return stamp.replace("T", " ").replace("+00:00", " UTC")


# ---------------------------------------------------------------- comparison


def _pct_for_chart(p: float | None) -> float | None:
    """P in percent, rounded so that rounding noise (1e-14 %) does not set the axis range."""
    return None if p is None else round(p * 100, 4) + 0.0


def _protocol_blocks(result: ComparisonResult, p: ProtocolComparison, charts: bool) -> list[Block]:
    labels = [b.label for b in result.bats]
    compared = result.compared
    length = {b.label: b.length for b in result.bats}
    metric = METRIC_NAMES.get(p.metric, p.metric)
    out: list[Block] = [
        Heading(2, f"Protocol {p.protocol}: {p.title}"),
        Para(f"Metric {metric}, impact at the {IMPACT_RULES.get(p.impact_rule, p.impact_rule)}, "
             f"pivot {show(p.pivot, 'length')} from the knob, ball {p.ball}; conditions combine "
             f"by {p.aggregate}. Reference: {p.reference} (version {p.version})."),
    ]
    head = ["Condition", "Set-up"] + [f"{metric}: {lab}" for lab in labels] + [
        f"P: {lab}" for lab in compared]
    rows = []
    for c in p.conditions:
        rows.append([c.name, c.setup] + [metric_text(c.bats[lab].value, p.metric)
                                         for lab in labels]
                    + [percent(c.bats[lab].relative) for lab in compared])
    blank = [""] * (1 + len(labels))
    rows.append(["mean of P across conditions"] + blank
                + [percent(p.relative_spread[lab].mean) for lab in compared])
    rows.append(["std of P (population)"] + blank
                + [DASH if p.relative_spread[lab].std is None
                   else f"{p.relative_spread[lab].std * 100:.2f} %" for lab in compared])
    rows.append(["range of P (min to max)"] + blank
                + [f"{percent(p.relative_spread[lab].min)} to {percent(p.relative_spread[lab].max)}"
                   for lab in compared])
    rows.append([f"aggregate ({p.aggregate})", ""]
                + [metric_text(p.aggregate_value[lab], p.metric) for lab in labels]
                + [percent(p.aggregate_relative[lab]) for lab in compared])
    out.append(Grid(head, rows, [False, False] + [True] * (len(labels) + len(compared))))
    if p.limit is not None:
        out.append(Para(f"Protocol limit {metric_text(p.limit, p.metric)}: "
                        + ", ".join(f"{lab} {p.verdicts[lab] or DASH}" for lab in labels) + "."))
    if charts:
        from batcert.reports import svg
        cats = [c.name for c in p.conditions]
        out.append(Chart(svg.bar_chart(
            cats, [svg.BarSeries(lab, [c.bats[lab].value for c in p.conditions])
                   for lab in labels], title=f"{p.protocol}: {metric} per condition",
            y_label=metric, limit=p.limit, value_format="{:.3f}")))
        pcts = [svg.BarSeries(lab, [_pct_for_chart(c.bats[lab].relative)
                                    for c in p.conditions]) for lab in compared]
        if any(v for s in pcts for v in s.values):
            out.append(Chart(svg.bar_chart(cats, pcts, title=f"{p.protocol}: P against the "
                                           "reference bat", y_label="P [%]",
                                           value_format="{:+.2f}")))
        else:  # a chart of zero-height bars says nothing (and has no y range)
            out.append(Para(f"{p.protocol}: P is 0.00 % (or undefined) in every condition; no "
                            "chart."))
    out.append(Heading(3, f"{p.protocol}: centre of percussion and sweet spot"))
    rows = []
    for c in p.conditions:
        for lab in labels:
            b = c.bats[lab]
            rows.append([c.name, lab, location_text(b.cop, p.pivot, length[lab]),
                         location_text(b.sweet_spot, p.pivot, length[lab]),
                         f"{b.sweet_spot_minus_cop * 100:+.1f} cm",
                         location_text(b.rigid_sweet_spot, p.pivot, length[lab]),
                         location_text(b.impact_location, p.pivot, length[lab]),
                         "yes (not located)" if b.sweet_spot_at_edge else "no"])
    out.append(Grid(["Condition", "Bat", "COP (Eq. 4)", "Sweet spot", "Sweet spot - COP",
                     "Rigid sweet spot (Eq. 7)", "Impact point", "Sweet spot on window edge"],
                    rows, [False, False, True, True, True, True, True, False]))
    if charts:
        from batcert.reports import svg
        out.append(Chart(svg.bar_chart(
            [c.name for c in p.conditions],
            [svg.BarSeries(f"{lab} sweet spot", [c.bats[lab].sweet_spot for c in p.conditions])
             for lab in labels]
            + [svg.BarSeries(f"{lab} COP", [c.bats[lab].cop for c in p.conditions])
               for lab in labels],
            title=f"{p.protocol}: sweet spot and COP per condition",
            y_label="distance from the pivot [m]", value_format="{:.3f}")))
    return out


def comparison_blocks(result: ComparisonResult, charts: bool = False) -> list[Block]:
    out: list[Block] = [Heading(1, f"Bat comparison: {result.title}")]
    facts = [["Study", f"{result.study} ({result.study_reference})" if result.study else DASH],
             ["Reference bat (P = 0)", result.reference],
             ["Relative performance", "P = (P_bat - P_ref) / P_ref (Smith 2001, Eq. 6)"],
             ["Engine", result.engine],
             ["Date", created_text(result.created)],
             ["batcert version", result.batcert_version]]
    out.append(Grid(["Item", "Value"], facts))
    out.append(Grid(["Bat", "Construction", "Material", "Length", "File"],
                    [[b.label, b.construction or DASH, b.material or DASH,
                      str(show(b.length, "length")), b.path] for b in result.bats]))
    out.append(Heading(2, "What the model finds"))
    out.append(Bullets(list(result.findings)))
    if result.claims:
        out.append(Heading(2, "The study's claims against the model"))
        out.append(Para("Each claim is tested with the check and dead band written in the study "
                        "file before running; 'not-supported' means this model, with these "
                        "inputs, does not reproduce the claim, and the evidence says why."))
        out.append(Grid(["Claim", "Statement", "Model", "Evidence"],
                        [[c.id, c.statement, c.status, c.evidence] for c in result.claims]))
    if result.study_notes:
        out.append(Heading(2, "Study notes"))
        out.append(Para(result.study_notes))
    if result.warnings:
        out.append(Heading(2, "Warnings"))
        out.append(Bullets(list(result.warnings)))
    for p in result.protocols:
        out.extend(_protocol_blocks(result, p, charts))
    out.append(Heading(2, "Mass properties about each pivot"))
    rows, seen = [], set()
    for p in result.protocols:
        for b in result.bats:
            key = (b.label, round(p.pivot, 9))
            if key in seen:
                continue
            seen.add(key)
            m = p.mass[b.label]
            rows.append([b.label, str(show(p.pivot, "length")), str(show(m.mass, "mass")),
                         str(show(m.cg, "length")), str(show(m.moi_pivot, "moi", 4)),
                         str(show(m.cop, "length"))])
    out.append(Grid(["Bat", "Pivot from knob", "Mass", "CG from pivot", "MOI about pivot",
                     "COP from pivot"], rows, [False] + [True] * 5))
    out.append(Heading(2, "Input files"))
    out.append(Grid(["Role", "Name", "Path", "SHA-256"],
                    [[i["role"], i["name"], i["path"], i["sha256"]] for i in result.inputs]))
    return out


# ---------------------------------------------------------------- league

VERDICT_TEXT = {"pass": "pass", "fail": "FAIL", "not-applicable": "not applicable",
                "not-modelled": "NOT MODELLED"}


def league_blocks(result: LeagueResult) -> list[Block]:
    out: list[Block] = [Heading(1, f"League rules: {result.title}")]
    out.append(Grid(["Item", "Value"], [
        ["League", f"{result.league} (version {result.version})"],
        ["Rule book", result.reference],
        ["Engine (performance rules)", result.engine],
        ["Date", created_text(result.created)],
        ["batcert version", result.batcert_version],
        ["League file", f"{result.path} (SHA-256 {result.sha256})"]]))
    out.append(Grid(["Bat", "Verdict", "Rules passed", "Failed", "Not modelled", "Not applicable"],
                    [[b.bat, b.verdict.upper(), *(str(sum(r.verdict == v for r in b.rules))
                                                  for v in ("pass", "fail", "not-modelled",
                                                            "not-applicable"))]
                     for b in result.bats]))
    out.append(Para("A bat passes only when every rule passes or does not apply. A rule marked "
                    "not modelled is one batcert cannot evaluate yet; it is never counted as a "
                    "pass (verdict 'incomplete' when nothing fails)."))
    if result.description:
        out.append(Para(result.description))
    for b in result.bats:
        out.append(Heading(2, f"{b.bat}: {b.verdict.upper()}"))
        f = b.facts
        out.append(Para(f"Length {show(f['length'], 'length')}, mass {show(f['mass'], 'mass')}, "
                        f"drop {f['drop']:.2f}, barrel {show(f['barrel_diameter'], 'length', 4)}, "
                        f"{f['construction']}, {f['material']} "
                        f"(class {f['material_class'] or 'unknown'}). File {b.path}."))
        out.append(Grid(["Rule", "Title", "Value", "Limit", "Verdict", "Margin", "Applies to",
                         "Source (confidence)", "Note"],
                        [[r.rule, r.title, rule_value_text(r.value, r.unit), limit_text(r),
                          VERDICT_TEXT.get(r.verdict, r.verdict), margin_text(r), r.applies_to,
                          f"{r.source} ({r.confidence})", r.note] for r in b.rules],
                        [False, False, True, True, False, True, False, False, False]))
        if b.warnings:
            out.append(Bullets([f"warning: {w}" for w in b.warnings]))
    if result.notes:
        out.append(Heading(2, "Notes on this league file"))
        out.append(Para(result.notes))
    return out


# ---------------------------------------------------------------- renderers


def _md_escape(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def blocks_to_markdown(blocks: Sequence[Block]) -> str:
    lines: list[str] = []
    for b in blocks:
        if isinstance(b, Heading):
            lines += ["#" * b.level + " " + _md_escape(b.text), ""]
        elif isinstance(b, Para):  # blank lines in the text separate paragraphs
            from batcert.reports import paragraphs
            for text in paragraphs(str(b.text)):
                lines += [_md_escape(text), ""]
        elif isinstance(b, Bullets):
            lines += [f"- {_md_escape(i)}" for i in b.items] + [""]
        elif isinstance(b, Grid):
            numeric = b.numeric or [False] * len(b.headers)
            lines.append("| " + " | ".join(_md_escape(h) for h in b.headers) + " |")
            lines.append("|" + "|".join("---:" if n else ":---" for n in numeric) + "|")
            lines += ["| " + " | ".join(_md_escape(c) or " " for c in row) + " |" for row in b.rows]
            lines.append("")
    return "\n".join(lines).rstrip() + "\n"


def render_comparison_markdown(result: ComparisonResult) -> str:
    return blocks_to_markdown(comparison_blocks(result))


def render_league_markdown(result: LeagueResult) -> str:
    return blocks_to_markdown(league_blocks(result))
