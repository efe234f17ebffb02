"""``batcert compare`` and ``batcert league``."""

from __future__ import annotations

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
    _stepper,
    main,
)
from batcert.console import views

COMPARE_EXIT_CODES = """\b
Exit codes:
  0  the comparison ran and no protocol limit fails (study protocols set no limit)
  1  a protocol with a limit fails for at least one bat
  2  usage error (unknown protocol, study, bat or engine; fewer than two bats)
  3  invalid input (a spec file has errors; nothing is written)
""" + ENVIRONMENT_EXIT_CODES

LEAGUE_EXIT_CODES = """\b
Exit codes:
  0  every bat passes every rule (rules that do not apply to a bat are skipped)
  1  a rule fails, or a rule is not modelled (never counted as a pass; see
     --allow-not-modelled)
  2  usage error (unknown league, bat or engine)
  3  invalid input (a spec file has errors; nothing is written)
""" + ENVIRONMENT_EXIT_CODES


@main.command(epilog=COMPARE_EXIT_CODES + """

\b
Examples:
  batcert compare --study smith2001
  batcert compare --study smith2001 --study-figures
  batcert compare ash-34 aluminium-34 -p proposed -p ncaa-bbcor
  batcert compare bats/*.yaml -p ncaa-bbcor --reference ash-34 --json""")
@click.argument("bats", nargs=-1, shell_complete=_complete("bat"))
@click.option("--protocol", "-p", "protocols", multiple=True,
              help="Shipped protocol id or protocol YAML path; repeat for several.")
@click.option("--study", default=None, shell_complete=_complete("study"),
              help="Shipped study id (e.g. smith2001) or study YAML "
              "path: its protocols, default bats and claims.")
@click.option("--reference", default=None, help="Reference bat of P = (P_bat - P_ref) / P_ref "
              "(Smith 2001 Eq. 6); default the first bat; added to the bats if not among them.")
@click.option("--study-figures", is_flag=True,
              help="Also compute the study's figures (sweeps of every bat: about 2 s for the "
              "2001 study) for the reports and the claims that read them; --figures implies it.")
@_output_options("comparison")
@FIGURES_OPTION
@_guard
def compare(bats, protocols, study, reference, study_figures, engine, out_dir, formats,
            no_reports, as_json, figures_dir):
    """Run every BAT under every protocol and compare them side by side: the metric per protocol
    and condition, the relative performance P against the reference bat with its mean and spread,
    the COP against the sweet spot, and a study's claims tested against the model."""
    from batcert.commands.compare import run_comparison
    fmts = _formats(formats)
    target = _report_dir(out_dir, no_reports, as_json)
    _check_figures_dir(figures_dir)
    clock = _Clock()
    with console.progress("comparing") as bar:
        result = run_comparison(list(bats), list(protocols), study, reference, engine,
                                on_step=_stepper(bar),
                                figures=study_figures or figures_dir is not None)
    clock.lap("inputs and engine")
    _finish(result, views.comparison_summary, target, fmts, as_json, clock, figures_dir)


@main.command(epilog=LEAGUE_EXIT_CODES + """

\b
Examples:
  batcert league ncaa bats/ash-34.yaml bats/aluminium-34.yaml
  batcert league mlb bats/*.yaml --json""")
@click.argument("league_id", metavar="LEAGUE", shell_complete=_complete("league"))
@click.argument("bats", nargs=-1, required=True, shell_complete=_complete("bat"))
@click.option("--allow-not-modelled", is_flag=True, help="Exit 0 when nothing fails, even if "
              "some rules are not modelled (they are still reported).")
@_output_options("league verdicts", "Impact engine tier for performance rules.")
@_guard
def league(league_id, bats, engine, allow_not_modelled, out_dir, formats, no_reports, as_json):
    """Check BATs against the rules of LEAGUE (shipped id such as ncaa, nfhs, usssa,
    usa-baseball, little-league, mlb, or a league YAML path): length, drop, barrel, construction,
    material and performance, each with measured value, limit and verdict."""
    from batcert.commands.league import run_league
    fmts = _formats(formats)
    target = _report_dir(out_dir, no_reports, as_json)
    clock = _Clock()
    with console.progress("checking the rules") as bar:
        result = run_league(league_id, list(bats), engine, on_step=_stepper(bar))
    clock.lap("inputs and engine")
    _finish(result, views.league_summary, target, fmts, as_json, clock,
            code=result.return_code(allow_not_modelled))
