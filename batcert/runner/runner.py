"""Run a protocol on a bat: conditions -> engine batches -> located impacts -> metrics -> verdict.

:func:`run_protocol` is the one way a protocol is run (``run``, ``compare`` and ``league`` all
call it). Its steps are small functions: check the protocol fits the bat, sweep the search window
and locate the peaks (:mod:`batcert.runner.locate`), let the impact rule choose the impact points
(:mod:`batcert.methods.rules`), solve there, aggregate and decide.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any, TypeVar

import numpy as np

from batcert.engines.base import Engine
from batcert.errors import Collector, InputError, Problem
from batcert.methods.metrics import AGGREGATES, METRICS, ImpactMetrics
from batcert.methods.rules import IMPACT_RULES, Choice
from batcert.model.build import BuiltBat
from batcert.model.diagnostics import bat_dynamics
from batcert.model.mass import CLEARANCE, mass_properties, pivot_problem
from batcert.physics import rigid
from batcert.results.run import BarrelRange, ConditionResult, InputFile, MassProperties, RunResult, Sweep
from batcert.results.serialise import utc_now
from batcert.runner import barrel_tests as abi
from batcert.runner.barrel_range import barrel_range_steps
from batcert.runner.bench import Bench, Steps, drive
from batcert.runner.conditions import Condition, conditions_from_spec
from batcert.runner.locate import Search, locate_steps
from batcert.specs.ball import BallSpec
from batcert.specs.bat import BatSpec
from batcert.specs.common import split_field
from batcert.specs.protocol import LimitSpec, ProtocolSpec
from batcert.specs.resolve import display_path
from batcert.version import __version__

T = TypeVar("T")


def check_applicable(protocol: ProtocolSpec, built: BuiltBat) -> None:
    """The protocol fits the bat, or an :class:`InputError` naming every protocol field that
    does not (with the protocol file's lines): the pivot lies on the handle side of the bat's
    CG, the search window, a fixed impact point and every bat-speed station lie between the
    pivot and the tip, at least :data:`CLEARANCE` from the pivot."""
    p, bat = protocol, built.model
    errors = Collector(p.path)
    on = f"bat {built.spec.name!r} ({bat.length * 100:.1f} cm, CG {bat.balance_point * 100:.1f} " \
         "cm from the knob)"
    reach = bat.length - p.pivot - CLEARANCE  # farthest from the tip an impact may be [m]
    short = f"at least {CLEARANCE * 100:.0f} cm short of the pivot " \
            f"({(bat.length - p.pivot) * 100:.1f} cm from the tip)"

    def add(field_: str, message: str) -> None:
        errors.add(p.line(*split_field(field_)), p.field(field_), f"{message}, for {on}")

    wrong = pivot_problem(bat, p.pivot)
    if wrong:
        add("pivot", wrong)
        errors.raise_if_any()  # every other check measures from the pivot
    loc = p.impact_location
    if loc.rule == "fixed-from-tip" and loc.from_tip is not None and loc.from_tip >= reach:
        add("impact_location.from_tip", f"the impact point ({loc.from_tip * 100:.1f} cm from "
            f"the tip) must be {short}")
    elif loc.window[1] >= reach:
        add("impact_location.window", f"the search window reaches {loc.window[1] * 100:.1f} cm "
            f"from the tip: it must end {short}")
    for i, c in enumerate(p.conditions):
        if c.bat_speed_from_tip is not None and c.bat_speed_from_tip >= reach:
            add(f"conditions[{i}].bat_speed_from_tip", f"the bat speed is given "
                f"{c.bat_speed_from_tip * 100:.1f} cm from the tip, at or beyond the pivot "
                f"({(bat.length - p.pivot) * 100:.1f} cm from the tip): it has no lever arm")
    errors.raise_if_any()


def _check_on_bat(choice: Choice, rule: str, tip: float, protocol: ProtocolSpec) -> None:
    off = (choice.location <= 0) | (choice.location >= tip)
    if np.any(off):
        bad = float(choice.location[np.argmax(off)])
        raise protocol.problem("impact_location.rule", f"the {rule} impact point "
                               f"({bad * 100:.1f} cm from the pivot) is not between the pivot "
                               f"and the tip ({tip * 100:.1f} cm) of this bat")


def _check_finite(built: BuiltBat, protocol: ProtocolSpec, ball: BallSpec, final: ImpactMetrics,
                  diag: dict[str, np.ndarray]) -> None:
    """The last line of defence against a degenerate input that passed every range check: a
    non-finite exit speed, metric or contact diagnostic is an input error, never a report."""
    numbers = [final.exit_speed, final.bat_angular_speed_after, final.cor]
    numbers += [v for k, v in diag.items() if k in ("contact_time", "peak_force")]
    if all(np.all(np.isfinite(np.asarray(v, float))) for v in numbers):
        return
    raise InputError([Problem(built.spec.path, None, "", "the engine found no finite solution "
                              f"for this bat with protocol {protocol.id!r} and ball "
                              f"{ball.name!r}: the bat or the ball is outside what the model "
                              "can represent (check its geometry, material and masses)")])


def _scalars(diag: dict[str, np.ndarray], i: int) -> dict[str, Any]:
    """Condition ``i``'s diagnostics as JSON-safe scalars (non-finite numbers become None)."""
    out: dict[str, Any] = {}
    for k, v in diag.items():
        x = np.asarray(v)[i, 0].item()
        out[k] = None if isinstance(x, float) and not np.isfinite(x) else x
    return out


def _condition_results(conds: list[Condition], choice: Choice, search: Search,
                       final: ImpactMetrics, diag: dict[str, np.ndarray], values: np.ndarray,
                       mp: MassProperties, ball_mass: float) -> list[ConditionResult]:
    out = []
    for i, c in enumerate(conds):
        rigid_ss = rigid.rigid_sweet_spot(mp.moi_pivot, ball_mass, final.pitch_speed[i, 0],
                                          final.bat_angular_speed[i, 0])
        if c.relative_speed is not None:
            rigid_ss = np.nan  # Eq. 7 assumes fixed speeds; matched conditions vary w1 with r
        f = {k: float(np.asarray(v)[i, 0]) for k, v in vars(final).items()}
        metrics = {m.field: f[m.field] for m in METRICS.values()}  # every registered metric
        out.append(ConditionResult(
            name=c.name, setup=c.setup, pitch_speed=f["pitch_speed"],
            bat_angular_speed=f["bat_angular_speed"], relative_speed=f["relative_speed"],
            impact_location=float(choice.location[i]),
            bat_angular_speed_after=f["bat_angular_speed_after"], cor=f["cor"],
            ball_cor=f["ball_cor"], **metrics, metric_value=float(values[i]),
            cop=mp.cop, sweet_spot=float(search.peaks.sweet_spot[i]),
            rigid_sweet_spot=None if not np.isfinite(rigid_ss) else float(rigid_ss),
            at_window_edge=bool(choice.at_edge[i]),
            sweep=Sweep(search.grid.tolist(), search.coarse.exit_speed[i].tolist(),
                        search.coarse_metric[i].tolist()),
            diagnostics=_scalars(diag, i)))
    return out


def body_warning(bat: BatSpec, protocol: ProtocolSpec, ball: BallSpec) -> list[str]:
    """One line when the bat is made for the other game than the protocol's ball (a softball
    bat under a baseball protocol); none when the bat file does not say its game (``body``)."""
    if bat.body is None or bat.body == ball.body:
        return []
    return [f"bat {bat.name!r} is a {bat.body} bat, but protocol {protocol.id!r} tests with a "
            f"{ball.body} ({ball.name}): a bat is certified with its own game's ball"]


def _warnings(protocol: ProtocolSpec, conds: list[Condition], choice: Choice,
              engine: Engine) -> list[str]:
    out = []
    for i, c in enumerate(conds):
        if choice.flat[i]:
            out.append(f"{c.name}: {protocol.metric} does not vary with impact location, so it "
                       "has no maximum; the sweet spot (maximum exit speed) is used")
        if choice.at_edge[i]:
            out.append(f"{c.name}: the located impact point lies on the search window's edge "
                       f"({choice.location[i] * 100:.1f} cm from the pivot); the true maximum "
                       "is outside the window")
    if protocol.metric in engine.limitations:
        out.append(engine.limitations[protocol.metric])
    return out


def decide(value: float | None, limit: LimitSpec | None, guard: float = 0.0
           ) -> tuple[float | None, str | None]:
    """Margin (limit + tolerance - guard - value) and verdict; (None, None) without a value or
    a limit. ``guard`` is a guard band taken off the limit (guarded acceptance: the expanded
    uncertainty, :data:`batcert.lab.certify.DECISION_RULES`); 0 is simple acceptance."""
    if value is None or limit is None:
        return None, None
    margin = limit.max + limit.tolerance - guard - value
    return margin, "pass" if margin >= 0 else "fail"


def run_protocol(built: BuiltBat, protocol: ProtocolSpec, ball: BallSpec, engine: Engine,
                 created: str | None = None) -> RunResult:
    """Run ``protocol`` on ``built`` with ``ball`` and ``engine``: the located impacts, every
    metric per condition, the aggregated metric, its margin and verdict, and the engine's and
    the bat's diagnostics. Raises :class:`~batcert.errors.InputError` when the protocol does not fit the bat.
    """
    return run_protocols([(built, protocol, ball)], engine, created)[0]


def run_protocols(jobs: list[tuple[BuiltBat, ProtocolSpec, BallSpec]], engine: Engine,
                  created: str | None = None,
                  on_step: Callable[[int, int, int], None] | None = None) -> list[RunResult]:
    """:func:`run_protocol` for several (bat, protocol, ball) at once, their engine batches
    solved together (:func:`drive`); the results are the same as one at a time."""
    stamp = created or utc_now()
    return drive([protocol_steps(b, p, ball, engine, stamp) for b, p, ball in jobs], engine,
                 on_step)


def protocol_steps(built: BuiltBat, protocol: ProtocolSpec, ball: BallSpec, engine: Engine,
                   created: str) -> Steps:
    """The steps of :func:`run_protocol` (a generator for :func:`drive`): the protocol's
    barrel tests (:mod:`batcert.runner.barrel_tests`) and the impacts; with a break-in that applies,
    the impacts before it too (the result is after it, with the before in ``break_in``)."""
    p = protocol
    check_applicable(p, built)
    test = p.barrel_compression if built.model.construction == "hollow" else None
    emulated = compression = None
    if test is not None and p.break_in is not None:
        emulated = _checked(p, abi.emulate, built.model, test, p.break_in)
        compression = emulated.compression  # of the bat the impacts below are run on
    elif test is not None:
        compression = _checked(p, abi.compression, built.model, test)
    if emulated is not None and emulated.model is not built.model:
        before = yield from _impact_steps(built, p, ball, engine, created)
        built = replace(built, model=emulated.model)
    result = yield from _impact_steps(built, p, ball, engine, created)
    result.compression = compression
    if emulated is not None:
        record = emulated.record
        if record.applies and not record.skipped:
            record.value_before, record.margin_before = before.value, before.margin
            record.verdict_before = before.verdict
        record.compression_before = record.steps[0].force
        result.break_in = record
    return result


def _checked(p: ProtocolSpec, fn: Callable[..., T], *args: Any) -> T:
    """``fn(*args)`` of the barrel tests, or an :class:`InputError` at the protocol's field the
    bat cannot meet (platens off the barrel, a break-in target the plies cannot reach)."""
    try:
        return fn(*args)
    except ValueError as exc:
        field_ = "barrel_compression" if "compression test" in str(exc) else "break_in"
        raise InputError([Problem(p.path, p.line(field_), field_, str(exc))]) from None


def _impact_steps(built: BuiltBat, p: ProtocolSpec, ball: BallSpec, engine: Engine,
                  created: str) -> Steps:
    """The impacts of :func:`protocol_steps` on ``built`` as it is."""
    bat = built.model
    conds = conditions_from_spec(p.conditions, bat, p.pivot)
    bench = Bench(built, ball, engine, p.pivot, p.support)
    mp = mass_properties(built, p.pivot)
    rule = IMPACT_RULES[p.impact_location.rule]
    metric = METRICS[p.metric]
    search: Search = yield from locate_steps(bench, conds, p.impact_location, metric,
                                             rule.needs_metric_peak, mp.cop)
    choice = rule.choose(search.peaks)
    _check_on_bat(choice, rule.name, search.peaks.tip, p)
    aggregate = AGGREGATES[p.aggregate]
    (final, diag), barrel = yield from _final_steps(bench, conds, choice.location, metric,
                                                     aggregate, p.limit)
    values = metric.value(final)[:, 0]
    _check_finite(built, p, ball, final, diag)
    value = aggregate.combine(values)
    margin, verdict = decide(value, p.limit)
    inputs = [InputFile("bat", built.spec.name, display_path(built.spec.path), built.spec.sha256),
              InputFile("protocol", p.id, display_path(p.path), p.sha256),
              InputFile("ball", ball.name, display_path(ball.path), ball.sha256)]
    return RunResult(
        protocol=p.id, protocol_title=p.title, protocol_version=p.version,
        protocol_reference=p.reference, protocol_notes=p.notes or "", bat=built.spec.name,
        ball=ball.name, metric=p.metric, aggregate=p.aggregate, value=value,
        limit=p.limit.max if p.limit else None, tolerance=p.limit.tolerance if p.limit else 0.0,
        margin=margin, verdict=verdict, impact_rule=rule.name, engine=engine.name,
        engine_settings=engine.settings(bat), support=p.support, mass_properties=mp,
        conditions=_condition_results(conds, choice, search, final, diag, values, mp,
                                      ball.model.mass),
        inputs=inputs, batcert_version=__version__, created=created,
        warnings=(body_warning(built.spec, p, ball) + _warnings(p, conds, choice, engine)
                  + _barrel_warning(barrel, metric.display)
                  + _wall_warning(conds, diag)),
        extras=bat_dynamics(built, p.pivot, engine.models_barrel), barrel=barrel, model_offset=metric.model_offset,
        bat_identification=identification(built.spec))


def identification(spec) -> dict[str, str]:
    """The bat file's ``identification:`` entries that are given (maker, model, serial, lot)."""
    return {k: str(v) for k, v in (spec.identification or {}).items() if v}


def _final_steps(bench: Bench, conds: list[Condition], locations: np.ndarray, metric,
                 aggregate, limit: LimitSpec | None):
    """The impacts at the chosen points, and in the same step the barrel's variants (hollow
    bats): ``((metrics, diagnostics), BarrelRange or None)``."""
    ranged = barrel_range_steps(bench, conds, locations, metric, aggregate, limit)
    variants = next(ranged)  # the variants' requests (possibly none)
    answers = yield [bench.request(conds, locations[:, None])] + variants
    try:
        ranged.send(answers[1:])
    except StopIteration as stop:
        return answers[0], stop.value
    raise RuntimeError("the barrel range asked for more than one step")


def _wall_warning(conds: list[Condition], diag: dict[str, np.ndarray]) -> list[str]:
    """A hollow bat whose wall the model bends beyond where a linear wall holds
    (:data:`batcert.engines.flexible.LINEAR_WALL` thicknesses under the peak force)."""
    ratio = diag.get("barrel_deflection_ratio")
    if ratio is None:  # a solid bat, or the rigid engine (which need not load the flexible one)
        return []
    from batcert.engines.flexible import LINEAR_WALL

    out = []
    for i, c in enumerate(conds):
        r = float(np.asarray(ratio)[i, 0])
        if np.isfinite(r) and r > LINEAR_WALL:
            mm = float(np.asarray(diag["barrel_deflection"])[i, 0]) * 1e3
            out.append(f"{c.name}: the barrel's wall deflects about {mm:.1f} mm under the peak "
                       f"force, {r:.1f} times its thickness; the model's wall is linear "
                       "elastic, and at such a deflection a real wall is not: it may dent, and "
                       "its large-amplitude ovalling may soften or stiffen it (the nonlinear "
                       "shell literature reports softening for such modes); the model leaves "
                       "both out and the direction of their effect is not established "
                       "(docs/physics.md)")
    return out


def _barrel_warning(barrel: BarrelRange | None, metric: str) -> list[str]:
    if barrel is None or barrel.calibrated:
        return []
    text = (f"the barrel was not calibrated by a measurement (hoop frequency or compression): "
            f"the {metric} spans {barrel.value_low:.4f} to {barrel.value_high:.4f} over the "
            "plausible barrel")
    if len(barrel.verdicts) > 1:
        text += ", and the verdict changes within that range"
    return [text]
