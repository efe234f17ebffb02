"""A study's figures: a parameter swept on one condition of one of its protocols, per bat.

Each figure is a sweep (:mod:`batcert.sweeps.sweep`) of every bat it concerns, on a copy of the
protocol reduced to the named condition; the quantities it plots come from the sweep's rows.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

from batcert.results.compare import StudyFigure, StudyFigureBat
from batcert.specs.study import FigureSpec
from batcert.sweeps.execute import execute
from batcert.sweeps.sweep import Plan, collect
from batcert.sweeps.variants import PARAMETERS, Case, parse_vary, read_range

if TYPE_CHECKING:
    from batcert.model.build import BuiltBat
    from batcert.specs.ball import BallSpec
    from batcert.specs.protocol import ProtocolSpec


def study_figure(spec: FigureSpec, bats: list[tuple[str, BuiltBat]], protocol: ProtocolSpec,
                 ball: BallSpec, engine: str, created: str) -> StudyFigure:
    """One figure: the sweep of ``spec.vary`` for every (label, bat), on ``spec.condition``."""
    name, text = parse_vary(spec.vary)
    p = protocol
    one = replace(p, conditions=tuple(c for c in p.conditions if c.name == spec.condition))
    out, percent = [], None
    for label, bat in bats:
        base = Case(bat.spec, one)
        axis = read_range(name, text, PARAMETERS[name].nominal(base, bat))
        plan = Plan(base, bat, ball, engine, (axis,), created)
        plan.check()
        result = collect(plan, execute(plan), None)
        series = result.conditions[0].series
        out.append(StudyFigureBat(label, axis.nominal, list(axis.values),
                                  {m: series[m] for m in spec.metrics}))
        if axis.percent and axis.nominal:
            percent = [v / axis.nominal * 100 for v in axis.values]
    dim = PARAMETERS[name].dimension
    return StudyFigure(spec.id, spec.title, p.id, spec.condition, name, dim, percent,
                       list(spec.metrics), out)


def check_figures(study) -> None:
    """Every figure of ``study`` (a StudySpec) names a parameter and quantities that exist:
    an :class:`~batcert.errors.InputError` at the figure's line otherwise."""
    from batcert.errors import Collector
    from batcert.results.sweep import CONDITION_FIELDS
    from batcert.sweeps.variants import ParameterError
    errors = Collector(study.path)
    for i, f in enumerate(study.figures):
        try:
            parse_vary(f.vary)
        except ParameterError as exc:
            errors.add(study.source.line("figures", i, "vary"), f"figures[{i}].vary", str(exc))
        for m in f.metrics:
            if m not in CONDITION_FIELDS:
                errors.add(study.source.line("figures", i, "metrics"), f"figures[{i}].metrics",
                           f"unknown quantity {m!r} (choose from {', '.join(CONDITION_FIELDS)})")
    errors.raise_if_any()
