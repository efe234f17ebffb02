"""The sweep and design report: everything its Markdown and HTML show, formatted once.

:func:`sweep_view` turns a :class:`~batcert.results.sweep.SweepResult` into tables of display
cells and the figures (:func:`sweep_figures`, also written by ``--figures``); the templates
``sweep.md.j2`` and ``sweep.html.j2`` only arrange them.
"""

from __future__ import annotations

from typing import Any

from batcert.reports import format as fmt
from batcert.reports.compare_view import VERDICT_BADGES, badge
from batcert.reports.figure import Figure, LineFigure
from batcert.reports.svg import Point, Series, VLine
from batcert.reports.sweep_axes import axis_label, axis_value, column_label, words
from batcert.reports.sweep_axes import x_values as _x
from batcert.reports.table import Table
from batcert.results.sweep import SweepResult

MAX_ROWS = 400  # table rows shown in a report; the JSON holds every variant
METRIC_PLOTS = {"exit_speed": ("Exit speed", "m/s"), "cor": ("Ball-bat COR", "-"),
                "bpf": ("BPF", "-"), "besr": ("BESR", "-"), "bbcor": ("BBCOR", "-"),
                "collision_efficiency": ("Collision efficiency e_A", "-")}


def _groups(result: SweepResult) -> list[tuple[str, list[int]]]:
    """The variants of each line of a figure: all of them (one axis), or one group per value
    of the second axis (a grid), each in order of the first axis."""
    n = len(result.points)
    if len(result.axes) == 1:
        return [("", list(range(n)))]
    second = result.axes[1]
    return [(f"{words(second)} {axis_value(second, v).si}",
             [i for i in range(n) if result.points[i][1] == v]) for v in second.values]


def _series(result: SweepResult, values: list[float | None], name: str,
            alone: str = "") -> list[Series]:
    """One series per line of a figure, named ``name`` and the line's group; ``alone`` names
    it where both are empty."""
    first = result.axes[0]
    out = []
    for label, idx in _groups(result):
        xs = _x(first, [result.points[i][0] for i in idx])
        ys = [values[i] for i in idx]
        out.append(Series(" ".join(x for x in (name, label) if x) or alone or result.metric,
                          xs, [float("nan") if y is None else y for y in ys]))
    return out


def sweep_figures(result: SweepResult) -> list[Figure]:
    """The protocol's metric, every metric per condition, the sweet spot and COP (with Eq. 7's
    rigid sweet spot where defined) and the mass properties, against the first parameter."""
    figs: list[Figure] = [_metric_figure(result)]
    figs += _condition_figures(result)
    figs.append(_sweet_spot_figure(result))
    if any(a.changes != "protocol" for a in result.axes):
        figs += _mass_figures(result)
    if result.design is not None:
        figs.append(_margin_figure(result))
    return figs


def _metric_figure(result: SweepResult) -> LineFigure:
    """The protocol's result against the first parameter, with the plausible barrel's range
    (one axis), the limit and the nominal bat as measured."""
    first = result.axes[0]
    metric = fmt.metric_name(result.metric)
    limit = [] if result.limit is None else [(result.limit + result.tolerance,
                                              f"limit {result.limit + result.tolerance:g}")]
    ranged = any(v is not None for v in result.series["value_low"])
    series = _series(result, result.series["value"], "nominal barrel" if ranged else "")
    if ranged and len(result.axes) == 1:
        series += _series(result, result.series["value_low"], "plausible barrel: low")
        series += _series(result, result.series["value_high"], "plausible barrel: high")
    nominal = _nominal_point(result)
    return LineFigure(
        "metric", f"{metric} ({result.aggregate}) against {words(first)}", axis_label(first),
        f"{metric} [{'m/s' if result.metric == 'exit-speed' else '-'}]", series,
        caption=f"The protocol's result against {words(first)}"
        + ("; the dashed line is its limit" if limit else "")
        + ("; the circle is the nominal bat with its measurements" if nominal else "") + ".",
        hlines=limit, points=nominal, point_legend="nominal bat as measured" if nominal else "",
        vlines=[] if first.nominal is None else [VLine(_x(first, [first.nominal])[0],
                                                        "nominal")])


def _nominal_point(result: SweepResult) -> list[Point]:
    """The nominal bat as measured, on its line (on a grid, that of the second axis's nominal
    value); none where it has no value or is off the figure's lines."""
    first = result.axes[0]
    line = 0
    if len(result.axes) == 2:
        second = result.axes[1]
        line = second.values.index(second.nominal) if second.nominal in second.values else -1
    if result.nominal is not None and result.nominal.value is not None \
            and first.nominal is not None and line >= 0:
        return [Point(_x(first, [first.nominal])[0], result.nominal.value, line, "as measured")]
    return []


def _condition_figures(result: SweepResult) -> list[Figure]:
    """One figure per metric of :data:`METRIC_PLOTS`, a line per condition."""
    first = result.axes[0]
    named = len(result.conditions) > 1  # a condition's name only where there are several
    figs: list[Figure] = []
    for key, (word, unit) in METRIC_PLOTS.items():
        lines = [s for c in result.conditions
                 for s in _series(result, c.series[key], c.name if named else "", word)]
        figs.append(LineFigure(key.replace("_", "-"), f"{word} against {words(first)}",
                               axis_label(first), f"{word} [{unit}]", lines,
                               caption=f"{word} at the impact point of each condition."))
    return figs


def _sweet_spot_figure(result: SweepResult) -> LineFigure:
    """The sweet spot, the COP and Eq. 7's rigid sweet spot of each condition."""
    first = result.axes[0]
    spots = []
    for c in result.conditions:
        spots += _series(result, c.series["sweet_spot"], f"{c.name}: sweet spot")
        spots += _series(result, c.series["cop"], f"{c.name}: COP")
        if c.rigid_applies:
            spots += _series(result, c.series["rigid_sweet_spot"],
                             f"{c.name}: rigid sweet spot (Eq. 7)")
    return LineFigure("sweet-spot", f"Sweet spot and COP against {words(first)}",
                      axis_label(first), "distance from the pivot [m]", spots,
                      caption="Sweet spot (maximum exit speed), centre of percussion "
                      "(Eq. 4) and, where the speeds are fixed and the bat swings, the "
                      "rigid-bat sweet spot (Smith 2001 Eq. 7).")


def _mass_figures(result: SweepResult) -> list[Figure]:
    """The bat's mass and MOI about the pivot."""
    first = result.axes[0]
    x_label = axis_label(first)
    return [LineFigure("mass", f"Mass against {words(first)}", x_label, "mass [kg]",
                       _series(result, result.series["mass"], "mass")),
            LineFigure("moi", f"MOI about the pivot against {words(first)}", x_label,
                       "MOI [kg m²]", _series(result, result.series["moi_pivot"], "MOI"))]


def _margin_figure(result: SweepResult) -> LineFigure:
    """A design's margin to the limit, with its roots."""
    assert result.design is not None
    first = result.axes[0]
    roots = [VLine(_x(first, [r.value])[0], f"root {axis_value(first, r.value).si}")
             for r in result.design.roots]
    return LineFigure("margin", f"Margin to the limit against {words(first)}", axis_label(first),
                      f"margin [{'m/s' if result.metric == 'exit-speed' else '-'}]",
                      _series(result, result.series["margin"], "margin"), hlines=[(0.0, "limit")],
                      vlines=roots, caption="Margin = limit + tolerance - value; "
                      "the protocol passes where it is at least zero.")


def _rows(result: SweepResult) -> list[int]:
    n = len(result.points)
    if n <= MAX_ROWS:
        return list(range(n))
    import numpy as np
    return sorted({int(i) for i in np.linspace(0, n - 1, MAX_ROWS).round()})


def _summary_table(result: SweepResult) -> Table:
    m = result.metric
    ranged = any(v is not None for v in result.series["value_low"])
    head = [column_label(a) for a in result.axes] + [fmt.metric_word(m)]
    head += ["plausible barrel"] if ranged else []
    head += ["margin", "verdict"] if result.limit is not None else []
    head += ["mass [kg]", "MOI [kg m²]", "hoop [Hz]"]
    rows = []
    for i in _rows(result):
        s = result.series
        row: list[Any] = [axis_value(a, result.points[i][k]) for k, a in enumerate(result.axes)]
        if result.errors[i]:
            rows.append(row + [f"no result: {result.errors[i]}"] + [""] * (len(head) - len(row) - 1))
            continue
        row.append(fmt.metric_value(s["value"][i], m))
        if ranged:
            row.append(f"{fmt.metric_value(s['value_low'][i], m).si} to "
                       f"{fmt.metric_value(s['value_high'][i], m).si}")
        if result.limit is not None:
            row += [fmt.metric_value(s["margin"][i], m, signed_=True),
                    badge(VERDICT_BADGES, result.verdicts[i])]
        row += [fmt.plain(s["mass"][i], 4), fmt.plain(s["moi_pivot"][i], 5),
                fmt.plain(s["hoop_frequency"][i], 0)]
        rows.append(row)
    return Table(head, rows, [True] * len(head))


def _condition_table(result: SweepResult, k: int) -> Table:
    c = result.conditions[k]
    keys = ["exit_speed", "cor", "bpf", "besr", "bbcor", "collision_efficiency",
            "impact_location", "sweet_spot", "cop", "rigid_sweet_spot"]
    head = [column_label(a) for a in result.axes] + [
        "exit speed [m/s]", "COR", "BPF", "BESR", "BBCOR", "e_A", "impact [m]",
        "sweet spot [m]", "COP [m]", "Eq. 7 [m]"]
    rows = []
    for i in _rows(result):
        if result.errors[i]:
            continue
        rows.append([axis_value(a, result.points[i][j]) for j, a in enumerate(result.axes)]
                    + [fmt.plain(c.series[key][i], 2 if key == "exit_speed" else 4)
                       for key in keys])
    return Table(head, rows, [True] * len(head))


def _facts(result: SweepResult) -> list[tuple[str, str]]:
    facts = [("Bat", f"{result.bat} ({result.bat_path})"),
             *([("Bat identification", fmt.identification(result.bat_identification))]
               if result.bat_identification else []),
             ("Protocol", f"{result.protocol}: {result.protocol_title}"),
             ("Metric", f"{fmt.metric_name(result.metric)}, {fmt.aggregate_word(result.aggregate)}"
                        f" of {len(result.conditions)} condition"
                        f"{'s' if len(result.conditions) != 1 else ''}"),
             ("Limit", fmt.DASH if result.limit is None else
              f"{fmt.metric_value(result.limit, result.metric)} (tolerance {result.tolerance:g})")]
    for a in result.axes:
        facts.append((f"Varied: {a.name}", f"{len(a.values)} values, "
                      f"{axis_value(a, a.values[0])} to {axis_value(a, a.values[-1])}; nominal "
                      + (fmt.DASH if a.nominal is None else axis_value(a, a.nominal).si)))
    facts += [("Variants", f"{len(result.points)} ({sum(e is None for e in result.errors)} with "
                           "a result)"),
              ("Engine", result.engine + "".join(f"; {k} {v}" for k, v in
                                                 result.engine_settings.items()
                                                 if k != "engine")),
              ("Date", fmt.created(result.created)), ("batcert version", result.batcert_version)]
    return facts


def _drop(length: float | None, mass: float | None) -> str:
    """A bat's drop (length in inches minus weight in ounces), as league rules read it."""
    from batcert.units import INCH, OUNCE
    if length is None or mass is None:
        return fmt.DASH
    return fmt.signed(f"{length / INCH - mass / OUNCE:.2f}")


def design_statement(result: SweepResult) -> str:
    """The design's answer in words: where the protocol passes and where the limit is met."""
    assert result.design is not None
    axis, roots = result.axes[0], result.design.roots
    name = axis.name
    ms = [m for m in result.series["margin"] if m is not None]

    def at(x: float) -> str:
        d = axis_value(axis, x)
        return f"{d.si} ({d.us})" if d.us else d.si

    lo, hi = axis.values[0], axis.values[-1]
    if not roots:
        if not ms:
            return f"No {name} in the range has a result."
        word = "passes" if ms[0] >= 0 else "fails"
        return (f"No {name} from {at(lo)} to {at(hi)} meets the limit: the protocol {word} "
                f"over the whole range (margin {min(ms):+.4g} to {max(ms):+.4g}); widen the "
                "range with --range")
    edges = [lo] + [r.value for r in roots] + [hi]
    first_passes = not roots[0].passes_above
    parts = []
    for k in range(len(edges) - 1):
        if (k % 2 == 0) == first_passes:
            a = "the start of the range searched, " if k == 0 else ""
            b = ", the end of the range searched" if k == len(edges) - 2 else ""
            parts.append(f"from {a}{at(edges[k])} to {at(edges[k + 1])}{b}")
    text = (f"The protocol passes for {name} " + " and ".join(parts)) if parts else \
        f"The protocol passes for no {name} in the range"
    def bat(r) -> str:  # the bat there, as a league rule reads it
        if r.mass is None:
            return ""
        return f" (mass {fmt.quantity(r.mass, 'mass')}, drop {_drop(r.length, r.mass)})"
    return text + f"; the limit is met at {', '.join(at(r.value) + bat(r) for r in roots)}"


def nominal_sentence(result: SweepResult) -> str:
    """Why the variants differ from ``run`` on the same bat, where they do: geometric variants
    are built from the geometry alone (docs/sweeps.md), the bat as measured is reconciled to its
    measurements; "" when the sweep states no measured bat."""
    n = result.nominal
    if n is None or n.value is None:
        return ""
    measured = fmt.quantity(n.measured_mass, "mass") if n.measured_mass else "its measurements"
    verdict = f", {n.verdict}" if n.verdict else ""
    return (f"The variants are built from the bat's geometry (mass "
            f"{fmt.quantity(n.geometry_mass, 'mass')}); the bat as measured ({measured}) gives "
            f"{fmt.metric_name(result.metric)} {fmt.metric_value(n.value, result.metric)}"
            f"{verdict}, as `batcert run` does: the nominal variant is not that result.")


def headline(result: SweepResult) -> str:
    """One sentence: where the verdict changes, or the metric's range."""
    m, vals = result.metric, result.series["value"]
    got = [(i, v) for i, v in enumerate(vals) if v is not None]
    if not got:
        return "No variant has a result."
    lo = min(got, key=lambda t: t[1])
    hi = max(got, key=lambda t: t[1])
    text = (f"{fmt.metric_name(m)} ranges from {fmt.metric_value(lo[1], m)} to "
            f"{fmt.metric_value(hi[1], m)} over the {len(result.points)} variants")
    if result.limit is not None:
        n_pass = sum(v == "pass" for v in result.verdicts)
        text += f"; {n_pass} of {len(result.points)} pass"
    if result.design is not None:
        text += ". " + design_statement(result)
    return text + "."


def sweep_view(result: SweepResult, charts: bool = True) -> dict[str, Any]:
    """Everything the sweep report shows, formatted; the templates only arrange it. Without
    ``charts`` the figures have no SVG (:func:`with_charts` draws it)."""
    view = _plain_view(result)
    return with_charts(view) if charts else view


def with_charts(view: dict[str, Any]) -> dict[str, Any]:
    """``view`` (:func:`sweep_view` without charts) with its figures drawn: the Markdown and
    HTML reports of one write share the rest (:data:`batcert.reports.write` renders a set
    from one view: the 400-row tables of an 800-variant sweep are formatted once)."""
    from markupsafe import Markup

    from batcert.reports.figure import svg_of
    return {**view, "figures": [{**f, "svg": Markup(svg_of(fig))}
                                for f, fig in zip(view["figures"], view["figure_objects"],
                                                  strict=True)]}


def _plain_view(result: SweepResult) -> dict[str, Any]:
    figs = sweep_figures(result)
    nominal = None
    if result.nominal is not None:
        n = result.nominal
        nominal = [("value as measured", str(fmt.metric_value(n.value, result.metric))
                    + (f", {n.verdict}" if n.verdict else "")),
                   ("mass: geometry / measured", f"{n.geometry_mass:.4f} kg / "
                    + (f"{n.measured_mass:.4f} kg" if n.measured_mass else fmt.DASH)),
                   ("corrections of the measurements", n.reconciliation)]
    design = None
    if result.design is not None:
        d = result.design
        first = result.axes[0]
        design = {"statement": design_statement(result) + ".",
                  "table": Table(["root", "bracket", "evaluations", "passes",
                                  "mass at the root", "drop at the root [in - oz]"],
                                 [[axis_value(first, r.value),
                                   f"{axis_value(first, r.bracket[0]).si} to "
                                   f"{axis_value(first, r.bracket[1]).si}",
                                   str(r.evaluations), "above" if r.passes_above else "below",
                                   fmt.quantity(r.mass, "mass") if r.mass else fmt.DASH,
                                   _drop(r.length, r.mass)]
                                  for r in d.roots], [True, False, True, False, True, True]),
                  "tolerance": axis_value(first, d.tolerance).si}
    title = ("Design" if result.design else "Sweep") + f": {result.bat}, {result.protocol}, " \
        + " x ".join(a.name for a in result.axes)
    return {
        "result": result, "title": title, "page_title": f"{title} \u2014 batcert",
        "headline": headline(result), "facts": _facts(result), "notes": result.notes,
        "nominal": nominal, "design": design, "warnings": result.warnings,
        "summary": _summary_table(result),
        "conditions": [(c.name, _condition_table(result, k))
                       for k, c in enumerate(result.conditions)],
        "shown_rows": len(_rows(result)), "variants": len(result.points),
        "figures": [{"svg": "", "caption": f.caption, "title": f.title} for f in figs],
        "figure_objects": figs,
        "errors": [(i, e) for i, e in enumerate(result.errors) if e][:50],
        "inputs": result.inputs, "date": fmt.created(result.created),
    }
