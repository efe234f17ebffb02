"""``batcert reduce``: measured hits to a certificate."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from batcert import console
from batcert.cli.base import (
    ENVIRONMENT_EXIT_CODES,
    FIGURES_OPTION,
    _check_figures_dir,
    _complete,
    _deliver,
    _figures,
    _formats,
    _guard,
    _output_options,
    _report_dir,
    main,
)
from batcert.console import views
from batcert.errors import InputError

REDUCE_EXIT_CODES = """\b
Exit codes:
  0  the certified value passes under the decision rule (or the protocol sets no limit)
  1  it fails, or no value can be certified (too few consecutive valid hits)
  2  usage error (unknown protocol, a metric a lab test does not measure)
  3  invalid input (the session, hits CSV, bat or ball has errors; nothing is written)
""" + ENVIRONMENT_EXIT_CODES


@main.command(epilog=REDUCE_EXIT_CODES + """

\b
Examples:
  batcert reduce examples/lab/synthetic-scatter.yaml -p ncaa-bbcor
  batcert reduce examples/lab/synthetic-scatter.yaml -p ncaa-bbcor --decision-rule guarded
  batcert reduce examples/lab/synthetic-exact.csv --bat aluminium-34 -p ncaa-bbcor""")
@click.argument("session")
@click.option("--protocol", "-p", "protocol", required=True, shell_complete=_complete("protocol"),
              help="The protocol whose metric, location rule and limit certify the bat.")
@click.option("--bat", default=None, shell_complete=_complete("bat"),
              help="For a bare hits CSV: the bat (the protocol gives the ball and the pivot).")
@click.option("--decision-rule", type=click.Choice(["simple", "guarded"]), default="simple",
              show_default=True, help="simple: the limit as written (the governing body's); "
                   "guarded: the value plus its expanded uncertainty must be within the limit.")
@click.option("--write-calibration", "calibrated_bat", default=None,
              type=click.Path(dir_okay=False, path_type=Path),
              help="Write a copy of the bat file with the barrel calibrated from the hits "
                   "(measured.hoop_frequency) to this path.")
@_output_options("certificate", "Impact engine of the model's prediction drawn beside the "
                 "measurement.")
@FIGURES_OPTION
@_guard
def reduce(session, protocol, bat, decision_rule, calibrated_bat, engine, out_dir, formats,
           no_reports, as_json, figures_dir):
    """Reduce a lab SESSION's measured hits (a session YAML naming its hits CSV, or a bare hits
    CSV with --bat; see docs/lab-reduction.md) to a certified value with its measurement
    uncertainty, and decide under a declared rule."""
    from batcert.commands.reduce import run_reduce
    fmts = _formats(formats)
    target = _report_dir(out_dir, no_reports, as_json)
    _check_figures_dir(figures_dir)
    if calibrated_bat is not None:  # before any work: never an input, never a device
        _check_calibration_target(calibrated_bat, _session_inputs(session, bat))
        if engine != "flexible":
            from batcert.errors import UsageProblem
            raise UsageProblem(f"--write-calibration needs the flexible engine (the {engine} "
                               "engine has no barrel to calibrate)")
    result = run_reduce(session, protocol, decision_rule, engine, bat)
    # the calibrated bat is made before any report is written: if there is none (a solid bat,
    # nothing certified), the usage error leaves nothing behind
    calibration = None if calibrated_bat is None else _calibration_text(result, session,
                                                                         calibrated_bat)
    _deliver(result, views.lab_summary, target, fmts, as_json)
    if calibration is not None:
        from batcert.reports.write import atomic_write_text
        atomic_write_text(calibrated_bat, calibration)
        console.note(f"wrote the calibrated bat to {calibrated_bat}")
    _figures(result, figures_dir)
    sys.exit(result.return_code())


def _session_inputs(session: str, bat: str | None) -> list[Path]:
    """The files a reduction will read, as far as they can be known before it runs: the
    session (or bare hits CSV), its hits CSV and its bat file. A session that cannot be read
    here is left to the reduction to report."""
    from batcert.errors import UsageProblem
    from batcert.specs.resolve import resolve
    from batcert.specs.session import is_hits_csv
    paths = [Path(session)]
    try:
        if is_hits_csv(session):
            if bat is not None:
                paths.append(Path(resolve("bat", bat)))
        else:
            from batcert.specs.session import load_session
            spec = load_session(session)
            here = Path(session)
            paths.append(here.parent / spec.hits)
            paths.append(Path(resolve("bat", spec.bat, relative_to=here)))
    except (InputError, UsageProblem, OSError, ValueError):
        pass
    return paths


def _check_calibration_target(target: Path, inputs: list[Path]) -> None:
    from batcert.reports.write import check_output_file
    check_output_file(target, inputs, "the calibrated bat")


def _calibration_text(result, session: str, target: Path) -> str:
    """The bat file with the fitted barrel (the softest fit when there are several), read back
    to check it is a valid bat file; the target is checked again against every input the
    reduction read (the ball and protocol files too). A usage error when there is no fit."""
    from batcert.commands.reduce import calibrated_bat_text
    from batcert.errors import UsageProblem
    from batcert.specs.resolve import resolve_display
    try:
        text = calibrated_bat_text(result, session)
    except ValueError as exc:
        raise UsageProblem(f"--write-calibration: {exc}") from None
    _check_calibration_target(target, [*_session_inputs(session, None),
                                       *(resolve_display(i["path"]) for i in result.inputs)])
    return text
