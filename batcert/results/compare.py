"""Results of a side-by-side comparison of bats under several protocols (SI units).

Built by :func:`batcert.analysis.compare.compare` from the bats' run results; reports only read
them and a saved comparison JSON re-renders through :meth:`ComparisonResult.from_dict`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from batcert.results.serialise import Serialisable


@dataclass
class Spread:
    """Mean and spread of P across a protocol's conditions [-]; None when any P is undefined."""

    mean: float | None
    std: float | None  # population standard deviation (ddof = 0): the conditions are all of them
    min: float | None
    max: float | None
    range: float | None  # max - min

    @classmethod
    def of(cls, values: Sequence[float | None]) -> Spread:
        if not values or any(v is None for v in values):
            return cls(None, None, None, None, None)
        vals = [float(v) for v in values if v is not None]
        mean = sum(vals) / len(vals)
        std = math.sqrt(sum((v - mean) ** 2 for v in vals) / len(vals))
        return cls(mean, std, min(vals), max(vals), max(vals) - min(vals))


@dataclass
class BatCondition:
    """One bat in one condition of one protocol. Positions are from the protocol's pivot [m]."""

    value: float  # the protocol metric
    relative: float | None  # P against the reference bat, Eq. 6 [-]
    exit_speed: float  # [m/s]
    pitch_speed: float  # [m/s], negative toward the bat
    bat_angular_speed: float  # [rad/s]
    relative_speed: float  # at the impact location [m/s]
    impact_location: float  # [m from pivot]
    cop: float  # centre of percussion, Eq. 4 [m from pivot]
    sweet_spot: float  # maximum exit speed in the window [m from pivot]
    sweet_spot_minus_cop: float  # [m]
    sweet_spot_at_edge: bool  # the exit-speed maximum lies on the search window's edge
    rigid_sweet_spot: float | None  # Eq. 7 [m from pivot]; None when w1 = 0 or speeds matched


@dataclass
class ConditionComparison:
    name: str
    setup: str
    bats: dict[str, BatCondition]  # by bat label


@dataclass
class BatMass:
    """Mass properties of one bat about one protocol's pivot."""

    mass: float  # [kg]
    cg: float  # [m from pivot]
    moi_pivot: float  # [kg m^2]
    cop: float  # [m from pivot]


@dataclass
class ProtocolComparison:
    protocol: str
    title: str
    reference: str
    version: str
    metric: str
    impact_rule: str
    aggregate: str
    pivot: float  # [m from knob]
    ball: str
    limit: float | None
    conditions: list[ConditionComparison]
    aggregate_value: dict[str, float]  # the run's aggregated metric, by bat label
    aggregate_relative: dict[str, float | None]  # P of the aggregated values
    relative_spread: dict[str, Spread]  # P across conditions, by bat label
    verdicts: dict[str, str | None]
    mass: dict[str, BatMass]


@dataclass
class BatEntry:
    label: str  # unique key used in every per-bat mapping
    name: str
    path: str
    sha256: str
    length: float  # [m]
    construction: str | None = None
    material: str | None = None


@dataclass
class ClaimResult:
    id: str
    statement: str
    source: str
    check: str
    status: str  # supported | not-supported | not-testable
    evidence: str  # what the model's numbers show, in one or two sentences


@dataclass
class StudyFigureBat:
    label: str
    nominal: float | None  # the bat's nominal value of the parameter [SI], if given
    values: list[float]  # the parameter's values for this bat [SI]
    series: dict[str, list[float | None]]  # quantity -> one value per parameter value


@dataclass
class StudyFigure:
    """A study figure: a parameter swept on one condition of a protocol, per bat."""

    id: str
    title: str
    protocol: str
    condition: str
    parameter: str
    dimension: str | None
    percent: list[float] | None  # the values as percent of each bat's nominal, when so given
    metrics: list[str]
    bats: list[StudyFigureBat]


@dataclass(repr=False)
class ComparisonResult(Serialisable):
    KIND = "comparison"
    SUMMARY = ("reference", "bats", "protocols", "claims", "engine")

    title: str
    study: str | None
    study_reference: str
    study_notes: str
    reference: str  # label of the reference bat
    bats: list[BatEntry]
    protocols: list[ProtocolComparison]
    claims: list[ClaimResult]
    findings: list[str]
    warnings: list[str]
    engine: str
    engine_settings: dict[str, Any]
    inputs: list[dict[str, str]]  # role, name, path, sha256 of every input file
    batcert_version: str
    created: str
    figures: list[StudyFigure] = field(default_factory=list)

    def return_code(self) -> int:
        """1 when a protocol with a limit fails for at least one bat, else 0."""
        return 1 if any(v == "fail" for p in self.protocols for v in p.verdicts.values()) else 0

    def protocol(self, pid: str) -> ProtocolComparison:
        return next(p for p in self.protocols if p.protocol == pid)

    @property
    def compared(self) -> list[str]:
        """Labels of the bats compared with the reference."""
        return [b.label for b in self.bats if b.label != self.reference]
