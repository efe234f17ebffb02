"""Impact-location rules: the registry of the protocol's ``impact_location.rule`` field.

The runner first sweeps the search window and locates, per condition, the sweet spot (maximum
exit speed) and, when a rule asks for it, the maximum of the protocol metric
(:mod:`batcert.runner.locate`). A rule then chooses each condition's impact point from those
:class:`Peaks`. Each :class:`ImpactRule` holds its name, display words, docs and function.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Peaks:
    """What the location search found, one entry per condition (arrays of shape (n,))."""

    sweet_spot: np.ndarray  # maximum exit speed [m from pivot]
    sweet_spot_at_edge: np.ndarray  # the maximum lies on the search window's edge
    metric_peak: np.ndarray  # maximum of the metric [m from pivot] (sweet spot if not searched)
    metric_peak_at_edge: np.ndarray
    metric_flat: np.ndarray  # the metric does not vary along the bat (no maximum)
    cop: float  # centre of percussion, Smith 2001 Eq. 4 [m from pivot]
    tip: float  # the tip's distance from the pivot [m]
    from_tip: float | None  # the fixed-from-tip distance [m], when the protocol gives one


@dataclass(frozen=True)
class Choice:
    """Each condition's impact point and whether it is to be flagged."""

    location: np.ndarray  # [m from pivot]
    at_edge: np.ndarray  # on the search window's edge: the true maximum is outside
    flat: np.ndarray  # max-metric fell back to the sweet spot (metric flat along the bat)


def _cop(p: Peaks) -> Choice:
    n = p.sweet_spot.size
    return Choice(np.full(n, p.cop), np.zeros(n, bool), np.zeros(n, bool))


def _sweet_spot(p: Peaks) -> Choice:
    return Choice(p.sweet_spot, p.sweet_spot_at_edge, np.zeros(p.sweet_spot.size, bool))


def _max_metric(p: Peaks) -> Choice:
    """The metric's maximum; a metric that does not vary along the bat has none: use the sweet
    spot (the runner warns)."""
    return Choice(np.where(p.metric_flat, p.sweet_spot, p.metric_peak),
                  np.where(p.metric_flat, p.sweet_spot_at_edge, p.metric_peak_at_edge),
                  p.metric_flat)


def _fixed_from_tip(p: Peaks) -> Choice:
    n = p.sweet_spot.size
    assert p.from_tip is not None  # the protocol schema requires from_tip for this rule
    return Choice(np.full(n, p.tip - p.from_tip), np.zeros(n, bool), np.zeros(n, bool))


@dataclass(frozen=True)
class ImpactRule:
    """One impact-location rule: name in files and JSON, display words, docs, function."""

    name: str
    display: str
    doc: str
    choose: Callable[[Peaks], Choice]
    needs_metric_peak: bool = False  # the search must also locate the metric's maximum


IMPACT_RULES: dict[str, ImpactRule] = {r.name: r for r in (
    ImpactRule("cop", "centre of percussion", "centre of percussion, q = I / (M rbar) "
               "(Smith 2001 Eq. 4; ASTM-style)", _cop),
    ImpactRule("sweet-spot", "sweet spot (maximum exit speed)", "maximum exit speed, located "
               "by sweeping the window (NCAA-style, Smith 2001 proposal)", _sweet_spot),
    ImpactRule("max-metric", "location of the maximum metric", "maximum of the protocol metric "
               "(NCAA BBCOR)", _max_metric, needs_metric_peak=True),
    ImpactRule("fixed-from-tip", "fixed distance from the tip", "a fixed distance from the tip, "
               "`from_tip`", _fixed_from_tip),
)}
