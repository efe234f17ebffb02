"""The lab certificate (``batcert reduce``): everything its Markdown and HTML show, formatted
once: the certified value beside its limit with its interval, the uncertainty budget, the
decision rule, the location scan and every hit with its validity."""

from __future__ import annotations

from typing import Any

from batcert.reports import format as fmt
from batcert.reports.barrel_view import history_table
from batcert.reports.compare_view import VERDICT_BADGES, badge
from batcert.reports.figure import LineFigure
from batcert.reports.svg import Point, Series, VLine
from batcert.reports.table import Badge, Table
from batcert.results.lab import CERTIFICATE_FIELDS, LabResult, certificate_values
from batcert.units import FAST_UNITS, INCH


def _v(x: float | None, digits: int = 4) -> str:
    return fmt.DASH if x is None else f"{x:.{digits}f}"


def lab_figures(result: LabResult) -> list[LineFigure]:
    """The metric of every hit against its distance from the tip, the location means and the
    certified value with its 95 % interval."""
    m = result.metric.replace("-", "_")  # the LabHit field of the protocol's metric
    valid = [h for h in result.hits if h.valid]
    invalid = [h for h in result.hits if not h.valid]
    series = [Series("location mean (valid hits)",
                     [loc.from_tip / INCH for loc in result.scan if loc.mean is not None],
                     [loc.mean for loc in result.scan if loc.mean is not None])]
    if result.model:
        series.append(Series(f"model ({result.model['engine']} engine)",
                             [x / INCH for x in result.model["from_tip"]],
                             result.model["metric"]))
    points = [Point(h.from_tip / INCH, getattr(h, m), 0) for h in valid]
    points += [Point(h.from_tip / INCH, getattr(h, m), 1, "invalid") for h in invalid]
    hlines = []
    if result.limit is not None:
        hlines.append((result.limit + result.tolerance, f"limit {result.limit:g}"))
    if result.value is not None:
        hlines += [(result.value + result.expanded, ""),  # unlabelled: the caption says
                   (result.value - result.expanded, "")]  # (a label would sit on the limit's)
    vlines = [] if result.location_from_tip is None else [
        VLine(result.location_from_tip / INCH, "certified location")]
    word = fmt.metric_word(result.metric)
    return [LineFigure("hits", f"Measured {word} of every hit against its location", "impact "
                       "location from the tip [in]", f"{word} [-]", series, points=points,
                       point_legend="hit", hlines=hlines, vlines=vlines,
                       caption="Each circle is a hit (invalid hits marked); the line joins the "
                       "locations' means; the labelled dashed line is the limit, the two "
                       "unlabelled ones the certified value's 95 % interval (value \u00b1 U); "
                       "the other line is the model's prediction of the same test.")]


def lab_view(result: LabResult, charts: bool = True) -> dict[str, Any]:
    """Everything the lab certificate shows, formatted; the templates only arrange it."""
    from markupsafe import Markup

    from batcert.reports.figure import svg_of
    verdict = badge(VERDICT_BADGES, result.verdict) if result.verdict else \
        Badge("NO VERDICT", "warn")
    word = fmt.metric_word(result.metric)
    figs = lab_figures(result)
    return {"result": result, "title": f"Lab certificate: {result.bat}, {result.protocol}",
            "page_title": f"Lab certificate: {result.bat} \u2014 batcert", "badge": verdict,
            "sentence": _sentence(result, word), "record": certificate_record(result),
            "signatures": result.lab.get("signatures") or [],
            "facts": _facts(result),
            "budget": _budget(result), "scan": _scan(result, word), "hits": _hits(result),
            "warnings": result.warnings, "inputs": result.inputs,
            "figures": [{"svg": Markup(svg_of(f)) if charts else "", "caption": f.caption,
                         "title": f.title} for f in figs],
            "break_in": None if result.break_in is None else {
                "outcome": result.break_in.outcome, "source": result.break_in.source,
                "history": history_table(result.break_in)},
            "date": fmt.created(result.created),
            "print_header": " \u2014 ".join(x for x in (
                result.lab.get("certificate_number"), result.bat, result.protocol,
                (result.verdict or "no verdict").upper()) if x)}


def _sentence(result: LabResult, word: str) -> str:
    """The certificate in one sentence: the value, its interval, the limit and the verdict."""
    if result.value is None:
        return "No value can be certified: " + "; ".join(result.warnings)
    return (f"Measured {word} {result.value:.4f} \u00b1 {result.expanded:.4f} (expanded "
            f"uncertainty, 95 % coverage, k = {result.coverage_factor:.2f})"
            + (f" against the limit {result.limit:g}" if result.limit is not None else "")
            + (f": {result.verdict.upper()} under {result.decision_rule} acceptance"
               if result.verdict else "") + ".")


MISSING = "MISSING"  # a certificate field the session does not give: shown, never left out


def certificate_record(result: LabResult) -> Table:
    """The certificate's record (ISO/IEC 17025:2017, 7.8) from the session's ``lab:`` block,
    every field in :data:`~batcert.results.lab.CERTIFICATE_FIELDS` order, MISSING where not
    given (:func:`~batcert.results.lab.certificate_values`: the method defaults to the
    protocol file's reference and version, the place to the laboratory's address)."""
    values = certificate_values(result.lab, result.protocol_reference, result.protocol_version)
    rows = [[f.word, _record_value(values[f.key], f.parts), f.clause] for f in CERTIFICATE_FIELDS]
    return Table(["item", "value", "ISO/IEC 17025"], rows, [False, False, False])


def _record_value(value: Any, parts: tuple[tuple[str, str], ...]) -> str:
    if value in (None, "", []):
        return MISSING
    if isinstance(value, list) and parts:  # equipment: one entry per instrument
        return "; ".join(f"{item.get('name')} (" + _parts(item, parts) + ")" for item in value)
    if isinstance(value, list):
        return "; ".join(map(str, value))
    if parts:
        return _parts(value, parts)
    return str(value)


def _parts(item: dict, parts: tuple[tuple[str, str], ...]) -> str:
    return ", ".join(f"{word} {item.get(k) or MISSING}" for k, word in parts)


def _facts(result: LabResult) -> list[tuple[str, str]]:
    """The test: session, bat, protocol, decision rule, certified location, the model beside
    the measurement, the barrel calibration, the bat's MOI and the ball's mass."""
    return [
        ("Session", f"{result.session} ({result.session_path})"), ("Bat", result.bat),
        *([("Bat identification", fmt.identification(result.bat_identification))]
          if result.bat_identification else []),
        ("Protocol", f"{result.protocol}: {result.protocol_title}"),
        ("Values", "measured (reduced from the hits), not computed by the model"),
        ("Decision rule", result.decision_rule_text),
        ("Certified location", fmt.DASH if result.location_from_tip is None else
         f"{result.location_from_tip / INCH:.2f} in from the tip"),
        ("Hits averaged", ", ".join(f"{h:g}" for h in result.hits_used) or fmt.DASH),
        ("Conformance probability", fmt.DASH if result.conformance_probability is None else
         f"{result.conformance_probability:.4f} (JCGM 106: the probability that the true value "
         "is within the limit, Monte Carlo)"),
        ("Margin", fmt.DASH if result.margin is None else f"{result.margin:+.4f} "
         f"({result.decision_rule} acceptance)"),
        ("Model (same bat, ball and test)", _model_fact(result)),
        ("Barrel calibrated from the hits", _barrel_fact(result)),
        ("Ball lot of the model", lot_fact(result.lot_calibration)),
        ("Bat MOI about the pivot", f"{result.moi_pivot:.6f} kg m\u00b2 ({result.moi_source}); "
         f"pivot {result.pivot / INCH:.2f} in from the knob"),
        ("Ball mass", f"{result.ball_mass * 1000:.2f} g"),
        ("Date", fmt.created(result.created)), ("batcert version", result.batcert_version)]


def _model_fact(result: LabResult) -> str:
    """The model's prediction of the same test beside the measured value."""
    if not result.model:
        return fmt.DASH
    return (f"{result.model['engine']} engine: {_v(result.model['at_certified_location'])} at "
            f"the certified location, measured minus model {_v(result.model['difference'])}; "
            f"the model's own result {_v(result.model['value'])} at "
            f"{result.model['location_from_tip'] / INCH:.2f} in from the tip"
            + ("" if result.model.get("barrel_calibrated") is not False else
               " (the model's barrel is not calibrated by a measurement)"))


def lot_fact(lot: dict[str, Any]) -> str:
    """The ball lot the model, the barrel calibration and the BPF use, and what calibrated it
    (:attr:`~batcert.results.lab.LabResult.lot_calibration`)."""
    if not lot:
        return fmt.DASH
    if not lot.get("calibrated"):
        return f"{lot['ball']}, as its ball tests give it (not calibrated on a reference bat)"
    where = (f"this session's reference bat, session {lot['reference_session']}"
             if lot["calibrated_on"] == "session" else "the ball file's reference bat")
    return (f"{lot['ball']}, CALIBRATED (an input) on {where}: {lot['reference_bat']} under "
            f"{lot['protocol']}, {lot['value']:.4f} \u00b1 {lot['uncertainty']:.4f} (standard "
            f"uncertainty; {lot['source']}); the lot's COR tests moved {lot['shift']:+.2f} "
            f"\u00b1 {lot['u_shift']:.2f} standard uncertainties. The measured values do not "
            "depend on it")


def _barrel_fact(result: LabResult) -> str:
    """The barrel stiffnesses calibrated from the hits."""
    if not result.barrel_fits:
        return fmt.DASH
    return ("; ".join(f"stiffness x{f['scale']:.3f} \u00b1 {f['u_scale']:.3f} (equivalent hoop "
                      f"frequency {f['hoop_frequency']:.0f} \u00b1 {f['u_hoop_frequency']:.0f} "
                      "Hz)" for f in result.barrel_fits)
            + ": the model then meets the measured value at the certified location (one point, "
            "not the whole scan); --write-calibration writes it into a copy of the bat file")


def _budget(result: LabResult) -> Table:
    """The uncertainty budget: type A, each type B, combined, expanded, the Monte Carlo."""
    return Table(["component", "standard uncertainty", "degrees of freedom"],
                 [["type A: scatter of the hits averaged", _v(result.u_a, 5),
                   f"{len(result.hits_used) - 1}"]]
                 + [[f"type B: {k}", _v(v, 5), "\u221e"] for k, v in result.u_b.items()]
                 + [["combined u_c", _v(result.u_c, 5),
                     "\u221e" if result.dof is None else f"{result.dof:.1f}"],
                    [f"expanded U = {result.coverage_factor:.3f} u_c (95 %)",
                     _v(result.expanded, 5), ""],
                    [f"Monte Carlo (JCGM 101, {result.mc_draws} draws): standard deviation",
                     _v(result.mc_std, 5), ""],
                    ["Monte Carlo 95 % interval", fmt.DASH if not result.mc_interval else
                     f"{result.mc_interval[0]:.4f} to {result.mc_interval[1]:.4f}", ""]],
                 [False, True, True])


def _scan(result: LabResult, word: str) -> Table:
    """The location scan: each location's hits, valid hits, mean and standard deviation."""
    return Table(["from tip [in]", "hits", "valid", f"mean {word}", "std"],
                 [[f"{loc.from_tip / INCH:.2f}", ", ".join(f"{h:g}" for h in loc.hits),
                   str(loc.valid_hits), _v(loc.mean), _v(loc.std)] for loc in result.scan],
                 [True, False, True, True, True])


def _hits(result: LabResult) -> Table:
    """Every hit: its measurements, its reduced values, its validity and use."""
    u = result.speed_unit  # the lab's own unit (the JSON keeps m/s)
    f = FAST_UNITS["speed"].get(u, 1.0)
    return Table(["hit", "ball", "line", f"v_i [{u}]", f"v_r [{u}]", "from tip [in]", "e_A", "k",
                  "BBCOR", "BESR", "BPF", "valid", "used", "reasons"],
                 [[f"{h.hit:g}", h.ball, str(h.line), f"{h.inbound_speed / f:.2f}",
                   f"{h.rebound_speed / f:.2f}", f"{h.from_tip / INCH:.3f}",
                   _v(h.collision_efficiency), _v(h.recoil_factor), _v(h.bbcor), _v(h.besr),
                   _v(h.bpf), "yes" if h.valid else "NO", "yes" if h.used else "",
                   "; ".join(h.reasons)] for h in result.hits],
                 [True, False, True, True, True, True, True, True, True, True, True, False,
                  False, False])
