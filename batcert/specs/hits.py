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
    speed_unit: str = "m/s"  # the unit the lab wrote its speeds in (shown back in it)


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
    rows = _content_rows(decode_text(raw, str(path)), path)
    head_line, head_raw = rows[0]
    split = _split_row(head_raw, head_line, errors)
    errors.raise_if_any()
    assert split is not None
    header, head_cols = split
    columns = _read_header(header, head_cols, head_line, location_from, gate_spacing, errors)
    errors.raise_if_any()
    if len(rows) - 1 > MAX_HITS:
        raise InputError([Problem(str(path), None, "", f"more than {MAX_HITS} hits")])
    hits = _read_hits(rows[1:], len(header), columns, gate_spacing, errors)
    if not hits:
        errors.add(head_line, "", "the file has a header but no hits")
    errors.raise_if_any()
    return _as_hits(path, sha256_of(raw), hits, _speed_unit(header))


def _speed_unit(header: list[str]) -> str:
    """The unit of the inbound speed column as the lab wrote it, if it is one batcert shows
    (m/s, mph, ft/s, km/h); else (or for gate times) m/s."""
    from batcert.units import FAST_UNITS
    for cell in header:
        m = _HEADER.match(cell)
        if m and m.group(1) == "inbound_speed" and m.group(2) in FAST_UNITS["speed"]:
            return m.group(2)
    return "m/s"


# the known columns of a header: name -> (index in a row, SI factor of its unit or None)
Columns = dict[str, tuple[int, float | None]]


def _content_rows(text_: str, path: Path) -> list[tuple[int, str]]:
    """The lines of a hits CSV that are neither blank nor comments, with their 1-based numbers;
    :class:`InputError` when there are none."""
    rows = [(n + 1, line) for n, line in enumerate(text_.splitlines()) if line.strip()
            and not line.lstrip().startswith("#")]
    if not rows:
        raise InputError([Problem(str(path), None, "", "no header row and no hits")])
    return rows


def _read_header(header: list[str], starts: list[int], line: int, location_from: str,
                 gate_spacing: float | None, errors: Collector) -> Columns:
    """The known columns of the header row (its cells ``header``, starting at the 1-based
    columns ``starts``) with the SI factors of their units; a problem for every unknown,
    repeated or unitless column and every required one that is missing."""
    columns: Columns = {}
    named: set[str] = set()  # known columns in the header, also those with a problem
    for j, cell in enumerate(header):
        m = _HEADER.match(cell)
        if not m or m.group(1) not in COLUMNS:
            _unknown_column(cell, m.group(1) if m else cell.strip(), j, line, starts[j], errors)
            continue
        name, unit = m.group(1), m.group(2)
        named.add(name)
        if name in columns:
            errors.add(line, name, "the column appears twice", column=starts[j])
            continue
        dimension = COLUMNS[name][0]
        if dimension is None:
            columns[name] = (j, None)
        elif unit is None:
            errors.add(line, name, f"give the unit in brackets, e.g. '{name} "
                       f"[{'in from tip' if name == 'impact_location' else 'm/s'}]'",
                       column=starts[j])
        else:
            columns[name] = (j, _column_factor(name, unit, dimension, location_from, line,
                                               starts[j], errors))
    _check_required(named, columns, line, gate_spacing, errors)
    return columns


def _unknown_column(cell: str, name: str, j: int, line: int, column: int,
                    errors: Collector) -> None:
    """The problem of a header cell that names no known column, with a did-you-mean."""
    import difflib
    close = difflib.get_close_matches(name, list(COLUMNS), n=1, cutoff=0.6)
    hint = f"; did you mean '{close[0]}'?" if close else ""
    errors.add(line, cell.strip() or f"column {j + 1}", f"unknown column {cell.strip()!r} (columns: "
               f"{', '.join(COLUMNS)}){hint}", column=column)


def _column_factor(name: str, unit: str, dimension: str, location_from: str, line: int,
                   column: int, errors: Collector) -> float | None:
    """The SI value of one ``unit`` of a column; ``impact_location``'s may name the end the
    locations are measured from (``in from tip``), which must be the session's."""
    if name == "impact_location":
        ends = _UNIT_AND_END.match(unit)
        if ends and ends.group(2) != location_from:
            errors.add(line, name, f"the header says from the {ends.group(2)}, the "
                       f"session says location_from: {location_from}", column=column)
        unit = ends.group(1) if ends else unit
    return _unit_factor(name, unit, dimension, line, column, errors)


def _check_required(named: set[str], columns: Columns, line: int, gate_spacing: float | None,
                    errors: Collector) -> None:
    """Every required column is in the header, and the ball's speeds or its gate times (these
    with the session's gate spacing)."""
    for name, (_, required) in COLUMNS.items():
        if required and name not in named:
            errors.add(line, name, f"the column {name!r} is missing")
    speeds = {"inbound_speed", "rebound_speed"} <= set(columns)
    gates = {"inbound_gate_time", "rebound_gate_time"} <= set(columns)
    pairs = ({"inbound_speed", "rebound_speed"}, {"inbound_gate_time", "rebound_gate_time"})
    if not any(pair <= named for pair in pairs):
        errors.add(line, "inbound_speed", "give the ball's speeds (inbound_speed and "
                   "rebound_speed) or its gate times (inbound_gate_time and rebound_gate_time)")
    if gates and not speeds and gate_spacing is None:
        errors.add(line, "inbound_gate_time", "gate times need the session's gate_spacing")


@dataclass(frozen=True)
class _Row:
    """One row of hits being read: its CSV line, its cells and the 1-based column where each
    starts, the header's columns, and where its problems go."""

    line: int
    cells: list[str]
    starts: list[int]
    columns: Columns
    errors: Collector

    def column(self, name: str) -> int:
        """Where the cell of the column ``name`` starts."""
        return self.starts[self.columns[name][0]]

    def text(self, name: str) -> str:
        """The cell of the column ``name``, stripped; "" where the header has no such column."""
        return self.cells[self.columns[name][0]].strip() if name in self.columns else ""

    def number(self, name: str) -> float:
        """The cell of the column ``name`` in SI; NaN where the header has no such column or
        the cell is no plausible number (then with a problem)."""
        if name not in self.columns:
            return float("nan")
        j, factor = self.columns[name]
        text_ = self.cells[j].strip()
        if text_ == "" and name == "bat_angular_speed_after":  # not measured on this hit
            return float("nan")
        try:
            value = float(text_.replace("_", "?"))  # "6_0.8" is not 60.8 to a lab
        except ValueError:
            self.errors.add(self.line, name, f"expected a number, got {text_!r}",
                            column=self.starts[j])
            return float("nan")
        if not np.isfinite(value):
            self.errors.add(self.line, name, f"expected a finite number, got {text_!r}",
                            column=self.starts[j])
            return float("nan")
        si = value * (factor if factor is not None else 1.0)
        dimension = COLUMNS[name][0]
        if dimension in PLAUSIBLE and abs(si) > PLAUSIBLE[dimension]:
            self.errors.add(self.line, name, f"{text_} is beyond any plausible "
                            f"{dimension.replace('_', ' ')} (at most {PLAUSIBLE[dimension]:g} "
                            "in SI units)", column=self.starts[j])
            return float("nan")
        return si

    def positive(self, name: str, value: float) -> float:
        """``value``, with a problem at the column ``name`` where it is not above zero."""
        if np.isfinite(value) and value <= 0:
            self.errors.add(self.line, name, "must be above zero", column=self.column(name))
        return value

    def speed_in_range(self, name: str, v: float, low: float,
                       gate_spacing: float | None) -> float:
        """``v`` [m/s] if within [low, the largest plausible speed]; otherwise a problem at the
        column ``name`` it came from (a speed, or a gate time over ``gate_spacing`` [m]) and
        NaN."""
        high = INBOUND_SPEED_RANGE[1]
        if np.isnan(v) or low <= v <= high:
            return v
        which, span = name.split("_")[0], f"{low:g}-{high:g} m/s"
        message = (f"gives {which} speed {v:.4g} m/s over the {gate_spacing:g} m gate "
                   f"spacing, outside {span} (check the time and its unit)"
                   if name.endswith("gate_time") else f"{v:.4g} m/s is outside {span}, "
                   f"the {which} speeds of a ball-cannon test (a unit or a typo?)")
        self.errors.add(self.line, name, message, column=self.column(name))
        return float("nan")


def _read_hits(rows: list[tuple[int, str]], width: int, columns: Columns,
               gate_spacing: float | None, errors: Collector) -> list[tuple]:
    """The hits of the rows after the header (:func:`_read_hit`); a problem for each row that
    is not well-formed CSV of ``width`` fields."""
    speeds = {"inbound_speed", "rebound_speed"} <= set(columns)
    hits = []
    for line, raw in rows:
        split = _split_row(raw, line, errors)
        if split is None:
            continue
        cells, starts = split
        if len(cells) != width:
            errors.add(line, "", f"{len(cells)} fields, the header has {width}")
            continue
        hits.append(_read_hit(_Row(line, cells, starts, columns, errors), speeds, gate_spacing))
    return hits


def _read_hit(row: _Row, speeds: bool, gate_spacing: float | None) -> tuple:
    """One hit, in the order of :class:`Hits`' fields from ``hit`` (SI; NaN where a value is
    missing or wrong)."""
    vi, vr = _ball_speeds(row, speeds, gate_spacing)
    valid_text = row.text("valid").lower()
    if valid_text not in ("", "yes", "no", "true", "false", "1", "0"):
        row.errors.add(row.line, "valid", f"expected yes or no, got {valid_text!r}",
                       column=row.column("valid"))
    return (row.number("hit"), row.text("ball"), vi, vr, row.number("impact_location"),
            row.number("bat_angular_speed_after"), valid_text not in ("no", "false", "0"),
            row.text("note"), row.line)


def _ball_speeds(row: _Row, speeds: bool, gate_spacing: float | None) -> tuple[float, float]:
    """The ball's inbound and rebound speeds [m/s]: the row's ``speeds``, or its gate times
    over ``gate_spacing`` [m]; NaN, with a problem, where one is out of range."""
    low = INBOUND_SPEED_RANGE[0]
    if speeds:
        vi = row.positive("inbound_speed", row.number("inbound_speed"))
        vi = row.speed_in_range("inbound_speed", vi, low, gate_spacing) if vi > 0 else vi
        vr = row.number("rebound_speed")
    else:
        ti = row.positive("inbound_gate_time", row.number("inbound_gate_time"))
        tr = row.positive("rebound_gate_time", row.number("rebound_gate_time"))
        assert gate_spacing is not None
        # a time <= 0 is reported above; a tiny one gives a speed reported here
        vi = row.speed_in_range("inbound_gate_time", gate_spacing / ti, low, gate_spacing) \
            if ti > 0 else float("nan")
        vr = row.speed_in_range("rebound_gate_time", gate_spacing / tr, 0.0, gate_spacing) \
            if tr > 0 else float("nan")
    if np.isfinite(vr) and vr < 0:
        row.errors.add(row.line, "rebound_speed", "is a magnitude: must not be negative",
                       column=row.column("rebound_speed") if speeds else None)
    return vi, vr


def _as_hits(path: Path, sha256: str, hits: list[tuple], speed_unit: str = "m/s") -> Hits:
    """:class:`Hits` from the tuples of :func:`_read_hit` (at least one)."""
    hit, ball, vi, vr, location, w2, valid, note, line = (
        list(c) for c in zip(*hits, strict=True))
    return Hits(str(path), sha256, np.asarray(hit), ball, np.asarray(vi), np.asarray(vr),
                np.asarray(location), np.asarray(w2), np.asarray(valid, bool), note, line,
                speed_unit)
