"""A study's figures: a parameter swept on one condition of one of its protocols, per bat.

Each figure is a sweep (:mod:`batcert.sweeps.sweep`) of every bat it concerns, on a copy of the
protocol reduced to the named condition; the quantities it plots come from the sweep's rows.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from batcert.results.compare import StudyFigure, StudyFigureBat
from batcert.specs.study import FigureSpec
from batcert.sweeps.sweep import Plan, collect
from batcert.sweeps.variants import PARAMETERS, Case, ParameterError, parse_vary, read_range

if TYPE_CHECKING:
    from batcert.model.build import BuiltBat
    from batcert.specs.ball import BallSpec
    from batcert.specs.protocol import ProtocolSpec


def figure_plans(spec: FigureSpec, bats: list[tuple[str, BuiltBat]], protocol: ProtocolSpec,
                 ball: BallSpec, engine: str, created: str) -> list[tuple[str, Plan]]:
    """The sweep of ``spec.vary`` for every (label, bat), on ``spec.condition``, planned and
    checked (a :class:`ParameterError` naming the figure, before anything runs)."""
    name, text = parse_vary(spec.vary)
    one = replace(protocol, conditions=tuple(c for c in protocol.conditions
                                             if c.name == spec.condition))
    plans = []
    for label, bat in bats:
        try:
            base = Case(bat.spec, one)
            axis = read_range(name, text, PARAMETERS[name].nominal(base, bat))
            plan = Plan(base, bat, ball, engine, (axis,), created)
            plan.check()
        except ParameterError as exc:
            raise ParameterError(f"study figure {spec.id!r}, bat {label!r}: {exc}") from None
        plans.append((label, plan))
    return plans


def study_figure(spec: FigureSpec, protocol: str, plans: list[tuple[str, Plan]]) -> StudyFigure:
    """One figure from its planned sweeps (:func:`figure_plans`)."""
    from batcert.sweeps.execute import execute  # worker pools and journals: 30 ms to import
    out, percent = [], None
    for label, plan in plans:
        (axis,) = plan.axes
        result = collect(plan, execute(plan)[0], None)
        series = result.conditions[0].series
        wanted = [*spec.metrics, "at_window_edge"]  # the edge: where a sweet spot is not located
        out.append(StudyFigureBat(label, axis.nominal, list(axis.values),
                                  {m: series[m] for m in wanted}))
        if axis.percent and axis.nominal:
            percent = [v / axis.nominal * 100 for v in axis.values]
    name = plans[0][1].axes[0].name if plans else parse_vary(spec.vary)[0]
    return StudyFigure(spec.id, spec.title, protocol, spec.condition, name,
                       PARAMETERS[name].dimension, percent, list(spec.metrics), out)


def check_figures(study) -> None:
    """Every figure of ``study`` (a StudySpec) names a parameter and quantities that exist:
    an :class:`~batcert.errors.InputError` at the figure's line otherwise."""
    from batcert.errors import Collector
    from batcert.results.sweep import CONDITION_FIELDS
    errors = Collector(study.path)
    for i, f in enumerate(study.figures):
        try:
            name, text = parse_vary(f.vary)
            read_range(name, text, 1.0, check_bounds=False)  # the form: units, N, percent
        except ParameterError as exc:
            errors.add(study.source.line("figures", i, "vary"), f"figures[{i}].vary", str(exc))
        for m in f.metrics:
            if m not in CONDITION_FIELDS:
                errors.add(study.source.line("figures", i, "metrics"), f"figures[{i}].metrics",
                           f"unknown quantity {m!r} (choose from {', '.join(CONDITION_FIELDS)})")
    errors.raise_if_any()
