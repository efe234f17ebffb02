"""Certification reports (Markdown, HTML with inline SVG plots, JSON) from a :class:`RunResult`.

``write_reports`` renders and writes them atomically. This module also holds what every text format
shows: :func:`build_view` turns a result into formatted tables (SI with US customary alongside), so
the Markdown and HTML templates only lay them out. Reports only read a result, never compute
physics, so they can be regenerated from a saved results JSON via ``RunResult.from_dict``.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from datetime import datetime
from functools import lru_cache
from typing import TYPE_CHECKING, Any

from batcert.reports.write import FORMATS, atomic_write_text, render, write_reports
from batcert.units import Display, show, to_us

if TYPE_CHECKING:
    import jinja2

    from batcert.results import RunResult

__all__ = ["FORMATS", "Table", "atomic_write_text", "build_view", "render", "write_reports"]

# Display names of metrics and impact rules: the one table for reports and the terminal.
METRIC_NAMES = {
    "exit-speed": "exit speed",
    "besr": "BESR",
    "bpf": "BPF",
    "bbcor": "BBCOR",
    "collision-efficiency": "collision efficiency e_A",
}
IMPACT_RULES = {
    "cop": "centre of percussion",
    "sweet-spot": "sweet spot (maximum exit speed)",
    "max-metric": "location of the maximum metric",
    "fixed-from-tip": "fixed distance from the tip",
}
AGGREGATES = {"mean": "mean", "min": "minimum", "max": "maximum"}
DASH = "\u2014"


@dataclass
class Table:
    """Column headers and rows of display cells (``Display`` or plain text)."""

    headers: list[str]
    rows: list[list[Display | str]] = field(default_factory=list)
    numeric: list[bool] = field(default_factory=list)  # right-align these columns


def metric_name(metric: str) -> str:
    """The metric's display name, capitalised for headings ("Exit speed", "BESR")."""
    name = METRIC_NAMES.get(metric, metric)
    return name[:1].upper() + name[1:]


def metric_value(value: float | None, metric: str, signed: bool = False) -> Display:
    """The protocol metric: exit speed in m/s (mph), everything else dimensionless."""
    if value is None:
        return Display(DASH, None)
    sign = "+" if signed else ""
    if metric == "exit-speed":
        return Display(f"{value:{sign}.2f} m/s", f"{to_us(value, 'speed'):{sign}.1f} mph")
    return Display(f"{value:{sign}.3f}", None)


def plain(value: float | None, digits: int = 3) -> Display:
    return Display(DASH if value is None else f"{value:.{digits}f}", None)


def signed_quantity(value: float, dimension: str, digits: int = 3) -> Display:
    shown = show(abs(value), dimension, digits)
    sign = "\u2212" if value < 0 else "+"
    us = f"{sign}{shown.us}" if shown.us else None
    return Display(f"{sign}{shown.si}", us)


def location(r: float | None, result: RunResult) -> Display:
    """A position on the bat: metres from the pivot, with inches from the tip alongside."""
    if r is None:
        return Display(DASH, None)
    mp = result.mass_properties
    from_tip = mp.length - mp.pivot - r
    tip = "from tip" if from_tip >= 0 else "beyond tip"
    return Display(f"{r:.3f} m from pivot", f"{abs(to_us(from_tip, 'length')):.2f} in {tip}")


def _nz(v: float) -> float:
    return v + 0.0  # turns -0.0 into 0.0


def verdict(result: RunResult) -> dict[str, Any]:
    """Badge text and the sentence stating the value against the limit."""
    name, m = metric_name(result.metric), result.metric
    value = metric_value(result.value, m)
    if result.verdict is None or result.limit is None:
        return {"label": "NO LIMIT", "css": "none", "value": value, "limit": None,
                "tolerance": None, "margin": None,
                "sentence": f"{name} {value}; the protocol sets no limit."}
    limit, tol = metric_value(result.limit, m), metric_value(result.tolerance, m)
    margin = metric_value(result.margin, m, signed=True)
    passed = result.verdict.lower() == "pass"
    relation = "\u2264" if passed else ">"
    tol_text = f" + tolerance {tol}" if result.tolerance else ""
    return {
        "label": "PASS" if passed else "FAIL", "css": "pass" if passed else "fail",
        "value": value, "limit": limit, "tolerance": tol, "margin": margin,
        "sentence": f"{name} {value} {relation} limit {limit}{tol_text}; margin {margin}.",
    }


def created(text: str) -> str:
    try:
        stamp = datetime.fromisoformat(text.replace("Z", "+00:00"))
    except ValueError:
        return text
    offset = stamp.utcoffset()
    zone = "" if offset is None else "UTC" if not offset else stamp.strftime("%z")
    return f"{stamp:%Y-%m-%d %H:%M:%S} {zone}".strip()


def header_rows(result: RunResult) -> list[tuple[str, str]]:
    n = len(result.conditions)
    title = f"{result.protocol} \u2014 {result.protocol_title}" if result.protocol_title \
        else result.protocol
    engine = f"{result.engine}, bat {result.support} at the pivot"
    return [
        ("Bat", result.bat),
        ("Ball", result.ball),
        ("Protocol", title),
        ("Protocol version", result.protocol_version or DASH),
        ("Reference", result.protocol_reference or DASH),
        ("Metric", f"{metric_name(result.metric)}, "
                   f"{AGGREGATES.get(result.aggregate, result.aggregate)} of {n} "
                   f"condition{'s' if n != 1 else ''}"),
        ("Impact location", IMPACT_RULES.get(result.impact_rule, result.impact_rule)),
        ("Engine", engine),
        ("Date", created(result.created)),
        ("batcert version", result.batcert_version),
    ]


def conditions_table(result: RunResult) -> Table:
    t = Table(["Condition", "Set-up", "Pitch speed (toward bat)", "Bat angular speed",
               "Relative speed", "Impact location", "Exit speed", "Bat angular speed after",
               ], numeric=[False, False] + [True] * 6)
    for c in result.conditions:
        t.rows.append([c.name, c.setup, show(_nz(-c.pitch_speed), "speed", 1),
                       show(_nz(c.bat_angular_speed), "angular_speed", 1),
                       show(c.relative_speed, "speed", 1), location(c.impact_location, result),
                       show(c.exit_speed, "speed", 2),
                       show(_nz(c.bat_angular_speed_after), "angular_speed", 1)])
    return t


def metrics_table(result: RunResult) -> Table:
    head = f"Metric: {metric_name(result.metric)}"
    t = Table(["Condition", "COR e", "Ball COR e_b", "BPF", "BESR", "BBCOR", "e_A", head],
              numeric=[False] + [True] * 7)
    for c in result.conditions:
        t.rows.append([c.name, plain(c.cor), plain(c.ball_cor), plain(c.bpf), plain(c.besr),
                       plain(c.bbcor), plain(c.collision_efficiency),
                       metric_value(c.metric_value, result.metric)])
    return t


def locations_table(result: RunResult) -> Table:
    t = Table(["Condition", "Centre of percussion", "Sweet spot (max exit speed)",
               "Sweet spot \u2212 COP", "Rigid sweet spot (Eq. 7)", "Impact point",
               "On window edge"], numeric=[False] + [True] * 5 + [False])
    for c in result.conditions:
        t.rows.append([c.name, location(c.cop, result), location(c.sweet_spot, result),
                       signed_quantity(c.sweet_spot - c.cop, "length"),
                       location(c.rigid_sweet_spot, result), location(c.impact_location, result),
                       "yes \u26a0" if c.at_window_edge else "no"])
    return t


def mass_table(result: RunResult) -> Table:
    mp = result.mass_properties
    t = Table(["Property", "Model (reconciled)", "Geometry", "Measured"],
              numeric=[False, True, True, True])
    t.rows = [
        ["Mass", show(mp.mass, "mass"), show(mp.geometry_mass, "mass"),
         show(mp.measured_mass, "mass")],
        ["CG from pivot", show(mp.cg, "length"), show(mp.geometry_cg, "length"),
         show(mp.measured_cg, "length")],
        ["MOI about pivot", show(mp.moi_pivot, "moi", 4), show(mp.geometry_moi_pivot, "moi", 4),
         show(mp.measured_moi_pivot, "moi", 4)],
        ["Centre of percussion from pivot", show(mp.cop, "length"),
         show(mp.geometry_cop, "length"), show(mp.measured_cop, "length")],
    ]
    return t


def bat_table(result: RunResult) -> Table:
    mp = result.mass_properties
    return Table(["Dimension", "Value"], [
        ["Length", show(mp.length, "length")],
        ["Pivot from knob", show(mp.pivot, "length")],
    ], numeric=[False, True])


def number(value: Any) -> str:
    """Generic display of a diagnostic value (numbers to 5 significant digits)."""
    if isinstance(value, bool) or value is None:
        return str(value).lower() if value is not None else DASH
    if isinstance(value, float):
        return f"{value:.5g}"
    if isinstance(value, (list, tuple)):
        return ", ".join(number(v) for v in value) or DASH
    return str(value)


def flatten(data: dict[str, Any], prefix: str = "") -> Iterator[tuple[str, str]]:
    """``{"barrel": {"k": 1}}`` -> ``("barrel.k", "1")``; lists are joined with commas."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            yield from flatten(value, name + ".")
        else:
            yield name, number(value)


def engine_table(result: RunResult) -> Table:
    rows: list[list[Display | str]] = [["engine", result.engine], ["support", result.support]]
    rows += [[k, v] for k, v in flatten(result.engine_settings)]
    rows += [[k, v] for k, v in flatten(result.extras)]
    return Table(["Setting or diagnostic", "Value"], rows)


def paragraphs(text: str) -> list[str]:
    blocks = [" ".join(b.split()) for b in text.replace("\r\n", "\n").split("\n\n")]
    return [b for b in blocks if b]


def build_view(result: RunResult) -> dict[str, Any]:
    """Everything a report template shows, formatted; the templates only arrange it."""
    mp = result.mass_properties
    return {
        "result": result,
        "title": f"{result.bat} \u2014 {result.protocol}",
        "metric_name": metric_name(result.metric),
        "verdict": verdict(result),
        "header": header_rows(result),
        "header_table": Table(["Item", "Value"], [list(r) for r in header_rows(result)]),
        "date": created(result.created),
        "pivot": show(mp.pivot, "length"),
        "inputs": result.inputs,
        "notes": paragraphs(result.protocol_notes or ""),
        "warnings": list(result.warnings),
        "conditions": conditions_table(result),
        "metrics": metrics_table(result),
        "locations": locations_table(result),
        "mass": mass_table(result),
        "bat": bat_table(result),
        "reconciliation": mp.reconciliation,
        "corrections": [(k, number(v)) for k, v in mp.corrections.items()],
        "engine": engine_table(result),
        "show_metric_plot": result.metric != "exit-speed",
    }


@lru_cache(maxsize=1)
def environment() -> jinja2.Environment:
    """Jinja environment over the package's templates (works from an installed wheel too)."""
    import jinja2

    return jinja2.Environment(
        loader=jinja2.PackageLoader("batcert.reports", "templates"),
        autoescape=jinja2.select_autoescape(enabled_extensions=("html.j2",), default=False,
                                            default_for_string=False),
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
