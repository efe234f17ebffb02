"""The names and meanings of the checks a study's claim can name and of the kinds a league's rule
can have: what an input file may say, and what the docs tables list. How each is evaluated
lives in :mod:`batcert.analysis.claims` (``CHECKS``) and :mod:`batcert.analysis.league`
(``EVALUATIONS``), keyed by these names (a test holds the two to the same names), so the spec
layer never imports the analysis layer."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["CLAIM_CHECKS", "RULE_KINDS", "ClaimKind", "RuleKind"]


@dataclass(frozen=True)
class ClaimKind:
    """One way of testing a study's claim against a comparison: its name and meaning."""

    name: str
    doc: str


CLAIM_CHECKS: dict[str, ClaimKind] = {c.name: c for c in (
    ClaimKind("sign-disagreement", "P of the compared bat takes both signs (beyond `tolerance`) "
               "across the protocols' conditions: the methods disagree on which bat is better."),
    ClaimKind("consistent-across-conditions", "In each protocol P has one sign in every "
               "condition, beyond `tolerance`, and its range across conditions is smaller than "
               "the range over `compare_with` (when given)."),
    ClaimKind("advantage", "`expected: shown`: the mean P of every compared bat exceeds "
               "`tolerance` in every protocol; `not-shown`: in none of them."),
    ClaimKind("lower-than", "The mean P under the first protocol is below the mean P under the "
               "second by more than `tolerance` (a metric that ignores MOI underrates a light "
               "bat)."),
    ClaimKind("cop-not-sweet-spot", "For every bat and condition the sweet spot lies more than "
               "`location_tolerance` from the centre of percussion."),
    ClaimKind("cop-offset-differs", "The mean sweet-spot-minus-COP offset differs between the "
               "bats by more than `location_tolerance`."),
    ClaimKind("sweet-spot-moves-less-than-rigid", "Across conditions with fixed speeds the "
               "sweet spot moves less than `factor` times the movement of the rigid sweet spot "
               "(Smith 2001 Eq. 7)."),
    ClaimKind("opposite-trends", "In the study figure `figure`, from the nominal value of "
               "its parameter down to the smallest, the two `metrics` change in opposite "
               "directions, each by more than `tolerance`, for every bat."),
    ClaimKind("figure-sweet-spot-less-than-rigid", "In the study figure `figure` (a speed "
               "swept), the sweet spot moves at most `factor` times as far as the rigid sweet "
               "spot (Smith 2001 Eq. 7), over the speeds where Eq. 7 is defined and the sweet "
               "spot lies inside the search window, for every bat."),
)}


@dataclass(frozen=True)
class RuleKind:
    """One kind of league rule: what it checks, what its ``limit`` is (``length``, ``number``,
    ``force``, ``metric``: a number, or a speed for an exit-speed protocol; None: no limit; the league
    schema reads it accordingly), what else it needs, and the unit of its value and limit in
    results."""

    name: str
    describe: str
    limit: str | None
    needs: tuple[str, ...] = ()  # other fields a modelled rule of this kind requires
    unit: str = ""  # "m", "kg m^2", "in - oz", "" ...


RULE_KINDS: dict[str, RuleKind] = {k.name: k for k in (
    RuleKind("max-length", "overall length at most `limit`", "length", unit="m"),
    RuleKind("max-drop", "drop = length [in] - weight [oz] at most `limit` (a plain number; "
             "BBCOR's -3 rule is `limit: 3`)", "number", unit="in - oz"),
    RuleKind("max-mass", "weight (the reconciled model's mass: the measured mass when the bat "
             "file gives one) at most `limit`", "mass", unit="kg"),
    RuleKind("max-barrel-diameter", "largest outer diameter at most `limit`", "length", unit="m"),
    RuleKind("min-diameter", "smallest outer diameter (the handle) at least `limit`", "length", unit="m"),
    RuleKind("construction", "construction must be `required` (solid or hollow)", None, ("required",)),
    RuleKind("material", "material must be one of `allowed` (library names or the classes wood, "
             "metal, composite)", None, ("allowed",)),
    RuleKind("performance", "the protocol's aggregated metric at most `limit` + `tolerance`",
             "metric", ("protocol",)),
    RuleKind("min-barrel-compression", "the barrel compression force of `protocol`'s "
             "compression test (its `barrel_compression`, after its break-in where it has one) "
             "at least `limit` (a force)", "force", ("protocol",), unit="N"),
    RuleKind("other", "any other requirement (only with status: not-modelled)", None),
)}
