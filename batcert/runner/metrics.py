"""Performance metrics from the speeds before and after impact (Smith 2001 Eqs. 1-5).

Each metric is a named entry of :data:`METRICS` reading an :class:`ImpactMetrics` record, so a new
metric is one line here and a name in the protocol schema.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from batcert.physics import rigid


@dataclass(frozen=True)
class ImpactMetrics:
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


def impact_metrics(impact_location, pitch_speed, bat_angular_speed, exit_speed,
                   bat_angular_speed_after, cor, ball_cor_at, k) -> ImpactMetrics:
    """All metrics for a batch. ``ball_cor_at`` maps relative speed [m/s] to the ball's COR;
    ``k`` is the bat's recoil factor at each impact (:func:`rigid.recoil_factor`)."""
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


METRICS: dict[str, Callable[[ImpactMetrics], np.ndarray]] = {
    "exit-speed": lambda m: m.exit_speed,
    "besr": lambda m: m.besr,
    "bpf": lambda m: m.bpf,
    "bbcor": lambda m: m.bbcor,
    "collision-efficiency": lambda m: m.collision_efficiency,
}

AGGREGATES: dict[str, Callable[[np.ndarray], float]] = {
    "mean": lambda v: float(np.mean(v)),
    "min": lambda v: float(np.min(v)),
    "max": lambda v: float(np.max(v)),
}
