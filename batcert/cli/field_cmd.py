"""``batcert field``: what a bat does in play for a batter like yours."""

from __future__ import annotations

import math

import click

from batcert import arguments as args
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

def _read(reader):
    """A click callback reading an option with ``reader`` (:mod:`batcert.arguments`, which the
    library uses too): its refusal is click's bad value (exit 2)."""
    def read(ctx, param, value):
        from batcert.arguments import ArgumentError
        try:
            return reader(value)
        except ArgumentError as exc:
            raise click.BadParameter(exc.reason) from None
    return read


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
@click.option("--pitch", "pitch_speed", default=None, callback=_read(args.pitch_speed),
              help="Pitch speed, e.g. 85mph [default: each batter profile's].")
@click.option("--launch-angle", default=28.0, show_default=True, type=float,
              callback=_read(args.launch_angle), help="Launch angle [deg], -10 to 60.")
@click.option("--backspin", default=None, type=float,
              callback=_read(lambda v: args.spin("backspin", v)),
              help="Backspin [rpm] [default: the trajectory calculator's for the launch "
                   "angle].")
@click.option("--sidespin", default=None, type=float,
              callback=_read(lambda v: args.spin("sidespin", v)),
              help="Sidespin [rpm] [default: the calculator's, -849 rpm].")
@click.option("--elevation", default="0 ft", show_default=True,
              callback=_read(args.elevation), help="Field elevation.")
@click.option("--temperature", default="70F", show_default=True, callback=_read(args.temperature),
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
