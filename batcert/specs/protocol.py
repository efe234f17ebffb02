"""Protocol specification: conditions, impact-location rule, metric, aggregation, limit."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from batcert.errors import Collector
from batcert.specs.common import sha256_of
from batcert.specs.schema import (Field, Schema, choice, integer, list_of, lookup, number, one_of, quantity,
                                  section, text, validate)
from batcert.specs.yamlio import Located, load_yaml

METRICS = ("exit-speed", "besr", "bpf", "bbcor", "collision-efficiency")
RULES = ("cop", "sweet-spot", "max-metric", "fixed-from-tip")


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
        return
    if v["stationary"] is None and v["pitch_speed"] is None:
        errors.add(data.line, f"{path}.stationary", "relative_speed needs stationary: bat|ball, or "
                   "a pitch_speed (the bat then makes up the rest)")
    if v["stationary"] is not None and v["pitch_speed"] is not None:
        errors.add(lookup(data, "pitch_speed")[0], f"{path}.pitch_speed", "with stationary set, "
                   "pitch_speed follows from relative_speed; remove one")
    if v["pitch_speed"] is not None and v["pitch_speed"] >= v["relative_speed"]:
        errors.add(lookup(data, "pitch_speed")[0], f"{path}.pitch_speed", "must be below "
                   "relative_speed (the bat must move toward the ball)")


CONDITION_SCHEMA = Schema("test condition", (
    Field("name", text(), "Condition name used in tables and JSON.", required=True),
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
), checks=(_check_condition,))


def _check_location(v: dict, data: Located, errors: Collector, path: str) -> None:
    if v["rule"] == "fixed-from-tip" and v["from_tip"] is None:
        errors.add(data.line, f"{path}.from_tip", "the fixed-from-tip rule needs from_tip")
    if v["window"] is not None and v["window"][0] >= v["window"][1]:
        errors.add(lookup(data, "window")[0], f"{path}.window", "give [nearest, farthest] "
                   "distance from the tip, nearest first")


LOCATION_SCHEMA = Schema("impact-location rule", (
    Field("rule", choice(*RULES), "cop: centre of percussion (Eq. 4); sweet-spot: maximum exit "
          "speed; max-metric: maximum of the metric; fixed-from-tip.", required=True),
    Field("window", list_of(quantity("length", minimum=0.0), min_items=2,
                            describe="[nearest, farthest] distance from the tip"),
          "Search window as distances from the tip.", default=[0.03, 0.30]),
    Field("sweep_points", integer(minimum=5, maximum=2001), "Coarse sweep points over the window.",
          default=71),
    Field("resolution", quantity("length", positive=True), "Located to at least this.",
          default=0.001),
    Field("from_tip", quantity("length", positive=True), "Impact distance from the tip for "
          "fixed-from-tip."),
), checks=(_check_location,))

LIMIT_SCHEMA = Schema("limit", (
    Field("max", one_of(number(), quantity("speed"), describe="a number, or a speed for "
                        "exit-speed"), "Largest passing value of the aggregated metric.",
          required=True),
    Field("tolerance", one_of(number(minimum=0.0), quantity("speed", minimum=0.0),
                              describe="a number, or a speed for exit-speed"),
          "Added to max before the verdict (measurement tolerance).", default=0.0),
    Field("source", text(), "Where the limit comes from."),
))


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


PROTOCOL_SCHEMA = Schema("protocol", (
    Field("id", text(), "Short identifier (`--protocol ID`).", required=True),
    Field("title", text(), "Full title.", required=True),
    Field("reference", text(), "Standard or paper the protocol follows.", required=True),
    Field("version", text(), "Version of this protocol definition.", required=True),
    Field("description", text(), "What the protocol measures."),
    Field("notes", text(), "Which details are assumed rather than taken from the reference."),
    Field("pivot", quantity("length", minimum=0.0), "Pivot distance from the knob end.",
          default=0.1524),
    Field("ball", text(), "Ball: shipped name (e.g. collegiate-baseball) or path relative to "
          "this file.", required=True),
    Field("support", choice("pinned", "free"), "Bat pinned at the pivot or free.",
          default="pinned"),
    Field("conditions", list_of(section(CONDITION_SCHEMA), min_items=1, describe="list of "
          "conditions"), "Test conditions (set-ups and speeds).", required=True),
    Field("impact_location", section(LOCATION_SCHEMA), "Where the ball strikes.", required=True),
    Field("metric", choice(*METRICS), "Performance metric.", required=True),
    Field("aggregate", choice("mean", "min", "max"), "How conditions combine.", default="mean"),
    Field("limit", section(LIMIT_SCHEMA), "Pass/fail limit (omit for no verdict)."),
), checks=(_check_limit,))


@dataclass(frozen=True)
class ProtocolSpec:
    path: str
    sha256: str
    id: str
    values: dict


def load_protocol(path: str | Path) -> ProtocolSpec:
    data = load_yaml(path)
    errors = Collector(path)
    v = validate(data, PROTOCOL_SCHEMA, errors)
    if not errors.problems:
        names = [c["name"] for c in v["conditions"]]
        for i, n in enumerate(names):
            if n in names[:i]:
                errors.add(lookup(data, "conditions", i, "name")[0], f"conditions[{i}].name",
                           f"duplicate condition name {n!r}")
    errors.raise_if_any()
    return ProtocolSpec(str(path), sha256_of(path), v["id"], v)
