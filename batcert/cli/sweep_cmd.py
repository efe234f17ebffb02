"""``batcert sweep`` and ``batcert design``: variants of a bat or a test."""

from __future__ import annotations

import sys

import click

from batcert import console
from batcert.arguments import BOUNDS
from batcert.cli.base import (
    FIGURES_OPTION,
    OUTPUT_EXIT_CODE,
    STOPPED_EXIT_CODES,
    _check_figures_dir,
    _Clock,
    _complete,
    _counter,
    _deliver,
    _figures,
    _finish,
    _formats,
    _guard,
    _output_options,
    _report_dir,
    main,
)
from batcert.console import views

SWEEP_EXIT_CODES = """\b
Exit codes:
  0  every variant was evaluated (whatever their verdicts; see the reports)
  2  usage error (unknown parameter or option, a value the parameter cannot take, a
     malformed scheduler address)
  3  invalid input (a spec file has errors; nothing is written)
  4  the reports (or the sweep's journal) cannot be written
  5  the dask scheduler cannot be used (dask not installed; unreachable, not
     dask, silent or without workers)
  130  interrupted (Ctrl-C); no report is half-written, and the journal beside the
     reports keeps the finished variants for --resume
  143  terminated (SIGTERM): stopped as on Ctrl-C, worker processes included"""

DESIGN_EXIT_CODES = """\b
Exit codes:
  0  the limit is met somewhere in the range (the values are reported)
  1  no value in the range meets the limit
  2  usage error (unknown parameter, a protocol without a limit, a bad range)
  3  invalid input (a spec file has errors; nothing is written)
""" + OUTPUT_EXIT_CODE + """
  5  the dask scheduler (--scheduler) cannot be used
""" + STOPPED_EXIT_CODES


class _WithParameters(click.Command):
    """A command whose help ends with the sweep parameters, read from their registry when the
    help is shown (not at start-up)."""

    def format_epilog(self, ctx, formatter) -> None:
        super().format_epilog(ctx, formatter)
        from batcert.commands.sweep import parameters_help
        formatter.write_paragraph()
        with formatter.indentation():
            formatter.write_text(parameters_help())


def _scale_options(func):
    """--workers and --scheduler, shared by sweep and design."""
    for option in reversed([
        click.option("--workers", type=click.IntRange(*BOUNDS["workers"]), default=1, show_default=True,
                     help="Evaluate variants in this many processes on this machine."),
        click.option("--scheduler", default=None, metavar="ADDRESS",
                     help="Run the variants on a dask.distributed cluster (e.g. "
                          "tcp://10.0.0.5:8786); needs pip install 'batcert[distributed]'."),
    ]):
        func = option(func)
    return func



@main.command(epilog=SWEEP_EXIT_CODES + """

\b
Examples:
  batcert sweep bats/aluminium-34.yaml -p ncaa-bbcor --vary wall=60%:140%:9
  batcert sweep ash-34 -p protocols/studies/smith2001-bpf-sweet-spot.yaml \
      --vary bat_angular_speed=5rad/s:60rad/s:12
  batcert sweep aluminium-34 -p proposed --vary wall=80%:120%:5 --vary relative_speed=50:70m/s:3
  batcert sweep aluminium-34 -p ncaa-bbcor --vary wall=50%:150%:201 --workers 2 --resume

\b
Values: START:STOP:N with units (2mm:3.5mm:7) or as percent of nominal (60%:140%:9).""",
              cls=_WithParameters)
@click.argument("bat", shell_complete=_complete("bat"))
@click.option("--protocol", "-p", "protocol", required=True, shell_complete=_complete("protocol"),
              help="Shipped protocol id or protocol YAML path.")
@click.option("--vary", "varies", multiple=True, required=True, metavar="PARAM=START:STOP:N",
              help="A parameter and its values; give two for a grid.")
@click.option("--resume", is_flag=True, help="Continue an interrupted sweep from its journal "
              "in the report directory, without redoing the finished variants.")
@_scale_options
@FIGURES_OPTION
@_output_options("sweep")
@_guard
def sweep(bat, protocol, varies, resume, workers, scheduler, figures_dir, engine, out_dir,
          formats, no_reports, as_json):
    """Run BAT under one protocol for every value of one or two parameters (a grid), and
    report every metric, the sweet spot and the COP against them."""
    from batcert.commands.sweep import finish_journal, journal_for, plan_sweep, run_sweep
    from batcert.reports.write import check_output_file, variants_stem
    fmts = _formats(formats)
    clock = _Clock()
    plan = plan_sweep(bat, protocol, list(varies), engine)
    target = _report_dir(out_dir, no_reports, as_json)
    if resume and target is None:
        raise click.UsageError("--resume needs the report directory that holds the journal "
                               "(drop --no-reports, or give --out with --json)")
    _check_figures_dir(figures_dir)
    clock.lap("inputs")
    journal = None
    if target is not None:
        journal = journal_for(target, variants_stem(plan.base.protocol.id,
                                                    [a.name for a in plan.axes],
                                                    plan.base.bat.path), plan)
        # a directory or a FIFO in its place: refused now (reading or opening a FIFO waits)
        check_output_file(journal, [], "the sweep's journal")
        if resume and not journal.exists():
            console.note(f"no journal of this sweep in {target} (same inputs, values, engine "
                         "and batcert version): it runs from the beginning")
    with console.progress("sweeping") as bar:
        result = run_sweep(plan, journal, resume, workers, scheduler, _counter(bar))
    clock.lap(f"engine ({len(result.points)} variants)")
    _deliver(result, views.sweep_summary, target, fmts, as_json)
    finish_journal(journal)
    _figures(result, figures_dir)
    clock.lap("reports")
    clock.report()
    sys.exit(result.return_code())


@main.command(epilog=DESIGN_EXIT_CODES + """

\b
Examples:
  batcert design bats/aluminium-34.yaml -p ncaa-bbcor --solve wall
  batcert design bbcor-alloy-34 -p ncaa-bbcor --solve hoop_frequency --range 1200Hz:3000Hz""",
              cls=_WithParameters)
@click.argument("bat", shell_complete=_complete("bat"))
@click.option("--protocol", "-p", "protocol", required=True, shell_complete=_complete("protocol"),
              help="Shipped protocol id or protocol YAML path (it must set a limit).")
@click.option("--solve", "parameter", required=True, metavar="PARAM",
              help="The parameter to solve for (the names of `batcert sweep`).")
@click.option("--range", "range_text", default=None, metavar="A:B",
              help="Where to look, with units or as percent of nominal [default: 50%:150%].")
@click.option("--points", type=click.IntRange(int(BOUNDS["points"][0]), int(BOUNDS["points"][1])),
              default=9, show_default=True,
              help="Points of the margin curve that brackets the roots.")
@click.option("--tolerance", default=None, help="Locate the root to within this (with its "
              "unit, e.g. '0.001 mm') [default: the parameter's own, see docs/sweeps.md].")
@_scale_options
@FIGURES_OPTION
@_output_options("design result")
@_guard
def design(bat, protocol, parameter, range_text, points, tolerance, workers, scheduler,
           figures_dir, engine, out_dir, formats, no_reports, as_json):
    """Find the value of one parameter of BAT at which the protocol's metric meets its limit
    (bracketed root finding on the engine), with the margin curve."""
    from batcert.commands.sweep import run_design
    fmts = _formats(formats)
    target = _report_dir(out_dir, no_reports, as_json)
    _check_figures_dir(figures_dir)
    clock = _Clock()
    with console.progress("designing") as bar:
        result = run_design(bat, protocol, parameter, range_text, engine, points, tolerance,
                            _counter(bar), workers, scheduler)
    clock.lap("engine")
    _finish(result, views.sweep_summary, target, fmts, as_json, clock, figures_dir)
