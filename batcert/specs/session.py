"""A lab session file (YAML): the bat, the ball lot, the pivot, the instruments and the hits CSV
(:mod:`batcert.specs.hits`) of a test; docs/lab-reduction.md documents it. A bare hits CSV gets a
session of defaults (:func:`session_for_hits`; :func:`load_bare_hits` checks one alone).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from batcert.conventions import DEFAULT_PIVOT
from batcert.errors import Collector, InputError, Problem
from batcert.specs.common import HEADER_FIELDS, Source, load_checked, sha256_of, spec_from
from batcert.specs.hits import COLUMNS, Hits, load_hits, read_hits_bytes
from batcert.specs.schema import (
    Field,
    Schema,
    choice,
    integer,
    label,
    list_of,
    lookup,
    quantity,
    section,
    text,
)
from batcert.specs.yamlio import Located, decode_text, load_yaml

UNCERTAINTY_SCHEMA = Schema("uncertainties", (
    Field("speed", quantity("speed", minimum=0.0), "Standard uncertainty of a measured speed "
          "(chronograph calibration: common to every hit).", default=0.0),
    Field("impact_location", quantity("length", minimum=0.0), "Standard uncertainty of an "
          "impact location.", default=0.0),
    Field("moi", quantity("moi", minimum=0.0), "Standard uncertainty of the bat's MOI about "
          "the pivot.", default=0.0),
    Field("ball_mass", quantity("mass", minimum=0.0), "Standard uncertainty of the ball's "
          "mass.", default=0.0),
))

ENVIRONMENT_SCHEMA = Schema("test environment", (
    Field("temperature", text(), "Air temperature during the hits, as measured (e.g. `21.5 C`)."),
    Field("humidity", text(), "Relative humidity during the hits, as measured (e.g. `48 %`)."),
))

BALL_LOT_SCHEMA = Schema("ball lot", (
    Field("lot", text(), "The balls' lot identifier (the maker's lot number)."),
    Field("temperature", text(), "Temperature the balls were conditioned at (e.g. `72 F`)."),
    Field("humidity", text(), "Relative humidity the balls were conditioned at (e.g. `50 %`)."),
    Field("conditioning", text(), "How long the balls were conditioned (e.g. `14 days`)."),
    Field("age", text(), "The balls' age or manufacture date."),
))

EQUIPMENT_SCHEMA = Schema("equipment", (
    Field("name", text(), "What it is (e.g. `ball cannon`, `light gates`, `MOI pendulum`).",
          required=True),
    Field("identifier", text(), "Its serial or asset number.", required=True),
    Field("calibrated", text(), "Date of its last calibration."),
    Field("calibration_due", text(), "When that calibration expires."),
))

LAB_SCHEMA = Schema("laboratory", (
    Field("laboratory", text(), "The testing laboratory's name and address."),
    Field("location", text(), "Where the hits were measured, if not at that address."),
    Field("accreditation", text(), "Accreditation body and number (e.g. ISO/IEC 17025)."),
    Field("operator", text(), "Who ran the test."),
    Field("customer", text(), "For whom: name and contact."),
    Field("standard", text(), "The test standard and its version as the lab applies it (default: "
          "the protocol file's reference and version)."),
    Field("deviations", text(), "Additions to, deviations from or exclusions from the method "
          "(`none` if none)."),
    Field("bat_serial", text(), "The tested bat's serial number."),
    Field("item_condition", text(), "The bat's condition on receipt."),
    Field("receipt_date", text(), "When the bat was received."),
    Field("test_date", text(), "When the hits were measured."),
    Field("issue_date", text(), "When the certificate is issued."),
    Field("certificate_number", text(), "The certificate's number."),
    Field("environment", section(ENVIRONMENT_SCHEMA), "The air during the hits."),
    Field("ball_lot", section(BALL_LOT_SCHEMA), "The ball lot and its conditioning."),
    Field("equipment", list_of(section(EQUIPMENT_SCHEMA), min_items=1,
                               describe="list of instruments with identifiers and calibration "
                               "dates"),
          "The instruments used (ball cannon, light gates, MOI pendulum, scale...)."),
    Field("signatures", list_of(text(), min_items=1, describe="list of names and roles"),
          "Who approves the certificate (name, role): a signature line each."),
))

def _check_readings(v: dict, data: Located, errors: Collector, path: str) -> None:
    if v["compression"] is not None and any(f is None or f <= 0 for f in v["compression"]):
        errors.add(lookup(data, "compression")[0], f"{path}.compression",
                   "every compression reading must be a positive force")


BREAK_IN_READINGS_SCHEMA = Schema("measured break-in", (
    Field("compression", list_of(quantity("force", positive=True), min_items=1,
                                 describe="forces: before rolling, then after each pass"),
          "The barrel compression before rolling, then after each rolling pass.",
          required=True),
    Field("new_compression", quantity("force", positive=True), "The compression of the bat "
          "new (the maker's, or of an unused sample): the skip rule compares the first reading "
          "with it."),
    Field("source", text(), "Who measured it, with which tester and conventions."),
), checks=(_check_readings,))


SESSION_SCHEMA = Schema("hit session", (
    Field("name", label(), "Session name shown in reports.", required=True),
    *HEADER_FIELDS,
    Field("bat", text(), "The bat tested: shipped name or path (relative to this file).",
          required=True),
    Field("ball", text(), "The ball lot: shipped name or path of a ball file (mass, COR).",
          required=True),
    Field("pivot", quantity("length", minimum=0.0), "Pivot of the test, from the knob.",
          default=DEFAULT_PIVOT),
    Field("hits", text(), "The hits CSV, relative to this file.", required=True),
    Field("location_from", choice("tip", "knob", "pivot"), "The end the CSV's "
          "impact_location is measured from.", default="tip"),
    Field("gate_spacing", quantity("length", positive=True), "Distance between the light "
          "gates, for hits given as gate times."),
    Field("location_step", quantity("length", minimum=0.1e-3, maximum=0.2), "Hits within half a "
          "step of a location are one location of the scan (the lab's nominal positions); "
          "0.1 mm to 0.2 m.",
          default=0.25 * 0.0254),
    Field("hits_required", integer(minimum=1, maximum=1000), "Consecutive valid hits at the "
          "certified location whose mean is certified (NCAA BBCOR: 6).", default=6),
    Field("speed_tolerance", quantity("speed", positive=True), "A hit whose inbound speed is "
          "further than this from the protocol's speed is invalid.", default=0.44704),
    Field("hits_per_ball", integer(minimum=1, maximum=1000), "A ball's hits beyond this many "
          "are invalid (the ball must be replaced)."),
    Field("uncertainty", section(UNCERTAINTY_SCHEMA), "Standard uncertainties of the "
          "instruments and of the inputs (GUM, JCGM 100); zero where not given."),
    Field("break_in", section(BREAK_IN_READINGS_SCHEMA), "Composite bats: the barrel "
          "compression measured through the accelerated break-in (ABI) before these hits; "
          "checked against the protocol's `break_in` rules and shown on the certificate."),
    Field("lab", section(LAB_SCHEMA), "The laboratory, operator, customer, bat serial, dates and "
          "signatures printed on the certificate."),
    Field("reference_session", text(), "A reference bat's session with the same balls (its "
          "session file, relative to this one): its hits, reduced under the same protocol, "
          "calibrate the ball lot that this session's model prediction, barrel calibration and "
          "BPF use, in place of the ball file's `reference_bat` (a CALIBRATION, an input; "
          "docs/lab-reduction.md)."),
))


@dataclass(frozen=True)
class SessionSpec:
    """A validated session file (SI values)."""

    source: Source
    name: str
    description: str | None
    reference: str | None
    version: str | None
    bat: str
    ball: str
    pivot: float  # [m from knob]
    hits: str  # CSV path relative to the session file
    location_from: str  # tip | knob | pivot
    gate_spacing: float | None  # [m]
    location_step: float  # [m]
    hits_required: int
    speed_tolerance: float  # [m/s]
    hits_per_ball: int | None
    uncertainty: dict | None  # speed [m/s], impact_location [m], moi [kg m^2], ball_mass [kg]
    lab: dict | None  # laboratory, accreditation, operator, ... (text), signatures (list)
    break_in: dict | None = None  # compression [N, list], new_compression [N], source
    reference_session: str | None = None  # a reference bat's session file, relative to this

    @property
    def path(self) -> str:
        return self.source.path


def is_hits_csv(path: str | Path) -> bool:
    """Whether ``path`` is a hits CSV by its name (``.csv``): the one kind of CSV batcert reads,
    as ``batcert reduce`` tells a bare hits CSV from a session YAML."""
    return Path(path).suffix.lower() == ".csv"


def _bare_header(path: Path) -> tuple[bytes, int | None, str]:
    """A bare hits CSV's bytes and its header line (its first line neither blank nor a
    comment), with its 1-based number (None and empty when there is none)."""
    raw = read_hits_bytes(path)
    return raw, *next(((n + 1, ln) for n, ln in enumerate(decode_text(raw, str(path)).splitlines())
                       if ln.strip() and not ln.lstrip().startswith("#")), (None, ""))


def _header_end(head: str) -> str:
    """The end a bare hits CSV's locations are measured from: the one its header names
    (``impact_location [in from knob]``), else the tip."""
    end = re.search(r"impact_location\s*\[[^\]]*\bfrom\s+(tip|knob|pivot)\s*\]", head)
    return end.group(1) if end else "tip"


def session_for_hits(csv_path: str | Path, bat: str, ball: str, pivot: float) -> SessionSpec:
    """A session for a bare hits CSV (``batcert reduce HITS.csv --bat BAT``): the bat given,
    the protocol's ball and pivot, locations from the end the CSV's header names (default the
    tip), every other field at its default."""
    path = Path(csv_path)
    data = Located()
    data.file, data.line, data.key_pos, data.value_pos = str(path), 1, {}, {}
    raw, _, head = _bare_header(path)
    defaults = {f.name: f.default for f in SESSION_SCHEMA.fields}
    return spec_from(SessionSpec, {**defaults, "name": f"hits {path.name}", "bat": bat,
                                   "ball": ball, "pivot": pivot, "hits": path.name,
                                   "location_from": _header_end(head)},
                     source=Source(str(path), sha256_of(raw), data))


def load_bare_hits(csv_path: str | Path) -> Hits:
    """A bare hits CSV read as ``batcert reduce HITS.csv --bat BAT`` reads it (the session's
    defaults: locations from the end its header names, no gate spacing), with every problem;
    a CSV whose header names none of the hits columns is said to be no hits CSV."""
    path = Path(csv_path)
    _, line, head = _bare_header(path)
    names = {cell.split("[")[0].strip() for cell in head.split(",")}
    if head and not names & set(COLUMNS):
        raise InputError([Problem(str(path), line, "", "not a hits CSV: batcert reads a CSV "
                                  "only as a lab's hits (batcert reduce), and this header names "
                                  f"none of their columns ({', '.join(COLUMNS)})")])
    return load_hits(path, _header_end(head), None)


def load_session(path: str | Path) -> SessionSpec:
    data = load_yaml(path)
    values = load_checked(path, SESSION_SCHEMA, data)
    return spec_from(SessionSpec, values, source=Source.of(path, data))
