"""League specification: the rules a bat must meet to be legal in a league, each with its source.

A league file lists rules. Each rule has a ``kind`` from
:data:`batcert.specs.kinds.RULE_KINDS` (the registry: the kind says how its ``limit`` is read,
which other fields it needs and how it is evaluated), the bats it ``applies_to`` (all,
wood or non-wood), a ``source`` and a ``confidence`` (H, M, L, D as in docs/references.md). A rule
that batcert cannot evaluate yet is written with ``status: not-modelled`` and a ``reason``; the
league report then lists it as not modelled instead of passing it. The evaluation itself lives in
:mod:`batcert.analysis.league`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from batcert.errors import Collector
from batcert.methods.metrics import METRIC_BOUND
from batcert.specs.common import Source, spec_from
from batcert.specs.kinds import RULE_KINDS
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
    one_of,
    quantity,
    section,
    text,
    validate,
)
from batcert.specs.yamlio import Located, LocatedList, load_yaml, where

MATERIAL_CLASSES = ("wood", "metal", "composite")
CONFIDENCE = ("H", "M", "L", "D")


# how each kind of limit of batcert.specs.kinds.RULE_KINDS is read
LIMIT_KINDS: dict[str, Kind] = {
    "length": quantity("length", positive=True),
    "number": number(),
    "force": quantity("force", positive=True),
    "mass": quantity("mass", positive=True),
    "metric": one_of(number(minimum=-METRIC_BOUND, maximum=METRIC_BOUND),
                     quantity("speed", minimum=0.0), describe="a number, or a speed for an "
                     "exit-speed protocol"),
}


def runs_protocol(kind: str | None) -> bool:
    """Whether a rule of ``kind`` reads a protocol's run (its kind needs ``protocol``); False
    for a kind that did not parse."""
    entry = RULE_KINDS.get(kind) if isinstance(kind, str) else None
    return entry is not None and "protocol" in entry.needs


def _raw() -> Kind:
    """A scalar kept as written; the rule's kind parses it in :func:`_check_rule`."""

    def parse(value: Any, errors: Collector, path: str) -> Any:
        if isinstance(value, (Located, LocatedList, bool)):
            raise FieldError(f"expected a single value, got {type(value).__name__}")
        return value

    return Kind("a value whose type depends on `kind` (see the kinds table)", parse)


def _check_rule(v: dict, data: Located, errors: Collector, path: str) -> None:
    kind = RULE_KINDS[v["kind"]]
    limit_kind = LIMIT_KINDS[kind.limit] if kind.limit else None

    def line_of(key: str) -> int | None:
        return lookup(data, key)[0] if key in data else data.line

    if v["status"] == "not-modelled":
        if not v["reason"]:
            errors.add(data.line, f"{path}.reason", "a not-modelled rule needs a reason (what is "
                       "missing to evaluate it)")
        if v["limit"] is not None and limit_kind is not None:  # keep it if it parses; else text
            trial = Collector(errors.file)
            try:
                v["limit"] = limit_kind.parse(v["limit"], trial, f"{path}.limit")
            except FieldError:
                v["limit"] = str(v["limit"])
        elif v["limit"] is not None:
            v["limit"] = str(v["limit"])
        return
    if v["kind"] == "other":
        errors.add(line_of("kind"), f"{path}.kind", "kind 'other' cannot be evaluated; set "
                   "status: not-modelled with a reason")
        return
    if limit_kind is not None:
        if v["limit"] is None:
            errors.add(data.line, f"{path}.limit", f"a {v['kind']} rule needs a limit "
                       f"({kind.describe})")
        else:
            try:
                v["limit"] = limit_kind.parse(v["limit"], errors, f"{path}.limit")
            except FieldError as exc:
                line, col = where(data, "limit")
                errors.add(line, f"{path}.limit", str(exc), col)
    elif v["limit"] is not None:
        errors.add(line_of("limit"), f"{path}.limit", f"a {v['kind']} rule takes no limit; "
                   f"use {', '.join(kind.needs) or 'nothing'}")
    for need in kind.needs:
        if v[need] is None:
            errors.add(data.line, f"{path}.{need}", f"a {v['kind']} rule needs {need}")
    for key in ("required", "allowed", "protocol"):
        if v[key] is not None and key not in kind.needs:
            errors.add(line_of(key), f"{path}.{key}", f"only used by "
                       f"{', '.join(k for k, r in RULE_KINDS.items() if key in r.needs)} rules")
    if v["tolerance"] and v["kind"] != "performance":
        errors.add(line_of("tolerance"), f"{path}.tolerance", "only performance rules take a "
                   "tolerance")
    if v["allowed"]:
        from batcert.specs.materials import LIBRARY
        known = (*MATERIAL_CLASSES, *LIBRARY)
        for i, name in enumerate(v["allowed"]):
            if name not in known:
                import difflib
                close = difflib.get_close_matches(str(name), known, n=1, cutoff=0.5)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                errors.add(lookup(data, "allowed", i)[0], f"{path}.allowed[{i}]",
                           f"unknown material or class {name!r} (known: {', '.join(known)}){hint}")


RULE_SCHEMA = Schema("league rule", (
    Field("id", label(), "Short rule name, unique in the file (`rule` in the JSON).",
          required=True),
    Field("title", label(), "What the rule says, in the report's words."),
    Field("kind", choice(*RULE_KINDS), "What is checked (see the kinds table).", required=True),
    Field("limit", _raw(), "The limit; its type depends on kind (a length, a plain number for "
          "drop, a metric value for performance)."),
    Field("tolerance", one_of(number(minimum=0.0, maximum=METRIC_BOUND),
                              quantity("speed", minimum=0.0),
                              describe="a number, or a speed for exit-speed"),
          "Performance rules: added to the limit before the verdict, where the rule has one.",
          default=0.0),
    Field("required", choice("solid", "hollow"), "Construction rules: the required construction."),
    Field("allowed", list_of(text(), min_items=1, describe="list of material names or classes"),
          "Material rules: allowed library materials or classes (wood, metal, composite)."),
    Field("protocol", text(), "Performance and compression rules: shipped protocol id or path "
          "(relative to this file). A performance rule's limit replaces the protocol's own."),
    Field("applies_to", choice("all", "wood", "non-wood"), "Which bats the rule applies to.",
          default="all"),
    Field("applies_from_length", quantity("length", positive=True), "The rule covers only bats "
          "at least this long."),
    Field("applies_below_length", quantity("length", positive=True), "The rule covers only bats "
          "shorter than this."),
    Field("status", choice("modelled", "not-modelled"), "not-modelled: reported as such, never "
          "as a pass.", default="modelled"),
    Field("reason", text(), "Why a rule is not modelled (required then)."),
    Field("source", text(), "Where the rule and its number come from.", required=True),
    Field("confidence", choice(*CONFIDENCE), "H primary source read, M credible secondary, "
          "L weak, D derived (docs/references.md's scale).", required=True),
    Field("note", text(), "Assumptions made to evaluate the rule."),
), checks=(_check_rule,))

LEAGUE_SCHEMA = Schema("league", (
    Field("id", label(), "Short identifier (`batcert league ID`).", required=True),
    Field("title", label(), "Full name of the league or rule set.", required=True),
    Field("reference", text(), "The rule book or standard the file follows.", required=True),
    Field("version", text(), "Version of this league definition.", required=True),
    Field("description", text(), "Which level of play and which bats the rules cover."),
    Field("notes", text(), "Rules left out, and why."),
    Field("rules", list_of(section(RULE_SCHEMA), min_items=1, describe="list of rules"),
          "The rules.", required=True),
))


@dataclass(frozen=True)
class RuleSpec:
    """One rule of a league file (lengths in m; ``limit`` parsed per kind)."""

    id: str
    title: str | None
    kind: str  # a name of batcert.specs.kinds.RULE_KINDS
    limit: Any  # float (SI), or text for a not-modelled rule's unparsed limit, or None
    tolerance: float
    required: str | None
    allowed: list[str] | None
    protocol: str | None
    applies_to: str  # all | wood | non-wood
    applies_from_length: float | None  # [m]
    applies_below_length: float | None  # [m]
    status: str  # modelled | not-modelled
    reason: str | None
    source: str
    confidence: str
    note: str | None


@dataclass(frozen=True)
class LeagueSpec:
    """A validated league file."""

    source: Source
    id: str
    title: str
    reference: str
    version: str
    description: str | None
    notes: str | None
    rules: tuple[RuleSpec, ...]

    @property
    def path(self) -> str:
        return self.source.path

    @property
    def sha256(self) -> str:
        return self.source.sha256


def load_league(path: str | Path) -> LeagueSpec:
    """Read and validate a league file; raise InputError with every problem of the file."""
    from batcert.specs.resolve import NotFound, resolve
    data = load_yaml(path)
    errors = Collector(path)
    values = validate(data, LEAGUE_SCHEMA, errors) or {}
    rules = values.get("rules") or []
    ids = [r["id"] if r else None for r in rules]
    for i, r in enumerate(rules):
        if not r:
            continue
        if r["id"] in ids[:i]:
            errors.add(lookup(data, "rules", i, "id")[0], f"rules[{i}].id",
                       f"duplicate rule id {r['id']!r}")
        if runs_protocol(r["kind"]) and r["status"] == "modelled" and r["protocol"]:
            try:
                resolve("protocol", r["protocol"], relative_to=Path(path))
            except NotFound as exc:
                errors.add(lookup(data, "rules", i, "protocol")[0], f"rules[{i}].protocol",
                           str(exc))
    errors.raise_if_any()
    values["rules"] = tuple(spec_from(RuleSpec, r) for r in rules)
    return spec_from(LeagueSpec, values, source=Source.of(path, data))
