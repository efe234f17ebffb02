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


class Serialisable:
    """Mixin for result dataclasses: ``to_dict``, ``to_json`` and ``from_dict``. A document
    starts with ``schema`` and its ``kind`` (the class's ``KIND``)."""

    KIND: typing.ClassVar[str] = ""

    def to_dict(self) -> dict[str, Any]:
        return {"schema": SCHEMA, "kind": self._kind(), **self._document()}

    def _kind(self) -> str:
        return self.KIND

    def _document(self) -> dict[str, Any]:
        return dataclasses.asdict(typing.cast(Any, self))

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2, allow_nan=False)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Any:
        return from_dict(cls, data)
