"""``batcert run``: one bat or a batch under one or more protocols."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from batcert import arguments as args
from batcert import console
from batcert.cli.base import (
    EXIT_CODES,
    FIGURES_OPTION,
    _check_figures_dir,
    _Clock,
    _complete,
    _counter,
    _figures,
    _formats,
    _guard,
    _output_options,
    _report_dir,
    _stepper,
    _write_then_show,
    main,
)
from batcert.console import views


def _read_bound(ctx, param, value):
    """--uncertainty-bound as the library reads it (:func:`batcert.arguments.positive`)."""
    if value is None:
        return None
    try:
        return args.positive("uncertainty_bound", _float(value))
    except args.ArgumentError as exc:
        raise click.BadParameter(exc.reason) from None


def _float(text: str):
    try:
        return float(text)
    except ValueError:
        return text  # refused by the reader as not a number



@main.command(epilog=EXIT_CODES + """

\b
Examples:
  batcert run bats/aluminium-34.yaml --protocol proposed
  batcert run ash-34 -p ncaa-bbcor -p ncaa-besr --out reports/ash
  batcert run ash-34 -p proposed --engine rigid --json | jq .results[0].value
  batcert run ash-34 -p ncaa-bbcor --uncertainty 1000""")
@click.argument("bats", nargs=-1, required=True, shell_complete=_complete("bat"))
@click.option("--protocol", "-p", "protocols", multiple=True, required=True,
              shell_complete=_complete("protocol"),
              help="Shipped protocol id (see `batcert list protocols`) or a protocol YAML path; "
                   "repeat for several.")
@click.option("--uncertainty", "samples", type=click.IntRange(2, 1_000_000), default=None,
              metavar="N", help="Also propagate the uncertainties the bat and ball files "
              "state ('mass: 863 g +/- 1 g') through the engine by Monte Carlo with N draws, "
              "and report the result's distribution and the probability of passing "
              "(docs/uncertainty.md). The verdict stays the nominal one.")
@click.option("--seed", type=click.IntRange(0, 2**63 - 1), default=None,
              help="Random seed of the --uncertainty draws [default: 20011; the same seed "
                   "gives the same draws].")
@click.option("--uncertainty-method", "method", type=click.Choice(args.UNCERTAINTY_METHODS),
              default=None, help="How the --uncertainty draws' results are found: 'surrogate', "
              "a response surface in the drawn inputs fitted on a few dozen engine runs and "
              "checked against the engine on 8 of the draws (every draw is solved when it "
              "misses there by more than --uncertainty-bound, and the report says so), or "
              "'full', every draw solved by the engine [default: surrogate].")
@click.option("--uncertainty-bound", "bound", default=None, metavar="X",
              callback=_read_bound,
              help="The largest difference between the surrogate and the engine on the checked "
                   "draws, in the metric's unit, beyond which every draw is solved [default: "
                   "the last digit the reports show: 1e-4, or 0.01 m/s for exit speed].")
@_output_options("results")
@FIGURES_OPTION
@_guard
def run(bats, protocols, samples, seed, method, bound, engine, out_dir, formats, no_reports,
        as_json, figures_dir):
    """Run each BAT (a bat YAML path or shipped bat name; several for a batch) under one or
    more protocols, print the predicted verdicts and write Markdown, HTML and JSON reports
    (one set per bat and protocol)."""
    from batcert.commands.inputs import load_protocol_any
    from batcert.commands.run import run as run_bat
    fmts = _formats(formats)
    clock = _Clock()
    batch = _load_batch(bats)
    inputs = [load_protocol_any(p) for p in protocols]  # all inputs validated before running
    console.log("bats " + ", ".join(str(b.path) for b in batch) + "; protocols "
                + ", ".join(str(p.protocol.path) for p in inputs))
    clock.lap("inputs")
    target = _report_dir(out_dir, no_reports, as_json)
    _check_figures_dir(figures_dir)
    _check_monte_carlo(batch, inputs, samples, seed, method, bound)
    results = []
    for i, loaded in enumerate(batch):
        what = "running" if len(batch) == 1 else f"bat {i + 1} of {len(batch)}"
        with console.progress(what) as bar:
            ran = run_bat(loaded, inputs, engine, on_step=_stepper(bar))
        clock.lap("engine")
        if samples is not None:
            from batcert.commands.run import with_uncertainty
            with console.progress("Monte Carlo") as bar:
                ran = with_uncertainty(loaded, inputs, ran, samples, seed, engine,
                                       on_progress=_counter(bar, "engine draws"),
                                       method=method or "surrogate", bound=bound)
            clock.lap("uncertainty")
        results += ran
    console.log(f"engine {engine}: " + "; ".join(f"{k} {v}" for k, v in
                                                 results[0].engine_settings.items()))

    def show(results, written):
        if as_json:
            console.print_results("run", [r.to_dict() for r in results])
            for r in results:
                console.warnings(r.warnings)
        else:
            for r, paths in zip(results, written, strict=True):
                views.run_summary(r, paths)
            if len(batch) > 1:
                judged = [r.verdict for r in results if r.verdict]
                console.note_out(f"{len(batch)} bats, {len(results)} runs: "
                                 f"{judged.count('pass')} predicted pass, "
                                 f"{judged.count('fail')} predicted fail"
                                 + (f", {len(results) - len(judged)} without a limit"
                                    if len(judged) < len(results) else ""))
    stems = _run_stems(results, [b for b in batch for _ in inputs])
    _write_then_show(results, target, fmts, show, stems)
    for r, stem in zip(results, stems, strict=True):
        _figures(r, figures_dir, stem)
    clock.lap("reports")
    clock.report()
    sys.exit(max(r.return_code() for r in results))


def _check_monte_carlo(batch: list, inputs: list, samples: int | None, seed: int | None,
                       method: str | None, bound: float | None) -> None:
    """Before anything runs: the Monte Carlo's options need --uncertainty N, and each bat's
    files state uncertainties whose draws are possible."""
    for given, name in ((seed, "--seed"), (method, "--uncertainty-method"),
                        (bound, "--uncertainty-bound")):
        if given is not None and samples is None:
            from batcert.errors import UsageProblem
            raise UsageProblem(f"{name} needs --uncertainty N")
    if samples is not None:
        from batcert.commands.run import check_uncertainty
        for loaded in batch:
            check_uncertainty(loaded, inputs, samples, seed)


def _load_batch(bats: tuple[str, ...]) -> list:
    """Every bat of a ``run``, loaded before anything runs; the same file twice is a usage
    error (its reports would be written twice)."""
    import os

    from batcert.commands.inputs import load_bat_any
    from batcert.errors import UsageProblem
    batch = [load_bat_any(b) for b in bats]
    seen: dict[tuple[int, int], str] = {}
    for given, loaded in zip(bats, batch, strict=True):
        st = os.stat(loaded.path)
        key = (st.st_dev, st.st_ino)
        if key in seen:
            raise UsageProblem(f"the bat {given} is given twice (also as {seen[key]})")
        seen[key] = given
    return batch


def _run_stems(results: list, bats: list) -> list[str]:
    """The report stem of each run result (docs/results-json.md): ``<bat>--<protocol>``; when
    two bats of a batch share a name, each also names its file
    (``<bat>--<file stem>--<protocol>``)."""
    from batcert.reports.write import report_stem, run_stem_with_file
    stems = [report_stem(r) for r in results]
    clash = {s for s in stems if stems.count(s) > 1}
    return [run_stem_with_file(r, Path(b.path).stem) if s in clash else s
            for r, b, s in zip(results, bats, stems, strict=True)]
