"""Spec helpers shared by bat, ball and protocol files: header fields, pairs, file hashes."""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

from batcert.errors import Collector
from batcert.specs.schema import Field, FieldError, Kind, text
from batcert.specs.yamlio import LocatedList
from batcert.units import DIMENSIONS, UnitError, parse_quantity

HEADER_FIELDS = (
    Field("description", text(), "Free text describing the file's content."),
    Field("reference", text(), "Where the values come from (paper, standard, measurement)."),
    Field("version", text(), "Version of this file's content."),
)


def sha256_of(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def pairs(first: str, second: str, first_name: str, second_name: str, *,
          second_positive: bool = True, min_items: int = 1) -> Kind:
    """A list of ``[first, second]`` quantity pairs, e.g. ``[20 in, 2.61 in]`` (position, diameter).

    Returns two tuples (firsts, seconds); the firsts must increase strictly.
    """
    ex1, ex2 = DIMENSIONS[first][3], DIMENSIONS[second][3]

    def parse(value: Any, errors: Collector, path: str):
        if not isinstance(value, LocatedList):
            raise FieldError(f"expected a list of [{first_name}, {second_name}] pairs, "
                             f"e.g. [[0 in, {ex2}], ...]")
        if len(value) < min_items:
            raise FieldError(f"needs at least {min_items} [{first_name}, {second_name}] pairs")
        xs, ys = [], []
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
                y = parse_quantity(item[1], second)
            except UnitError as exc:
                errors.add(line, sub, str(exc), col)
                ok = False
                continue
            if second_positive and not y > 0:
                errors.add(line, sub, f"{second_name} must be positive, got {item[1]}", col)
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

    return Kind(f"list of [{first_name}, {second_name}] pairs", parse, DIMENSIONS[second][1])
