"""The batcert command line: a thin click layer over batcert.commands, console and reports."""

from __future__ import annotations

import contextlib
import os
import sys
from pathlib import Path

# The engine's matrices are small (a few hundred DOFs): a second BLAS thread only spins, doubling
# CPU time, and under load slows small factorisations tenfold (measured). Set before numpy loads;
# a user's own setting wins.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import click  # noqa: E402

from batcert import console  # noqa: E402
from batcert.errors import InputError  # noqa: E402
from batcert.version import __version__  # noqa: E402

OUTPUT_EXIT_CODE = """  4  the reports cannot be written (permissions, full disk, a path that is a file)"""
STOPPED_EXIT_CODES = """  130  interrupted (Ctrl-C); no partial or temporary file is left
  143  terminated (SIGTERM): stopped and cleaned up as on Ctrl-C"""
ENVIRONMENT_EXIT_CODES = OUTPUT_EXIT_CODE + "\n" + STOPPED_EXIT_CODES

EXIT_CODES = """\b
Exit codes:
  0  every verdict passes (or the protocol sets no limit)
  1  at least one verdict fails
  2  usage error (unknown option, unknown protocol name, missing file argument)
  3  invalid input (a spec file has errors; nothing is written)
""" + ENVIRONMENT_EXIT_CODES

CHECK_EXIT_CODES = """\b
Exit codes:
  0  the input is valid (and was shown)
  2  usage error (unknown option, unknown shipped name, missing file argument)
  3  invalid input (a spec file has errors)"""

FORMATS = ("md", "html", "json")


def _guard(func):
    """Map input problems to exit code 3 and lookup and usage problems (an unknown shipped
    name or engine, fewer than two bats) to 2, with one clear message."""
    import functools

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from batcert.engines import EngineUnavailable
        from batcert.errors import SchedulerUnavailable, UsageProblem
        from batcert.reports.write import OutputError
        from batcert.specs.resolve import NotFound
        _use_cache()
        try:
            with _sigterm_as_interrupt():
                return func(*args, **kwargs)
        except InputError as exc:
            console.input_error(exc.render())
            sys.exit(3)
        except (NotFound, EngineUnavailable, UsageProblem) as exc:
            raise click.UsageError(str(exc)) from None
        except OutputError as exc:
            console.error(str(exc))
            sys.exit(4)
        except SchedulerUnavailable as exc:
            console.error(str(exc))
            sys.exit(5)
        except _Terminated:
            console.error("terminated")
            sys.exit(143)
        except KeyboardInterrupt:
            console.error("interrupted")
            sys.exit(130)

    return wrapper


class _Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the command is, so that it stops and cleans up as on Ctrl-C (worker
    processes ended, no partial file, a sweep's journal kept)."""


@contextlib.contextmanager
def _sigterm_as_interrupt():
    """SIGTERM raises :class:`_Terminated` in the command while it runs (where signals can be
    handled: the main thread)."""
    import signal
    import threading
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def terminated(signum, frame):
        raise _Terminated

    previous = signal.signal(signal.SIGTERM, terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL if previous is None else previous)


def _use_cache() -> None:
    """Keep costly intermediate results in the cache directory between runs, as the library
    does (:func:`batcert.api.use_cache`): a wall costs 0.1-0.3 s to compute and its scipy
    import 0.15 s more; a bat's modes 5 ms per support and pivot; likewise a viscoelastic
    ball's fit (about a second) and its rigid-wall table (about 20 ms)."""
    from batcert.api import use_cache
    use_cache()


def _formats(value: str) -> list[str]:
    items = [v.strip() for v in value.split(",") if v.strip()]
    bad = [v for v in items if v not in FORMATS]
    if bad or not items:
        raise click.BadParameter(f"choose from {', '.join(FORMATS)} (comma-separated), got {value!r}")
    return items


def _complete(kind: str):
    """Shell completion of an argument naming a ``kind`` of input: the shipped names that
    start with what was typed, and files (the shell's own file completion)."""
    def complete(ctx, param, incomplete: str):
        from click.shell_completion import CompletionItem

        from batcert.specs.resolve import shipped_names
        items = [CompletionItem(n) for n in shipped_names(kind) if n.startswith(incomplete)]
        return items + [CompletionItem(incomplete, type="file")]
    return complete


class _Clock:
    """Wall time per phase, logged with ``--verbose``."""

    def __init__(self) -> None:
        import time
        self._time = time.perf_counter
        self._last = self._time()
        self.laps: list[tuple[str, float]] = []

    def lap(self, name: str) -> None:
        now = self._time()
        self.laps.append((name, now - self._last))
        self._last = now

    def report(self) -> None:
        console.log("timings: " + ", ".join(f"{n} {t:.3f} s" for n, t in self.laps))


def _stepper(bar):
    """An ``on_step`` callback that shows the engine's steps on a progress display."""
    def on_step(step: int, runs: int, impacts: int) -> None:
        bar.update(f"step {step}, {runs} protocol run{'s' if runs != 1 else ''}, "
                   f"{impacts} impacts")
        console.log(f"engine step {step}: {runs} runs, {impacts} impacts", level=2)
    return on_step


def _report_dir(out_dir: Path | None, no_reports: bool, as_json: bool) -> Path | None:
    """Where the reports go, or None for none: ``--no-reports`` writes nothing, ``--json``
    writes only where ``--out`` says, otherwise ``--out`` or ./reports. A location that
    cannot hold them is refused now, before any work (exit 4)."""
    if no_reports or (as_json and out_dir is None):
        return None
    target = out_dir if out_dir is not None else Path("reports")
    from batcert.reports.write import check_output_dir
    check_output_dir(target)
    return target


def _write_then_show(results: list, target: Path | None, fmts: list[str], show,
                     stems: list[str] | None = None) -> None:
    """Write every result's reports (each set whole or not at all), then ``show(results,
    paths)``. If writing fails, the results are still shown (the verdict is not lost) before
    the failure ends the command (exit 4)."""
    paths: list[list[Path]] = [[] for _ in results]
    failure = None
    if target is not None:
        from batcert.reports.write import OutputError, write_reports
        try:
            for i, r in enumerate(results):
                paths[i] = write_reports(r, target, fmts, None if stems is None else stems[i])
        except OutputError as exc:
            failure = exc
    show(results, paths)
    if failure is not None:
        raise failure


def _output_options(printed: str, engine_help: str = "Impact engine tier."):
    """The options shared by run, compare and league: engine, report directory and formats,
    --no-reports and --json (one definition, so the three commands cannot drift apart)."""
    options = [
        click.option("--engine", type=click.Choice(["rigid", "flexible"]), default="flexible",
                     show_default=True, help=engine_help),
        click.option("--out", "out_dir", type=click.Path(path_type=Path),
                     default=None, help="Directory for the reports [default: reports; with "
                     "--json, reports are written only if --out is given]."),
        click.option("--format", "formats", default="md,html,json", show_default=True,
                     help="Report formats, comma-separated: md, html, json."),
        click.option("--no-reports", is_flag=True,
                     help=f"Print the {printed} only; write no files."),
        click.option("--json", "as_json", is_flag=True,
                     help=f"Print only the {printed} JSON on stdout (no report files unless "
                          "--out is given)."),
    ]

    def decorate(func):
        for option in reversed(options):
            func = option(func)
        return func

    return decorate


FIGURES_OPTION = click.option(
    "--figures", "figures_dir", type=click.Path(file_okay=False, path_type=Path), default=None,
    help="Also write every figure of the report as SVG, PDF and PNG files into this directory "
         "(drawn with matplotlib).")


def _check_figures_dir(figures_dir: Path | None) -> None:
    """A figures directory that cannot hold the files is refused before any work (exit 4)."""
    if figures_dir is not None:
        from batcert.reports.write import check_output_dir
        check_output_dir(figures_dir)


def _figures(result, figures_dir: Path | None, stem: str | None = None) -> None:
    if figures_dir is None:
        return
    from batcert.reports.figures import figures_of, write_figures
    from batcert.reports.write import check_output_dir, report_stem
    check_output_dir(figures_dir)
    paths = write_figures(figures_of(result), figures_dir, stem or report_stem(result))
    console.note(f"wrote {len(paths)} figure files to {figures_dir}")


_GLOBAL_FLAGS = {"-q", "--quiet", "-v", "--verbose"}


class _Batcert(click.Group):
    """The ``batcert`` group: ``-q`` and ``-v`` are also taken after the subcommand
    (``batcert run ... -q``), where a user types them as often as before it; no subcommand has
    options of those names. Everything after ``--`` is left as it is."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        names = set(self.commands)
        at = next((i for i, a in enumerate(args) if a in names), None)
        if at is not None:
            head, tail = args[:at + 1], args[at + 1:]
            stop = tail.index("--") if "--" in tail else len(tail)
            hoisted = [a for a in tail[:stop] if a in _GLOBAL_FLAGS or
                       (len(a) > 2 and a.startswith("-v") and set(a[1:]) == {"v"})]
            if hoisted:
                kept = [a for a in tail[:stop] if a not in hoisted] + tail[stop:]
                args = hoisted + head + kept
        return super().parse_args(ctx, args)


@click.group(cls=_Batcert, epilog=EXIT_CODES + """

\b
Examples:
  batcert run bats/aluminium-34.yaml --protocol proposed
  batcert compare --study smith2001
  batcert sweep aluminium-34 -p ncaa-bbcor --vary wall=60%:140%:9
  batcert design aluminium-34 -p ncaa-bbcor --solve wall --range 100%:250%
  batcert list bats
Shell completion: see docs/cli.md (e.g. eval "$(_BATCERT_COMPLETE=bash_source batcert)").""",
             context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", "-V", prog_name="batcert")
@click.option("--verbose", "-v", count=True, help="Log to stderr what is done and how long it "
              "takes (-v: inputs, engine settings, timings).")
@click.option("--quiet", "-q", is_flag=True, help="Print only verdicts and errors.")
def main(verbose: int, quiet: bool) -> None:
    """Certify baseball bats against test protocols with a reduced-order impact engine."""
    console.configure(verbose=0 if quiet else verbose, quiet=quiet)
    from batcert.specs.resolve import set_notifier
    set_notifier(console.note)


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
@_output_options("results")
@FIGURES_OPTION
@_guard
def run(bats, protocols, samples, seed, engine, out_dir, formats, no_reports, as_json,
        figures_dir):
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
    if seed is not None and samples is None:
        from batcert.errors import UsageProblem
        raise UsageProblem("--seed needs --uncertainty N")
    if samples is not None:
        from batcert.commands.run import check_uncertainty
        for loaded in batch:
            check_uncertainty(loaded, inputs, samples, seed)
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
                                       on_progress=_counter(bar, "draws"))
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
                console.run_summary(r, paths)
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


@main.command(epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert inspect bats/aluminium-34.yaml
  batcert inspect ash-34 --pivot '6 in' --json
  batcert inspect protocols/balls/collegiate-baseball.yaml""")
@click.argument("file", shell_complete=_complete("bat"))
@click.option("--pivot", type=str, default=None, help="Pivot from the knob for the mass "
              "properties, e.g. '6 in' (default: the measured pivot, else 6 in).")
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout (SI units).")
@_guard
def inspect(file, pivot, as_json):
    """Show a bat's mass properties, COP and bending modes (or a ball's COR and contact time)."""
    from batcert.commands import inspect as inspecting
    from batcert.commands.inputs import detect_kind, load_bat_any
    from batcert.reports.inspect_view import ball_view, bat_view
    from batcert.specs.resolve import resolve
    from batcert.units import UnitError, parse_quantity
    if Path(file).is_file():
        path = file
    else:  # a shipped bat, else a shipped ball
        from batcert.specs.resolve import NotFound
        try:
            path = str(resolve("bat", file))
        except NotFound:
            try:
                path = str(resolve("ball", file))
            except NotFound:
                raise click.UsageError(f"{file!r} is neither a file nor a shipped bat or ball "
                                       "(batcert list bats, batcert list balls)") from None
    kind = detect_kind(path)
    if kind not in ("bat", "ball"):
        raise click.UsageError(f"{file} is a {kind} file; inspect takes a bat or a ball "
                               "(check it with `batcert validate`)")
    if kind == "ball":
        from batcert.specs.ball import load_ball
        info = inspecting.inspect_ball(load_ball(path))
        console.print_results("inspect", [info]) if as_json else console.blocks(ball_view(info))
        return
    p = None
    if pivot is not None:
        try:
            p = parse_quantity(pivot, "length")
        except UnitError as exc:
            raise click.BadParameter(str(exc), param_hint="--pivot") from None
    info = inspecting.inspect_bat(load_bat_any(path).built, p)
    console.print_results("inspect", [info]) if as_json else console.blocks(bat_view(info))


@main.command(epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert protocols
  batcert protocols --json | jq '.results[].id'""")
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout.")
def protocols(as_json):
    """List the shipped protocols."""
    from batcert.commands.listing import list_protocols
    from batcert.reports.format import DASH
    from batcert.reports.table import Table
    items = list_protocols()
    if as_json:
        console.print_results("protocols", items)
        return
    console.table(Table(["id", "title", "metric", "impact rule", "limit", "conditions"],
                        [[p["id"], p["title"], p["metric"], p["rule"],
                          DASH if p["limit"] is None else f"{p['limit']:g}",
                          ", ".join(p["conditions"])] for p in items]), "shipped protocols")


@main.command(epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert validate bats/*.yaml protocols/*.yaml
  batcert validate my-bat.yaml ncaa-bbcor""")
@click.argument("files", nargs=-1, required=True, type=click.Path())
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout: each file "
              "with its kind and every problem (file, line, column, field, message).")
def validate(files, as_json):
    """Check spec files (bat, ball, protocol, league, study; paths or shipped names) and the
    files they name; report every problem of every file."""
    from batcert.commands.validate import shipped_path, validate_file
    from batcert.specs.resolve import NotFound
    failed = False
    report = []
    for f in files:
        entry: dict = {"file": f, "kind": None, "ok": True, "problems": []}
        try:
            entry["kind"] = validate_file(shipped_path(f))
            if not as_json:
                console.note_out(f"ok  {f} ({entry['kind']})")
        except InputError as exc:
            entry["ok"] = False
            entry["problems"] = [{"file": p.file, "line": p.line, "column": p.column,
                                  "field": p.field, "message": p.message}
                                 for p in exc.problems]
            if not as_json:
                console.input_error(exc.render())
        except NotFound as exc:
            entry["ok"] = False
            entry["problems"] = [{"file": f, "line": None, "column": None, "field": "",
                                  "message": str(exc)}]
            if not as_json:
                console.error(f"{f}: {exc}")
        failed = failed or not entry["ok"]
        report.append(entry)
    if as_json:
        console.print_results("validate", report)
    sys.exit(3 if failed else 0)


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


def _all_warnings(result) -> list[str]:
    """A result's warnings, a league's per bat too."""
    out = list(getattr(result, "warnings", []) or [])
    for bat in getattr(result, "bats", []) or []:
        out += [w for w in getattr(bat, "warnings", []) or [] if w not in out]
    return out


def _deliver(result, summary, target, fmts, as_json: bool) -> None:
    """Write the reports (see :func:`_write_then_show`), then print JSON or the summary."""
    command = click.get_current_context().info_name or "batcert"

    def show(results, paths):
        if as_json:
            console.print_results(command, [results[0].to_dict()])
            console.warnings(_all_warnings(results[0]))
        else:
            summary(results[0], paths[0])
    _write_then_show([result], target, fmts, show)


@main.command(epilog=COMPARE_EXIT_CODES + """

\b
Examples:
  batcert compare --study smith2001
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
@_output_options("comparison")
@FIGURES_OPTION
@_guard
def compare(bats, protocols, study, reference, engine, out_dir, formats, no_reports, as_json,
            figures_dir):
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
                                on_step=_stepper(bar))
    clock.lap("inputs and engine")
    _deliver(result, console.comparison_summary, target, fmts, as_json)
    _figures(result, figures_dir)
    clock.lap("reports")
    clock.report()
    sys.exit(result.return_code())


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
    _deliver(result, console.league_summary, target, fmts, as_json)
    clock.lap("reports")
    clock.report()
    sys.exit(result.return_code(allow_not_modelled))


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
        click.option("--workers", type=click.IntRange(1, 256), default=1, show_default=True,
                     help="Evaluate variants in this many processes on this machine."),
        click.option("--scheduler", default=None, metavar="ADDRESS",
                     help="Run the variants on a dask.distributed cluster (e.g. "
                          "tcp://10.0.0.5:8786); needs pip install 'batcert[distributed]'."),
    ]):
        func = option(func)
    return func


def _counter(bar, what: str = "variants"):
    def on_progress(done: int, total: int) -> None:
        bar.count(done, total, what)
        console.log(f"{done} of {total} {what}", level=2)
    return on_progress


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
    _deliver(result, console.sweep_summary, target, fmts, as_json)
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
@click.option("--points", type=click.IntRange(3, 1001), default=9, show_default=True,
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
    _deliver(result, console.sweep_summary, target, fmts, as_json)
    _figures(result, figures_dir)
    clock.lap("reports")
    clock.report()
    sys.exit(result.return_code())


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
    _deliver(result, console.lab_summary, target, fmts, as_json)
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
    from batcert.errors import InputError, UsageProblem
    from batcert.specs.resolve import resolve
    paths = [Path(session)]
    try:
        if Path(session).suffix.lower() == ".csv":
            if bat is not None:
                paths.append(Path(resolve("bat", bat)))
        else:
            from batcert.specs.hits import load_session
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


@main.command("list", epilog=CHECK_EXIT_CODES + """

\b
Examples:
  batcert list
  batcert list studies
  batcert list bats --json""")
@click.argument("kind", required=False,
                type=click.Choice(["bats", "balls", "protocols", "leagues", "studies"]))
@click.option("--json", "as_json", is_flag=True, help="Print only JSON on stdout.")
def list_(kind, as_json):
    """List the shipped bats, balls, protocols, leagues and studies (or one KIND of them):
    the names that every command accepts in place of a file path."""
    from batcert.commands.listing import LIST_KINDS, list_shipped
    from batcert.reports.table import Table
    kinds = [kind] if kind else list(LIST_KINDS)
    data = {k: list_shipped(k) for k in kinds}
    if as_json:
        console.print_results("list", [{"kind": k, "entries": v} for k, v in data.items()])
        return
    for k, items in data.items():
        console.table(Table(["name", "title", "file"],
                            [[i["name"], i["title"], i["path"]] for i in items]), k)


def entry() -> None:
    """The installed ``batcert`` command (and ``python -m batcert``): :func:`main`, then an exit
    that skips the interpreter's teardown.

    Freeing every module and object at exit costs 15-25 ms after numpy, jinja2 and the specs
    are loaded (measured: ``import numpy`` alone 94 ms with teardown, 74 ms without), a tenth of
    a rigid run, and does nothing a finished command needs. What exit does that matters still
    happens first: the ``atexit`` handlers run (temporary-file finalisers, logging, a profiler's
    save) and stdout and stderr are flushed. The reports are closed and renamed before
    ``main`` returns (:mod:`batcert.reports.write`). While any other thread is alive (a pool
    still winding down, a client's connection) the normal exit is used, which waits for the
    threads that must be waited for."""
    try:
        main(prog_name="batcert")
    except SystemExit as done:
        _exit_now(done.code)


def _exit_now(code) -> None:
    import atexit
    import threading
    run_exit_handlers = getattr(atexit, "_run_exitfuncs", None)
    if run_exit_handlers is None or threading.active_count() > 1:
        sys.exit(code)
    if code is None:
        status = 0
    elif isinstance(code, int):
        status = code
    else:  # as the interpreter does for sys.exit("message")
        print(code, file=sys.stderr)
        status = 1
    run_exit_handlers()
    for stream in (sys.stdout, sys.stderr):
        if stream is None or stream.closed:
            continue
        try:
            stream.flush()
        except OSError:  # a closed pipe: the status the interpreter's own flush exits with
            status = 120
    os._exit(status & 0xFF)


if __name__ == "__main__":
    entry()
