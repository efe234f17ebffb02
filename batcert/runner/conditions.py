"""Test conditions: ball and bat speeds before impact as functions of the impact location."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from batcert.physics.swing import swing_speed

if TYPE_CHECKING:
    from batcert.physics.batmodel import BatModel
    from batcert.specs.protocol import ConditionSpec


@dataclass(frozen=True)
class Condition:
    """One set-up. Speeds follow the study's signs: ``pitch_speed`` negative toward the bat."""

    name: str
    description: str
    setup: str  # "stationary-bat" | "stationary-ball" | "pitched-and-swung"
    pitch: float  # ball speed toward the bat [m/s] (>= 0) for explicit conditions
    bat_angular_speed: float | None  # explicit w1 [rad/s]
    relative_speed: float | None  # matched relative normal speed [m/s]

    def speeds(self, impact_location: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pitch speed v_p [m/s] (negative toward the bat) and bat angular speed w1 [rad/s] at
        each impact location [m from pivot]."""
        r = np.asarray(impact_location, dtype=float)
        vp = np.full_like(r, -self.pitch)
        if self.relative_speed is None:
            return vp, np.full_like(r, self.bat_angular_speed)
        # matched: the moving body makes the relative normal speed equal the target at r
        return vp, (self.relative_speed - self.pitch) / r


def _given(value: float | None) -> float:
    """A speed the protocol schema's checks guarantee is present."""
    assert value is not None
    return value


def _setup(pitch: float, moving_bat: bool) -> str:
    if pitch == 0:
        return "stationary-ball"
    return "pitched-and-swung" if moving_bat else "stationary-bat"


def conditions_from_spec(spec_conditions: Sequence[ConditionSpec], bat: BatModel,
                         pivot: float) -> list[Condition]:
    """The protocol's conditions as speeds for ``bat``: matched relative speeds, explicit angular
    speeds, or a linear bat speed at a distance from the tip converted to an angular speed about
    the pivot; an explicit bat speed is scaled with the bat's MOI about the pivot where the
    condition says so (:func:`batcert.physics.swing.swing_speed`)."""
    bat_length = bat.length
    out = []
    for c in spec_conditions:
        if c.relative_speed is not None:
            v = c.relative_speed
            if c.stationary == "bat":
                pitch, moving = v, False
            elif c.stationary == "ball":
                pitch, moving = 0.0, True
            else:
                pitch, moving = _given(c.pitch_speed), True
            out.append(Condition(c.name, c.description or "", _setup(pitch, moving), pitch,
                                 None, v))
            continue
        if c.bat_angular_speed is not None:
            w1 = c.bat_angular_speed
        else:  # linear bat speed given at a distance from the tip
            w1 = _given(c.bat_speed) / (bat_length - _given(c.bat_speed_from_tip) - pivot)
        if c.bat_speed_from_moi is not None:
            law = c.bat_speed_from_moi
            w1 = float(swing_speed(bat.moi_about(pivot), w1, law.reference_moi, law.exponent))
        pitch = _given(c.pitch_speed)
        out.append(Condition(c.name, c.description or "", _setup(pitch, w1 > 0), pitch, w1,
                             None))
    return out
