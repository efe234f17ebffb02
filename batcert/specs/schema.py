"""A small declarative schema for spec files: fields as data, all errors at once.

Each spec module (bat, ball, protocol, league) declares its fields as a tuple of :class:`Field`.
:func:`validate` walks a :class:`~batcert.specs.yamlio.Located` mapping against such a schema,
converts quantities to SI, fills defaults and records every problem with its file, line and
dotted field name. Unknown keys are errors with a did-you-mean suggestion. The same field tables
generate the field-by-field reference in ``docs/inputs.md``.
"""

from __future__ import annotations

import difflib
import math
import unicodedata
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from batcert.errors import Collector
from batcert.specs.yamlio import Located, LocatedList, where
from batcert.units import DIMENSIONS, UnitError, parse_quantity, parse_uncertain

LARGEST_NUMBER = 1e15  # a plain number larger than this (or nan, inf) is refused


class FieldError(ValueError):
    """Raised by a field parser; the schema walker adds file, line and field name."""


@dataclass(frozen=True)
class Kind:
    """How to read one value: a parser plus a short description for the docs."""

    describe: str
    parse: Callable[[Any, Collector, str], Any]
    unit: str = ""
    schema: Schema | None = None  # the nested schema of a section (for the generated docs)


@dataclass(frozen=True)
class Field:
    name: str
    kind: Kind
    doc: str
    required: bool = False
    default: Any = None


@dataclass(frozen=True)
class Schema:
    title: str
    fields: tuple[Field, ...]
    doc: str = ""
    # cross-field checks run after the fields parse: (values, mapping, collector, path) -> None
    checks: tuple[Callable[[dict, Located, Collector, str], None], ...] = field(default_factory=tuple)

    def names(self) -> list[str]:
        return [f.name for f in self.fields]


def _join(path: str, name: str | int) -> str:
    if isinstance(name, int):
        return f"{path}[{name}]"
    return f"{path}.{name}" if path else name


def validate(data: Any, schema: Schema, errors: Collector, path: str = "") -> dict | None:
    """Validate ``data`` against ``schema``; return SI values (None where a field failed)."""
    if not isinstance(data, Located):
        line = getattr(data, "line", None)
        errors.add(line, path, f"expected a mapping of fields ({', '.join(schema.names())})")
        return None
    known = {f.name: f for f in schema.fields}
    n_before = len(errors.problems)
    for key in data:
        if key not in known:
            line, col = data.key_pos[key]
            close = difflib.get_close_matches(key, list(known), n=1, cutoff=0.6)
            hint = f"; did you mean '{close[0]}'?" if close else f"; known fields: {', '.join(known)}"
            errors.add(line, _join(path, key), f"unknown field{hint}", col)
    out: dict[str, Any] = {}
    for f in schema.fields:
        sub = _join(path, f.name)
        if f.name not in data or data[f.name] is None:
            if f.required:
                line = data.key_pos[f.name][0] if f.name in data else data.line
                errors.add(line, sub, "required field is missing" if f.name not in data
                           else "required field is empty")
            out[f.name] = f.default
            continue
        at, at_col = where(data, f.name)
        try:
            out[f.name] = f.kind.parse(data[f.name], errors, sub)
        except FieldError as exc:
            errors.add(at, sub, str(exc), at_col)
            out[f.name] = None
    if len(errors.problems) == n_before:  # cross-field checks only on fields that all parsed
        for check in schema.checks:
            check(out, data, errors, path)
    return out


# ---------------------------------------------------------------- kinds


def quantity(dimension: str, *, positive: bool = False, minimum: float | None = None,
             maximum: float | None = None, nonzero: bool = False,
             uncertain: bool = False) -> Kind:
    """A quantity with its unit; ``uncertain``: it may carry its standard uncertainty,
    ``863 g +/- 1 g`` (an :class:`~batcert.units.Uncertain`, for ``run --uncertainty``)."""
    _, si, _, example = DIMENSIONS[dimension]
    read = parse_uncertain if uncertain else parse_quantity

    def parse(value: Any, errors: Collector, path: str) -> float:
        try:
            v = read(value, dimension)
        except UnitError as exc:
            raise FieldError(str(exc)) from None
        if positive and not v > 0:
            raise FieldError(f"must be positive, got {value}")
        if nonzero and v == 0:
            raise FieldError(f"must not be zero, got {value}")
        if minimum is not None and v < minimum:
            raise FieldError(f"must be at least {minimum:g} {si}, got {value}")
        if maximum is not None and v > maximum:
            raise FieldError(f"must be at most {maximum:g} {si}, got {value}")
        return v

    rule = " > 0" if positive else ""
    also = "; may carry `+/- u`" if uncertain else ""
    return Kind(f"quantity ({dimension.replace('_', ' ')}{rule}), e.g. `{example}`{also}",
                parse, si)


def number(*, minimum: float | None = None, maximum: float | None = None,
           exclusive_minimum: float | None = None) -> Kind:
    def parse(value: Any, errors: Collector, path: str) -> float:
        if isinstance(value, str):  # YAML 1.1 reads 6.53e7 (no sign in the exponent) as text
            try:
                value = float(value)
            except ValueError:
                pass
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise FieldError(f"expected a plain number, got {value!r}")
        try:
            v = float(value)
        except OverflowError:  # an integer too large for a float
            v = math.inf
        if not math.isfinite(v) or abs(v) > LARGEST_NUMBER:
            raise FieldError(f"expected a finite number of reasonable size (at most "
                             f"{LARGEST_NUMBER:g}), got {value!r}")
        if minimum is not None and v < minimum:
            raise FieldError(f"must be at least {minimum:g}, got {value}")
        if maximum is not None and v > maximum:
            raise FieldError(f"must be at most {maximum:g}, got {value}")
        if exclusive_minimum is not None and not v > exclusive_minimum:
            raise FieldError(f"must be greater than {exclusive_minimum:g}, got {value}")
        return v

    rng = []
    if minimum is not None:
        rng.append(f">= {minimum:g}")
    if exclusive_minimum is not None:
        rng.append(f"> {exclusive_minimum:g}")
    if maximum is not None:
        rng.append(f"<= {maximum:g}")
    return Kind("number" + (f" ({', '.join(rng)})" if rng else ""), parse)


def integer(*, minimum: int | None = None, maximum: int | None = None) -> Kind:
    def parse(value: Any, errors: Collector, path: str) -> int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise FieldError(f"expected a whole number, got {value!r}")
        if minimum is not None and value < minimum:
            raise FieldError(f"must be at least {minimum}, got {value}")
        if maximum is not None and value > maximum:
            raise FieldError(f"must be at most {maximum}, got {value}")
        return value

    rng = [f">= {minimum}"] if minimum is not None else []
    rng += [f"<= {maximum}"] if maximum is not None else []
    return Kind("whole number" + (f" ({', '.join(rng)})" if rng else ""), parse)


# characters that reorder what follows them on a terminal or page (bidirectional embeddings,
# overrides and isolates): a label could show other text than it holds
_BIDI_CONTROLS = frozenset("\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


def label() -> Kind:
    """A name or title: text shown on one line, its runs of spaces, tabs and line breaks
    collapsed to one space (a line break in a name would start a new line in the terminal or
    a new block in a Markdown report), without bidirectional controls."""
    base = text()

    def parse(value: Any, errors: Collector, path: str) -> str:
        out = " ".join(base.parse(value, errors, path).split())
        bad = next((c for c in out if c in _BIDI_CONTROLS), None)
        if bad is not None:
            raise FieldError(f"contains the character U+{ord(bad):04X}, a bidirectional control "
                             "that makes a label show other text than it holds")
        return out

    return Kind("text (one line)", parse)


def text() -> Kind:
    def parse(value: Any, errors: Collector, path: str) -> str:
        if isinstance(value, (Located, LocatedList)) or isinstance(value, bool):
            raise FieldError(f"expected text, got {type(value).__name__}")
        out = str(value)
        bad = next((c for c in out if c not in "\t\n" and unicodedata.category(c) in ("Cc", "Cs")),
                   None)
        if bad is not None:  # e.g. "\0" or a lone "\ud800" written as a YAML escape
            raise FieldError(f"contains the character U+{ord(bad):04X}, which is not text (a "
                             "control character or half of a surrogate pair)")
        return out

    return Kind("text", parse)


def choice(*options: str) -> Kind:
    def parse(value: Any, errors: Collector, path: str) -> str:
        if value not in options:
            close = difflib.get_close_matches(str(value), options, n=1, cutoff=0.5)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise FieldError(f"must be one of {', '.join(options)}; got {value!r}{hint}")
        return value

    return Kind("one of " + ", ".join(f"`{o}`" for o in options), parse)


def section(schema: Schema) -> Kind:
    def parse(value: Any, errors: Collector, path: str) -> dict | None:
        if not isinstance(value, Located):
            raise FieldError(f"expected a mapping with fields {', '.join(schema.names())}")
        return validate(value, schema, errors, path)

    return Kind(f"mapping: {schema.title}", parse, schema=schema)


def list_of(item: Kind, *, min_items: int = 0, max_items: int | None = None,
            describe: str | None = None) -> Kind:
    def parse(value: Any, errors: Collector, path: str) -> list:
        if not isinstance(value, LocatedList):
            raise FieldError(f"expected a list ({describe or item.describe})")
        if len(value) < min_items:
            raise FieldError(f"needs at least {min_items} item{'s' if min_items > 1 else ''}")
        if max_items is not None and len(value) > max_items:
            exactly = "exactly" if max_items == min_items else "at most"
            raise FieldError(f"needs {exactly} {max_items} item{'s' if max_items > 1 else ''} "
                             f"({describe or item.describe}), got {len(value)}")
        out = []
        for i, v in enumerate(value):
            sub = _join(path, i)
            try:
                out.append(item.parse(v, errors, sub))
            except FieldError as exc:
                line, col = value.item_pos[i]
                errors.add(line, sub, str(exc), col)
                out.append(None)
        return out

    return Kind(describe or f"list of {item.describe}", parse, item.unit, item.schema)


def one_of(*kinds: Kind, describe: str) -> Kind:
    """Accept the first kind that parses (e.g. a constant quantity or a per-station list)."""

    def parse(value: Any, errors: Collector, path: str) -> Any:
        messages = []
        for k in kinds:
            trial = Collector(errors.file)
            try:
                result = k.parse(value, trial, path)
            except FieldError as exc:
                messages.append(str(exc))
                continue
            errors.problems.extend(trial.problems)
            return result
        raise FieldError(f"expected {describe}: {messages[0]}")

    units = {k.unit for k in kinds}  # a unit for the docs only when every alternative shares it
    return Kind(describe, parse, units.pop() if len(units) == 1 else "")


def lookup(data: Located, *keys: str | int) -> tuple[int | None, int | None]:
    """Line and column of a nested key (or list item), for cross-field checks.

    A mapping key gives the key's own position, so that a block value (``measured:`` followed by
    indented fields) is reported on the line that names it rather than on its first sub-field.
    """
    node: Any = data
    pos: tuple[int | None, int | None] = (getattr(data, "line", None), None)
    for k in keys:
        if isinstance(node, (Located, LocatedList)):
            try:
                if isinstance(node, Located) and isinstance(k, str) and k in node.key_pos:
                    pos = node.key_pos[k]
                else:
                    pos = where(node, k)
                node = node[k]  # type: ignore[index]  # a wrong key type is caught below
            except (KeyError, IndexError, TypeError):
                break
    return pos


def describe_schema(schema: Schema, seen: Sequence[str] = ()) -> str:
    """Markdown table of a schema's fields (used to write docs/inputs.md)."""
    rows = ["| field | meaning | type | unit (SI) | required | default |", "|---|---|---|---|---|---|"]
    for f in schema.fields:
        default = "" if f.default is None else f"`{f.default}`"
        rows.append(f"| `{f.name}` | {f.doc} | {f.kind.describe} | {f.kind.unit} | "
                    f"{'yes' if f.required else 'no'} | {default} |")
    return "\n".join(rows)
