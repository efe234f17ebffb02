"""A protocol's result for a drawn bat (the Monte Carlo of :mod:`batcert.uncertainty`), from
a few impacts around the nominal bat's impact points.

A drawn bat differs from the nominal one by its inputs' uncertainties, so its sweet spot (or
metric maximum, or centre of percussion) lies close to the nominal one. Locating it afresh
(a sweep, then a parabola through the best three points of a stencil) would add the search's
own scatter, a fraction of the stencil's spacing, which for BPF at the sweet spot is larger than
the effect of a gram. Instead each draw, like the nominal bat, is solved on one fixed stencil
around each nominal impact point (:data:`POINTS` points :data:`SPACING` apart), and the
least-squares parabolas through them give the rest:

- the impact point: the nominal one moved by the shift of the parabola's vertex (of the exit
  speed for the sweet-spot rule, of the metric for the max-metric rule), by the move of the
  centre of percussion (cop rule) or not at all (fixed from the tip);
- the result: the nominal one plus the change of the metric's parabola between the two points,
  ``fit_draw(x_draw) - fit_nominal(x_nominal)``.

Both are smooth functions of the inputs and the parabolas' own error cancels in the
differences; the nominal inputs give the nominal point and result exactly. How close this is
to a full run of the drawn bat is checked on every run (``full_run_difference``,
:mod:`batcert.uncertainty.propagate`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.methods.metrics import AGGREGATES, METRICS
from batcert.methods.rules import IMPACT_RULES
from batcert.model.mass import mass_properties
from batcert.results.run import RunResult
from batcert.runner.bench import Bench, Steps
from batcert.runner.conditions import conditions_from_spec
from batcert.specs.protocol import ProtocolSpec

POINTS = 5  # stencil points around each nominal impact point
# their spacing [m]: wide enough that the curve changes across the stencil by far more than the
# engine's rounding (a 1 mm stencil sees BBCOR change by about 1e-5 and places its peak to no
# better than millimetres), narrow enough to stay parabolic
SPACING = 0.005


@dataclass(frozen=True)
class Fit:
    """Each condition's stencil and the least-squares parabolas through it: ``c[0] t^2 +
    c[1] t + c[2]`` in ``t = x - centre``."""

    points: np.ndarray  # [m from pivot], (n, POINTS)
    centre: np.ndarray  # (n,)
    metric: np.ndarray  # the metric's coefficients, (n, 3)
    locator: np.ndarray | None  # the located curve's coefficients (exit speed or metric)
    cop: float  # the bat's centre of percussion [m from pivot]

    def vertex(self) -> np.ndarray:
        assert self.locator is not None
        return self.centre - self.locator[:, 1] / (2.0 * self.locator[:, 0])

    def metric_at(self, x: np.ndarray) -> np.ndarray:
        t = x - self.centre
        return (self.metric[:, 0] * t + self.metric[:, 1]) * t + self.metric[:, 2]


def _parabolas(points: np.ndarray, values: np.ndarray) -> np.ndarray:
    t = points - points.mean(axis=1, keepdims=True)
    return np.array([np.polyfit(t[i], values[i], 2) for i in range(points.shape[0])])


def _flat(nominal: RunResult, rule) -> np.ndarray:
    """Conditions whose metric was flat along the nominal bat: the max-metric rule fell back
    to the sweet spot there (and so does a draw)."""
    return np.array([rule.needs_metric_peak and c.impact_location == c.sweet_spot
                     for c in nominal.conditions])


def fit_steps(bench: Bench, protocol: ProtocolSpec, nominal: RunResult) -> Steps:
    """Steps (for :func:`~batcert.runner.bench.drive`) that solve ``bench``'s bat on the
    stencils around the ``nominal`` run's impact points and return its :class:`Fit`."""
    p = protocol
    rule = IMPACT_RULES[p.impact_location.rule]
    conds = conditions_from_spec(p.conditions, bench.built.model, p.pivot)
    located = np.array([c.impact_location for c in nominal.conditions])
    offsets = (np.arange(POINTS) - POINTS // 2) * SPACING
    points = located[:, None] + offsets
    ((got, _),) = yield [bench.request(conds, points)]
    metric = METRICS[p.metric].value(got)
    locator = None
    if rule.name == "sweet-spot" or rule.needs_metric_peak:
        by_speed = _flat(nominal, rule) | (not rule.needs_metric_peak)
        locator = _parabolas(points, np.where(by_speed[:, None], got.exit_speed, metric))
    cop = mass_properties(bench.built, p.pivot).cop if rule.name == "cop" else float("nan")
    return Fit(points, located, _parabolas(points, metric), locator, cop)


def drawn_result(protocol: ProtocolSpec, nominal: RunResult, at_nominal: Fit,
                 drawn: Fit) -> tuple[float, np.ndarray]:
    """The protocol's aggregated result for a drawn bat and its impact points [m from pivot],
    (n,), from its :class:`Fit` and the nominal bat's (module notes)."""
    rule = IMPACT_RULES[protocol.impact_location.rule]
    located = at_nominal.centre
    if drawn.locator is not None and at_nominal.locator is not None:
        # a maximum on the window's edge (the true one lies outside) stays on the edge, as
        # the full search leaves it; so does a curve with no maximum near the point
        held = np.array([c.at_window_edge for c in nominal.conditions]) | (
            at_nominal.locator[:, 0] >= 0) | (drawn.locator[:, 0] >= 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            moved = located + (drawn.vertex() - at_nominal.vertex())
        window = nominal.conditions[0].sweep.impact_location
        x = np.where(held, located, np.clip(moved, window[0], window[-1]))
    elif rule.name == "cop":
        x = located + (drawn.cop - at_nominal.cop)
    else:
        x = located
    values = np.array([c.metric_value for c in nominal.conditions]) + (
        drawn.metric_at(x) - at_nominal.metric_at(located))
    return float(AGGREGATES[protocol.aggregate].combine(values)), x
