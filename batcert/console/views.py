"""The commands' terminal views: each result as its headline, tables, warnings and the
report files written, through :mod:`batcert.console`'s primitives."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from batcert.console import (
    STYLES,
    _cell_text,
    _emit,
    _Settings,
    _verdict,
    _wrote,
    table,
)
from batcert.console import warnings as _warnings
from batcert.reports import format as fmt
from batcert.reports.table import Table


def run_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a :class:`~batcert.results.run.RunResult`: a model prediction, said
    so on its first line ("predicted PASS"), with the model's known offset for the metric."""
    m = result.metric
    limit = "" if result.limit is None else (
        f" against limit {fmt.metric_value(result.limit, m)}"
        + (f" + {result.tolerance:g}" if result.tolerance else "")
        + f", margin {fmt.metric_value(result.margin, m, signed_=True)}")
    label, style = _verdict(result.verdict)
    _emit([(f"predicted {label}" if result.verdict else label, style),
           (f"  {result.bat} \u2014 {result.protocol} ({result.protocol_title})", "")])
    n = len(result.conditions)
    _emit([(f"  predicted {fmt.metric_word(m)} ({fmt.aggregate_word(result.aggregate)} of {n} "
             f"condition{'s' if n > 1 else ''}) = {fmt.metric_value(result.value, m)}"
             f"{limit}   [model: engine {result.engine}, {result.support}]", "")])
    if result.model_offset:  # with -q too: it qualifies the verdict
        _emit([(f"  known offset of the model: {result.model_offset}", "")])
    shown = fmt.condition_metrics()
    t = Table(["condition", "pitch\n[m/s]", "bat w1\n[rad/s]", "impact\n[m from pivot]",
               "COP\n[m]", "sweet spot\n[m]", "exit speed\n[m/s (mph)]", "COR",
               *[heading for _, _, heading in shown]], numeric=[False] + [True] * (7 + len(shown)))
    for c in result.conditions:
        t.rows.append([c.name, f"{-c.pitch_speed + 0.0:.1f}", f"{c.bat_angular_speed:.1f}",
                       f"{c.impact_location:.3f}" + ("*" if c.at_window_edge else ""),
                       f"{c.cop:.3f}", f"{c.sweet_spot:.3f}",
                       fmt.quantity(c.exit_speed, "speed", 2), fmt.plain(c.cor, 4),
                       *[fmt.metric_value(getattr(c, field), name) for name, field, _ in shown]])
    table(t)
    if result.uncertainty is not None:
        from batcert.reports.uncertainty_view import summary_sentence
        _emit([("  " + summary_sentence(result), "")])
    _warnings(result.warnings)
    _wrote(paths)


def comparison_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a comparison: per protocol the report's table of the metric and P per
    condition, then the study's claims and the findings."""
    from batcert.reports.compare_view import comparison_view
    view = comparison_view(result, charts=False)
    _emit([(view["title"], "bold"),
           (f"  (reference {result.reference}; engine {result.engine})", "")])
    for p in view["protocols"]:
        table(p["grid"], f"{p['id']} \u2014 {p['title']}")
    if view["claims"]:
        table(Table(["claim", "model", "evidence"],
                    [[c["id"], c["badge"], c["evidence"]] for c in view["claims"]]),
              "study claims against the model")
    for f in [] if _Settings.quiet else result.findings:
        _emit([(f"  - {f}", "")], hang=4)
    _warnings(result.warnings)
    _wrote(paths)


def league_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a league evaluation: with several bats a summary first that fits one
    screen (a row per bat: its verdict and the rules it fails; only that with ``--quiet``),
    then a table per bat and rule."""
    from batcert.reports.league_view import league_view
    view = league_view(result)
    if len(result.bats) > 1:
        _league_brief(result)
        if _Settings.quiet:
            _offsets(view["offsets"])
            return
    for b in view["bats"]:
        badge = b["badge"]
        _emit([(_cell_text(badge), STYLES.get(getattr(badge, "css", ""), "")),
               (f"  {b['bat']} \u2014 {result.league} ({result.title})", "")])
        table(Table(["rule", "value", "limit", "verdict", "margin", "note"],
                    [[r["id"], r["value"], r["limit"], r["badge"], r["margin"], r["note"]]
                     for r in b["rules"]], [False, True, True, False, True, False]))
        _warnings(b["warnings"])
    _offsets(view["offsets"])
    _wrote(paths)


def _offsets(offsets: Sequence[str]) -> None:
    """The model's known offset of each metric a verdict rests on (with ``-q`` too)."""
    for o in offsets:
        _emit([(f"known offset of the model ({o})", "")])


def _league_brief(result) -> None:
    """The league's verdict and a row per bat: name, verdict, failing (else not modelled)
    rules, the last wrapped under itself."""
    from batcert.reports.league_view import brief_rows, overall
    badge, sentence = overall(result.bats)
    _emit([(_cell_text(badge), STYLES.get(badge.css, "")),
           (f"  {result.league} \u2014 {result.title}: {sentence}", "")])
    rows = [("bat", None, "failing rules"), *brief_rows(result)]
    name = max(len(n) for n, _, _ in rows)
    verdict = max(len(_cell_text(b)) if b else len("verdict") for _, b, _ in rows)
    for n, b, why in rows:
        word = _cell_text(b) if b else "verdict"
        _emit([(f"  {n.ljust(name)}  ", ""), (word, STYLES.get(b.css, "") if b else "bold"),
               (" " * (verdict - len(word)) + f"  {why}", "")], hang=name + verdict + 6)
    if not _Settings.quiet:
        _emit([("", "")])  # then the detail


def field_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of an in-play prediction: per batter profile, the bats' table."""
    from batcert.reports.field_view import prediction, terminal_tables
    _emit([("model prediction", "bold"), (f"  {prediction(result)}", "")])
    for title, t in terminal_tables(result):
        table(t, title)
    _warnings(result.warnings)
    _wrote(paths)


def sweep_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a sweep or design study: the headline, the table per variant (up to
    40 rows; the reports hold more) and the design's answer; warnings alike but for their
    numbers grouped (:mod:`batcert.reports.warning_groups`)."""
    from batcert.reports.sweep_view import headline, nominal_sentence, sweep_view
    view = sweep_view(result, charts=False)
    _emit([(view["title"], "bold")])
    _emit([(f"  {headline(result)}", "")])
    if nominal_sentence(result) and not _Settings.quiet:
        _emit([(f"  {nominal_sentence(result)}", "")])
    t = view["summary"]
    if len(t.rows) > 40:
        step = -(-len(t.rows) // 40)
        t = Table(t.headers, t.rows[::step], t.numeric)
        _emit([(f"  (every {step}th variant shown; the reports hold all)", "dim")])
    table(t)
    from batcert.reports.warning_groups import grouped_warnings
    _warnings(grouped_warnings(result))  # alike ones as one line; the result keeps them all
    _wrote(paths)


def lab_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a lab certificate: verdict, sentence, uncertainty budget, scan."""
    from batcert.reports.lab_view import lab_view
    view = lab_view(result, charts=False)
    b = view["badge"]
    _emit([(_cell_text(b), STYLES.get(getattr(b, "css", ""), "")), (f"  {view['title']}", "")])
    _emit([(f"  {view['sentence']}", "")])
    if result.conformance_probability is not None:
        _emit([(f"  conformance probability {result.conformance_probability:.4f}; decision "
                f"rule: {result.decision_rule} acceptance", "")])
    if result.lot_calibration.get("calibrated_on") == "session":
        from batcert.reports.lab_view import lot_fact
        _emit([(f"  ball lot: {lot_fact(result.lot_calibration)}", "")])
    table(view["budget"], "measurement uncertainty")
    table(view["scan"], "location scan")
    _warnings(result.warnings)
    _wrote(paths)
