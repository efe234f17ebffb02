"""The report of one protocol run, a model prediction (not a certificate: only `reduce`, from
measured hits, makes one): everything its Markdown and HTML show, formatted."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from batcert.reports import format as fmt
from batcert.reports.barrel_view import break_in_view, compression_table
from batcert.reports.table import Table
from batcert.reports.uncertainty_view import uncertainty_view
from batcert.results.run import RunResult
from batcert.units import Display, to_us, us_unit


@dataclass(frozen=True)
class ShownVerdict:
    """A run's verdict as its reports show it: the badge's ``label`` and ``css`` class, the
    formatted value, limit, tolerance and margin (None without a limit), the ``sentence``
    stating the value against the limit, the ``basis`` (a model prediction) and the model's
    known ``offset`` for the metric ("" if none)."""

    label: str
    css: str
    value: Display
    limit: Display | None
    tolerance: Display | None
    margin: Display | None
    sentence: str
    basis: str
    offset: str


def verdict(result: RunResult) -> ShownVerdict:
    """Badge text and the sentence stating the value against the limit."""
    name, m = fmt.metric_name(result.metric), result.metric
    value = fmt.metric_value(result.value, m)
    if result.verdict is None or result.limit is None:
        return ShownVerdict("NO LIMIT", "none", value, None, None, None,
                            f"Predicted {name} {value}; the protocol sets no limit.",
                            basis(result), offset(result))
    limit, tol = fmt.metric_value(result.limit, m), fmt.metric_value(result.tolerance, m)
    margin = fmt.metric_value(result.margin, m, signed_=True)
    passed = result.verdict.lower() == "pass"
    relation = "\u2264" if passed else ">"
    tol_text = f" + tolerance {tol}" if result.tolerance else ""
    return ShownVerdict(
        "PREDICTED PASS" if passed else "PREDICTED FAIL", "pass" if passed else "fail",
        value, limit, tol, margin,
        f"Predicted {name} {value} {relation} limit {limit}{tol_text}; margin {margin}.",
        basis(result), offset(result))


TITLE = "Predicted bat performance"  # a run's report: a model prediction, never a certificate


def basis(result: RunResult) -> str:
    """Whether the values were measured or computed, and how."""
    return (f"A model prediction, not a certificate: values computed by batcert's "
            f"{result.engine} model of the bat from its specification, not measured on a "
            "bench (a certificate comes from measured hits: batcert reduce).")


def offset(result: RunResult) -> str:
    """The model's known offset for the metric (docs/validation.md), as a sentence, or ""."""
    return f"Known offset of the model: {result.model_offset}." if result.model_offset else ""


def header_rows(result: RunResult) -> list[tuple[str, str]]:
    n = len(result.conditions)
    title = f"{result.protocol} \u2014 {result.protocol_title}" if result.protocol_title \
        else result.protocol
    ident = fmt.identification(result.bat_identification)
    return [
        ("Bat", result.bat),
        *([("Bat identification", ident)] if ident else []),
        ("Ball", result.ball),
        ("Protocol", title),
        ("Protocol version", result.protocol_version or fmt.DASH),
        ("Reference", result.protocol_reference or fmt.DASH),
        ("Metric", f"{fmt.metric_name(result.metric)}, {fmt.aggregate_word(result.aggregate)} "
                   f"of {n} condition{'s' if n != 1 else ''}"),
        ("Impact location", fmt.rule_word(result.impact_rule)),
        ("Engine", f"{result.engine}, bat {result.support} at the pivot"),
        ("Date", fmt.created(result.created)),
        ("batcert version", result.batcert_version),
    ]


def _location(r: float | None, result: RunResult) -> Display:
    mp = result.mass_properties
    return fmt.location(r, mp.pivot, mp.length)


def conditions_table(result: RunResult) -> Table:
    t = Table(["Condition", "Set-up", "Pitch speed (toward bat)", "Bat angular speed",
               "Relative speed", "Impact location", "Exit speed", "Bat angular speed after"],
              numeric=[False, False] + [True] * 6)
    for c in result.conditions:
        t.rows.append([c.name, c.setup, fmt.quantity(-c.pitch_speed, "speed", 1),
                       fmt.quantity(c.bat_angular_speed, "angular_speed", 1),
                       fmt.quantity(c.relative_speed, "speed", 1),
                       _location(c.impact_location, result),
                       fmt.quantity(c.exit_speed, "speed", 2),
                       fmt.quantity(c.bat_angular_speed_after, "angular_speed", 1)])
    return t


def metrics_table(result: RunResult) -> Table:
    shown = fmt.condition_metrics()
    t = Table(["Condition", "COR e", "Ball COR e_b", *[heading for _, _, heading in shown],
               f"Metric: {fmt.metric_name(result.metric)}"],
              numeric=[False] + [True] * (3 + len(shown)))
    for c in result.conditions:
        t.rows.append([c.name, fmt.plain(c.cor, 4), fmt.plain(c.ball_cor, 4)]
                      + [fmt.metric_value(getattr(c, field), name) for name, field, _ in shown]
                      + [fmt.metric_value(c.metric_value, result.metric)])
    return t


def locations_table(result: RunResult) -> Table:
    t = Table(["Condition", "Centre of percussion", "Sweet spot (max exit speed)",
               "Sweet spot \u2212 COP", "Rigid sweet spot (Eq. 7)", "Impact point",
               "On window edge"], numeric=[False] + [True] * 5 + [False])
    for c in result.conditions:
        t.rows.append([c.name, _location(c.cop, result), _location(c.sweet_spot, result),
                       fmt.offset(c.sweet_spot - c.cop), _location(c.rigid_sweet_spot, result),
                       _location(c.impact_location, result),
                       "yes \u26a0" if c.at_window_edge else "no"])
    return t


def energy_table(result: RunResult) -> Table | None:
    """Where the energy of each impact went (flexible engine): the energy of the approach in the
    impact's frame, ``1/2 mu v_rel^2`` with ``mu = m / (1 + k)``, what the relative motion keeps
    (``e^2`` of it), what the ball dissipated and what is left vibrating in the bending modes and
    in the barrel; with the contact's time, force and compression. None without diagnostics."""
    rows = [c for c in result.conditions if c.diagnostics]
    if not rows:
        return None
    hollow = any("barrel_energy" in c.diagnostics for c in rows)
    head = ["Condition", "Contact time", "Peak force", "Ball compression", "Energy of approach",
            "Returned (e²)", "Lost in the ball", "Left in bending"]
    if hollow:
        head += ["Left in the barrel", "Barrel share at maximum compression"]
    t = Table(head, numeric=[False] + [True] * (len(head) - 1))
    for c in rows:
        d = c.diagnostics
        approach = d.get("approach_energy")
        barrel = d.get("barrel_energy", 0.0)
        row = [c.name, Display(f"{d['contact_time'] * 1e3:.2f} ms", None),
               Display(f"{d['peak_force'] / 1e3:.1f} kN",
                       f"{to_us(d['peak_force'], 'force'):,.0f} {us_unit('force')}"),
               Display(f"{d['max_compression'] * 1e3:.1f} mm", None), _joules(approach),
               _joules(None if approach is None else approach * c.cor**2),
               _joules(d.get("ball_energy_loss")), _joules(d["vibrational_energy"] - barrel)]
        if hollow:
            row += [_joules(d.get("barrel_energy")),
                    Display(fmt.DASH if d.get("barrel_energy_share") is None
                            else f"{100 * d['barrel_energy_share']:.1f} %", None)]
        t.rows.append(row)
    return t


def _joules(value: float | None) -> Display:
    return Display(fmt.DASH if value is None else f"{value:.1f} J", None)


def mass_table(result: RunResult) -> Table:
    mp = result.mass_properties
    t = Table(["Property", "Model (reconciled)", "Geometry", "Measured"],
              numeric=[False, True, True, True])
    t.rows = [
        ["Mass", fmt.quantity(mp.mass, "mass"), fmt.quantity(mp.geometry_mass, "mass"),
         fmt.quantity(mp.measured_mass, "mass")],
        ["CG from pivot", fmt.quantity(mp.cg, "length"), fmt.quantity(mp.geometry_cg, "length"),
         fmt.quantity(mp.measured_cg, "length")],
        ["MOI about pivot", fmt.quantity(mp.moi_pivot, "moi", 4),
         fmt.quantity(mp.geometry_moi_pivot, "moi", 4),
         fmt.quantity(mp.measured_moi_pivot, "moi", 4)],
        ["Centre of percussion from pivot", fmt.quantity(mp.cop, "length"),
         fmt.quantity(mp.geometry_cop, "length"), fmt.quantity(mp.measured_cop, "length")],
    ]
    return t


def bat_table(result: RunResult) -> Table:
    mp = result.mass_properties
    return Table(["Dimension", "Value"], [
        ["Length", fmt.quantity(mp.length, "length")],
        ["Pivot from knob", fmt.quantity(mp.pivot, "length")],
    ], numeric=[False, True])


MODE_KEYS = ("modes_hz", "mode_nodes")  # shown in the modes table, each node with its mode


def engine_table(result: RunResult) -> Table:
    """The engine's settings and the bat's diagnostics, each with its unit (SI)."""
    rows: list[list[Any]] = [] if "engine" in result.engine_settings else \
        [["engine", result.engine, ""]]
    rows += [["support", result.support, ""]]
    rows += [[k, v, fmt.unit_of(k)] for k, v in fmt.flatten(result.engine_settings)]
    extras = {k: v for k, v in result.extras.items() if k not in MODE_KEYS}
    rows += [[k, v, fmt.unit_of(k)] for k, v in fmt.flatten(extras)]
    return Table(["Setting or diagnostic", "Value", "Unit"], rows)


def modes_table(result: RunResult) -> Table | None:
    """The bat's free-free bending modes, each with its nodes; None without them."""
    freqs = result.extras.get("modes_hz") or []
    nodes = result.extras.get("mode_nodes") or []
    if not freqs:
        return None
    t = Table(["Mode", "Frequency [Hz]", "Nodes [cm from knob]"], numeric=[True, True, False])
    for i, f in enumerate(freqs):
        at = nodes[i] if i < len(nodes) else []
        t.rows.append([str(i + 1), f"{f:.0f}", ", ".join(f"{100 * z:.1f}" for z in at)
                       or fmt.DASH])
    return t


def corrections_table(result: RunResult) -> Table | None:
    """The reconciliation's and calibrations' corrections, each with its unit (SI)."""
    corr = result.mass_properties.corrections
    if not corr:
        return None
    return Table(["Correction", "Value", "Unit"],
                 [[k, fmt.number(v), fmt.unit_of(k)] for k, v in corr.items()],
                 numeric=[False, True, False])


def barrel_note(result: RunResult) -> str:
    """The certificate's sentence on the barrel of a hollow bat: calibrated, or the range of
    the result over the plausible barrel."""
    b = result.barrel
    if b is None:
        return ""
    hoop = f"model hoop frequency {b.hoop_frequency:.0f} Hz"
    if b.calibrated:
        return f"Barrel {b.basis} ({hoop})."
    low, high = (fmt.metric_value(v, result.metric) for v in (b.value_low, b.value_high))
    text = (f"Barrel {b.basis}: {fmt.metric_word(result.metric)} from {low} to {high} "
            f"({hoop})")
    if b.verdicts:
        text += ("; the verdict is " + b.verdicts[0] + " throughout" if len(b.verdicts) == 1
                 else "; the verdict changes within this range")
    return text + "."


def shows_metric_plot(result: RunResult) -> bool:
    """The metric gets its own plot unless it is the exit speed (already plotted)."""
    return result.metric != "exit-speed"


def run_view(result: RunResult) -> dict[str, Any]:
    """Everything a run report shows, formatted; the templates only arrange it."""
    mp = result.mass_properties
    shown = verdict(result)
    return {
        "result": result,
        "title": f"{result.bat} \u2014 {result.protocol}",
        "kind": TITLE,
        "metric_name": fmt.metric_name(result.metric),
        "verdict": shown,
        "barrel_note": barrel_note(result),
        "header": header_rows(result),
        "header_table": Table(["Item", "Value"], [list(r) for r in header_rows(result)]),
        "date": fmt.created(result.created),
        "pivot": fmt.quantity(mp.pivot, "length"),
        "inputs": result.inputs,
        "notes": fmt.paragraphs(result.protocol_notes),
        "warnings": list(result.warnings),
        "conditions": conditions_table(result),
        "metrics": metrics_table(result),
        "locations": locations_table(result),
        "energy": energy_table(result),
        "mass": mass_table(result),
        "bat": bat_table(result),
        "reconciliation": mp.reconciliation,
        "corrections": corrections_table(result),
        "engine": engine_table(result),
        "modes": modes_table(result),
        "print_header": f"{result.bat} \u2014 {result.protocol} \u2014 {shown.label}",
        "show_metric_plot": shows_metric_plot(result),
        "uncertainty": uncertainty_view(result),
        "compression": compression_table(result),
        "break_in": break_in_view(result),
    }
