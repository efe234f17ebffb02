"""What bats do in play for batter profiles: swing speed from each bat's MOI, batted-ball speed
along the barrel, the sweet zone, and how far the best-hit ball carries, with gains over a
reference bat under several swing-law scenarios (the law's uncertainty; the constant swing
speed that the study shows under-rates light bats).

Everything here is the model's prediction from the bat, ball and batter files.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.engines.base import Engine
from batcert.inplay.barrel import Swung, barrel_grid, sweet_zone, swing_barrels
from batcert.model.build import BuiltBat
from batcert.physics.swing import swing_speed
from batcert.physics.trajectory import Baseball, fly
from batcert.results.field import BarrelCurve, FieldBat, FieldBatter, FieldOutcome
from batcert.specs.ball import BallSpec
from batcert.specs.batter import BatterSpec
from batcert.units import MPH

__all__ = ["MODEL_OFFSET", "SCENARIOS", "Launch", "Scenario", "evaluate_batter"]

# What docs/validation.md (section 4b) finds of these predictions against published numbers,
# shown beside every in-play result as the metrics' known offsets are beside their verdicts
MODEL_OFFSET = (
    "ash-34 for the pro profile hits 107.8 mph where Nathan's formula with Statcast's averages "
    "gives 104.6 (+3 mph; the ball lot is calibrated on a wood bat); hollow bats out-hit ash "
    "by 8-11 mph where 19 batters measured +5 mph metal over wood (Greenwald et al. 2001), so "
    "their gains over wood are about twice the measured ones (docs/validation.md, section 4b)")


@dataclass(frozen=True)
class Scenario:
    """One way of swinging: the swing law's inputs moved from the profile's nominal values."""

    name: str
    describe: str
    exponent_sigma: float = 0.0  # n + k u(n)
    speed_sigma: float = 0.0  # bat speed + k u(bat speed)
    constant: bool = False  # n = 0: every bat at the reference rate
    bat_speed_step: float = 0.0  # added swing speed at the profile's station [m/s]
    pitch_step: float = 0.0  # added pitch speed [m/s]


SCENARIOS: dict[str, Scenario] = {s.name: s for s in (
    Scenario("nominal", "the profile's bat speed and swing-law exponent n"),
    Scenario("exponent-low", "n one standard uncertainty lower", exponent_sigma=-1.0),
    Scenario("exponent-high", "n one standard uncertainty higher", exponent_sigma=1.0),
    Scenario("bat-speed-low", "the profile's bat speed one standard uncertainty lower",
             speed_sigma=-1.0),
    Scenario("bat-speed-high", "the profile's bat speed one standard uncertainty higher",
             speed_sigma=1.0),
    Scenario("constant-swing", "n = 0: every bat swung at the profile's rate whatever its "
             "MOI (for bats of one length, what a lab test at one bat speed assumes)",
             constant=True),
    Scenario("plus-1mph-bat", "nominal, swung 1 mph faster at the profile's station",
             bat_speed_step=MPH),
    Scenario("plus-1mph-pitch", "nominal, pitched 1 mph faster", pitch_step=MPH),
)}


@dataclass(frozen=True)
class Launch:
    """How the batted ball leaves the bat and the air it flies through."""

    launch_angle: float  # [rad]
    backspin: float  # [rad/s]
    sidespin: float  # [rad/s]
    air_density: float  # [kg/m^3]


def angular_speeds(batter: BatterSpec, moi_axis: float, station: float) -> np.ndarray:
    """The bat's swing rate about the axis [rad/s] under each scenario of :data:`SCENARIOS`;
    ``station``: the distance from the axis of the profile's measuring point on this bat [m]."""
    law = batter.swing
    out = []
    for s in SCENARIOS.values():
        v_ref = float(law.bat_speed) + s.speed_sigma * law.bat_speed_uncertainty
        w = float(swing_speed(moi_axis, v_ref / law.station_radius, law.reference_moi, _exponent(law, s)))
        out.append(w + s.bat_speed_step / station)
    return np.array(out)


def _flight_ball(ball: BallSpec) -> Baseball:
    """The flying ball: the ball file's mass and size (softballs fly with the baseball's
    coefficients: an assumption the report states)."""
    return Baseball(mass=float(ball.model.mass), circumference=2 * np.pi * ball.model.radius)


def _carry(speeds: np.ndarray, launch: Launch, ball: Baseball):
    flight = fly(np.ravel(speeds), launch.launch_angle, launch.backspin, launch.sidespin,
                 air=launch.air_density, ball=ball)
    return flight.distance.reshape(np.shape(speeds)), flight.hang_time.reshape(np.shape(speeds))


def _swings(batter: BatterSpec, bats: list[tuple[str, str, BuiltBat]], pitch: np.ndarray
            ) -> tuple[list[Swung], list[float]]:
    """Each bat's swing under every scenario, and the distance of the profile's measuring station
    on it from the axis [m]."""
    law = batter.swing
    swung, station = [], []
    for _, _, built in bats:
        moi = float(built.model.moi_about(law.axis_from_knob))
        station.append(built.model.length - law.speed_from_tip - law.axis_from_knob)
        swung.append(Swung(built, law.axis_from_knob, angular_speeds(batter, moi, station[-1]),
                           pitch))
    return swung, station


def _exponent(law, s: Scenario) -> float:
    return 0.0 if s.constant else max(law.exponent + s.exponent_sigma * law.exponent_uncertainty,
                                      0.0)


def _outcomes(law, swung: Swung, station: float, zone, efficiency: np.ndarray,
              best_ref: np.ndarray, flight: tuple[np.ndarray, np.ndarray, np.ndarray]
              ) -> list[FieldOutcome]:
    """One bat's outcome per scenario; ``flight``: this bat's distances and hang times, and the
    reference bat's distances, per scenario."""
    distance, hang, distance_ref = flight
    return [FieldOutcome(
        s.name, _exponent(law, s), float(swung.angular_speed[k]),
        float(swung.angular_speed[k] * station), float(swung.pitch_speed[k]), float(zone.best[k]),
        float(zone.at[k]), float(zone.length_1[k]), float(zone.length_5[k]), bool(zone.open[k]),
        float(efficiency[k]), float(distance[k]), float(hang[k]),
        float(zone.best[k] - best_ref[k]), float(distance[k] - distance_ref[k]))
        for k, s in enumerate(SCENARIOS.values())]


def evaluate_batter(batter: BatterSpec, ball: BallSpec, bats: list[tuple[str, str, BuiltBat]],
                    reference: int, engine: Engine, launch: Launch) -> FieldBatter:
    """Every bat of ``bats`` (name, display path, built bat) swung by ``batter``: each bat's
    best batted-ball speed, sweet zone, e_A and carry under every scenario of
    :data:`SCENARIOS`, with gains over ``bats[reference]``, and its curves along the barrel."""
    law = batter.swing
    from_tip = barrel_grid()
    pitch = np.array([batter.pitch_speed + s.pitch_step for s in SCENARIOS.values()])
    swung, station = _swings(batter, bats, pitch)
    sweeps = swing_barrels(engine, ball.model, swung, from_tip)
    zones = [sweet_zone(from_tip, s.exit_speed) for s in sweeps]
    best = np.stack([z.best for z in zones])  # (n_bats, n_scenarios)
    nominal = list(SCENARIOS).index("nominal")
    along = np.stack([s.exit_speed[nominal] for s in sweeps])
    slope_at = best[0, nominal] + np.array([-0.5, 0.5]) * MPH
    carried, hang = _carry(np.concatenate([best.ravel(), along.ravel(), slope_at]), launch,
                           _flight_ball(ball))
    dist, hang_best = (x[:best.size].reshape(best.shape) for x in (carried, hang))
    dist_along = carried[best.size:best.size + along.size].reshape(along.shape)
    out = []
    for b, ((name, path, built), z, sweep) in enumerate(zip(bats, zones, sweeps, strict=True)):
        e_a = [np.interp(z.at[k], from_tip, sweep.collision_efficiency[k])
               for k in range(len(SCENARIOS))]
        outcomes = _outcomes(law, swung[b], station[b], z, np.array(e_a), best[reference],
                             (dist[b], hang_best[b], dist[reference]))
        m = built.model
        out.append(FieldBat(name, path, built.spec.sha256, float(m.length), float(m.mass),
                            float(m.moi_about(law.axis_from_knob)), outcomes,
                            BarrelCurve(from_tip.tolist(), along[b].tolist(),
                                        dist_along[b].tolist()), is_reference=b == reference))
    rate = {s: out[0].outcome(s).best_exit_speed for s in SCENARIOS}
    return FieldBatter(
        batter.id, batter.name, batter.path, batter.sha256, batter.body, ball.name,
        batter.pitch_speed, float(law.bat_speed), law.bat_speed_uncertainty, law.speed_from_tip,
        law.reference_length, law.reference_moi, law.axis_from_knob, law.exponent,
        law.exponent_uncertainty, law.source, batter.pitch_source, out,
        (rate["plus-1mph-bat"] - rate["nominal"]) / MPH,
        (rate["plus-1mph-pitch"] - rate["nominal"]) / MPH,
        float(np.diff(carried[-2:])[0] / MPH))
