"""The comparison report: everything its Markdown and HTML show, formatted once.

:func:`comparison_view` turns a :class:`~batcert.results.compare.ComparisonResult` into tables of
display cells, badges and (for HTML) inline SVG charts; ``compare.md.j2`` and ``compare.html.j2``
only arrange them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from batcert.reports import format as fmt
from batcert.reports.figure import BarFigure, Figure, LineFigure, svg_of
from batcert.reports.table import Badge, Table
from batcert.results.compare import ComparisonResult, ProtocolComparison

CLAIM_BADGES = {"supported": Badge("supported", "pass"),
                "not-supported": Badge("not supported", "fail"),
                "not-testable": Badge("not testable", "warn")}
VERDICT_BADGES = {"pass": Badge("PASS", "pass"), "fail": Badge("FAIL", "fail"),
                  "not-modelled": Badge("NOT MODELLED", "warn"),
                  "not-applicable": Badge("not applicable", "na"),
                  "incomplete": Badge("INCOMPLETE", "warn")}
# a verdict the model computed from the bat's specification, not a measurement (run, compare,
# a league's performance rules); a measured verdict (reduce) keeps VERDICT_BADGES
PREDICTED_BADGES = {**VERDICT_BADGES, "pass": Badge("predicted PASS", "pass"),
                    "fail": Badge("predicted FAIL", "fail")}


def badge(table: dict[str, Badge], key: str | None) -> Badge:
    if key is None:
        return Badge(fmt.DASH, "na")
    return table.get(key.lower(), Badge(key, "info"))


def chart_width(categories: Sequence[str], per_group: int = 1, least: int = 640) -> int:
    """Wide enough that the category labels under the groups do not overlap (viewBox units)."""
    longest = max((len(c) for c in categories), default=0)
    return max(least, int(84 + len(categories) * max(longest * 7.2 + 18, 30 * per_group)))


def _pct_for_chart(p: float | None) -> float | None:
    """P in percent, rounded so that rounding noise (1e-14 %) does not set the axis range."""
    return None if p is None else round(p * 100, 4) + 0.0


def _protocol_figures(result: ComparisonResult, p: ProtocolComparison) -> list[BarFigure]:
    """The protocol's figures: metric per condition, P per condition, sweet spot and COP."""
    from batcert.reports import svg
    labels, compared = [b.label for b in result.bats], result.compared
    metric = fmt.metric_word(p.metric)
    cats = [c.name for c in p.conditions]
    width = chart_width(cats, len(labels), least=500)  # two charts side by side
    out = []
    unit = " [m/s]" if p.metric == "exit-speed" else " [-]"
    slug = fmt.slugify(p.protocol)
    out.append(BarFigure(
        f"{slug}--metric", f"{metric} per condition", metric + unit, cats,
        [svg.BarSeries(lab, [c.bats[lab].value for c in p.conditions], style=k)
         for k, lab in enumerate(labels)],
        caption=f"{metric} of each bat in each condition"
        + (f"; the dashed line is the protocol limit "
           f"{fmt.metric_value(p.limit, p.metric)}." if p.limit is not None else "."),
        limit=p.limit, value_format="{:.2f}" if p.metric == "exit-speed" else "{:.3f}",
        width=width))
    pcts = [svg.BarSeries(lab, [_pct_for_chart(c.bats[lab].relative) for c in p.conditions],
                          style=labels.index(lab)) for lab in compared]
    if any(v for s in pcts for v in s.values):
        out.append(BarFigure(
            f"{slug}--relative", f"P against {result.reference}", "P [%]", cats, pcts,
            caption=f"Relative performance P of each bat against the reference bat "
                    f"{result.reference} (P = 0), per condition.", value_format="{:+.2f}",
            width=width))
    spots = []
    for k, lab in enumerate(labels):  # each bat's sweet spot next to its COP, one colour a bat
        spots.append(svg.BarSeries(f"{lab}: sweet spot",
                                   [c.bats[lab].sweet_spot for c in p.conditions], style=k))
        spots.append(svg.BarSeries(f"{lab}: COP (lighter)", [c.bats[lab].cop for c in p.conditions],
                                   style=k, shade=True))
    edge = sum(c.bats[lab].sweet_spot_at_edge for c in p.conditions for lab in labels)
    edge_text = (f" In {edge} of {len(p.conditions) * len(labels)} bat-conditions the sweet spot "
                 "lies on the search window's edge: the bar shows the edge, not a located "
                 "maximum." if edge else "")
    out.append(BarFigure(
        f"{slug}--sweet-spot", "Sweet spot and centre of percussion per condition",
        "distance from the pivot [m]", cats, spots,
        caption="Sweet spot (maximum exit speed) and centre of percussion of each bat, in "
                f"metres from the pivot ({fmt.quantity(p.pivot, 'length')} from the knob); "
                "the axis does not start at zero. The table above gives inches from the tip."
                + edge_text, value_format="{:.3f}", baseline=None,
        width=chart_width(cats, 2 * len(labels))))
    return out


QUANTITY_WORDS = {"sweet_spot": "sweet spot", "rigid_sweet_spot": "rigid sweet spot (Eq. 7)",
                  "cop": "COP", "bpf": "BPF", "besr": "BESR", "bbcor": "BBCOR",
                  "exit_speed": "exit speed", "cor": "COR", "metric_value": "metric",
                  "collision_efficiency": "e_A", "impact_location": "impact point"}


def study_figures(result: ComparisonResult) -> list[LineFigure]:
    """The study's figures: each quantity of each bat against the swept parameter."""
    from batcert.reports.svg import Series
    from batcert.units import si_unit
    out = []
    for f in result.figures:
        pct = f.percent is not None
        series = [Series(f"{b.label}: {QUANTITY_WORDS.get(m, m)}",
                         f.percent if pct and f.percent else b.values,
                         [float("nan") if v is None else v for v in b.series[m]])
                  for b in f.bats for m in f.metrics]
        unit = "% of nominal" if pct else (si_unit(f.dimension) if f.dimension else "-")
        located = {"sweet_spot", "rigid_sweet_spot", "cop", "impact_location"}
        y = "distance from the pivot [m]" if set(f.metrics) <= located else \
            ", ".join(QUANTITY_WORDS.get(m, m) for m in f.metrics) + " [-]"
        out.append(LineFigure(
            f"study--{fmt.slugify(f.id)}", f.title, f"{f.parameter} [{unit}]", y, series,
            caption=f"Protocol {f.protocol}, condition {f.condition}, {f.parameter} varied "
                    "(the variants' mass properties come from their geometry when it "
                    "varies; docs/sweeps.md)."))
    return out


def comparison_figures(result: ComparisonResult) -> list[Figure]:
    """Every figure of the comparison report (what ``--figures`` writes)."""
    out: list[Figure] = []
    overview = _overview_figure(result)
    if overview is not None:
        out.append(overview)
    for p in result.protocols:
        out += _protocol_figures(result, p)
    return out + study_figures(result)


def _charts(result: ComparisonResult, p: ProtocolComparison) -> list[dict[str, Any]]:
    from markupsafe import Markup
    return [{"svg": Markup(svg_of(f)), "caption": f.caption}
            for f in _protocol_figures(result, p)]


def _values(result: ComparisonResult, p: ProtocolComparison, show_setup: bool) -> Table:
    """The metric of each bat and P of each compared bat, per condition, with P's spread."""
    labels, compared = [b.label for b in result.bats], result.compared
    head = ["Condition"] + (["Set-up"] if show_setup else []) + \
        [f"{fmt.metric_word(p.metric)}: {lab}" for lab in labels] + [f"P: {lab}" for lab in compared]
    rows = [[c.name] + ([c.setup] if show_setup else [])
            + [fmt.metric_value(c.bats[lab].value, p.metric) for lab in labels]
            + [fmt.percent(c.bats[lab].relative) for lab in compared] for c in p.conditions]
    pad = [""] * (len(labels) + (1 if show_setup else 0))
    spread = p.relative_spread
    foot: list[list[Any]] = [
        ["mean of P across conditions"] + pad + [fmt.percent(spread[lab].mean) for lab in compared],
        ["std of P (population)"] + pad + [fmt.percent_std(spread[lab].std) for lab in compared],
        ["range of P (min to max)"] + pad
        + [fmt.DASH if spread[lab].min is None
           else f"{fmt.percent(spread[lab].min)} to {fmt.percent(spread[lab].max)}"
           for lab in compared],
        [f"protocol result ({fmt.aggregate_word(p.aggregate)} of the metric over the "
         "conditions), and its P"] + ([""] if show_setup else [])
        + [fmt.metric_value(p.aggregate_value[lab], p.metric) for lab in labels]
        + [fmt.percent(p.aggregate_relative[lab]) for lab in compared],
    ]
    n_num = len(labels) + len(compared)
    return Table(head, rows, [False] * (2 if show_setup else 1) + [True] * n_num, foot=foot)


def _locations(result: ComparisonResult, p: ProtocolComparison) -> Table:
    labels = [b.label for b in result.bats]
    length = {b.label: b.length for b in result.bats}
    rows, classes = [], []
    for c in p.conditions:
        for i, lab in enumerate(labels):
            b = c.bats[lab]

            def at(r: float | None, lab: str = lab):
                return fmt.location(r, p.pivot, length[lab])
            rows.append([c.name if i == 0 else "", lab, at(b.cop), at(b.sweet_spot),
                         fmt.offset(b.sweet_spot_minus_cop), at(b.rigid_sweet_spot),
                         at(b.impact_location),
                         Badge("on edge: not located", "warn") if b.sweet_spot_at_edge else "no"])
            classes.append("group-start" if i == 0 else "")
    return Table(["Condition", "Bat", "Centre of percussion (Eq. 4)",
                  "Sweet spot (max exit speed)", "Sweet spot \u2212 COP",
                  "Rigid sweet spot (Eq. 7)", "Impact point", "Sweet spot on window edge"],
                 rows, [False, False, True, True, True, True, True, False], classes)


def _protocol_view(result: ComparisonResult, p: ProtocolComparison,
                   charts: bool) -> dict[str, Any]:
    labels, compared = [b.label for b in result.bats], result.compared
    metric = fmt.metric_word(p.metric)
    show_setup = any(c.setup != c.name for c in p.conditions)
    figures = _charts(result, p) if charts else []
    limit = None
    if p.limit is not None:
        limit = {"value": fmt.metric_value(p.limit, p.metric),
                 "bats": [(lab, fmt.metric_value(p.aggregate_value[lab], p.metric),
                           badge(PREDICTED_BADGES, p.verdicts[lab])) for lab in labels]}
    n = len(p.conditions)
    return {
        "id": p.protocol, "title": p.title, "anchor": "protocol-" + fmt.slugify(p.protocol),
        "metric": metric, "labels": labels, "compared": compared, "show_setup": show_setup,
        "facts": [("Metric", f"{metric}, {fmt.aggregate_word(p.aggregate)} over {n} "
                             f"condition{'s' if n != 1 else ''}"),
                  ("Impact at", fmt.rule_word(p.impact_rule)),
                  ("Pivot", f"{fmt.quantity(p.pivot, 'length')} from the knob"),
                  ("Ball", p.ball),
                  ("Reference", f"{p.reference} (version {p.version})" if p.reference
                   else f"version {p.version}")],
        "pivot": fmt.quantity(p.pivot, "length"), "grid": _values(result, p, show_setup),
        "limit": limit, "cop": _locations(result, p),
        "charts": figures[:-1], "spot_chart": figures[-1] if figures else None,
    }


def _overview(result: ComparisonResult, charts: bool) -> dict[str, Any]:
    """P at a glance: per protocol the mean and spread of P of each compared bat."""
    compared = result.compared
    rows = []
    for p in result.protocols:
        row: list[Any] = [p.protocol, f"{fmt.metric_word(p.metric)} at the "
                                      f"{fmt.rule_word(p.impact_rule)}"]
        for lab in compared:
            s = p.relative_spread[lab]
            row += [fmt.percent(s.mean), fmt.percent_std(s.std),
                    fmt.DASH if s.min is None else f"{fmt.percent(s.min)} to {fmt.percent(s.max)}"]
        rows.append(row)
    headers = ["Protocol", "Metric and impact location"]
    for lab in compared:
        headers += [f"mean P: {lab}", "std of P", "range of P"]
    table = Table(headers, rows, [False, False] + [True] * (3 * len(compared)))
    chart = None
    fig = _overview_figure(result) if charts else None
    if fig is not None:
        from markupsafe import Markup
        chart = Markup(svg_of(fig))
    return {"table": table, "chart": chart}


def _overview_figure(result: ComparisonResult) -> BarFigure | None:
    """Mean P of each compared bat under each protocol (None when every P is zero)."""
    from batcert.reports import svg
    compared, labels = result.compared, [b.label for b in result.bats]
    series_values = [[_pct_for_chart(p.relative_spread[lab].mean) for p in result.protocols]
                     for lab in compared]
    if not any(v for s in series_values for v in s):
        return None

    def spread(lab: str, p: ProtocolComparison) -> tuple[float, float] | None:
        s = p.relative_spread[lab]
        if s.min is None or s.max is None or len(p.conditions) < 2:
            return None
        return (round(s.min * 100, 4), round(s.max * 100, 4))
    cats = [p.protocol for p in result.protocols]
    return BarFigure("overview", f"Mean P against {result.reference}", "mean P across the "
                     "conditions [%]", cats,
                     [svg.BarSeries(lab, vals, style=labels.index(lab),
                                    errors=[spread(lab, p) for p in result.protocols])
                      for lab, vals in zip(compared, series_values, strict=True)],
                     caption="Mean of P over each protocol's conditions, for each bat; the "
                     "bars' whiskers span P's range (smallest to largest condition).",
                     value_format="{:+.2f}", width=chart_width(cats, len(compared)))


def _mass(result: ComparisonResult) -> Table:
    rows, seen = [], set()
    for p in result.protocols:
        for b in result.bats:
            key = (b.label, round(p.pivot, 9))
            if key in seen:
                continue
            seen.add(key)
            m = p.mass[b.label]
            rows.append([b.label, fmt.quantity(p.pivot, "length"), fmt.quantity(m.mass, "mass"),
                         fmt.quantity(m.cg, "length"), fmt.quantity(m.moi_pivot, "moi", 4),
                         fmt.quantity(m.cop, "length")])
    return Table(["Bat", "Pivot from knob", "Mass", "CG from pivot", "MOI about pivot",
                  "COP from pivot"], rows, [False] + [True] * 5)


def _figure_table(result: ComparisonResult, k: int) -> Table:
    """A study figure's numbers: the parameter, then each bat's quantities."""
    f = result.figures[k]
    head = [f"{f.parameter} [% of nominal]" if f.percent else f.parameter]
    head += [f"{b.label}: {QUANTITY_WORDS.get(m, m)}" for b in f.bats for m in f.metrics]
    n = len(f.bats[0].values) if f.bats else 0
    rows = []
    for i in range(n):
        x = f"{f.percent[i]:.4g}" if f.percent else f"{f.bats[0].values[i]:.4g}"
        rows.append([x] + [fmt.plain(b.series[m][i], 4) for b in f.bats for m in f.metrics])
    return Table(head, rows, [True] * len(head))


def comparison_view(result: ComparisonResult, charts: bool = True) -> dict[str, Any]:
    """Everything the comparison report shows, formatted; ``charts`` adds the SVG figures."""
    from markupsafe import Markup
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
              ("Date", fmt.created(result.created)),
              ("batcert version", result.batcert_version)]
    bats = Table(["Bat", "Construction", "Material", "Length", "File"],
                 [[b.label + (" (reference)" if b.label == result.reference else ""),
                   b.construction or fmt.DASH, b.material or fmt.DASH,
                   fmt.quantity(b.length, "length"), b.path] for b in result.bats],
                 [False, False, False, True, False])
    statuses = list(CLAIM_BADGES) + sorted({c.status for c in result.claims} - set(CLAIM_BADGES))
    tally = [(badge(CLAIM_BADGES, k), sum(c.status == k for c in result.claims))
             for k in statuses]
    claims = [{"id": c.id, "statement": fmt.one_line(c.statement), "check": c.check,
               "source": c.source, "badge": badge(CLAIM_BADGES, c.status),
               "evidence": c.evidence} for c in result.claims]
    return {
        "result": result, "title": title, "page_title": f"Comparison: {title} \u2014 batcert",
        "facts": facts, "bats": bats, "inputs": result.inputs,
        "findings": list(result.findings), "claims": claims,
        "tally": tally if result.claims else [],
        "notes": fmt.paragraphs(result.study_notes), "warnings": list(result.warnings),
        "overview": _overview(result, charts) if result.compared else None,
        "protocols": [_protocol_view(result, p, charts) for p in result.protocols],
        "study_figures": [{"svg": Markup(svg_of(f)) if charts else "", "title": f.title,
                           "caption": f.caption, "table": _figure_table(result, k)}
                          for k, f in enumerate(study_figures(result))],
        "mass": _mass(result),
        "engine": Table(["Setting", "Value"], [[k, v] for k, v in
                                               fmt.flatten(result.engine_settings)]),
        "date": fmt.created(result.created),
    }
