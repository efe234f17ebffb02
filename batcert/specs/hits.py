"""Measured hit data: the hits CSV of a lab session (one row per hit, units in the header; the
session file: :mod:`batcert.specs.session`). docs/lab-reduction.md documents both.

A hits CSV::

    hit,ball,inbound_speed [m/s],rebound_speed [m/s],impact_location [in from tip],valid,note
    1,B01,60.80,15.12,6.0,yes,
    2,B01,60.75,15.31,6.5,yes,

Columns (any order; names as in docs/nomenclature.md, the unit in brackets after the name):
``hit`` (a number), ``ball`` (an identifier), ``inbound_speed`` and ``rebound_speed`` (a
speed) or ``inbound_gate_time`` and ``rebound_gate_time`` (the time to cross the session's
``gate_spacing``), ``impact_location`` (a length, from the end named by the session's
``location_from``), optionally ``bat_angular_speed_after`` (BPF method), ``valid`` (yes/no,
default yes) and ``note``. Every problem of the file is reported at once, with its line, column
and field, as for YAML inputs.
"""

from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from batcert.errors import Collector, InputError, Problem
from batcert.specs.common import sha256_of
from batcert.specs.yamlio import decode_text, read_input
from batcert.units import PLAUSIBLE

# column -> (dimension or None, required); a speed pair or a gate-time pair is required
COLUMNS: dict[str, tuple[str | None, bool]] = {
    "hit": (None, True), "ball": (None, True),
    "inbound_speed": ("speed", False), "rebound_speed": ("speed", False),
    "inbound_gate_time": ("time", False), "rebound_gate_time": ("time", False),
    "impact_location": ("length", True), "bat_angular_speed_after": ("angular_speed", False),
    "valid": (None, False), "note": (None, False),
}
_HEADER = re.compile(r"^\s*([A-Za-z_]+)\s*(?:\[\s*(.+?)\s*\])?\s*$")
_UNIT_AND_END = re.compile(r"^(.*?)\s+from\s+(tip|knob|pivot)$")
MAX_HITS = 100_000
# The inbound speeds a hit may have [m/s], given or from gate times: a ball cannon fires at tens of
# m/s, and ball COR tests start at 1 m/s; below, e_A = v_r / v_i grows without bound (a gate
# time of 1e-300 s or a speed of 1e-300 m/s made infinite reduced values). Rebound speeds lie in
# [0, the upper bound]. Documented in docs/lab-reduction.md.
INBOUND_SPEED_RANGE = (1.0, PLAUSIBLE["speed"])
# A hits CSV larger than this is refused before it is parsed: 100,000 hits with short notes take
# about 6 MB (documented in docs/inputs.md and docs/lab-reduction.md).
MAX_BYTES = 16_000_000


@dataclass(frozen=True)
class Hits:
    """The hits of a CSV, as arrays (SI; NaN where a value is not given)."""

    path: str
    sha256: str
    hit: np.ndarray  # hit numbers as written
    ball: list[str]  # ball identifiers
    inbound_speed: np.ndarray  # [m/s]
    rebound_speed: np.ndarray  # [m/s]
    impact_location: np.ndarray  # [m from the session's location_from end]
    bat_angular_speed_after: np.ndarray  # [rad/s], NaN where not measured
    valid: np.ndarray  # bool: the operator's validity flag
    note: list[str]
    line: list[int]  # the CSV line of each hit


def read_hits_bytes(path: Path) -> bytes:
    """The bytes of a hits CSV: a regular file of at most :data:`MAX_BYTES`."""
    return read_input(path, MAX_BYTES, "a hits CSV", f"a hits CSV of {MAX_HITS:,} hits takes "
                      "about 6 MB (is this the right file?)")


def _split_row(raw: str, line: int, errors: Collector) -> tuple[list[str], list[int]] | None:
    """The fields of one CSV line and the 1-based column where each starts; None (and a
    problem at the line) when the line is not well-formed CSV: a quote opens a quoted field only
    as its first character, the field ends at the closing quote (a quote inside is written
    ``""``), and a field holds at most ``csv.field_size_limit()`` characters."""
    try:
        cells = next(csv.reader([raw], strict=True))
    except csv.Error as exc:
        text_ = str(exc)
        if "field limit" in text_:
            message = (f"a field longer than {csv.field_size_limit():,} characters (a hits row "
                       "is a few dozen)")
        elif "end of data" in text_:
            message = ("a quoted field is not closed on this line: a '\"' that starts a field "
                       "must end it, and a '\"' inside it is written '\"\"'")
        elif "expected after" in text_:
            message = ("text after a quoted field's closing '\"': quote the whole field, "
                       "writing a '\"' inside it as '\"\"'")
        else:
            message = f"not a well-formed CSV row ({text_})"
        errors.add(line, "", message)
        return None
    return cells, _cell_columns(raw)


def _cell_columns(raw: str) -> list[int]:
    """1-based column where each field of a well-formed CSV line starts: a quote opens a quoted
    field only as a field's first character, and ``""`` inside one is a quote, as for
    :mod:`csv`."""
    starts, quoted, first, closed = [1], False, True, False
    for col, ch in enumerate(raw, start=1):
        if quoted:
            quoted, closed = ch != '"', ch == '"'
            continue
        if ch == '"' and (first or closed):  # opens the field, or "" inside it
            quoted = True
        elif ch == ",":
            starts.append(col + 1)
        first, closed = ch == ",", False
    return starts


def _unit_factor(name: str, unit: str, dimension: str, line: int, column: int,
                 errors: Collector) -> float | None:
    """The SI value of one ``unit`` of ``dimension`` (a header's bracket)."""
    from batcert.units import UnitError, parse_quantity
    try:
        return parse_quantity(f"1 {unit}", dimension)
    except UnitError as exc:
        errors.add(line, name, f"the unit in the header: {exc}", column=column)
        return None


def load_hits(path: str | Path, location_from: str = "tip",
              gate_spacing: float | None = None) -> Hits:
    """Read a hits CSV; raise :class:`InputError` with every problem (line, column, field)."""
    path = Path(path)
    raw = read_hits_bytes(path)
    errors = Collector(path)
    lines = decode_text(raw, str(path)).splitlines()
    rows = [(n + 1, line) for n, line in enumerate(lines) if line.strip()
            and not line.lstrip().startswith("#")]
    if not rows:
        raise InputError([Problem(str(path), None, "", "no header row and no hits")])
    head_line, head_raw = rows[0]
    split = _split_row(head_raw, head_line, errors)
    errors.raise_if_any()
    assert split is not None
    header, head_cols = split
    columns: dict[str, tuple[int, float | None]] = {}  # name -> (index, SI factor)
    named: set[str] = set()  # known columns in the header, also those with a problem
    for j, cell in enumerate(header):
        m = _HEADER.match(cell)
        if not m or m.group(1) not in COLUMNS:
            import difflib
            name = m.group(1) if m else cell.strip()
            close = difflib.get_close_matches(name, list(COLUMNS), n=1, cutoff=0.6)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            errors.add(head_line, cell.strip() or f"column {j + 1}", f"unknown column {cell.strip()!r} (columns: "
                       f"{', '.join(COLUMNS)}){hint}", column=head_cols[j])
            continue
        name, unit = m.group(1), m.group(2)
        named.add(name)
        if name in columns:
            errors.add(head_line, name, "the column appears twice", column=head_cols[j])
            continue
        dimension = COLUMNS[name][0]
        factor = None
        if dimension is not None:
            if unit is None:
                errors.add(head_line, name, f"give the unit in brackets, e.g. '{name} "
                           f"[{'in from tip' if name == 'impact_location' else 'm/s'}]'",
                           column=head_cols[j])
                continue
            if name == "impact_location":
                ends = _UNIT_AND_END.match(unit)
                if ends and ends.group(2) != location_from:
                    errors.add(head_line, name, f"the header says from the {ends.group(2)}, the "
                               f"session says location_from: {location_from}",
                               column=head_cols[j])
                unit = ends.group(1) if ends else unit
            factor = _unit_factor(name, unit, dimension, head_line, head_cols[j], errors)
        columns[name] = (j, factor)
    for name, (_, required) in COLUMNS.items():
        if required and name not in named:
            errors.add(head_line, name, f"the column {name!r} is missing")
    speeds = {"inbound_speed", "rebound_speed"} <= set(columns)
    gates = {"inbound_gate_time", "rebound_gate_time"} <= set(columns)
    pairs = ({"inbound_speed", "rebound_speed"}, {"inbound_gate_time", "rebound_gate_time"})
    if not any(pair <= named for pair in pairs):
        errors.add(head_line, "inbound_speed", "give the ball's speeds (inbound_speed and "
                   "rebound_speed) or its gate times (inbound_gate_time and rebound_gate_time)")
    if gates and not speeds and gate_spacing is None:
        errors.add(head_line, "inbound_gate_time", "gate times need the session's gate_spacing")
    errors.raise_if_any()
    if len(rows) - 1 > MAX_HITS:
        raise InputError([Problem(str(path), None, "", f"more than {MAX_HITS} hits")])

    out: dict[str, list] = {k: [] for k in ("hit", "ball", "vi", "vr", "r", "w2", "valid",
                                           "note", "line")}
    for line_no, row_raw in rows[1:]:
        split = _split_row(row_raw, line_no, errors)
        if split is None:
            continue
        cells, starts = split
        if len(cells) != len(header):
            errors.add(line_no, "", f"{len(cells)} fields, the header has {len(header)}")
            continue

        def number(name: str, line_no=line_no, cells=cells, starts=starts) -> float:
            if name not in columns:
                return float("nan")
            j, factor = columns[name]
            text_ = cells[j].strip()
            if text_ == "" and name == "bat_angular_speed_after":  # not measured on this hit
                return float("nan")
            try:
                value = float(text_.replace("_", "?"))  # "6_0.8" is not 60.8 to a lab
            except ValueError:
                errors.add(line_no, name, f"expected a number, got {text_!r}", column=starts[j])
                return float("nan")
            if not np.isfinite(value):
                errors.add(line_no, name, f"expected a finite number, got {text_!r}",
                           column=starts[j])
                return float("nan")
            si = value * (factor if factor is not None else 1.0)
            dimension = COLUMNS[name][0]
            if dimension in PLAUSIBLE and abs(si) > PLAUSIBLE[dimension]:
                errors.add(line_no, name, f"{text_} is beyond any plausible "
                           f"{dimension.replace('_', ' ')} (at most {PLAUSIBLE[dimension]:g} "
                           "in SI units)", column=starts[j])
                return float("nan")
            return si

        def positive(name: str, value: float, line_no=line_no, starts=starts) -> float:
            if np.isfinite(value) and value <= 0:
                errors.add(line_no, name, "must be above zero", column=starts[columns[name][0]])
            return value

        def speed_range(name: str, v: float, low: float, line_no=line_no,
                        starts=starts) -> float:
            """``v`` [m/s] if within [low, the largest plausible speed]; otherwise a problem
            at the column ``name`` it came from (a speed, or a gate time) and NaN."""
            high = INBOUND_SPEED_RANGE[1]
            if np.isnan(v) or low <= v <= high:
                return v
            which, span = name.split("_")[0], f"{low:g}-{high:g} m/s"
            message = (f"gives {which} speed {v:.4g} m/s over the {gate_spacing:g} m gate "
                       f"spacing, outside {span} (check the time and its unit)"
                       if name.endswith("gate_time") else f"{v:.4g} m/s is outside {span}, "
                       f"the {which} speeds of a ball-cannon test (a unit or a typo?)")
            errors.add(line_no, name, message, column=starts[columns[name][0]])
            return float("nan")

        if speeds:
            vi = positive("inbound_speed", number("inbound_speed"))
            vi = speed_range("inbound_speed", vi, INBOUND_SPEED_RANGE[0]) if vi > 0 else vi
            vr = number("rebound_speed")
        else:
            ti = positive("inbound_gate_time", number("inbound_gate_time"))
            tr = positive("rebound_gate_time", number("rebound_gate_time"))
            assert gate_spacing is not None
            # a time <= 0 is reported above; a tiny one gives a speed reported here
            vi = speed_range("inbound_gate_time", gate_spacing / ti, INBOUND_SPEED_RANGE[0]) \
                if ti > 0 else float("nan")
            vr = speed_range("rebound_gate_time", gate_spacing / tr, 0.0) \
                if tr > 0 else float("nan")
        if np.isfinite(vr) and vr < 0:
            errors.add(line_no, "rebound_speed", "is a magnitude: must not be negative",
                       column=starts[columns["rebound_speed"][0]] if speeds else None)
        valid_text = cells[columns["valid"][0]].strip().lower() if "valid" in columns else ""
        if valid_text not in ("", "yes", "no", "true", "false", "1", "0"):
            errors.add(line_no, "valid", f"expected yes or no, got {valid_text!r}",
                       column=starts[columns["valid"][0]])
        out["hit"].append(number("hit"))
        out["ball"].append(cells[columns["ball"][0]].strip())
        out["vi"].append(vi)
        out["vr"].append(vr)
        out["r"].append(number("impact_location"))
        out["w2"].append(number("bat_angular_speed_after"))
        out["valid"].append(valid_text not in ("no", "false", "0"))
        out["note"].append(cells[columns["note"][0]].strip() if "note" in columns else "")
        out["line"].append(line_no)
    if not out["line"]:
        errors.add(head_line, "", "the file has a header but no hits")
    errors.raise_if_any()
    return Hits(str(path), sha256_of(raw), np.asarray(out["hit"]), out["ball"],
                np.asarray(out["vi"]), np.asarray(out["vr"]), np.asarray(out["r"]),
                np.asarray(out["w2"]), np.asarray(out["valid"], bool), out["note"], out["line"])
