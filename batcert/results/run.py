"""Results of a protocol run: plain dataclasses in SI units, serialisable to JSON.

Reports and the terminal only read these; they never compute physics. A results JSON written by
``batcert run`` can be loaded back with :meth:`RunResult.from_dict` and re-rendered.
Units are given per field in brackets; all positions along the bat are stated with their origin.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from batcert.results.serialise import Serialisable


@dataclass
class Sweep:
    """Exit speed (and the protocol metric) against impact location for one condition."""

    impact_location: list[float]  # [m from pivot]
    exit_speed: list[float]  # [m/s]
    metric: list[float]  # protocol metric at each location [-] or [m/s] for exit-speed


@dataclass
class ConditionResult:
    name: str
    setup: str  # "stationary-bat" | "stationary-ball" | "pitched-and-swung"
    pitch_speed: float  # ball speed before impact [m/s], negative toward the bat
    bat_angular_speed: float  # bat angular speed before impact about the pivot [rad/s]
    relative_speed: float  # normal approach speed of ball and bat at the impact location [m/s]
    impact_location: float  # [m from pivot]
    exit_speed: float  # ball speed after impact [m/s], positive away from the bat
    bat_angular_speed_after: float  # Smith 2001 Eq. 1 (pinned); free bat: its angular velocity [rad/s]
    cor: float  # ball-bat coefficient of restitution, Smith 2001 Eq. 3 [-]
    ball_cor: float  # the ball's rigid-wall COR at relative_speed [-]
    bpf: float  # bat performance factor cor / ball_cor, Smith 2001 Eq. 5 [-]
    besr: float  # NCAA ball exit speed ratio, Smith 2001 Eq. 2 [-]
    bbcor: float  # ball-bat COR from collision efficiency, e_A (1 + k) + k [-]
    collision_efficiency: float  # e_A = (v_b - v_bat) / (v_pitch + v_bat) [-]
    metric_value: float  # the protocol metric at impact_location
    cop: float  # centre of percussion, Smith 2001 Eq. 4 [m from pivot]
    sweet_spot: float  # location of maximum exit speed within the window [m from pivot]
    rigid_sweet_spot: float | None  # Smith 2001 Eq. 7 [m from pivot], None when undefined (w1 = 0)
    at_window_edge: bool  # the located impact point lies on the search window's edge
    sweep: Sweep
    # the engine's diagnostics of the impact at impact_location (flexible engine: contact_time
    # [s], peak_force [N], max_compression [m], vibrational_energy [J], e0 [-], separated, ...)
    diagnostics: dict[str, Any] = field(default_factory=dict)


@dataclass
class MassProperties:
    """Bat mass properties about the protocol pivot: model (reconciled) against measured."""

    length: float  # [m]
    pivot: float  # [m from knob]
    mass: float  # [kg]
    cg: float  # [m from pivot]
    moi_pivot: float  # [kg m^2]
    cop: float  # [m from pivot]
    geometry_mass: float  # profile x material, before reconciliation [kg]
    geometry_cg: float  # [m from pivot]
    geometry_moi_pivot: float  # [kg m^2]
    measured_mass: float | None  # [kg]
    measured_cg: float | None  # [m from pivot]
    measured_moi_pivot: float | None  # [kg m^2]
    reconciliation: str  # one-line description of the correction applied
    corrections: dict[str, float] = field(default_factory=dict)  # named correction values, SI
    geometry_cop: float | None = None  # COP of the geometry-derived model [m from pivot]
    measured_cop: float | None = None  # COP from the measured values (Eq. 4) [m from pivot]


@dataclass
class BarrelRange:
    """How sure the barrel of a hollow bat is: calibrated to a measurement, or the range of
    the result over the plausible barrel (batcert.runner.barrel_range)."""

    calibrated: bool  # the barrel shell was calibrated to a measured hoop frequency/compression
    basis: str  # what calibrated it, or what the range spans, in words
    hoop_frequency: float  # the model's barrel hoop (n = 2) frequency [Hz]
    measured_hoop_frequency: float | None  # [Hz]
    stiffness_scales: list[float]  # barrel stiffness scales explored [-] (empty if calibrated)
    loss_factors: list[float]  # wall loss factors explored [-] (empty if calibrated)
    value_low: float | None  # smallest aggregated metric over the range (None if calibrated)
    value_high: float | None  # largest
    verdicts: list[str]  # the distinct verdicts over the range ("pass", "fail"), if a limit


@dataclass
class CompressionResult:
    """A barrel compression test (batcert.runner.barrel_tests): the force on one platen at the stated
    approach of two flat platens."""

    position: float  # centre of the platens from the tip [m]
    platen_width: float  # [m]
    deflection: float  # approach of the platens [m]
    force: float  # on one platen at that approach [N]
    stiffness: float  # force per approach [N/m]
    min: float | None  # smallest passing force [N], None without a limit
    margin: float | None  # force - min [N]
    verdict: str | None  # pass | fail | None
    source: str = ""  # the test's conventions, as the protocol states them


@dataclass
class BreakInStep:
    """One reading of an accelerated break-in: after ``passes`` rolling passes."""

    passes: int
    damage: float | None  # the model's ply damage [-]; None for a measured reading
    force: float  # barrel compression [N]
    drop: float  # 1 - force / initial force [-]


@dataclass
class BreakInResult:
    """The accelerated break-in before the test (batcert.runner.barrel_tests): its compression history
    and the test's result before it (the run's own result is after it)."""

    applies: bool  # whether the barrel breaks in (composite plies)
    skipped: bool  # not rolled: compression already fell beyond skip_drop
    outcome: str  # in words
    steps: list[BreakInStep]
    target_drop: float  # [-]
    skip_drop: float  # [-]
    damage_per_pass: float  # [-] (emulation; assumed)
    source: str
    measured: bool  # a lab's readings (True) or the model's emulation
    value_before: float | None = None  # the protocol's aggregated metric on the new bat
    margin_before: float | None = None
    verdict_before: str | None = None
    compression_before: float | None = None  # [N]

    @property
    def complete(self) -> bool:
        """Whether the procedure was carried through: not needed (no break-in, or skipped), or
        the last reading at least ``target_drop`` below the first."""
        return not self.applies or self.skipped or self.steps[-1].drop >= self.target_drop


@dataclass
class InputUncertainty:
    """One input whose stated uncertainty went into the Monte Carlo, and what it did."""

    file: str  # "bat" | "ball"
    path: str  # the file, as given
    field: str  # dotted field in the file ("measured.mass", "wall", "cor")
    line: int | None
    dimension: str | None  # batcert.units dimension of nominal and u; None for the COR
    nominal: list[float]  # [SI] one value, or one per wall station / COR point
    u: list[float]  # standard uncertainties (k = 1) [SI], same shape
    distribution: str  # normal | uniform (then u is the half-width / sqrt 3)
    sensitivity: float  # change of the result per standard uncertainty of this input (the
    # least-squares slope of the result on the input's standard normal draws) [metric unit]
    variance_share: float  # sensitivity^2 over the sum of all sensitivities^2 [-]


@dataclass
class Propagation:
    """How the draws' results were found: every draw solved by the engine (``full``), or a
    response surface in the drawn inputs fitted on engine runs and checked on a sample of the
    draws against the engine (``surrogate``; docs/uncertainty.md)."""

    method: str  # "surrogate" | "full": what gave the reported draws' results
    requested: str  # the method asked for (--uncertainty-method)
    engine_draws: int  # draws (and design points) the engine solved, in all [-]
    design_points: int  # engine-solved points the surface was fitted on (0 without one) [-]
    checked_draws: int  # actual draws the engine solved to check the surface (0 without) [-]
    largest_difference: float | None  # the largest |surface - engine| over those draws
    # [metric unit]; None when no surface was fitted
    bound: float  # the largest difference the surface may make before every draw is solved
    # by the engine [metric unit]
    reason: str = ""  # why every draw was solved when the surface was asked for


@dataclass
class PredictedUncertainty:
    """The result's distribution over the stated input uncertainties (``run --uncertainty``):
    Monte Carlo through the engine (JCGM 101), with the probability of passing."""

    samples: int  # Monte Carlo draws [-]
    seed: int  # random seed of the draws [-]
    method: str  # how each draw was solved, in words
    inputs: list[InputUncertainty]
    mean: float  # [metric unit]
    standard_deviation: float  # [metric unit]
    median: float
    interval_low: float  # 2.5th percentile: with interval_high the 95 % coverage interval
    interval_high: float  # 97.5th percentile (probabilistically symmetric, JCGM 101 7.7)
    minimum: float
    maximum: float
    mean_standard_error: float  # standard deviation / sqrt(samples) [metric unit]
    linear_r2: float  # share of the variance a linear model in the draws explains [-]
    pass_probability: float | None  # share of draws within the limit (None without a limit)
    pass_probability_standard_error: float | None  # sqrt(p (1 - p) / samples)
    nominal_value: float  # the run's result [metric unit]
    full_run_difference: float  # the largest difference, over the checked draws, between a
    # draw's result as the Monte Carlo reports it (the surface's, or Ritz modes and a stencil
    # around the nominal impact points) and as a full run of the drawn bat finds it [metric unit]
    checked_draws: int  # draws checked so (the farthest from the mean and the first) [-]
    largest_location_shift: float  # the largest move of an engine-solved draw's impact point
    # from the nominal one (with a surface: of its design points and checked draws) [m]
    values: list[float]  # the result of every draw, in draw order
    note: str = ""  # what the distribution does not include (e.g. the barrel's range)
    propagation: Propagation | None = None  # surface or full draws, and the surface's check


@dataclass
class InputFile:
    role: str  # "bat" | "protocol" | "ball"
    name: str
    path: str
    sha256: str


@dataclass(repr=False)
class RunResult(Serialisable):
    KIND = "run"
    SUMMARY = ("bat", "protocol", "metric", "value", "verdict", "engine")

    protocol: str  # protocol id
    protocol_title: str
    protocol_version: str
    protocol_reference: str
    protocol_notes: str
    bat: str  # bat name
    ball: str  # ball name
    metric: str  # exit-speed | besr | bpf | bbcor | collision-efficiency
    aggregate: str  # how conditions combine: mean | min | max
    value: float  # aggregated metric
    limit: float | None  # maximum allowed value, None when the protocol sets no limit
    tolerance: float  # added to the limit before the verdict
    margin: float | None  # limit + tolerance - value (positive passes), None without a limit
    verdict: str | None  # "pass" | "fail" | None without a limit
    impact_rule: str  # cop | sweet-spot | max-metric | fixed-from-tip
    engine: str  # rigid | flexible
    engine_settings: dict[str, Any]
    support: str  # pinned | free
    mass_properties: MassProperties
    conditions: list[ConditionResult]
    inputs: list[InputFile]
    batcert_version: str
    created: str  # ISO 8601 UTC timestamp
    warnings: list[str] = field(default_factory=list)
    extras: dict[str, Any] = field(default_factory=dict)  # the bat's dynamics (modes, barrel)
    barrel: BarrelRange | None = None  # hollow bats with the flexible engine
    uncertainty: PredictedUncertainty | None = None  # with `run --uncertainty N`
    # "predicted": computed by the model from the bat's specification, not measured (only
    # `reduce`, from measured hits, makes a certificate); model_offset: what docs/validation.md
    # measures of the model's offset for this metric ("" where nothing anchors it)
    statement: str = "predicted"
    model_offset: str = ""
    bat_identification: dict[str, str] = field(default_factory=dict)  # maker, model, serial, lot
    compression: CompressionResult | None = None  # the protocol's barrel compression test
    break_in: BreakInResult | None = None  # the protocol's accelerated break-in

    def return_code(self) -> int:
        """The command line's exit code for this result: 1 when the predicted verdict fails,
        else 0 (also without a limit)."""
        return 1 if self.verdict == "fail" else 0
