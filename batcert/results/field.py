"""Results of ``batcert field``: what a bat does in play for a batter profile (SI units).

Built by :func:`batcert.analysis.field.evaluate_field`; reports only read them and a saved field
JSON re-renders through :meth:`FieldResult.from_dict`. Every number is the model's prediction
from the bat, ball and batter files, not a measurement.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from batcert.results.serialise import Serialisable

# the scenarios (batcert.inplay.evaluate.SCENARIOS) over which a gain's range is given: the
# swing law's exponent and bat speed one standard uncertainty either way, and the nominal law
RANGE_SCENARIOS = ("nominal", "exponent-low", "exponent-high", "bat-speed-low", "bat-speed-high")


@dataclass
class FieldOutcome:
    """One bat swung by one batter under one swing-law scenario (nominal, the exponent or the
    bat speed at one end of its uncertainty, constant swing speed ...)."""

    scenario: str  # a name of batcert.analysis.field.SCENARIOS
    exponent: float  # n used [-]
    angular_speed: float  # the bat's swing rate about the axis [rad/s]
    swing_speed: float  # bat speed at 6 in from this bat's tip [m/s]
    pitch_speed: float  # [m/s], toward the bat
    best_exit_speed: float  # the largest batted-ball speed along the barrel [m/s]
    sweet_spot: float  # where it is, from the tip [m]
    sweet_zone_1mph: float  # barrel length within 1 mph of the best [m]
    sweet_zone_5mph: float  # within 5 mph [m]
    zone_open: bool  # the 5 mph zone reaches an end of the searched window (a lower bound)
    collision_efficiency: float  # e_A at the sweet spot, in play [-]
    distance: float  # carry of the best batted ball [m]
    hang_time: float  # [s]
    gain_exit_speed: float  # best exit speed minus the reference bat's, same scenario [m/s]
    gain_distance: float  # [m]


@dataclass
class BarrelCurve:
    """Batted-ball speed and carry along the barrel (nominal scenario)."""

    from_tip: list[float]  # impact locations [m from the tip]
    exit_speed: list[float]  # [m/s]
    distance: list[float]  # [m]


@dataclass
class FieldBat:
    bat: str
    path: str
    sha256: str
    length: float  # [m]
    mass: float  # [kg]
    moi_axis: float  # about the swing axis [kg m^2]
    outcomes: list[FieldOutcome]
    along: BarrelCurve
    is_reference: bool = False

    def outcome(self, scenario: str) -> FieldOutcome:
        return next(o for o in self.outcomes if o.scenario == scenario)


@dataclass
class FieldBatter:
    """One batter profile and every bat it swung."""

    batter: str  # profile id (file stem)
    name: str
    path: str
    sha256: str
    body: str  # baseball | softball
    ball: str  # ball name
    pitch_speed: float  # [m/s]
    bat_speed: float  # the profile's bat speed on its reference bat [m/s]
    bat_speed_uncertainty: float  # [m/s]
    speed_from_tip: float  # [m]
    reference_length: float  # [m]
    reference_moi: float  # about the axis [kg m^2]
    axis_from_knob: float  # [m]
    exponent: float  # [-]
    exponent_uncertainty: float  # [-]
    swing_source: str
    pitch_source: str
    bats: list[FieldBat]
    exit_per_bat_speed: float  # d(best exit speed)/d(swing speed), the first bat [-]
    exit_per_pitch_speed: float  # d(best exit speed)/d(pitch speed), the first bat [-]
    distance_per_exit_speed: float  # d(distance)/d(exit speed) at its best hit [s]


@dataclass(repr=False)
class FieldResult(Serialisable):
    KIND = "field"
    SUMMARY = ("reference", "bats", "batters", "engine")

    reference: str  # the reference bat's name
    engine: str
    launch_angle: float  # [rad]
    backspin: float  # [rad/s]
    sidespin: float  # [rad/s]
    spin_source: str
    air_density: float  # [kg/m^3]
    temperature: float  # [K]
    elevation: float  # [m]
    relative_humidity: float  # [-]
    window_from_tip: list[float]  # the impact locations searched [m from the tip]
    batters: list[FieldBatter]
    batcert_version: str
    created: str
    warnings: list[str] = field(default_factory=list)
    model_offset: str = ""  # what docs/validation.md finds of these predictions

    def return_code(self) -> int:
        """0: a field prediction has no verdict to fail."""
        return 0
