"""Spec helpers shared by every input file: where a spec came from, header fields, pairs.

Every loaded spec is a frozen dataclass whose fields are the file's validated values in SI,
named as in the file, plus a :class:`Source`: the file's path, its SHA-256 and the parsed YAML
with the line and column of every key, so that any later stage can point into the user's file
(:meth:`Source.line`) without reading it again.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any, TypeVar

from batcert.errors import Collector, InputError, Problem
from batcert.specs.schema import Field, FieldError, Kind, Schema, lookup, text
from batcert.specs.yamlio import Located, LocatedList
from batcert.units import DIMENSIONS, UnitError, parse_quantity, parse_uncertain

HEADER_FIELDS = (
    Field("description", text(), "Free text describing the file's content."),
    Field("reference", text(), "Where the values come from (paper, standard, measurement)."),
    Field("version", text(), "Version of this file's content."),
)

T = TypeVar("T")


def sha256_of(source: str | Path | bytes) -> str:
    """The SHA-256 of a file, or of the bytes already read from one."""
    data = source if isinstance(source, bytes) else Path(source).read_bytes()
    return hashlib.sha256(data).hexdigest()


@dataclass(frozen=True)
class Source:
    """Where a loaded spec came from: its file, content hash and parsed YAML with positions."""

    path: str
    sha256: str
    data: Located

    @classmethod
    def of(cls, path: str | Path, data: Located) -> Source:
        return cls(str(path), sha256_of(path), data)

    def line(self, *keys: str | int) -> int | None:
        """1-based line of a nested key or list item, e.g. ``line("limit", "max")``."""
        return lookup(self.data, *keys)[0]

    def problem(self, field_: str, message: str) -> InputError:
        """An :class:`InputError` at the dotted ``field_`` (``"measured.mass"``,
        ``"rules[2].protocol"``) of this file."""
        return InputError([Problem(self.path, self.line(*split_field(field_)), field_, message)])


def split_field(dotted: str) -> list[str | int]:
    """``"rules[2].protocol"`` -> ``["rules", 2, "protocol"]``."""
    keys: list[str | int] = []
    for part in dotted.split("."):
        name, *indices = part.replace("]", "").split("[")
        if name:
            keys.append(name)
        keys += [int(i) for i in indices]
    return keys


def spec_from(cls: type[T], values: dict[str, Any], **extra: Any) -> T:
    """The spec dataclass ``cls`` from a schema's validated values (field names match)."""
    names = {f.name for f in fields(cls)}  # type: ignore[arg-type]
    return cls(**{k: v for k, v in values.items() if k in names}, **extra)


def load_checked(path: str | Path, schema: Schema, data: Located) -> dict[str, Any]:
    """Validate ``data`` against ``schema``; raise every problem of the file at once."""
    from batcert.specs.schema import validate
    errors = Collector(path)
    values = validate(data, schema, errors)
    errors.raise_if_any()
    assert values is not None
    return values


def pairs(first: str, second: str, first_name: str, second_name: str, *,
          second_positive: bool = True, min_items: int = 1,
          second_range: tuple[float, float] | None = None,
          second_uncertain: bool = False) -> Kind:
    """A list of ``[first, second]`` quantity pairs, e.g. ``[20 in, 2.61 in]`` (position, diameter).

    Returns two tuples (firsts, seconds); the firsts must increase strictly.
    ``second_uncertain``: the second may carry its standard uncertainty (``2.7 mm +/- 0.05 mm``).
    """
    read_second = parse_uncertain if second_uncertain else parse_quantity
    ex1, ex2 = DIMENSIONS[first][3], DIMENSIONS[second][3]

    def parse(value: Any, errors: Collector, path: str):
        if not isinstance(value, LocatedList):
            raise FieldError(f"expected a list of [{first_name}, {second_name}] pairs, "
                             f"e.g. [[0 in, {ex2}], ...]")
        if len(value) < min_items:
            raise FieldError(f"needs at least {min_items} [{first_name}, {second_name}] pairs")
        xs: list[float] = []
        ys: list[float] = []
        ok = True
        for i, item in enumerate(value):
            line, col = value.item_pos[i]
            sub = f"{path}[{i}]"
            if not isinstance(item, LocatedList) or len(item) != 2:
                errors.add(line, sub, f"expected a pair [{first_name}, {second_name}], "
                           f"e.g. [{ex1}, {ex2}]", col)
                ok = False
                continue
            try:
                x = parse_quantity(item[0], first)
                y = read_second(item[1], second)
            except UnitError as exc:
                errors.add(line, sub, str(exc), col)
                ok = False
                continue
            if second_positive and not y > 0:
                errors.add(line, sub, f"{second_name} must be positive, got {item[1]}", col)
                ok = False
                continue
            if second_range is not None and not second_range[0] <= y <= second_range[1]:
                si = DIMENSIONS[second][1]
                errors.add(line, sub, f"{second_name} must be {second_range[0]:g}-"
                           f"{second_range[1]:g} {si}, got {item[1]}", col)
                ok = False
                continue
            if xs and not x > xs[-1]:
                errors.add(line, sub, f"{first_name}s must increase; {item[0]} follows "
                           f"{value[i - 1][0]}", col)
                ok = False
                continue
            xs.append(x)
            ys.append(y)
        return (tuple(xs), tuple(ys)) if ok else None

    also = f"; each {second_name} may carry `+/- u`" if second_uncertain else ""
    return Kind(f"list of [{first_name}, {second_name}] pairs{also}", parse,
                DIMENSIONS[second][1])
