"""The command line's shared parts: the ``batcert`` group, the guard that maps problems to exit
codes, the options every reporting command takes, report and figure writing, and the installed
command's exit. Each command lives in a module of its own beside this one."""

from __future__ import annotations

import contextlib
import os
import sys
from pathlib import Path
from typing import Any

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
        from batcert.cache import warnings_as_lines
        from batcert.engines import EngineUnavailable
        from batcert.errors import SchedulerUnavailable, UsageProblem
        from batcert.reports.write import OutputError
        from batcert.specs.resolve import NotFound
        _use_cache()
        try:
            with _sigterm_as_interrupt(), warnings_as_lines(lambda m: console.warnings([m])):
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
    with console.progress("drawing figures") as bar:
        paths = write_figures(figures_of(result), figures_dir, stem or report_stem(result),
                              on_progress=_counter(bar, "figures"))
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

    def main(self, *args, standalone_mode: bool = True, **kwargs):
        """As click's, but an interrupt outside a command's own guard (while the arguments are
        parsed) exits 130 with one line, as inside it, not with click's "Aborted!" and exit 1,
        which a script reads as "a verdict fails"."""
        click_main: Any = super().main  # its overloads by standalone_mode's literal
        if not standalone_mode:
            return click_main(*args, standalone_mode=False, **kwargs)
        try:
            code = click_main(*args, standalone_mode=False, **kwargs)
        except click.Abort as exc:
            if isinstance(exc.__cause__, _Terminated):
                console.error("terminated")
                sys.exit(143)
            console.error("interrupted")
            sys.exit(130)
        except click.ClickException as exc:
            exc.show()
            sys.exit(exc.exit_code)
        sys.exit(code if isinstance(code, int) else 0)


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

def _finish(result, summary, target, fmts, as_json: bool, clock, figures_dir: Path | None = None,
            code: int | None = None) -> None:
    """A command's end: deliver the result (:func:`_deliver`), write its figures, time the
    reports, and exit with ``code`` (default: the result's own)."""
    _deliver(result, summary, target, fmts, as_json)
    _figures(result, figures_dir)
    clock.lap("reports")
    clock.report()
    sys.exit(result.return_code() if code is None else code)


def _counter(bar, what: str = "variants"):
    def on_progress(done: int, total: int) -> None:
        bar.count(done, total, what)
        console.log(f"{done} of {total} {what}", level=2)
    return on_progress


def entry() -> None:
    """The command line (started by :func:`batcert.launch.entry`): :func:`main`, then an exit
    that skips the interpreter's teardown.

    Freeing every module and object at exit costs 15-25 ms after numpy, jinja2 and the specs
    are loaded (measured: ``import numpy`` alone 94 ms with teardown, 74 ms without), a tenth of
    a rigid run, and 55-75 ms once a run has loaded scipy too (benchmarks/bench_exit.py, 2-core
    machine, 2026-11-26: about 0.6 of ``python -c "import numpy"``), and does nothing a
    finished command needs. What exit does that matters still happens first: the ``atexit``
    handlers run (temporary-file finalisers, logging, a profiler's save) and stdout and stderr
    are flushed. The reports are closed and renamed before
    ``main`` returns (:mod:`batcert.reports.write`). While any other thread is alive (a pool
    still winding down, a client's connection) the normal exit is used, which waits for the
    threads that must be waited for."""
    try:
        main(prog_name="batcert")
    except SystemExit as done:
        _exit_now(done.code)


def _exit_now(code) -> None:
    """Leave with ``code`` as ``sys.exit`` would, but without the interpreter's shutdown
    (:func:`entry` says why): the exit handlers run and the streams are flushed, then
    ``os._exit``; with other threads alive the normal exit is taken."""
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
