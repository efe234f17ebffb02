"""All terminal output goes through here: rich tables on stdout, messages on stderr.

With ``--json`` only JSON is written to stdout so that scripts can parse it. Tables are the
reports' own :class:`~batcert.reports.table.Table` objects with the reports' formatting
(:mod:`batcert.reports.format`); every piece of user text is shown as plain text, never read as
console markup.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Sequence
from typing import Any

from rich.console import Console
from rich.table import Table as RichTable
from rich.text import Text

from batcert.reports import format as fmt
from batcert.reports.table import Badge, Table

out = Console(highlight=False, soft_wrap=True, width=None if sys.stdout.isatty() else 140)
err = Console(stderr=True, highlight=False, soft_wrap=True)

STYLES = {"pass": "green", "fail": "red", "warn": "yellow", "na": "dim", "info": "bold"}


def print_json(data: Any) -> None:
    sys.stdout.write(json.dumps(data, indent=2, allow_nan=False) + "\n")
    sys.stdout.flush()


def error(message: str) -> None:
    err.print(Text.assemble(("error: ", "bold red"), message))


def input_error(text: str) -> None:
    err.print(Text("invalid input", style="bold red"))
    err.print(Text(text))


def note(message: str) -> None:
    err.print(Text(message))


def _cell(value: Any) -> Text:
    if isinstance(value, Badge):
        return Text(value.text, style=STYLES.get(value.css, ""))
    return Text(str(value))


def table(t: Table, title: str = "") -> None:
    """A report table on the terminal (summary rows after a blank line)."""
    r = RichTable(title=Text(title or t.title) if (title or t.title) else None, box=None,
                  title_justify="left", header_style="bold", pad_edge=False)
    for i, h in enumerate(t.headers):
        r.add_column(Text(h), justify="right" if t.is_numeric(i) else "left")
    for row in t.rows:
        r.add_row(*(_cell(c) for c in row))
    for row in t.foot:
        r.add_row(*(_cell(c) for c in row), style="bold")
    out.print(r)


def kv_table(title: str, rows: Sequence[tuple[str, Any]]) -> None:
    t = RichTable(title=Text(title), show_header=False, box=None, title_justify="left",
                  pad_edge=False)
    t.add_column("", style="bold")
    t.add_column("")
    for k, v in rows:
        t.add_row(Text(k), _cell(v))
    out.print(t)


def _verdict_text(verdict: str | None) -> Text:
    return {"pass": Text("PASS", style="bold green"), "fail": Text("FAIL", style="bold red")
            }.get(verdict or "", Text("no limit", style="bold"))


def _wrote(paths: Sequence[Any]) -> None:
    for p in paths:
        out.print(Text(f"  wrote {p}"))


def _warnings(warnings: Sequence[str]) -> None:
    for w in warnings:
        out.print(Text.assemble(("  warning: ", "yellow"), w))


def run_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a :class:`~batcert.results.run.RunResult`."""
    m = result.metric
    limit = "" if result.limit is None else (
        f" against limit {fmt.metric_value(result.limit, m)}"
        + (f" + {result.tolerance:g}" if result.tolerance else "")
        + f", margin {fmt.metric_value(result.margin, m, signed_=True)}")
    out.print(Text.assemble(_verdict_text(result.verdict),
                            f"  {result.bat} \u2014 {result.protocol} ({result.protocol_title})"))
    n = len(result.conditions)
    out.print(Text(f"  {fmt.metric_word(m)} ({fmt.aggregate_word(result.aggregate)} of {n} "
                   f"condition{'s' if n > 1 else ''}) = {fmt.metric_value(result.value, m)}"
                   f"{limit}   [engine {result.engine}, {result.support}]"))
    t = Table(["condition", "pitch\n[m/s]", "bat w1\n[rad/s]", "impact\n[m from pivot]",
               "COP\n[m]", "sweet spot\n[m]", "exit speed\n[m/s (mph)]", "COR", "BPF", "BESR",
               "BBCOR", "e_A"], numeric=[False] + [True] * 11)
    for c in result.conditions:
        t.rows.append([c.name, f"{-c.pitch_speed + 0.0:.1f}", f"{c.bat_angular_speed:.1f}",
                       f"{c.impact_location:.3f}" + ("*" if c.at_window_edge else ""),
                       f"{c.cop:.3f}", f"{c.sweet_spot:.3f}",
                       fmt.quantity(c.exit_speed, "speed", 2), fmt.plain(c.cor, 4),
                       fmt.metric_value(c.bpf, "bpf"), fmt.metric_value(c.besr, "besr"),
                       fmt.metric_value(c.bbcor, "bbcor"),
                       fmt.metric_value(c.collision_efficiency, "collision-efficiency")])
    table(t)
    _warnings(result.warnings)
    _wrote(paths)


def comparison_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a comparison: per protocol the report's table of the metric and P per
    condition, then the study's claims and the findings."""
    from batcert.reports.compare_view import comparison_view
    view = comparison_view(result, charts=False)
    out.print(Text.assemble((view["title"], "bold"),
                            f"  (reference {result.reference}; engine {result.engine})"))
    for p in view["protocols"]:
        table(p["grid"], f"{p['id']} \u2014 {p['title']}")
    if view["claims"]:
        table(Table(["claim", "model", "evidence"],
                    [[c["id"], c["badge"], c["evidence"]] for c in view["claims"]]),
              "study claims against the model")
    for f in result.findings:
        out.print(Text(f"  - {f}"))
    _warnings(result.warnings)
    _wrote(paths)


def league_summary(result, paths: Sequence[Any]) -> None:
    """Terminal view of a league evaluation: a table per bat and rule."""
    from batcert.reports.league_view import league_view
    view = league_view(result)
    for b in view["bats"]:
        out.print(Text.assemble(_cell(b["badge"]), f"  {b['bat']} \u2014 {result.league} "
                                f"({result.title})"))
        table(Table(["rule", "value", "limit", "verdict", "margin", "note"],
                    [[r["id"], r["value"], r["limit"], r["badge"], r["margin"], r["note"]]
                     for r in b["rules"]], [False, True, True, False, True, False]))
        _warnings(b["warnings"])
    _wrote(paths)


def note_out(message: str) -> None:
    """A plain line on stdout (e.g. ``ok  file.yaml (bat)``)."""
    out.print(Text(message))
