"""Results of a sweep (a bat or test parameter varied) and of a design study (a parameter solved
for the protocol's limit): plain dataclasses in SI units, every array aligned with ``values``.

A variant the model cannot build or solve has None in every array and its reason in ``errors``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from batcert.results.serialise import Serialisable

# The per-condition quantities a sweep records for every variant, with their units (the names
# of batcert.results.run.ConditionResult).
CONDITION_FIELDS: dict[str, str] = {
    "metric_value": "protocol metric", "exit_speed": "m/s", "cor": "-", "bpf": "-", "besr": "-",
    "bbcor": "-", "collision_efficiency": "-", "impact_location": "m from pivot",
    "sweet_spot": "m from pivot", "rigid_sweet_spot": "m from pivot", "cop": "m from pivot",
    "pitch_speed": "m/s", "bat_angular_speed": "rad/s", "relative_speed": "m/s",
    "at_window_edge": "bool",  # the located impact point lies on the search window's edge
}
# The per-variant quantities (the bat's mass properties about the pivot, the barrel).
VARIANT_FIELDS: dict[str, str] = {
    "value": "protocol metric", "margin": "protocol metric", "value_low": "protocol metric",
    "value_high": "protocol metric", "mass": "kg", "cg": "m from pivot",
    "moi_pivot": "kg m^2", "cop": "m from pivot", "hoop_frequency": "Hz",
}


@dataclass
class SweepAxis:
    name: str  # a name of batcert.sweeps.variants.PARAMETERS
    dimension: str | None  # batcert.units dimension of the values
    unit: str  # SI unit of the values
    changes: str  # geometry | measured | protocol
    doc: str
    nominal: float | None  # the nominal bat's or protocol's value [SI] (None: not given)
    values: list[float]  # [SI]
    percent: bool  # given on the command line as percent of nominal
    label: str = ""  # the parameter in words ("bat angular speed"); "" in 0.2's documents


@dataclass
class SweepCondition:
    name: str
    rigid_applies: bool  # Eq. 7's rigid sweet spot is defined (fixed speeds, w1 > 0)
    series: dict[str, list[float | None]]  # CONDITION_FIELDS name -> one value per variant


@dataclass
class NominalRun:
    """The nominal bat as its file gives it (with its measurements), for contrast."""

    value: float | None
    margin: float | None
    verdict: str | None
    reconciliation: str  # the corrections its measurements made to the geometry
    corrections: dict[str, float]
    geometry_mass: float  # [kg]
    measured_mass: float | None  # [kg]
    error: str | None = None


@dataclass(repr=False)
class SweepResult(Serialisable):
    KIND = "sweep"
    SUMMARY = ("bat", "protocol", "metric", "axes", "points", "engine")

    bat: str
    bat_path: str
    protocol: str
    protocol_title: str
    metric: str
    aggregate: str
    limit: float | None
    tolerance: float
    engine: str
    engine_settings: dict[str, Any]
    axes: list[SweepAxis]
    points: list[list[float]]  # one row per variant: its value of each axis [SI]
    series: dict[str, list[float | None]]  # VARIANT_FIELDS name -> one value per variant
    verdicts: list[str | None]
    errors: list[str | None]  # why a variant has no result, None where it has one
    conditions: list[SweepCondition]
    nominal: NominalRun | None  # the bat as measured (None when nothing was measured)
    notes: list[str]  # what the variants are built from, in words
    warnings: list[str]
    inputs: list[dict[str, str]]
    batcert_version: str
    created: str
    design: DesignResult | None = None
    bat_identification: dict[str, str] = field(default_factory=dict)  # maker, model, serial, lot

    def return_code(self) -> int:
        """A sweep: 0. A design: 0 when a value meets the limit, 1 when none does."""
        return 0 if self.design is None or self.design.roots else 1

    @property
    def parameter(self) -> str | list[str]:
        names = [a.name for a in self.axes]
        return names[0] if len(names) == 1 else names

    @property
    def values(self) -> list[float] | list[list[float]]:
        return [p[0] for p in self.points] if len(self.axes) == 1 else self.points

    def _kind(self) -> str:
        return "design" if self.design is not None else "sweep"

    def _document(self) -> dict[str, Any]:
        """The dataclass, led by ``parameter`` and ``values`` (a list for one axis, a list of
        [value, value] pairs for a grid), then ``metrics``: every quantity's array aligned with
        ``values``."""
        data = super()._document()
        metrics: dict[str, Any] = dict(self.series)
        metrics["verdict"] = self.verdicts
        for c in self.conditions:
            for k, v in c.series.items():
                metrics[f"{c.name}.{k}"] = v
        return {"parameter": self.parameter, "values": self.values, "metrics": metrics, **data}


@dataclass
class DesignRoot:
    value: float  # the parameter value where the margin is zero [SI]
    bracket: list[float]  # the values that bracketed it [SI]
    evaluations: int  # engine evaluations of the refinement
    passes_above: bool  # the protocol passes for values above the root
    mass: float | None = None  # the bat's mass at the root [kg] (its geometry's, as variants)
    length: float | None = None  # and its length [m]: the drop a league rule reads


@dataclass
class DesignResult:
    parameter: str
    tolerance: float  # the root is located to within this [SI]
    roots: list[DesignRoot]
    range: list[float]  # the range searched [SI]
