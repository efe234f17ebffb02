"""``batcert sweep`` and ``batcert design``: a protocol run on variants of a bat or a test.

Every input is loaded and every variant checked before anything runs (:meth:`Plan.check`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from batcert.commands.inputs import load_bat_any, load_protocol_any
from batcert.results.serialise import utc_now
from batcert.results.sweep import SweepResult
from batcert.runner.runner import check_applicable
from batcert.sweeps.execute import Journal, execute, sweep_key
from batcert.sweeps.sweep import Plan, collect, nominal_run
from batcert.sweeps.variants import PARAMETERS, Case, ParameterError, parse_vary, read_range

MAX_AXES = 2


def plan_sweep(bat: str, protocol: str, varies: list[str], engine: str = "flexible",
               points: int | None = None, need_limit: bool = False) -> Plan:
    """Load the bat and the protocol, read every ``--vary`` and check every variant can be
    made (a :class:`ParameterError` otherwise, before any work)."""
    if not varies:
        raise ParameterError("give a parameter to vary: --vary PARAM=START:STOP:N "
                             f"({', '.join(PARAMETERS)})")
    if len(varies) > MAX_AXES:
        raise ParameterError(f"at most {MAX_AXES} --vary options (a grid)")
    loaded = load_bat_any(bat)
    pin = load_protocol_any(protocol)
    if need_limit and pin.protocol.limit is None:
        raise ParameterError(f"protocol {pin.protocol.id!r} sets no limit: there is nothing to "
                             "design to")
    check_applicable(pin.protocol, loaded.built)
    base = Case(loaded.built.spec, pin.protocol)
    axes = []
    for text in varies:
        name, spec = parse_vary(text)
        nominal = PARAMETERS[name].nominal(base, loaded.built)
        axes.append(read_range(name, spec, nominal, points))
    plan = Plan(base, loaded.built, pin.ball, engine, tuple(axes), utc_now())
    plan.check()
    return plan


def journal_for(out_dir: Path, stem: str, plan: Plan) -> Path:
    """The journal of ``plan``'s sweep in ``out_dir`` beside its reports named ``stem``
    (:func:`journal_path`)."""
    return journal_path(out_dir, stem, sweep_key(plan))


def journal_path(out_dir: Path, stem: str, key: str) -> Path:
    """Where a sweep keeps its journal in ``out_dir``: named by the report's stem and the
    sweep's key (:func:`~batcert.sweeps.execute.sweep_key`), so that two sweeps of the same bat,
    protocol and parameters over other values never share one."""
    return out_dir / f"{stem}.{key[:16]}.partial.jsonl"


def run_sweep(plan: Plan, journal_at: Path | None = None, resume: bool = False,
              workers: int = 1, scheduler: str | None = None,
              on_progress: Callable[[int, int], None] | None = None) -> SweepResult:
    """Evaluate every variant (resuming a journal when asked) and collect the result; the
    journal is removed once the result is complete."""
    journal, done = None, {}
    if journal_at is not None:
        journal = Journal(journal_at, sweep_key(plan), plan.created)
        if resume:
            done = journal.load()
            plan = replace(plan, created=journal.created)
    rows, nominal_row = execute(plan, journal, done, workers, scheduler, on_progress,
                                nominal=True)
    return collect(plan, rows, nominal_run(plan, nominal_row))


def finish_journal(journal_at: Path | None) -> None:
    """The reports are written: the journal has served."""
    if journal_at is not None:
        journal_at.unlink(missing_ok=True)


DEFAULT_RANGE = "50%:150%"
DEFAULT_POINTS = 9


def run_design(bat: str, protocol: str, parameter: str, range_text: str | None = None,
               engine: str = "flexible", points: int = DEFAULT_POINTS,
               tolerance: str | None = None, on_progress=None, workers: int = 1,
               scheduler: str | None = None) -> SweepResult:
    """The margin curve of ``parameter`` over the range, and every value where the protocol's
    metric meets its limit (:func:`batcert.sweeps.design.solve`)."""
    from batcert.sweeps.design import solve
    from batcert.sweeps.variants import lookup_parameter, read_value
    param = lookup_parameter(parameter)
    tol = param.tolerance
    if tolerance is not None:
        tol, _ = read_value(tolerance, param, None)
        if not tol > 0:
            raise ParameterError(f"--tolerance {tolerance!r}: must be above zero")
    if range_text is not None and range_text.count(":") > 1:  # A:B:N would bypass --points
        raise ParameterError(f"--range {range_text!r}: give A:B; the margin curve's number of "
                             "points is --points")
    plan = plan_sweep(bat, protocol, [f"{parameter}={range_text or DEFAULT_RANGE}"], engine,
                      points, need_limit=True)
    if len(plan.axes[0].values) < 2:
        raise ParameterError("--range needs two ends, A:B")
    curve = run_sweep(plan, workers=workers, scheduler=scheduler, on_progress=on_progress)
    curve.design = solve(plan, curve, tol)
    return curve


_CHANGES = {"geometry": "the bat's geometry and material; the variants' mass properties then "
                        "come from the geometry",
            "measured": "measured properties", "protocol": "the protocol's speeds"}


def parameters_help() -> str:
    """The parameters a sweep or design can vary, from the registry
    (:data:`batcert.sweeps.variants.PARAMETERS`), grouped by what they change: the help's
    closing paragraph."""
    from batcert.sweeps.variants import PARAMETERS
    groups: dict[str, list[str]] = {}
    for p in PARAMETERS.values():
        groups.setdefault(p.changes, []).append(p.name)
    return "Parameters: " + "; ".join(f"{', '.join(names)} ({_CHANGES.get(changes, changes)})"
                                      for changes, names in groups.items()) + "."

