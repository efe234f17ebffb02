"""All terminal output goes through here: rich tables on stdout, messages on stderr.

With ``--json`` only JSON is written to stdout so that scripts can parse it.
"""

from __future__ import annotations

import json
import sys
from typing import Any

from rich.console import Console
from rich.markup import escape
from rich.table import Table

from batcert.reports import METRIC_NAMES
from batcert.results import RunResult
from batcert.units import show, to_us

out = Console(highlight=False, soft_wrap=True, width=None if sys.stdout.isatty() else 140)
err = Console(stderr=True, highlight=False, soft_wrap=True)



def print_json(data: Any) -> None:
    sys.stdout.write(json.dumps(data, indent=2, allow_nan=False) + "\n")
    sys.stdout.flush()


def error(message: str) -> None:
    err.print(f"[bold red]error:[/] {message}", markup=True, highlight=False)


def input_error(text: str) -> None:
    err.print("[bold red]invalid input[/]", markup=True)
    err.print(text, markup=False)


def note(message: str) -> None:
    err.print(message, markup=False)


def _fmt(value: float | None, metric: str) -> str:
    if value is None:
        return "—"
    if metric == "exit-speed":
        return str(show(value, "speed", 2))
    return f"{value:.4f}"


def run_summary(result: RunResult, paths: list) -> None:
    verdict = {"pass": "[bold green]PASS[/]", "fail": "[bold red]FAIL[/]"}.get(
        result.verdict or "", "[bold]no limit[/]")
    limit = "" if result.limit is None else (
        f" against limit {_fmt(result.limit, result.metric)}"
        + (f" + {result.tolerance:g}" if result.tolerance else "")
        + f", margin {_fmt(result.margin, result.metric)}")
    out.print(f"{verdict}  {result.bat} — {result.protocol} ({result.protocol_title})", markup=True)
    out.print(f"  {METRIC_NAMES[result.metric]} ({result.aggregate} of {len(result.conditions)} "
              f"condition{'s' if len(result.conditions) > 1 else ''}) = "
              f"{_fmt(result.value, result.metric)}{limit}   [engine {result.engine}, "
              f"{result.support}]", markup=False)
    t = Table(show_header=True, header_style="bold", box=None, pad_edge=False)
    cols = ["condition", "pitch\n[m/s]", "bat w1\n[rad/s]", "impact\n[m from pivot]",
            "COP\n[m]", "sweet spot\n[m]", "exit speed\n[m/s (mph)]", "COR", "BPF", "BESR",
            "BBCOR", "e_A"]
    for col in cols:
        t.add_column(escape(col), justify="left" if col == "condition" else "right")
    for c in result.conditions:
        t.add_row(c.name, f"{-c.pitch_speed:.1f}", f"{c.bat_angular_speed:.1f}",
                  f"{c.impact_location:.3f}" + ("*" if c.at_window_edge else ""), f"{c.cop:.3f}",
                  f"{c.sweet_spot:.3f}", f"{c.exit_speed:.2f} ({to_us(c.exit_speed, 'speed'):.1f})",
                  f"{c.cor:.3f}", f"{c.bpf:.3f}", f"{c.besr:.3f}", f"{c.bbcor:.3f}",
                  f"{c.collision_efficiency:.3f}")
    out.print(t)
    for w in result.warnings:
        out.print(f"  [yellow]warning:[/] {w}", markup=True)
    for p in paths:
        out.print(f"  wrote {p}", markup=False)


def kv_table(title: str, rows: list[tuple[str, str]]) -> None:
    t = Table(title=title, show_header=False, box=None, title_justify="left", pad_edge=False)
    t.add_column("", style="bold")
    t.add_column("")
    for k, v in rows:
        t.add_row(k, v)
    out.print(t)


def table(title: str, columns: list[str], rows: list[list[str]]) -> None:
    t = Table(title=title, box=None, title_justify="left", header_style="bold", pad_edge=False)
    for i, c in enumerate(columns):
        t.add_column(c, justify="left" if i == 0 else "right")
    for r in rows:
        t.add_row(*r)
    out.print(t)


def comparison_summary(result, paths: list) -> None:
    """Terminal view of a :class:`~batcert.compare.ComparisonResult`: per protocol the metric
    and P of each bat per condition, then the study's claims and the findings."""
    from rich.markup import escape
    from rich.text import Text

    from batcert.compare import percent
    from batcert.compare_reports import metric_text
    labels = [b.label for b in result.bats]
    out.print(f"[bold]{escape(result.title)}[/]  (reference {escape(result.reference)}; engine "
              f"{result.engine})", markup=True)
    for p in result.protocols:
        name = METRIC_NAMES.get(p.metric, p.metric)
        cols = ["condition"] + [f"{name}: {lab}" for lab in labels] + [
            f"P: {lab}" for lab in result.compared]
        rows = [[c.name] + [metric_text(c.bats[lab].value, p.metric) for lab in labels]
                + [percent(c.bats[lab].relative) for lab in result.compared]
                for c in p.conditions]
        spreads = [p.relative_spread[lab] for lab in result.compared]
        rows.append(["mean P (std)"] + [""] * len(labels) + [
            f"{percent(s.mean)} ({'—' if s.std is None else f'{s.std * 100:.2f} %'})"
            for s in spreads])
        table(escape(f"{p.protocol} — {p.title}"), [escape(c) for c in cols],
              [[escape(c) for c in r] for r in rows])
    if result.claims:
        style = {"supported": "green", "not-supported": "red", "not-testable": "yellow"}
        t = Table(title="study claims against the model", box=None, title_justify="left",
                  header_style="bold", pad_edge=False)
        for col in ("claim", "model", "evidence"):
            t.add_column(col)
        for c in result.claims:
            t.add_row(Text(c.id), Text(c.status, style=style.get(c.status, "bold")),
                      Text(c.evidence))
        out.print(t)
    for f in result.findings:
        out.print(f"  - {f}", markup=False)
    for w in result.warnings:
        out.print(Text.assemble(("  warning: ", "yellow"), w))
    for p in paths:
        out.print(f"  wrote {p}", markup=False)


def league_summary(result, paths: list) -> None:
    """Terminal view of a :class:`~batcert.league.LeagueResult`: a table per bat and rule."""
    from rich.text import Text

    from batcert.compare_reports import VERDICT_TEXT, limit_text, margin_text, rule_value_text
    style = {"pass": "green", "fail": "red", "not-modelled": "yellow", "not-applicable": "dim",
             "incomplete": "yellow"}
    for b in result.bats:
        out.print(Text.assemble((b.verdict.upper(), f"bold {style[b.verdict]}"),
                                f"  {b.bat} — {result.league} ({result.title})"))
        t = Table(box=None, header_style="bold", pad_edge=False)
        for col in ("rule", "value", "limit", "verdict", "margin", "note"):
            t.add_column(col, justify="right" if col in ("value", "limit", "margin") else "left")
        for r in b.rules:
            t.add_row(Text(r.rule), Text(rule_value_text(r.value, r.unit)), Text(limit_text(r)),
                      Text(VERDICT_TEXT[r.verdict], style=style[r.verdict]),
                      Text(margin_text(r)), Text(r.note))
        out.print(t)
        for w in b.warnings:
            out.print(Text.assemble(("  warning: ", "yellow"), w))
    for p in paths:
        out.print(f"  wrote {p}", markup=False)
