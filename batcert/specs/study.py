"""Study specification: a named set of protocols to compare bats under, and the claims to test.

A study (e.g. ``protocols/studies/smith2001.yaml``) lists protocols by shipped id, by path
relative to the study file, or inline (a mapping with the protocol fields). It may name default
bats (the first is the reference of the relative performance P) and the published ``claims`` to
test against the model's results: each claim names a check from :data:`CLAIM_CHECKS` (evaluated in
:mod:`batcert.compare`) and the protocols it concerns. The comparison report states, for each
claim, whether the model supports it, and with which numbers; nothing is fitted to make it so.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from batcert.errors import Collector, InputError
from batcert.specs.common import sha256_of
from batcert.specs.protocol import PROTOCOL_SCHEMA, ProtocolSpec, load_protocol
from batcert.specs.schema import (Field, FieldError, Kind, Schema, choice, list_of, lookup, number,
                                  quantity, section, text, validate)
from batcert.specs.yamlio import Located, load_yaml

CLAIM_CHECKS = {
    "sign-disagreement": "P of the compared bat takes both signs (beyond `tolerance`) across the "
                         "protocols' conditions: the methods disagree on which bat is better.",
    "consistent-across-conditions": "In each protocol P has one sign in every condition, beyond "
                                    "`tolerance`, and its range across conditions is smaller than "
                                    "the range over `compare_with` (when given).",
    "advantage": "`expected: shown`: the mean P of every compared bat exceeds `tolerance` in "
                 "every protocol; `not-shown`: in none of them.",
    "lower-than": "The mean P under the first protocol is below the mean P under the second by "
                  "more than `tolerance` (a metric that ignores MOI underrates a light bat).",
    "cop-not-sweet-spot": "For every bat and condition the sweet spot lies more than "
                          "`location_tolerance` from the centre of percussion.",
    "cop-offset-differs": "The mean sweet-spot-minus-COP offset differs between the bats by more "
                          "than `location_tolerance`.",
    "sweet-spot-moves-less-than-rigid": "Across conditions with fixed speeds the sweet spot "
                                        "moves less than `factor` times the movement of the rigid "
                                        "sweet spot (Smith 2001 Eq. 7).",
}


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
    Field("id", text(), "Short claim name.", required=True),
    Field("statement", text(), "The study's claim in words.", required=True),
    Field("source", text(), "Where the study makes it."),
    Field("check", choice(*CLAIM_CHECKS), "How the model's results test it.", required=True),
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
          "rigid: largest accepted ratio of movements.", default=0.5),
))

STUDY_SCHEMA = Schema("study", (
    Field("id", text(), "Short identifier (`--study ID`).", required=True),
    Field("title", text(), "Full title.", required=True),
    Field("reference", text(), "The study replayed.", required=True),
    Field("version", text(), "Version of this study definition.", required=True),
    Field("description", text(), "What is compared and how."),
    Field("notes", text(), "What differs from the study, and what the model cannot reproduce."),
    Field("bats", list_of(text(), min_items=1, describe="list of bat names or paths"),
          "Default bats (shipped names or paths relative to the study); the first is the "
          "reference."),
    Field("protocols", list_of(_protocol_entry(), min_items=1, describe="list of protocols"),
          "Protocols, in report order.", required=True),
    Field("claims", list_of(section(CLAIM_SCHEMA), describe="list of claims"),
          "The study's conclusions, each tested against the model's results.", default=[]),
))


@dataclass(frozen=True)
class StudySpec:
    path: str
    sha256: str
    id: str
    values: dict
    protocols: list[ProtocolSpec]  # resolved and validated, in study order
    bats: list[Path]  # resolved default bats (may be empty)

    @property
    def claims(self) -> list[dict]:
        return self.values["claims"] or []


def _inline_protocol(entry: dict, study: Path, sha: str, data: Located, i: int,
                     errors: Collector) -> ProtocolSpec:
    v = entry["inline"]
    names = [c["name"] for c in v["conditions"]]
    for j, n in enumerate(names):
        if n in names[:j]:
            errors.add(lookup(data, "protocols", i, "conditions", j, "name")[0],
                       f"protocols[{i}].conditions[{j}].name", f"duplicate condition name {n!r}")
    return ProtocolSpec(str(study), sha, v["id"], v)


def load_study(path: str | Path) -> StudySpec:
    """Read a study, load every protocol it names, check its claims refer to them.

    Raises InputError with every problem of the study file (a referenced protocol file with
    errors raises that file's problems).
    """
    from batcert.specs.resolve import NotFound, resolve

    path = Path(path)
    data = load_yaml(path)
    errors = Collector(path)
    v = validate(data, STUDY_SCHEMA, errors)
    errors.raise_if_any()
    sha = sha256_of(path)
    protocols: list[ProtocolSpec] = []
    nested: list[InputError] = []
    for i, entry in enumerate(v["protocols"]):
        if isinstance(entry, dict):
            protocols.append(_inline_protocol(entry, path, sha, data, i, errors))
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
            ball_of, rel = protocols[-1].values["ball"], p
        try:
            resolve("ball", ball_of, relative_to=rel)
        except NotFound as exc:
            errors.add(lookup(data, "protocols", i)[0], f"protocols[{i}]", str(exc))
    ids = [p.id for p in protocols]
    for i, pid in enumerate(ids):
        if pid in ids[:i]:
            errors.add(lookup(data, "protocols")[0], "protocols", f"protocol id {pid!r} appears "
                       "twice; a comparison needs distinct ids")
    if not nested:
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
    bats: list[Path] = []
    for i, b in enumerate(v["bats"] or []):
        try:
            bats.append(resolve("bat", b, relative_to=path))
        except NotFound as exc:
            errors.add(lookup(data, "bats", i)[0], f"bats[{i}]", str(exc))
    problems = list(errors.problems) + [p for e in nested for p in e.problems]
    if problems:
        raise InputError(problems)
    return StudySpec(str(path), sha, v["id"], v, protocols, bats)
