"""Comparison and league reports as self-contained HTML pages, styled like the run report.

:func:`comparison_view` / :func:`league_view` format the content as display cells (SI with US
customary below, coloured status badges) for the templates ``compare.html.j2`` / ``league.html.j2``
of the reports package, which include the run report's ``style.css.j2``. Every page is one file
(inline CSS and SVG, no scripts, nothing loaded from the network).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from batcert.compare import ComparisonResult, ProtocolComparison, percent
from batcert.league import LeagueResult, RuleResult
from batcert.reports.compare_markdown import (
    DASH,
    _pct_for_chart,
    location_display,
    metric_display,
    metric_text,
    rule_value_display,
)
from batcert.reports import IMPACT_RULES, METRIC_NAMES
from batcert.reports.write import slugify
from batcert.units import INCH, show

# ---------------------------------------------------------------- styled HTML views
#
# The views hold display cells only: plain text, ``Display`` (SI, with US customary below it) or
# ``Badge`` (a coloured status label). The templates lay them out and escape every string.


@dataclass(frozen=True)
class Badge:
    """A status label; ``css`` picks its colour: pass, fail, warn, na or info."""

    text: str
    css: str

    def __str__(self) -> str:
        return self.text


@dataclass
class HtmlTable:
    """A table for the templates: headers, rows of cells, right-aligned columns, row classes."""

    headers: list[str]
    rows: list[list[Any]] = field(default_factory=list)
    numeric: list[bool] = field(default_factory=list)
    row_classes: list[str] = field(default_factory=list)
    foot: list[list[Any]] = field(default_factory=list)  # summary rows below the body


CLAIM_BADGES = {"supported": Badge("supported", "pass"),
                "not-supported": Badge("not supported", "fail"),
                "not-testable": Badge("not testable", "warn")}
RULE_BADGES = {"pass": Badge("PASS", "pass"), "fail": Badge("FAIL", "fail"),
               "not-modelled": Badge("NOT MODELLED", "warn"),
               "not-applicable": Badge("not applicable", "na")}
BAT_BADGES = {"pass": Badge("PASS", "pass"), "fail": Badge("FAIL", "fail"),
              "incomplete": Badge("INCOMPLETE", "warn")}
MINUS = "\u2212"


def _badge(table: dict[str, Badge], key: str | None) -> Badge:
    if key is None:
        return Badge(DASH, "na")
    return table.get(key.lower(), Badge(key, "info"))


def _signed(text: str) -> str:
    """A typographic minus sign instead of the hyphen of Python's formatting."""
    return MINUS + text[1:] if text.startswith("-") else text


def offset_display(d: float | None) -> Any:
    """A signed distance along the bat in cm, with inches below it."""
    from batcert.units import Display
    if d is None:
        return DASH
    return Display(_signed(f"{d * 100:+.1f} cm"), _signed(f"{d / INCH:+.2f} in"))


def rule_limit_display(r: RuleResult) -> Any:
    from batcert.units import Display
    shown = rule_value_display(r.limit, r.unit)
    if not r.tolerance:
        return shown
    if isinstance(shown, Display):
        return Display(f"{shown.si} + {r.tolerance:g} tolerance", shown.us)
    return f"{shown} + {r.tolerance:g} tolerance"


def rule_margin_display(r: RuleResult) -> Any:
    """limit (+ tolerance) minus value; positive passes. Only for pass/fail verdicts."""
    from batcert.units import Display
    if r.margin is None or r.verdict not in ("pass", "fail"):
        return DASH
    if r.unit == "m":
        return Display(_signed(f"{r.margin * 1000:+.1f} mm"), _signed(f"{r.margin / INCH:+.3f} in"))
    if r.unit == "m/s":
        s = show(abs(r.margin), "speed", 2)
        sign = MINUS if r.margin < 0 else "+"
        return Display(sign + s.si, (sign + s.us) if s.us else None)
    return Display(_signed(f"{r.margin:+.2f}" if r.unit == "in - oz" else f"{r.margin:+.4f}"),
                   None)


def _paragraphs(text: str) -> list[str]:
    from batcert.reports import paragraphs
    return paragraphs(text or "")


def _chart_width(categories: Sequence[str], per_group: int = 1, least: int = 640) -> int:
    """Wide enough that the category labels under the groups do not overlap (viewBox units)."""
    longest = max((len(c) for c in categories), default=0)
    return max(least, int(84 + len(categories) * max(longest * 7.2 + 18, 30 * per_group)))


def _charts(result: ComparisonResult, p: ProtocolComparison) -> list[dict[str, Any]]:
    """The protocol's figures: metric per condition, P per condition, sweet spot and COP."""
    from markupsafe import Markup

    from batcert.reports import svg
    labels, compared = [b.label for b in result.bats], result.compared
    metric = METRIC_NAMES.get(p.metric, p.metric)
    cats = [c.name for c in p.conditions]
    width = _chart_width(cats, len(labels), least=500)  # two charts side by side
    out = []
    unit = " [m/s]" if p.metric == "exit-speed" else " [-]"
    out.append({"svg": Markup(svg.bar_chart(
        cats, [svg.BarSeries(lab, [c.bats[lab].value for c in p.conditions]) for lab in labels],
        title=f"{metric} per condition", y_label=metric + unit, limit=p.limit,
        value_format="{:.2f}" if p.metric == "exit-speed" else "{:.3f}", width=width)),
        "caption": f"{metric} of each bat in each condition"
                   + (f"; the dashed line is the protocol limit {metric_text(p.limit, p.metric)}."
                      if p.limit is not None else ".")})
    pcts = [svg.BarSeries(lab, [_pct_for_chart(c.bats[lab].relative) for c in p.conditions])
            for lab in compared]
    if any(v for s in pcts for v in s.values):
        out.append({"svg": Markup(svg.bar_chart(
            cats, pcts, title=f"P against {result.reference}", y_label="P [%]",
            value_format="{:+.2f}", width=width)),
            "caption": f"Relative performance P of each bat against the reference bat "
                       f"{result.reference} (P = 0), per condition."})
    spots = []
    for lab in labels:  # each bat's sweet spot next to its COP
        spots.append(svg.BarSeries(f"{lab}: sweet spot",
                                   [c.bats[lab].sweet_spot for c in p.conditions]))
        spots.append(svg.BarSeries(f"{lab}: COP", [c.bats[lab].cop for c in p.conditions]))
    edge = sum(c.bats[lab].sweet_spot_at_edge for c in p.conditions for lab in labels)
    edge_text = (f" In {edge} of {len(p.conditions) * len(labels)} bat-conditions the sweet spot "
                 "lies on the search window's edge: the bar shows the edge, not a located "
                 "maximum." if edge else "")
    out.append({"svg": Markup(svg.bar_chart(
        cats, spots, title="Sweet spot and centre of percussion per condition",
        y_label="distance from the pivot [m]", value_format="{:.3f}", baseline=None,
        width=_chart_width(cats, 2 * len(labels)))),
        "caption": "Sweet spot (maximum exit speed) and centre of percussion of each bat, in "
                   f"metres from the pivot ({show(p.pivot, 'length')} from the knob); the axis "
                   "does not start at zero. The table above gives inches from the tip."
                   + edge_text})
    return out


def _protocol_view(result: ComparisonResult, p: ProtocolComparison) -> dict[str, Any]:
    labels, compared = [b.label for b in result.bats], result.compared
    length = {b.label: b.length for b in result.bats}
    metric = METRIC_NAMES.get(p.metric, p.metric)
    show_setup = any(c.setup != c.name for c in p.conditions)
    rows = []
    for c in p.conditions:
        rows.append([c.name] + ([c.setup] if show_setup else [])
                    + [metric_display(c.bats[lab].value, p.metric) for lab in labels]
                    + [percent(c.bats[lab].relative) for lab in compared])
    pad = [""] * (len(labels) + (1 if show_setup else 0))
    spread = p.relative_spread
    foot = [
        ["mean of P across conditions"] + pad + [percent(spread[lab].mean) for lab in compared],
        ["std of P (population)"] + pad
        + [DASH if spread[lab].std is None else f"{spread[lab].std * 100:.2f} %"
           for lab in compared],
        ["range of P (min to max)"] + pad
        + [DASH if spread[lab].min is None
           else f"{percent(spread[lab].min)} to {percent(spread[lab].max)}" for lab in compared],
        [f"aggregate ({p.aggregate})"] + ([""] if show_setup else [])
        + [metric_display(p.aggregate_value[lab], p.metric) for lab in labels]
        + [percent(p.aggregate_relative[lab]) for lab in compared],
    ]
    n_num = len(labels) + len(compared)
    values = HtmlTable([], rows, [False] * (2 if show_setup else 1) + [True] * n_num, foot=foot)
    cop_rows, cop_classes = [], []
    for c in p.conditions:
        for i, lab in enumerate(labels):
            b = c.bats[lab]
            cop_rows.append([c.name if i == 0 else "", lab,
                             location_display(b.cop, p.pivot, length[lab]),
                             location_display(b.sweet_spot, p.pivot, length[lab]),
                             offset_display(b.sweet_spot_minus_cop),
                             location_display(b.rigid_sweet_spot, p.pivot, length[lab]),
                             location_display(b.impact_location, p.pivot, length[lab]),
                             Badge("on edge: not located", "warn") if b.sweet_spot_at_edge
                             else "no"])
            cop_classes.append("group-start" if i == 0 else "")
    cop = HtmlTable(["Condition", "Bat", "Centre of percussion (Eq. 4)",
                     "Sweet spot (max exit speed)", "Sweet spot \u2212 COP",
                     "Rigid sweet spot (Eq. 7)", "Impact point", "Sweet spot on window edge"],
                    cop_rows, [False, False, True, True, True, True, True, False], cop_classes)
    charts = _charts(result, p)
    limit = None
    if p.limit is not None:
        limit = {"value": metric_display(p.limit, p.metric),
                 "bats": [(lab, metric_display(p.aggregate_value[lab], p.metric),
                           _badge(RULE_BADGES, p.verdicts[lab])) for lab in labels]}
    return {
        "id": p.protocol, "title": p.title, "anchor": "protocol-" + slugify(p.protocol),
        "metric": metric, "labels": labels, "compared": compared, "show_setup": show_setup,
        "facts": [("Metric", f"{metric}, {p.aggregate} over {len(p.conditions)} condition"
                             f"{'s' if len(p.conditions) != 1 else ''}"),
                  ("Impact at", IMPACT_RULES.get(p.impact_rule, p.impact_rule)),
                  ("Pivot", str(show(p.pivot, "length")) + " from the knob"),
                  ("Ball", p.ball),
                  ("Reference", f"{p.reference} (version {p.version})" if p.reference
                   else f"version {p.version}")],
        "pivot": show(p.pivot, "length"), "grid": values, "limit": limit, "cop": cop,
        "charts": charts[:-1], "spot_chart": charts[-1],
    }


def _overview(result: ComparisonResult) -> dict[str, Any]:
    """P at a glance: per protocol the aggregate metric and the mean and spread of P."""
    from markupsafe import Markup

    from batcert.reports import svg
    compared = result.compared
    rows = []
    for p in result.protocols:
        metric = METRIC_NAMES.get(p.metric, p.metric)
        where = IMPACT_RULES.get(p.impact_rule, p.impact_rule)
        row: list[Any] = [p.protocol, f"{metric} at the {where}"]
        for lab in compared:
            s = p.relative_spread[lab]
            row.append(percent(s.mean))
            row.append(DASH if s.std is None else f"{s.std * 100:.2f} %")
            row.append(DASH if s.min is None else f"{percent(s.min)} to {percent(s.max)}")
        rows.append(row)
    headers = ["Protocol", "Metric and impact location"]
    for lab in compared:
        headers += [f"mean P: {lab}", "std of P", "range of P"]
    table = HtmlTable(headers, rows, [False, False] + [True] * (3 * len(compared)))
    chart = None
    series = [svg.BarSeries(lab, [_pct_for_chart(p.relative_spread[lab].mean)
                                  for p in result.protocols]) for lab in compared]
    if any(v for s in series for v in s.values):
        cats = [p.protocol for p in result.protocols]
        chart = Markup(svg.bar_chart(cats, series, title=f"Mean P against {result.reference}",
                                     y_label="mean P [%]", value_format="{:+.2f}",
                                     width=_chart_width(cats, len(compared))))
    return {"table": table, "chart": chart}


def comparison_view(result: ComparisonResult) -> dict[str, Any]:
    """Everything the comparison page shows, formatted; ``compare.html.j2`` only arranges it."""
    from batcert.reports import created, flatten
    labels = [b.label for b in result.bats]
    title = result.title or " vs ".join(labels)
    protos = ", ".join(p.protocol for p in result.protocols)
    facts = []
    if result.study:
        facts.append(("Study", result.study + (f" \u2014 {result.study_reference}"
                                               if result.study_reference else "")))
    facts += [("Protocols", f"{len(result.protocols)}: {protos}"),
              ("Bats", ", ".join(labels)),
              ("Reference bat", f"{result.reference} (P = 0)"),
              ("Relative performance", "P = (P_bat \u2212 P_ref) / P_ref (Smith 2001, Eq. 6), "
                                       "per condition"),
              ("Engine", result.engine),
              ("Date", created(result.created)),
              ("batcert version", result.batcert_version)]
    bats = HtmlTable(["Bat", "Construction", "Material", "Length", "File"],
                     [[b.label + (" (reference)" if b.label == result.reference else ""),
                       b.construction or DASH, b.material or DASH, show(b.length, "length"),
                       b.path] for b in result.bats],
                     [False, False, False, True, False])
    statuses = list(CLAIM_BADGES) + sorted({c.status for c in result.claims} - set(CLAIM_BADGES))
    tally = [(_badge(CLAIM_BADGES, k), sum(c.status == k for c in result.claims))
             for k in statuses]
    claims = [{"id": c.id, "statement": " ".join(c.statement.split()), "check": c.check,
               "source": c.source, "badge": _badge(CLAIM_BADGES, c.status),
               "evidence": c.evidence} for c in result.claims]
    mass_rows, seen = [], set()
    for p in result.protocols:
        for b in result.bats:
            key = (b.label, round(p.pivot, 9))
            if key in seen:
                continue
            seen.add(key)
            m = p.mass[b.label]
            mass_rows.append([b.label, show(p.pivot, "length"), show(m.mass, "mass"),
                              show(m.cg, "length"), show(m.moi_pivot, "moi", 4),
                              show(m.cop, "length")])
    mass = HtmlTable(["Bat", "Pivot from knob", "Mass", "CG from pivot", "MOI about pivot",
                      "COP from pivot"], mass_rows, [False] + [True] * 5)
    engine = HtmlTable(["Setting", "Value"], [[k, v] for k, v in flatten(result.engine_settings)])
    return {
        "result": result, "title": title, "page_title": f"Comparison: {title} \u2014 batcert",
        "facts": facts, "bats": bats, "inputs": result.inputs,
        "findings": list(result.findings), "claims": claims,
        "tally": tally if result.claims else [],
        "notes": _paragraphs(result.study_notes), "warnings": list(result.warnings),
        "overview": _overview(result) if result.compared else None,
        "protocols": [_protocol_view(result, p) for p in result.protocols],
        "mass": mass, "engine": engine, "date": created(result.created),
    }


def _overall(bats: Sequence[Any]) -> tuple[Badge, str]:
    """The league page's headline badge and sentence (the worst bat verdict decides)."""
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
    return BAT_BADGES[worst], sentence


def _rule_row(r: RuleResult) -> dict[str, Any]:
    return {"id": r.rule, "title": r.title, "applies_to": r.applies_to, "kind": r.kind,
            "protocol": r.protocol, "value": rule_value_display(r.value, r.unit),
            "limit": rule_limit_display(r), "badge": _badge(RULE_BADGES, r.verdict),
            "verdict": r.verdict, "margin": rule_margin_display(r), "source": r.source,
            "confidence": r.confidence, "note": r.note}


def league_view(result: LeagueResult) -> dict[str, Any]:
    """Everything the league page shows, formatted; ``league.html.j2`` only arranges it."""
    from batcert.reports import created
    from batcert.units import Display
    badge, sentence = _overall(result.bats)
    verdicts = ("pass", "fail", "not-modelled", "not-applicable")
    summary, bats = [], []
    for i, b in enumerate(result.bats):
        anchor = f"bat-{i + 1}"
        counts = {v: sum(r.verdict == v for r in b.rules) for v in verdicts}
        summary.append({"bat": b.bat, "anchor": anchor, "badge": _badge(BAT_BADGES, b.verdict),
                        "counts": [counts[v] for v in verdicts]})
        f = b.facts
        cls = f.get("material_class") or "class unknown"
        facts = [("Length", show(f["length"], "length")), ("Mass", show(f["mass"], "mass")),
                 ("Drop (length in \u2212 weight oz)", Display(f"{f['drop']:.2f}", None)),
                 ("Barrel diameter", show(f["barrel_diameter"], "length", 4)),
                 ("Smallest diameter", show(f["min_diameter"], "length", 4)),
                 ("Construction", Display(str(f["construction"]), None)),
                 ("Material", Display(f"{f['material']} ({cls})", None))]
        not_modelled = [r for r in b.rules if r.verdict == "not-modelled"]
        bats.append({"bat": b.bat, "anchor": anchor, "badge": _badge(BAT_BADGES, b.verdict),
                     "path": b.path, "sha256": b.sha256, "facts": facts,
                     "rules": [_rule_row(r) for r in b.rules],
                     "not_modelled": [(r.rule, r.note or "no reason given")
                                      for r in not_modelled],
                     "warnings": list(b.warnings)})
    inputs = [{"role": "league", "name": result.league, "path": result.path,
               "sha256": result.sha256}]
    inputs += [{"role": "bat", "name": b.bat, "path": b.path, "sha256": b.sha256}
               for b in result.bats]
    return {
        "result": result, "page_title": f"League rules: {result.title} \u2014 batcert",
        "badge": badge, "sentence": sentence,
        "facts": [("League", f"{result.league} (version {result.version})"),
                  ("Rule book", result.reference or DASH),
                  ("Engine (performance rules)", result.engine),
                  ("Date", created(result.created)),
                  ("batcert version", result.batcert_version)],
        "inputs": inputs, "summary": summary, "bats": bats,
        "description": _paragraphs(result.description), "notes": _paragraphs(result.notes),
        "date": created(result.created),
    }


def html_cell(value: object) -> Any:
    """A template cell: a badge, SI with US customary below it, or escaped text."""
    from markupsafe import Markup

    from batcert.reports.html import cell
    if isinstance(value, Badge):
        return Markup('<span class="badge badge-{}">{}</span>').format(value.css, value.text)
    return cell(value)


def _render_template(name: str, view: dict[str, Any]) -> str:
    from batcert.reports import environment
    env = environment().overlay()
    env.filters.update(cell=html_cell)
    return env.get_template(name).render(**view)


def render_comparison_html(result: ComparisonResult) -> str:
    """The comparison as one self-contained, styled HTML5 page (template ``compare.html.j2``)."""
    return _render_template("compare.html.j2", comparison_view(result))


def render_league_html(result: LeagueResult) -> str:
    """The league evaluation as one self-contained, styled HTML5 page (``league.html.j2``)."""
    return _render_template("league.html.j2", league_view(result))
