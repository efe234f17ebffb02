"""``batcert field``: what a bat does in play for a batter like yours."""

from __future__ import annotations

import math

import click

from batcert import console
from batcert.cli.base import (
    ENVIRONMENT_EXIT_CODES,
    FIGURES_OPTION,
    _check_figures_dir,
    _Clock,
    _complete,
    _finish,
    _formats,
    _guard,
    _output_options,
    _report_dir,
    main,
)
from batcert.console import views

FIELD_EXIT_CODES = """\b
Exit codes:
  0  the prediction ran (it has no pass or fail)
  2  usage error (unknown bat, batter or engine; a value that cannot be read)
  3  invalid input (a spec file has errors; nothing is written)
""" + ENVIRONMENT_EXIT_CODES

_TEMPERATURE = {"f": lambda t: (t - 32) * 5 / 9 + 273.15, "c": lambda t: t + 273.15,
                "k": lambda t: t}


def _quantity(dimension: str, lo: float, hi: float):
    """A click callback reading ``85 mph`` / ``5280 ft`` into SI, within [lo, hi] (which may
    lie beyond what a bat's quantities take: a field's elevation)."""
    def read(ctx, param, value):
        if value is None:
            return None
        from batcert.units import UnitError, parse_quantity
        try:
            v = parse_quantity(value, dimension, largest=max(abs(lo), abs(hi)))
        except UnitError as exc:
            raise click.BadParameter(str(exc)) from None
        if not lo <= v <= hi:
            raise click.BadParameter(f"{value} is outside {lo:g} to {hi:g} (SI)")
        return v
    return read


def _temperature(ctx, param, value):
    text = value.strip().replace("\u00b0", "").replace(" ", "").lower()
    try:
        kelvin = _TEMPERATURE[text[-1]](float(text[:-1]))
    except (KeyError, ValueError, IndexError):
        raise click.BadParameter(f"cannot read {value!r}: give a number with F, C or K, "
                                 "e.g. 70F or 21C") from None
    # -43 to 57 C, ends included (issue 40: 57C itself was refused by a bound in kelvin)
    if not -43.0 - 1e-9 <= kelvin - 273.15 <= 57.0 + 1e-9:  # compared in C: 1e-9 of rounding
        raise click.BadParameter(f"{value} is outside -43 to 57 C")
    return kelvin


@main.command(epilog=FIELD_EXIT_CODES + """

\b
Examples:
  batcert field bbcor-alloy-34
  batcert field aluminium-34 --batter pro --reference ash-34
  batcert field bbcor-alloy-34 composite-bbcor-34 --batter all --elevation 5280ft
  batcert field fastpitch-alloy-33 --batter fastpitch --pitch 65mph --json""")
@click.argument("bats", nargs=-1, required=True, shell_complete=_complete("bat"))
@click.option("--batter", "-b", "batters", multiple=True, shell_complete=_complete("batter"),
              help="Batter profile (shipped: youth-12u, high-school, college, pro, fastpitch, "
                   "slowpitch; or a batter YAML path; 'all' for every shipped one); repeat for "
                   "several [default: college].")
@click.option("--reference", default=None, shell_complete=_complete("bat"),
              help="Reference bat the gains are measured from [default: ash-34].")
@click.option("--pitch", "pitch_speed", default=None, callback=_quantity("speed", 0.0, 60.0),
              help="Pitch speed, e.g. 85mph [default: each batter profile's].")
@click.option("--launch-angle", default=28.0, show_default=True,
              type=click.FloatRange(-10.0, 60.0), help="Launch angle [deg].")
@click.option("--backspin", default=None, type=click.FloatRange(-5000.0, 6000.0),
              help="Backspin [rpm] [default: the trajectory calculator's for the launch "
                   "angle].")
@click.option("--sidespin", default=None, type=click.FloatRange(-5000.0, 5000.0),
              help="Sidespin [rpm] [default: the calculator's, -849 rpm].")
@click.option("--elevation", default="0 ft", show_default=True,
              callback=_quantity("length", -500.0, 5000.0), help="Field elevation.")
@click.option("--temperature", default="70F", show_default=True, callback=_temperature,
              help="Air temperature (F, C or K).")
@_output_options("in-play prediction")
@FIGURES_OPTION
@_guard
def field(bats, batters, reference, pitch_speed, launch_angle, backspin, sidespin, elevation,
          temperature, engine, out_dir, formats, no_reports, as_json, figures_dir):
    """How hard and how far BATs hit for a batter profile, against a reference bat: each bat
    swung at the speed its moment of inertia allows (w = C / I^n), the batted-ball speed along
    the barrel, the sweet zone, e_A in play, and the carry of the best-hit ball, with the gains
    over the reference and their range over the swing law's uncertainty; also under a constant
    swing speed (n = 0). A model prediction, not a measurement."""
    from batcert.commands.field import FieldSettings, run_field
    from batcert.physics.trajectory import RPM
    fmts = _formats(formats)
    target = _report_dir(out_dir, no_reports, as_json)
    _check_figures_dir(figures_dir)
    clock = _Clock()
    settings = FieldSettings(
        launch_angle=math.radians(launch_angle),
        backspin=None if backspin is None else backspin * RPM,
        sidespin=None if sidespin is None else sidespin * RPM,
        temperature=temperature, elevation=elevation, pitch_speed=pitch_speed)
    with console.progress("swinging the bats"):
        result = run_field(list(bats), list(batters), reference, engine, settings)
    clock.lap("inputs and engine")
    _finish(result, views.field_summary, target, fmts, as_json, clock, figures_dir)
