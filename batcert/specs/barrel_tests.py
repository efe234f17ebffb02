"""A protocol's static tests of a hollow barrel: the barrel compression test and the
accelerated break-in (ABI) that uses it (fields only; the procedure is
:mod:`batcert.runner.barrel_tests`)."""

from __future__ import annotations

from dataclasses import dataclass

from batcert.specs.schema import Field, Schema, integer, number, quantity, text

COMPRESSION_TEST_SCHEMA = Schema("barrel compression test", (
    Field("position", quantity("length", positive=True), "Centre of the platens, from the tip "
          "(the field testers: 6 in).", required=True),
    Field("platen_width", quantity("length", positive=True, maximum=0.2), "Length of barrel each "
          "flat platen touches, along the bat.", required=True),
    Field("deflection", quantity("length", positive=True, maximum=0.01), "Approach of the two "
          "platens at which the force is read.", required=True),
    Field("min", quantity("force", positive=True), "Smallest passing force (a league's field "
          "limit); omitted: the force is reported without a verdict."),
    Field("source", text(), "Where the test's conventions come from, and which are assumed."),
))

BREAK_IN_SCHEMA = Schema("accelerated break-in", (
    Field("skip_drop", number(minimum=0.0, maximum=0.9), "Rolling is skipped when the bat's "
          "compression has already fallen by more than this share of the new bat's.",
          default=0.15),
    Field("target_drop", number(minimum=0.001, maximum=0.9), "Rolling continues until the "
          "compression has fallen by at least this share of the initial compression.",
          default=0.05),
    Field("damage_per_pass", number(minimum=1e-4, maximum=0.5), "Break-in damage each rolling "
          "pass adds (the loss of the plies' E2 and G12): assumed, as no measured rolling-to-"
          "damage relation was found; the smaller it is, the closer the final drop lies to "
          "`target_drop`.", default=0.01),
    Field("max_passes", integer(minimum=1, maximum=10000), "Passes after which the emulation "
          "stops and says the target was not reached.", default=95),
    Field("source", text(), "Where the procedure comes from, and which steps are assumed."),
))


@dataclass(frozen=True)
class CompressionTestSpec:
    """The barrel compression test (SI)."""

    position: float  # centre of the platens from the tip [m]
    platen_width: float  # [m]
    deflection: float  # platens' approach [m]
    min: float | None  # smallest passing force [N]
    source: str | None


@dataclass(frozen=True)
class BreakInSpec:
    """The accelerated break-in procedure (shares of the compression; damage per pass)."""

    skip_drop: float
    target_drop: float
    damage_per_pass: float
    max_passes: int
    source: str | None
