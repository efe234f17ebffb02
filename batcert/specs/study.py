"""Study specification: a named set of protocols to compare bats under, and the claims to test.

A study (e.g. ``protocols/studies/smith2001.yaml``) lists protocols by shipped id, by path relative
to the study file, or inline (a mapping with the protocol fields). It may name default bats (the
first is the reference of the relative performance P) and the published ``claims`` to test against
the model's results: each claim names a check from :data:`batcert.specs.kinds.CLAIM_CHECKS` (the
registry of checks, evaluated there) and the protocols it concerns. The comparison report states,
for each claim, whether the model supports it, and with which numbers; nothing is fitted to make it
so."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from batcert.errors import Collector, InputError
from batcert.specs.common import Source, spec_from
from batcert.specs.kinds import CLAIM_CHECKS
from batcert.specs.protocol import (
    PROTOCOL_SCHEMA,
    ProtocolSpec,
    duplicate_condition_names,
    load_protocol,
    protocol_from_values,
)
from batcert.specs.schema import (
    Field,
    FieldError,
    Kind,
    Schema,
    choice,
    label,
    list_of,
    lookup,
    number,
    quantity,
    section,
    text,
    validate,
)
from batcert.specs.yamlio import Located, load_yaml


def _protocol_entry() -> Kind:
    inline = section(PROTOCOL_SCHEMA)

    def parse(value, errors: Collector, path: str):
        if isinstance(value, Located):
            return {"inline": inline.parse(value, errors, path), "data": value}
        if isinstance(value, (str, int, float)) and not isinstance(value, bool):
            return str(value)
        raise FieldError("expected a protocol id, a path, or an inline protocol mapping")

    return Kind("protocol id, path (relative to the study) or inline protocol mapping", parse)


CLAIM_SCHEMA = Schema("study claim", (
    Field("id", label(), "Short claim name.", required=True),
    Field("statement", text(), "The study's claim in words.", required=True),
    Field("source", text(), "Where the study makes it."),
    Field("check", choice(*CLAIM_CHECKS), "How the model's results test it (the claim checks "
          "table below).", required=True),
    Field("protocols", list_of(text(), min_items=1, describe="list of protocol ids"),
          "Protocol ids (of this study) the check reads.", required=True),
    Field("compare_with", list_of(text(), min_items=1, describe="list of protocol ids"),
          "consistent-across-conditions: protocols whose spread of P is the yardstick."),
    Field("expected", choice("shown", "not-shown"), "advantage: what the study says.",
          default="shown"),
    Field("tolerance", number(minimum=0.0), "Dead band on P [-]: |P| below it counts as no "
          "difference.", default=0.005),
    Field("location_tolerance", quantity("length", minimum=0.0), "Dead band on positions.",
          default=0.01),
    Field("factor", number(exclusive_minimum=0.0, maximum=1.0), "sweet-spot-moves-less-than-"
          "rigid and figure-sweet-spot-less-than-rigid: largest accepted ratio of movements.",
          default=0.5),
    Field("figure", text(), "Figure checks: the id of the study figure the check reads."),
    Field("metrics", list_of(text(), min_items=2, max_items=2, describe="two metric names"),
          "opposite-trends: the two metrics whose trends are compared."),
))

FIGURE_SCHEMA = Schema("study figure", (
    Field("id", label(), "Short figure name (file names, claims' `figure`).", required=True),
    Field("title", label(), "What the figure shows.", required=True),
    Field("protocol", text(), "Protocol id (of this study) whose test the figure varies.",
          required=True),
    Field("condition", text(), "The protocol's condition that is run.", required=True),
    Field("vary", text(), "PARAM=START:STOP:N, as `batcert sweep --vary`.", required=True),
    Field("metrics", list_of(text(), min_items=1, describe="list of quantities"),
          "Quantities plotted against the parameter (sweep names: bpf, besr, sweet_spot, "
          "rigid_sweet_spot, cop, ...).", required=True),
    Field("bats", choice("all", "compared"), "Every bat, or the bats compared with the "
          "reference.", default="all"),
))

STUDY_SCHEMA = Schema("study", (
    Field("id", label(), "Short identifier (`--study ID`).", required=True),
    Field("title", label(), "Full title.", required=True),
    Field("reference", text(), "The study replayed.", required=True),
    Field("version", text(), "Version of this study definition.", required=True),
    Field("description", text(), "What is compared and how."),
    Field("notes", text(), "What differs from the study, and what the model cannot reproduce."),
    Field("bats", list_of(text(), min_items=1, describe="list of bat names or paths"),
          "Default bats (shipped names or paths relative to the study); the first is the "
          "reference."),
    Field("protocols", list_of(_protocol_entry(), min_items=1, describe="list of protocols"),
          "Protocols, in report order.", required=True),
    Field("figures", list_of(section(FIGURE_SCHEMA), describe="list of figures"),
          "Figures of the study: a parameter swept on a protocol's condition, per bat.",
          default=[]),
    Field("claims", list_of(section(CLAIM_SCHEMA), describe="list of claims"),
          "The study's conclusions, each tested against the model's results.", default=[]),
))


@dataclass(frozen=True)
class ClaimSpec:
    """One published claim of a study and how the model's results test it."""

    id: str
    statement: str
    source: str | None
    check: str  # a name of batcert.specs.kinds.CLAIM_CHECKS
    protocols: list[str]
    compare_with: list[str] | None
    expected: str  # shown | not-shown
    tolerance: float  # dead band on P [-]
    location_tolerance: float  # dead band on positions [m]
    factor: float  # sweet-spot-moves-less-than-rigid: largest accepted ratio [-]
    figure: str | None = None  # figure checks: the study figure read
    metrics: list[str] | None = None  # opposite-trends: the two metrics


@dataclass(frozen=True)
class FigureSpec:
    """A study figure: a parameter swept on one condition of one of the study's protocols."""

    id: str
    title: str
    protocol: str  # protocol id of this study
    condition: str
    vary: str  # PARAM=START:STOP:N
    metrics: list[str]
    bats: str  # all | compared


@dataclass(frozen=True)
class StudySpec:
    """A validated study: its protocols loaded, its default bats resolved, its claims."""

    source: Source
    id: str
    title: str
    reference: str
    version: str
    description: str | None
    notes: str | None
    protocols: tuple[ProtocolSpec, ...]  # resolved and validated, in study order
    bats: tuple[Path, ...]  # resolved default bats (may be empty)
    claims: tuple[ClaimSpec, ...]
    figures: tuple[FigureSpec, ...] = ()

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def sha256(self) -> str:
        return self.source.sha256


def _inline_protocol(entry: dict, source: Source, i: int, errors: Collector) -> ProtocolSpec:
    duplicate_condition_names(entry["inline"], source.data, errors, f"protocols[{i}]")
    return protocol_from_values(entry["inline"], source, ("protocols", i))


def load_study(path: str | Path) -> StudySpec:
    """Read a study, load every protocol it names, check its claims refer to them.

    Raises InputError with every problem of the study file (a referenced protocol file with
    errors raises that file's problems).
    """
    path = Path(path)
    data = load_yaml(path)
    errors = Collector(path)
    v = validate(data, STUDY_SCHEMA, errors)
    errors.raise_if_any()
    assert v is not None
    source = Source.of(path, data)
    protocols, nested = _load_protocols(v, path, source, data, errors)
    ids = [p.id for p in protocols]
    for i, pid in enumerate(ids):
        if pid in ids[:i]:
            errors.add(lookup(data, "protocols")[0], "protocols", f"protocol id {pid!r} appears "
                       "twice; a comparison needs distinct ids")
    if not nested:
        _check_claims(v, ids, data, errors)
        _check_figures(v, protocols, data, errors)
    bats = _resolve_bats(v, path, data, errors)
    problems = list(errors.problems) + [p for e in nested for p in e.problems]
    if problems:
        raise InputError(problems)
    claims = tuple(spec_from(ClaimSpec, c) for c in v["claims"] or [])
    figures = tuple(spec_from(FigureSpec, f) for f in v["figures"] or [])
    return spec_from(StudySpec, {**v, "protocols": tuple(protocols), "bats": tuple(bats),
                                 "claims": claims, "figures": figures}, source=source)


def _load_protocols(v: dict, path: Path, source: Source, data: Located, errors: Collector
                    ) -> tuple[list[ProtocolSpec], list[InputError]]:
    """The study's protocols, inline or from their files, each with its ball resolved; the
    problems of protocol files that do not load are kept apart (``nested``), whole."""
    from batcert.specs.resolve import NotFound, resolve

    protocols: list[ProtocolSpec] = []
    nested: list[InputError] = []
    for i, entry in enumerate(v["protocols"]):
        if isinstance(entry, dict):
            protocols.append(_inline_protocol(entry, source, i, errors))
            ball_of, rel = entry["inline"]["ball"], path
        else:
            try:
                p = resolve("protocol", entry, relative_to=path)
            except NotFound as exc:
                errors.add(lookup(data, "protocols", i)[0], f"protocols[{i}]", str(exc))
                continue
            try:
                protocols.append(load_protocol(p))
            except InputError as exc:
                nested.append(exc)
                continue
            ball_of, rel = protocols[-1].ball, p
        try:
            resolve("ball", ball_of, relative_to=rel)
        except NotFound as exc:
            errors.add(lookup(data, "protocols", i)[0], f"protocols[{i}]", str(exc))
    return protocols, nested


def _check_claims(v: dict, ids: list[str], data: Located, errors: Collector) -> None:
    """A claim reads protocols of the study (``ids``); lower-than reads exactly two."""
    for i, claim in enumerate(v["claims"] or []):
        for key in ("protocols", "compare_with"):
            for j, pid in enumerate(claim[key] or []):
                if pid not in ids:
                    errors.add(lookup(data, "claims", i, key, j)[0],
                               f"claims[{i}].{key}[{j}]", f"{pid!r} is not a protocol of this "
                               f"study ({', '.join(ids)})")
        if claim["check"] == "lower-than" and len(claim["protocols"]) != 2:
            errors.add(lookup(data, "claims", i, "protocols")[0], f"claims[{i}].protocols",
                       "lower-than compares exactly two protocols: [lower, higher]")


def _resolve_bats(v: dict, path: Path, data: Located, errors: Collector) -> list[Path]:
    """The study's default bats, resolved (shipped names or paths relative to the study)."""
    from batcert.specs.resolve import NotFound, resolve

    bats: list[Path] = []
    for i, b in enumerate(v["bats"] or []):
        try:
            bats.append(resolve("bat", b, relative_to=path))
        except NotFound as exc:
            errors.add(lookup(data, "bats", i)[0], f"bats[{i}]", str(exc))
    return bats


def _check_figures(v: dict, protocols: list[ProtocolSpec], data: Located,
                   errors: Collector) -> None:
    """A figure names a protocol and condition of the study; a figure claim names a figure of
    the study. (Its parameter and quantities are checked against their registries by
    :func:`batcert.sweeps.study_figures.check_figures`.)"""
    by_id = {p.id: p for p in protocols}
    for i, f in enumerate(v["figures"] or []):
        def add(key: str, message: str, i: int = i) -> None:
            errors.add(lookup(data, "figures", i, key)[0], f"figures[{i}].{key}", message)
        p = by_id.get(f["protocol"])
        if p is None:
            add("protocol", f"{f['protocol']!r} is not a protocol of this study "
                f"({', '.join(by_id)})")
        elif f["condition"] not in [c.name for c in p.conditions]:
            add("condition", f"protocol {p.id!r} has no condition {f['condition']!r} "
                f"({', '.join(c.name for c in p.conditions)})")
    ids = [f["id"] for f in v["figures"] or []]
    for i, fid in enumerate(ids):
        if fid in ids[:i]:
            errors.add(lookup(data, "figures", i, "id")[0], f"figures[{i}].id",
                       f"figure id {fid!r} appears twice (it names the figure's files)")
    metrics_of = {f["id"]: f["metrics"] for f in v["figures"] or []}
    for i, claim in enumerate(v["claims"] or []):
        if claim["check"].startswith(("opposite-trends", "figure-")):
            if claim["figure"] not in ids:
                errors.add(lookup(data, "claims", i, "figure")[0] if claim["figure"] else
                       lookup(data, "claims", i)[0], f"claims[{i}].figure",
                           f"the {claim['check']} check needs `figure:`, the id of one of the "
                           f"study's figures ({', '.join(ids) or 'none'})")
        if claim["check"] == "opposite-trends" and not claim["metrics"]:
            errors.add(lookup(data, "claims", i)[0], f"claims[{i}].metrics",
                       "opposite-trends needs the two `metrics:` to compare")
        elif claim["check"] == "opposite-trends" and claim["figure"] in metrics_of:
            missing = [m for m in claim["metrics"] if m not in metrics_of[claim["figure"]]]
            if missing:
                errors.add(lookup(data, "claims", i, "metrics")[0], f"claims[{i}].metrics",
                           f"figure {claim['figure']!r} does not plot {', '.join(missing)} "
                           f"(it plots {', '.join(metrics_of[claim['figure']])})")
