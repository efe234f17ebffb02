"""Batter profile: how fast a batter of some level swings, what is pitched, and which ball.

A batter file states a level of play (youth, high school, college, professional, fast- and
slow-pitch softball) by cited figures: the bat speed measured at a station near the head of a
typical bat of stated length and moment of inertia, the exponent of the swing law ``w = C / I^n``
(:func:`batcert.physics.swing.swing_speed`) with its uncertainty, and the pitch speed. ``batcert
field`` swings any bat at the speed this law gives it and reports how hard and how far it hits.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from batcert.conventions import BODIES
from batcert.specs.common import HEADER_FIELDS, Source, load_checked, spec_from
from batcert.specs.schema import Field, Schema, choice, label, number, quantity, section, text
from batcert.specs.yamlio import load_yaml

__all__ = ["BATTER_SCHEMA", "BatterSpec", "SwingLawSpec", "load_batter"]

SWING_SCHEMA = Schema("swing", (
    Field("bat_speed", quantity("speed", minimum=5.0, maximum=60.0, uncertain=True),
          "Bat speed of the level's batters at `speed_from_tip` on the reference bat (5-60 m/s); "
          "`+/- u` states its standard uncertainty (the spread of the level's mean, not of its "
          "batters).", required=True),
    Field("speed_from_tip", quantity("length", minimum=0.0, maximum=0.3), "Where on the bat "
          "`bat_speed` is measured, from the tip (bat tracking: 6 in).", default=0.1524),
    Field("reference_length", quantity("length", minimum=0.5, maximum=1.2), "Length of the bat "
          "`bat_speed` was measured with (a typical bat of the level).", required=True),
    Field("reference_moi", quantity("moi", positive=True), "That bat's moment of inertia about "
          "the swing axis (`axis_from_knob`).", required=True),
    Field("axis_from_knob", quantity("length", minimum=-0.3, maximum=0.3), "Where the swing's "
          "axis of rotation crosses the bat at impact, from the knob toward the barrel "
          "(negative: beyond the knob). Nathan et al. (2011) put it near the knob.",
          default=0.0),
    Field("exponent", number(minimum=0.0, maximum=1.0), "n of `w = C / I^n` (Cross & Bower "
          "2006: 0.25-0.27).", required=True),
    Field("exponent_uncertainty", number(minimum=0.0, maximum=0.5), "Standard uncertainty of "
          "`exponent`.", default=0.0),
    Field("source", text(), "Where the bat speed, the reference bat and the exponent come "
          "from.", required=True),
))

BATTER_SCHEMA = Schema("batter", (
    Field("name", label(), "Profile name shown in reports.", required=True),
    *HEADER_FIELDS,
    Field("body", choice(*BODIES), "The game: which ball flies.", required=True),
    Field("ball", label(), "Shipped ball name or ball file path (relative to this file): the "
          "ball hit.", required=True),
    Field("pitch_speed", quantity("speed", minimum=0.0, maximum=60.0), "Pitch speed at the "
          "plate (0-60 m/s).", required=True),
    Field("pitch_source", text(), "Where the pitch speed comes from.", required=True),
    Field("swing", section(SWING_SCHEMA), "The swing law and its reference point.",
          required=True),
), doc="A level of play for `batcert field`: its bat speed, swing law, pitch and ball.")


@dataclass(frozen=True)
class SwingLawSpec:
    """The batter's swing law ``w = w_ref (I / I_ref)^-n`` about the axis near the knob."""

    bat_speed: float  # at speed_from_tip on the reference bat [m/s]; may be Uncertain
    speed_from_tip: float  # [m]
    reference_length: float  # [m]
    reference_moi: float  # about the axis [kg m^2]
    axis_from_knob: float  # [m]
    exponent: float  # [-]
    exponent_uncertainty: float  # standard uncertainty [-]
    source: str

    @property
    def station_radius(self) -> float:
        """The measuring station's distance from the swing axis on the reference bat [m]: the
        bat speed over it is the reference rate ``w_ref``."""
        return self.reference_length - self.speed_from_tip - self.axis_from_knob

    @property
    def bat_speed_uncertainty(self) -> float:
        """The stated standard uncertainty of ``bat_speed`` [m/s] (0 when none)."""
        return float(getattr(self.bat_speed, "u", 0.0))


@dataclass(frozen=True)
class BatterSpec:
    """A validated batter file."""

    source: Source
    name: str
    description: str | None
    reference: str | None
    version: str | None
    body: str
    ball: str  # shipped name or path relative to the file
    pitch_speed: float  # [m/s]
    pitch_source: str
    swing: SwingLawSpec

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def id(self) -> str:
        return Path(self.source.path).stem

    @property
    def sha256(self) -> str:
        return self.source.sha256


def load_batter(path: str | Path) -> BatterSpec:
    """Read and validate a batter file; raise InputError with every problem of the file."""
    data = load_yaml(path)
    v = load_checked(path, BATTER_SCHEMA, data)
    swing = spec_from(SwingLawSpec, v["swing"])
    if swing.station_radius <= 0.05:
        raise Source.of(path, data).problem(
            "swing.speed_from_tip", "the station where the bat speed is measured must lie more "
            "than 5 cm from the swing axis (reference_length - speed_from_tip - axis_from_knob)")
    return spec_from(BatterSpec, {**v, "swing": swing}, source=Source.of(path, data))
