"""One serialisation for every result type: dataclasses to JSON and back.

Results are plain dataclasses in SI units. :class:`Serialisable` gives them ``to_dict`` /
``to_json`` and a ``from_dict`` that rebuilds nested dataclasses (in lists, dicts and optional
fields) from their type hints, so a saved results JSON re-renders without recomputing anything.
"""

from __future__ import annotations

import dataclasses
import json
import sys
import types
import typing
from typing import Any, TypeVar, Union, get_args, get_origin, get_type_hints

T = TypeVar("T")

# the JSON contract's name and version: the first key of every result document and of every
# command's --json output (docs/results-json.md); the number changes when a key changes meaning
# or goes away, not when one is added
SCHEMA = "batcert/1"


def utc_now() -> str:
    """The ``created`` stamp of every result: now, UTC, ISO 8601 to the second."""
    import datetime as _dt
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def map_floats(data: Any, fn: typing.Callable[[float], Any]) -> Any:
    """``data`` (dicts, lists and tuples, as lists) with ``fn`` applied to every float in it."""
    if isinstance(data, float):
        return fn(data)
    if isinstance(data, dict):
        return {k: map_floats(v, fn) for k, v in data.items()}
    if isinstance(data, (list, tuple)):
        return [map_floats(v, fn) for v in data]
    return data


def from_dict(cls: type[T], data: dict[str, Any]) -> T:
    """Rebuild ``cls`` (a dataclass) from :func:`dataclasses.asdict` output; keys not among its
    fields are ignored, missing ones take the field's default."""
    hints = get_type_hints(cls, None, vars(sys.modules[cls.__module__]))
    kw = {f.name: _convert(hints[f.name], data[f.name])
          for f in dataclasses.fields(cls) if f.name in data}  # type: ignore[arg-type]
    return cls(**kw)


def _convert(tp: Any, value: Any) -> Any:
    if value is None:
        return None
    origin = get_origin(tp)
    if origin in (Union, types.UnionType):
        options = [a for a in get_args(tp) if a is not type(None)]
        for a in options:
            if dataclasses.is_dataclass(a) and isinstance(value, dict):
                return from_dict(a, value)  # type: ignore[arg-type]
        return _convert(options[0], value) if len(options) == 1 else value
    if dataclasses.is_dataclass(tp) and isinstance(value, dict):
        return from_dict(tp, value)  # type: ignore[arg-type]
    if origin is list:
        (item,) = get_args(tp) or (Any,)
        return [_convert(item, v) for v in value]
    if origin is dict:
        _, item = get_args(tp) or (Any, Any)
        return {k: _convert(item, v) for k, v in value.items()}
    return value


def envelope(command: str, results: list[Any], version: str) -> dict[str, Any]:
    """What every command prints with ``--json``: the schema, the command, the batcert
    ``version``, and its ``results`` (always a list: result documents, or a listing's
    entries)."""
    return {"schema": SCHEMA, "command": command, "batcert_version": version,
            "results": results}


_SCALARS = (str, int, float, bool, type(None))


def plain(x: Any) -> Any:
    """``dataclasses.asdict`` for a result: dataclasses as dicts of their fields, lists and
    tuples as lists (tuples as tuples), dicts as dicts, recursively, every container copied;
    scalars as they are (asdict deep-copies each one, which took 0.18 s of an 800-variant
    sweep's reports)."""
    if isinstance(x, _SCALARS):
        return x
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return {f.name: plain(getattr(x, f.name)) for f in dataclasses.fields(x)}
    if isinstance(x, list):
        return [v if isinstance(v, _SCALARS) else plain(v) for v in x]
    if isinstance(x, tuple):
        return type(x)(*(plain(v) for v in x)) if hasattr(x, "_fields") else tuple(
            plain(v) for v in x)
    if isinstance(x, dict):
        return {plain(k): plain(v) for k, v in x.items()}
    import copy
    return copy.deepcopy(x)


def dumps(doc: Any, indent: int = 2) -> str:
    """``doc`` as JSON, each object's keys and each list of objects or lists indented; a list
    of numbers, strings and nulls on one line. Equal to ``json.loads`` of ``json.dumps(doc,
    indent=indent)``, and faster on large documents (an 800-variant sweep's 0.2 s to 0.03 s:
    the standard library's indenting encoder is written in Python, its compact one in C).
    NaN and infinities are refused (``allow_nan=False``), as everywhere in batcert's JSON."""
    compact = json.JSONEncoder(allow_nan=False, separators=(", ", ": ")).encode
    step = " " * indent

    def encode(x: Any, depth: int) -> str:
        inner = "\n" + step * (depth + 1)
        if isinstance(x, dict) and x:
            items = (f"{compact(str(k))}: {encode(v, depth + 1)}" for k, v in x.items())
            return "{" + inner + ("," + inner).join(items) + "\n" + step * depth + "}"
        if isinstance(x, (list, tuple)) and any(isinstance(v, (dict, list, tuple)) for v in x):
            items = (encode(v, depth + 1) for v in x)
            return "[" + inner + ("," + inner).join(items) + "\n" + step * depth + "]"
        return compact(x)

    return encode(doc, 0)


class Serialisable:
    """Mixin for result dataclasses: ``to_dict``, ``to_json`` and ``from_dict``. A document
    starts with ``schema`` and its ``kind`` (the class's ``KIND``)."""

    KIND: typing.ClassVar[str] = ""
    # the fields a short repr shows (a result dataclass sets ``repr=False`` to use it: the
    # generated repr of a run printed every sweep sample, thousands of lines)
    SUMMARY: typing.ClassVar[tuple[str, ...]] = ()

    def __repr__(self) -> str:
        """``RunResult(bat='Ash 34 in', protocol='ncaa-bbcor', value=0.49, ...)``: the
        :data:`SUMMARY` fields, lists by their length, floats to six digits."""
        parts = []
        for name in self.SUMMARY:
            value = getattr(self, name)
            if isinstance(value, list):
                text = f"[{len(value)}]"
            elif isinstance(value, float):
                text = f"{value:.6g}"
            else:
                text = repr(value)
            parts.append(f"{name}={text}")
        return f"{type(self).__name__}({', '.join(parts)})"

    def to_dict(self) -> dict[str, Any]:
        return {"schema": SCHEMA, "kind": self._kind(), **self._document()}

    def _kind(self) -> str:
        return self.KIND

    def _document(self) -> dict[str, Any]:
        return plain(self)

    def to_json(self) -> str:
        return dumps(self.to_dict())

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Any:
        return from_dict(cls, data)
