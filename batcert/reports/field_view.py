"""The in-play report (``batcert field``): everything its Markdown, HTML and terminal views show,
formatted once, and its figures."""

from __future__ import annotations

import math
from typing import Any

from batcert.reports import format as fmt
from batcert.reports.figure import Figure, LineFigure
from batcert.reports.svg import Series
from batcert.reports.table import Table
from batcert.results.field import RANGE_SCENARIOS, FieldBat, FieldBatter, FieldResult
from batcert.units import FOOT as FT
from batcert.units import INCH, MPH, OUNCE, Display

OZ_IN2 = OUNCE * INCH**2
PREDICTION = ("Model prediction from the bat, ball and batter files (swing law, impact engine, "
              "trajectory), not a measurement.")


def prediction(result: FieldResult) -> str:
    """What the numbers are (the model's), with the model's known offset for them."""
    if not result.model_offset:
        return PREDICTION
    return f"{PREDICTION} Known offset of the model: {result.model_offset}."


def gain_speed(v: float) -> str:
    return f"{v / MPH:+.1f} mph"


def distance(d: float) -> Display:
    return Display(f"{d:.1f} m", f"{d / FT:.0f} ft")


def gain_distance(d: float) -> str:
    return f"{d / FT:+.0f} ft"


def inches(x: float) -> Display:
    return Display(f"{x * 1000:.0f} mm", f"{x / INCH:.2f} in")


def _range(b: FieldBat, field: str, show) -> str:
    values = [getattr(b.outcome(s), field) for s in RANGE_SCENARIOS]
    return f"{show(min(values))} to {show(max(values))}"


def _nominal_table(fb: FieldBatter) -> Table:
    t = Table(["Bat", "MOI about the swing axis", "Swing speed at 6 in from the tip",
               "Best batted-ball speed", "Sweet spot from the tip", "Sweet zone (1 mph)",
               "Sweet zone (5 mph)", "e_A in play", "Carry", "Gain over reference",
               "Gain range (swing law)"], numeric=[False] + [True] * 10)
    for b in fb.bats:
        o = b.outcome("nominal")
        zone5 = inches(o.sweet_zone_5mph)
        if o.zone_open:
            zone5 = Display("\u2265 " + zone5.si, "\u2265 " + str(zone5.us))
        gain = ("reference" if b.is_reference else
                f"{gain_speed(o.gain_exit_speed)}, {gain_distance(o.gain_distance)}")
        spread = ("" if b.is_reference else
                  f"{_range(b, 'gain_exit_speed', gain_speed)}; "
                  f"{_range(b, 'gain_distance', gain_distance)}")
        t.rows.append([b.bat, Display(f"{b.moi_axis:.4f} kg m^2", f"{b.moi_axis / OZ_IN2:,.0f} "
                                      "oz in^2"),
                       fmt.quantity(o.swing_speed, "speed", 1), fmt.quantity(o.best_exit_speed, "speed", 1),
                       inches(o.sweet_spot), inches(o.sweet_zone_1mph), zone5,
                       fmt.plain(o.collision_efficiency, 3), distance(o.distance), gain, spread])
    return t


def _constant_table(fb: FieldBatter) -> Table:
    t = Table(["Bat", "Exponent", "Swing speed at 6 in", "Best batted-ball speed", "Carry",
               "Gain over reference"], numeric=[False, True, True, True, True, True])
    for b in fb.bats:
        for s in ("constant-swing", "nominal"):
            o = b.outcome(s)
            gain = ("reference" if b.is_reference else
                    f"{gain_speed(o.gain_exit_speed)}, {gain_distance(o.gain_distance)}")
            t.rows.append([b.bat, f"n = {o.exponent:.2f}", fmt.quantity(o.swing_speed, "speed", 1),
                           fmt.quantity(o.best_exit_speed, "speed", 1), distance(o.distance), gain])
    return t


def terminal_tables(result: FieldResult) -> list[tuple[str, Table]]:
    """Per batter profile, the bats' headline numbers in mph, inches and feet (the terminal)."""
    out = []
    for fb in result.batters:
        t = Table(["bat", "swing\n[mph]", "best exit\n[mph]", "zone 1 / 5 mph\n[in]",
                   "carry\n[ft]", "gain\n[mph, ft]", "gain at n = 0\n[mph, ft]"],
                  numeric=[False] + [True] * 6)
        for b in fb.bats:
            o, c = b.outcome("nominal"), b.outcome("constant-swing")
            t.rows.append([b.bat, f"{o.swing_speed / MPH:.1f}", f"{o.best_exit_speed / MPH:.1f}",
                           f"{o.sweet_zone_1mph / INCH:.2f} / {o.sweet_zone_5mph / INCH:.2f}"
                           + ("+" if o.zone_open else ""), f"{o.distance / FT:.0f}",
                           "reference" if b.is_reference else
                           f"{o.gain_exit_speed / MPH:+.1f}, {o.gain_distance / FT:+.0f}",
                           "reference" if b.is_reference else
                           f"{c.gain_exit_speed / MPH:+.1f}, {c.gain_distance / FT:+.0f}"])
        out.append((f"{fb.batter} \u2014 {fb.name}: pitch {fb.pitch_speed / MPH:.0f} mph, "
                    f"n = {fb.exponent:.2f}", t))
    return out


def ranking(fb: FieldBatter, scenario: str) -> str:
    """The bats from the hardest-hitting down, by best batted-ball speed."""
    order = sorted(fb.bats, key=lambda b: -b.outcome(scenario).best_exit_speed)
    return " > ".join(f"{b.bat} ({b.outcome(scenario).best_exit_speed / MPH:.1f} mph)"
                      for b in order)


def field_figures(result: FieldResult) -> list[Figure]:
    """Per batter: batted-ball speed and carry along the barrel, one line per bat."""
    figs: list[Figure] = []
    def series(fb: FieldBatter, field: str, scale: float) -> list[Series]:
        return [Series(b.bat, [x / INCH for x in b.along.from_tip],
                       [y / scale for y in getattr(b.along, field)]) for b in fb.bats]

    for fb in result.batters:
        figs.append(LineFigure(
            f"{fb.batter}-exit-speed", f"Batted-ball speed along the barrel: {fb.name}",
            "Impact location from the tip [in]", "Batted-ball speed [mph]",
            series(fb, "exit_speed", MPH), caption=f"{fb.name}: each bat swung at the speed its "
            "MOI allows (nominal swing law); model prediction."))
        figs.append(LineFigure(
            f"{fb.batter}-carry", f"Carry along the barrel: {fb.name}",
            "Impact location from the tip [in]", "Carry [ft]", series(fb, "distance", FT),
            caption=f"{fb.name}: launched at {math.degrees(result.launch_angle):.0f} deg; model "
            "prediction."))
    return figs


def _batter_view(fb: FieldBatter, first: str) -> dict[str, Any]:
    u_v = f" \u00b1 {fb.bat_speed_uncertainty / MPH:.1f} mph" if fb.bat_speed_uncertainty else ""
    n_u = f" \u00b1 {fb.exponent_uncertainty:.2f}" if fb.exponent_uncertainty else ""
    return {
        "id": fb.batter, "name": fb.name, "path": fb.path, "sha256": fb.sha256,
        "facts": [
            ("Bat speed", f"{fb.bat_speed / MPH:.1f} mph{u_v} at {fb.speed_from_tip / INCH:.0f} "
             f"in from the tip of a {fb.reference_length / INCH:.0f} in bat of "
             f"{fb.reference_moi / OZ_IN2:,.0f} oz in^2 about the swing axis"),
            ("Swing law", f"w = C / I^n about an axis {fb.axis_from_knob / INCH:.1f} in from the "
             f"knob, n = {fb.exponent:.2f}{n_u}"),
            ("Pitch speed", f"{fb.pitch_speed / MPH:.1f} mph"),
            ("Ball", f"{fb.ball} ({fb.body})"),
            ("Swing source", fb.swing_source), ("Pitch source", fb.pitch_source)],
        "nominal": _nominal_table(fb), "constant": _constant_table(fb),
        "ranking_n": ranking(fb, "nominal"), "ranking_0": ranking(fb, "constant-swing"),
        "exponent": f"{fb.exponent:.2f}",
        "slopes": (f"For {first}: +1 mph of swing speed gives {fb.exit_per_bat_speed:+.2f} mph "
                   f"of batted-ball speed, +1 mph of pitch {fb.exit_per_pitch_speed:+.2f} mph; "
                   f"the best-hit ball carries {fb.distance_per_exit_speed * MPH / FT:.1f} ft "
                   "farther per mph of batted-ball speed."),
    }


def field_view(result: FieldResult, charts: bool = True) -> dict[str, Any]:
    """Everything the in-play report shows, formatted; the templates only arrange it."""
    from markupsafe import Markup

    from batcert.reports.figure import svg_of
    first = result.batters[0].bats[0].bat if result.batters else ""
    bats = result.batters[0].bats if result.batters else []
    inputs = [{"role": "reference bat" if b.is_reference else "bat", "name": b.bat,
               "path": b.path, "sha256": b.sha256} for b in bats]
    inputs += [{"role": "batter", "name": fb.name, "path": fb.path, "sha256": fb.sha256}
               for fb in result.batters]
    figures = [{"svg": Markup(svg_of(f)) if charts else "", "caption": f.caption,
                "name": f.name} for f in field_figures(result)]
    views = [_batter_view(fb, first) for fb in result.batters]
    for v in views:
        v["figures"] = [f for f in figures if f["name"].startswith(f"{v['id']}-")]
    return {
        "result": result, "page_title": f"In play against {result.reference} \u2014 batcert",
        "title": f"In play: {', '.join(b.bat for b in bats if not b.is_reference)} against "
                 f"{result.reference}",
        "sentence": prediction(result),
        "facts": [
            ("Reference bat", result.reference), ("Engine", f"{result.engine}, free bat"),
            ("Launch", f"{math.degrees(result.launch_angle):.1f} deg, backspin "
             f"{result.backspin * 30 / math.pi:.0f} rpm, sidespin "
             f"{result.sidespin * 30 / math.pi:.0f} rpm ({result.spin_source})"),
            ("Air", f"{result.air_density:.4f} kg/m^3 ({result.temperature - 273.15:.1f} C, "
             f"{result.elevation:.0f} m elevation, {result.relative_humidity:.0%} humidity)"),
            ("Impact locations", f"{result.window_from_tip[0] / INCH:.1f}-"
             f"{result.window_from_tip[1] / INCH:.1f} in from the tip"),
            ("Date", fmt.created(result.created)),
            ("batcert version", result.batcert_version)],
        "batters": views,
        "inputs": inputs, "warnings": list(result.warnings),
        "date": fmt.created(result.created),
    }
