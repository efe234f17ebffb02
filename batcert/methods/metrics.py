"""Performance metrics and how conditions are aggregated: the two registries of the protocol's
``metric`` and ``aggregate`` fields.

Each :class:`Metric` holds its name (as written in protocol files and JSON), its display word,
its documentation, the function that reads it from an :class:`ImpactMetrics` record, its unit and
its display precision; nothing else in batcert lists metrics. A new metric is one entry here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from batcert.physics import rigid

# a dimensionless metric (BBCOR, BESR, BPF, e_A) and any limit on one lie within +-METRIC_BOUND
METRIC_BOUND = 10.0

@dataclass(frozen=True)
class ImpactMetrics:
    """Speeds and every metric of a batch of impacts, arrays of one shape."""

    impact_location: np.ndarray  # [m from pivot]
    pitch_speed: np.ndarray  # [m/s], negative toward the bat
    bat_angular_speed: np.ndarray  # [rad/s]
    relative_speed: np.ndarray  # [m/s]
    exit_speed: np.ndarray  # [m/s]
    bat_angular_speed_after: np.ndarray  # [rad/s], Eq. 1
    cor: np.ndarray  # Eq. 3
    ball_cor: np.ndarray  # ball's rigid-wall COR at relative_speed
    bpf: np.ndarray  # Eq. 5
    besr: np.ndarray  # Eq. 2
    bbcor: np.ndarray  # e_A (1 + k) + k
    collision_efficiency: np.ndarray  # e_A

    def reshape(self, shape: tuple[int, ...]) -> ImpactMetrics:
        return ImpactMetrics(**{k: np.asarray(v).reshape(shape) for k, v in vars(self).items()})


def impact_metrics(impact_location, pitch_speed, bat_angular_speed, exit_speed,
                   bat_angular_speed_after, cor, ball_cor_at, k) -> ImpactMetrics:
    """All metrics for a batch (Smith 2001 Eqs. 1-5; ASTM F2219).

    ``ball_cor_at`` maps relative speed [m/s] to the ball's COR; ``k`` is the bat's recoil factor
    at each impact, as the engine computed it (:func:`batcert.physics.rigid.recoil_factor`).
    """
    r = np.asarray(impact_location, float)
    rel = bat_angular_speed * r - pitch_speed
    e_b = ball_cor_at(rel)
    e_a = rigid.collision_efficiency_from_speeds(r, pitch_speed, bat_angular_speed, exit_speed)
    return ImpactMetrics(
        impact_location=r, pitch_speed=np.asarray(pitch_speed, float),
        bat_angular_speed=np.asarray(bat_angular_speed, float), relative_speed=rel,
        exit_speed=np.asarray(exit_speed, float),
        bat_angular_speed_after=np.asarray(bat_angular_speed_after, float),
        cor=np.asarray(cor, float), ball_cor=e_b, bpf=np.asarray(cor) / e_b,
        besr=rigid.besr(r, pitch_speed, bat_angular_speed, exit_speed),
        bbcor=rigid.bbcor_from_collision_efficiency(e_a, k), collision_efficiency=e_a)


@dataclass(frozen=True)
class Metric:
    """One performance metric: name in files and JSON, display word, docs, where it is kept.

    ``field`` names the metric's array in :class:`ImpactMetrics` (computed in
    :func:`impact_metrics`), its number in a run's per-condition result
    (:class:`batcert.results.run.ConditionResult`, filled from this registry) and, where a
    stationary-bat lab test measures it (``lab``), in a lab's reduction of its hits
    (:class:`batcert.methods.reduction.HitReduction`). Views list the metrics from here."""

    name: str
    display: str  # as shown in reports and the terminal
    doc: str
    field: str
    unit: str = ""  # SI unit of the value; "" for dimensionless metrics
    digits: int = 4  # decimals shown for the SI value (exit speed: m/s)
    # what docs/validation.md measures of the model's offset from bench results for this
    # metric, stated on every predicted result ("" where no published level anchors it)
    model_offset: str = ""
    column: str = ""  # short table heading (default: display)
    lab: bool = False  # a stationary-bat lab test measures it (batcert reduce certifies it)

    def value(self, m: ImpactMetrics) -> np.ndarray:
        """The metric of every impact of ``m``."""
        return getattr(m, self.field)


METRICS: dict[str, Metric] = {m.name: m for m in (
    Metric("exit-speed", "exit speed", "Ball speed after impact, v_b.", "exit_speed",
           "m/s", 2),
    Metric("besr", "BESR", "NCAA ball exit speed ratio, Smith 2001 Eq. 2 (assumes w2 = w1).",
           "besr", model_offset=(
               "the model puts a 34 in ash bat at BESR 0.730 where the 97 mph cap (0.728) was "
               "set from such bats: +0.002 for wood, and alloy bats 0.02-0.03 above ash "
               "(docs/validation.md, section 2)"), lab=True),
    Metric("bpf", "BPF", "Bat performance factor e / e_b, Smith 2001 Eq. 5 (w2 from Eq. 1).",
           "bpf", lab=True),
    Metric("bbcor", "BBCOR", "Ball-bat COR from the collision efficiency, e_A (1 + k) + k "
           "(ASTM F2219, NCAA).", "bbcor", model_offset=(
               "wood bats sit at the NCAA's wood level (0.490) because the ball lot is "
               "CALIBRATED on a wood reference bat there (a calibration, not a validation); "
               "typical alloy bats come out 0.03-0.06 above wood, where certified alloy bats "
               "measure at wood level (docs/validation.md, sections 2 and 3)"), lab=True),
    Metric("collision-efficiency", "collision efficiency e_A",
           "e_A = (v_b - v_bat) / (v_pitch + v_bat) (ASTM F2219).", "collision_efficiency",
           column="e_A", lab=True),
)}


@dataclass(frozen=True)
class Aggregate:
    """How a protocol combines its conditions' metric values into one."""

    name: str
    display: str
    doc: str
    combine: Callable[[np.ndarray], float]


AGGREGATES: dict[str, Aggregate] = {a.name: a for a in (
    Aggregate("mean", "mean", "Arithmetic mean over the conditions.",
              lambda v: float(np.mean(v))),
    Aggregate("min", "minimum", "Smallest condition value.", lambda v: float(np.min(v))),
    Aggregate("max", "maximum", "Largest condition value.", lambda v: float(np.max(v))),
)}
