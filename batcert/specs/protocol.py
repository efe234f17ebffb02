"""Protocol specification: conditions, impact-location rule, metric, aggregation, limit.

The names a protocol may use for its metric, aggregate and impact rule are those of the runner's
registries (:data:`batcert.methods.metrics.METRICS`, :data:`~batcert.methods.metrics.AGGREGATES`,
:data:`batcert.methods.rules.IMPACT_RULES`), so adding one there makes it valid here.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from batcert.conventions import DEFAULT_PIVOT
from batcert.errors import Collector, InputError, Problem
from batcert.methods.metrics import AGGREGATES, METRIC_BOUND, METRICS
from batcert.methods.rules import IMPACT_RULES
from batcert.specs.barrel_tests import (
    BREAK_IN_SCHEMA,
    COMPRESSION_TEST_SCHEMA,
    BreakInSpec,
    CompressionTestSpec,
)
from batcert.specs.common import Source, spec_from, split_field
from batcert.specs.schema import (
    Field,
    Schema,
    choice,
    integer,
    label,
    list_of,
    lookup,
    number,
    one_of,
    quantity,
    section,
    text,
    validate,
    where,
)
from batcert.specs.yamlio import Located, load_yaml

MIN_RESOLUTION = 5e-5  # [m] finest impact-location resolution accepted


def _check_condition(v: dict, data: Located, errors: Collector, path: str) -> None:
    explicit = v["bat_angular_speed"] is not None or v["bat_speed"] is not None
    matched = v["relative_speed"] is not None
    if explicit and matched:
        errors.add(data.line, path, "give either explicit speeds (pitch_speed with "
                   "bat_angular_speed or bat_speed) or a matched relative_speed, not both")
        return
    if not explicit and not matched:
        errors.add(data.line, path, "give the speeds: pitch_speed and bat_angular_speed (or "
                   "bat_speed), or relative_speed with stationary: bat|ball")
        return
    if explicit:
        if v["bat_angular_speed"] is not None and v["bat_speed"] is not None:
            errors.add(lookup(data, "bat_speed")[0], f"{path}.bat_speed", "give bat_angular_speed "
                       "or bat_speed, not both")
        if v["bat_speed"] is not None and v["bat_speed_from_tip"] is None:
            errors.add(lookup(data, "bat_speed")[0], f"{path}.bat_speed_from_tip", "bat_speed needs "
                       "bat_speed_from_tip (where on the bat the speed is measured)")
        if v["pitch_speed"] is None:
            errors.add(data.line, f"{path}.pitch_speed", "required with explicit speeds "
                       "(use 0 m/s for a stationary ball)")
        if v["stationary"] is not None:
            errors.add(lookup(data, "stationary")[0], f"{path}.stationary", "only used with "
                       "relative_speed")
        if v["bat_speed_from_moi"] is not None and v["pitch_speed"] is not None and \
                not (v["bat_angular_speed"] or v["bat_speed"]):
            errors.add(lookup(data, "bat_speed_from_moi")[0], f"{path}.bat_speed_from_moi",
                       "scales the bat speed, which is zero here (a stationary bat)")
        bat_speed = v["bat_angular_speed"] if v["bat_angular_speed"] is not None \
            else v["bat_speed"]
        if v["pitch_speed"] == 0 and bat_speed == 0:
            errors.add(lookup(data, "pitch_speed")[0], f"{path}.pitch_speed", "the ball and "
                       "the bat are both at rest and never meet: give a pitch speed or a bat "
                       "speed above zero")
        return
    if v["bat_speed_from_moi"] is not None:
        errors.add(lookup(data, "bat_speed_from_moi")[0], f"{path}.bat_speed_from_moi", "only "
                   "with bat_speed or bat_angular_speed (a matched relative speed is fixed)")
    if v["stationary"] is None and v["pitch_speed"] is None:
        errors.add(data.line, f"{path}.stationary", "relative_speed needs stationary: bat|ball, or "
                   "a pitch_speed (the bat then makes up the rest)")
    if v["stationary"] is not None and v["pitch_speed"] is not None:
        errors.add(lookup(data, "pitch_speed")[0], f"{path}.pitch_speed", "with stationary set, "
                   "pitch_speed follows from relative_speed; remove one")
    if v["pitch_speed"] is not None and v["pitch_speed"] >= v["relative_speed"]:
        errors.add(lookup(data, "pitch_speed")[0], f"{path}.pitch_speed", "must be below "
                   "relative_speed (the bat must move toward the ball)")


SWING_SCHEMA = Schema("bat speed from the MOI", (
    Field("reference_moi", quantity("moi", positive=True), "MOI about the protocol's pivot at "
          "which the condition's bat speed applies.", required=True),
    Field("exponent", number(minimum=0.0, maximum=1.0), "n of the power law "
          "v = v_ref (I / I_ref)^-n (batcert.physics.swing).", required=True),
    Field("source", text(), "Where the law and its numbers come from (or that they are "
          "assumed)."),
))


CONDITION_SCHEMA = Schema("test condition", (
    Field("name", label(), "Condition name used in tables and JSON.", required=True),
    Field("description", text(), "What the set-up is."),
    Field("pitch_speed", quantity("speed", minimum=0.0), "Ball speed toward the bat before "
          "impact (stored negative, toward the bat, in results)."),
    Field("bat_angular_speed", quantity("angular_speed", minimum=0.0), "Bat angular speed about "
          "the pivot before impact."),
    Field("bat_speed", quantity("speed", minimum=0.0), "Bat linear speed at bat_speed_from_tip "
          "(alternative to bat_angular_speed)."),
    Field("bat_speed_from_tip", quantity("length", positive=True), "Where bat_speed is taken, "
          "measured from the tip (NCAA: 6 in)."),
    Field("relative_speed", quantity("speed", positive=True), "Matched relative normal speed "
          "at the impact point (Smith 2001 proposal)."),
    Field("stationary", choice("bat", "ball"), "With relative_speed: which body is at rest."),
    Field("bat_speed_from_moi", section(SWING_SCHEMA), "With bat_speed or bat_angular_speed: "
          "scale that speed with the bat's MOI about the pivot, as a batter swings a heavier "
          "bat slower (USA Softball's batted-ball speed)."),
), checks=(_check_condition,))


def _check_location(v: dict, data: Located, errors: Collector, path: str) -> None:
    if v["rule"] == "fixed-from-tip" and v["from_tip"] is None:
        errors.add(data.line, f"{path}.from_tip", "the fixed-from-tip rule needs from_tip")
    if v["window"] is not None and v["window"][0] >= v["window"][1]:
        errors.add(lookup(data, "window")[0], f"{path}.window", "give [nearest, farthest] "
                   "distance from the tip, nearest first")
    elif v["window"] is not None and v["window"][1] - v["window"][0] < v["resolution"]:
        errors.add(lookup(data, "window")[0], f"{path}.window", "the window is shorter than "
                   f"the resolution ({v['resolution'] * 1000:g} mm)")


LOCATION_SCHEMA = Schema("impact-location rule", (
    Field("rule", choice(*IMPACT_RULES), "; ".join(f"{r.name}: {r.doc}" for r in
                                                    IMPACT_RULES.values()) + ".", required=True),
    Field("window", list_of(quantity("length", minimum=0.0), min_items=2, max_items=2,
                            describe="[nearest, farthest] distance from the tip"),
          "Search window as distances from the tip.", default=[0.03, 0.30]),
    Field("sweep_points", integer(minimum=5, maximum=2001), "Coarse sweep points over the window "
          "(the curve the reports plot; the peak is then refined to `resolution`).", default=36),
    Field("resolution", quantity("length", minimum=MIN_RESOLUTION, maximum=0.05), "Located to "
          "at least this. Finer than 0.05 mm is refused: the exit-speed curve is flat at its "
          "peak (it changes by about 1e-8 of itself 0.05 mm away), so finer steps would locate "
          "rounding, not the bat.",
          default=0.001),
    Field("from_tip", quantity("length", positive=True), "Impact distance from the tip for "
          "fixed-from-tip."),
), checks=(_check_location,))

LIMIT_SCHEMA = Schema("limit", (
    Field("max", one_of(number(), quantity("speed", minimum=0.0), describe="a number, or a "
                        "speed for "
                        "exit-speed"), "Largest passing value of the aggregated metric.",
          required=True),
    Field("tolerance", one_of(number(minimum=0.0), quantity("speed", minimum=0.0),
                              describe="a number, or a speed for exit-speed"),
          "Added to max before the verdict (measurement tolerance).", default=0.0),
    Field("source", text(), "Where the limit comes from."),
))


def _check_break_in(v: dict, data: Located, errors: Collector, path: str) -> None:
    if v["break_in"] is not None and v["barrel_compression"] is None:
        errors.add(lookup(data, "break_in")[0], "break_in", "the break-in reads the barrel's "
                   "compression: add `barrel_compression`")


def _is_plain_number(value: object) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return True
    try:
        float(str(value))
    except ValueError:
        return False
    return True


def _check_limit(v: dict, data: Located, errors: Collector, path: str) -> None:
    """An exit-speed limit is a speed with its unit; the other metrics' limits are numbers."""
    if v["limit"] is None or not isinstance(data.get("limit"), Located):
        return
    raw = data["limit"]
    for key in ("max", "tolerance"):
        if raw.get(key) is None:
            continue
        plain = _is_plain_number(raw[key])
        if v["metric"] == "exit-speed" and plain:
            errors.add(lookup(data, "limit", key)[0], f"limit.{key}", "the exit-speed limit is a "
                       f"speed: give its unit, e.g. '97 mph', got {raw[key]!r}")
        elif v["metric"] != "exit-speed" and not plain:
            errors.add(lookup(data, "limit", key)[0], f"limit.{key}", f"{v['metric']} is "
                       f"dimensionless: give a plain number, got {raw[key]!r}")
        elif v["metric"] != "exit-speed" and abs(v["limit"][key]) > METRIC_BOUND:
            errors.add(lookup(data, "limit", key)[0], f"limit.{key}", f"{v['metric']} limits "
                       f"lie within +-{METRIC_BOUND:g}, got {raw[key]!r}")


PROTOCOL_SCHEMA = Schema("protocol", (
    Field("id", label(), "Short identifier (`--protocol ID`).", required=True),
    Field("title", label(), "Full title.", required=True),
    Field("reference", text(), "Standard or paper the protocol follows.", required=True),
    Field("version", text(), "Version of this protocol definition.", required=True),
    Field("description", text(), "What the protocol measures."),
    Field("notes", text(), "Which details are assumed rather than taken from the reference."),
    Field("pivot", quantity("length", minimum=0.0), "Pivot distance from the knob end.",
          default=DEFAULT_PIVOT),
    Field("ball", text(), "Ball: shipped name (e.g. collegiate-baseball) or path relative to "
          "this file.", required=True),
    Field("support", choice("pinned", "free"), "Bat pinned at the pivot or free.",
          default="pinned"),
    Field("conditions", list_of(section(CONDITION_SCHEMA), min_items=1, describe="list of "
          "conditions"), "Test conditions (set-ups and speeds).", required=True),
    Field("impact_location", section(LOCATION_SCHEMA), "Where the ball strikes.", required=True),
    Field("metric", choice(*METRICS), "Performance metric: " + "; ".join(
        f"{m.name}: {m.doc}" for m in METRICS.values()), required=True),
    Field("aggregate", choice(*AGGREGATES), "How conditions combine: " + "; ".join(
        f"{a.name}: {a.doc}" for a in AGGREGATES.values()), default="mean"),
    Field("limit", section(LIMIT_SCHEMA), "Pass/fail limit (omit for no verdict)."),
    Field("barrel_compression", section(COMPRESSION_TEST_SCHEMA), "Hollow bats: a static "
          "barrel compression test (ASTM F2844-style; docs/physics.md), reported with the run."),
    Field("break_in", section(BREAK_IN_SCHEMA), "Barrels whose plies break in (composite): "
          "the accelerated break-in emulated before the test, which is run before and after "
          "it; needs `barrel_compression`."),
), checks=(_check_limit, _check_break_in))



@dataclass(frozen=True)
class ConditionSpec:
    """One test set-up of a protocol (SI; None where not given)."""

    name: str
    description: str | None
    pitch_speed: float | None  # toward the bat [m/s], >= 0
    bat_angular_speed: float | None  # [rad/s]
    bat_speed: float | None  # linear, at bat_speed_from_tip [m/s]
    bat_speed_from_tip: float | None  # [m]
    relative_speed: float | None  # matched relative normal speed [m/s]
    stationary: str | None  # bat | ball, with relative_speed
    bat_speed_from_moi: SwingScalingSpec | None = None


@dataclass(frozen=True)
class SwingScalingSpec:
    """The bat speed's dependence on the bat's MOI (:func:`batcert.physics.swing.swing_speed`)."""

    reference_moi: float  # about the protocol's pivot [kg m^2]
    exponent: float  # [-]
    source: str | None


@dataclass(frozen=True)
class LocationSpec:
    """The impact-location rule and its search window."""

    rule: str  # a name of batcert.methods.rules.IMPACT_RULES
    window: tuple[float, float]  # [nearest, farthest] distance from the tip [m]
    sweep_points: int
    resolution: float  # [m]
    from_tip: float | None  # fixed-from-tip distance [m]


@dataclass(frozen=True)
class LimitSpec:
    """The pass/fail limit of the aggregated metric."""

    max: float  # largest passing value (m/s for exit speed)
    tolerance: float  # added to max before the verdict
    source: str | None


@dataclass(frozen=True)
class ProtocolSpec:
    """A validated protocol (a file, or an inline entry of a study file)."""

    source: Source
    id: str
    title: str
    reference: str
    version: str
    description: str | None
    notes: str | None
    pivot: float  # from the knob [m]
    ball: str  # shipped name or path relative to the file
    support: str  # pinned | free
    conditions: tuple[ConditionSpec, ...]
    impact_location: LocationSpec
    metric: str  # a name of batcert.methods.metrics.METRICS
    aggregate: str  # a name of batcert.methods.metrics.AGGREGATES
    limit: LimitSpec | None
    origin: tuple[str | int, ...] = ()
    barrel_compression: CompressionTestSpec | None = None
    break_in: BreakInSpec | None = None  # keys of an inline protocol inside its study file

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def sha256(self) -> str:
        return self.source.sha256

    def line(self, *keys: str | int) -> int | None:
        """Line of one of this protocol's keys in its file."""
        return self.source.line(*self.origin, *keys)

    def field(self, dotted: str) -> str:
        """The dotted name of one of this protocol's fields in its file (an inline protocol's
        fields are under its place in the study file)."""
        prefix = "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in self.origin)
        return (prefix.lstrip(".") + "." + dotted) if prefix else dotted

    def problem(self, dotted: str, message: str) -> InputError:
        """An :class:`InputError` at one of this protocol's fields (dotted, e.g.
        ``"impact_location.window"``), with its line."""
        return InputError([Problem(self.path, self.line(*split_field(dotted)),
                                   self.field(dotted), message)])


def protocol_from_values(values: dict[str, Any], source: Source,
                         origin: tuple[str | int, ...] = ()) -> ProtocolSpec:
    """A :class:`ProtocolSpec` from the validated values of :data:`PROTOCOL_SCHEMA`."""
    v = dict(values)
    v["conditions"] = tuple(spec_from(ConditionSpec, {**c, "bat_speed_from_moi": spec_from(
        SwingScalingSpec, c["bat_speed_from_moi"]) if c.get("bat_speed_from_moi") else None})
        for c in v["conditions"])
    loc = dict(v["impact_location"])
    loc["window"] = tuple(loc["window"])
    v["impact_location"] = spec_from(LocationSpec, loc)
    v["limit"] = spec_from(LimitSpec, v["limit"]) if v["limit"] else None
    v["barrel_compression"] = (spec_from(CompressionTestSpec, v["barrel_compression"])
                               if v.get("barrel_compression") else None)
    v["break_in"] = spec_from(BreakInSpec, v["break_in"]) if v.get("break_in") else None
    return spec_from(ProtocolSpec, v, source=source, origin=origin)


def duplicate_condition_names(values: dict[str, Any], data: Located, errors: Collector,
                              path: str = "") -> None:
    """Condition names must be unique within a protocol (they key the results)."""
    names = [c["name"] for c in values["conditions"]]
    prefix = f"{path}." if path else ""
    for i, n in enumerate(names):
        if n in names[:i]:
            errors.add(lookup(data, "conditions", i, "name")[0], f"{prefix}conditions[{i}].name",
                       f"duplicate condition name {n!r}")


def load_protocol(path: str | Path) -> ProtocolSpec:
    """Read and validate a protocol file; raise InputError with every problem of the file."""
    data = load_yaml(path)
    errors = Collector(path)
    values = validate(data, PROTOCOL_SCHEMA, errors)  # every field's problem, then the ones below
    if values is not None:
        if values.get("conditions") is not None:
            duplicate_condition_names(values, data, errors)
        _check_ball_exists(values.get("ball"), data, errors, Path(path))
    errors.raise_if_any()
    assert values is not None
    return protocol_from_values(values, Source.of(path, data))


def _check_ball_exists(ball: str | None, data: Located, errors: Collector, path: Path) -> None:
    """The ball a protocol names is a shipped ball or a file (relative to the protocol):
    said with the file's other problems, not after they are fixed."""
    from batcert.specs.resolve import NotFound, resolve
    if not ball:
        return
    try:
        resolve("ball", ball, relative_to=path)
    except NotFound as exc:
        line, col = where(data, "ball")
        errors.add(line, "ball", str(exc), col)
