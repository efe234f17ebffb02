"""YAML loading that remembers where every key and value came from.

Mappings load as :class:`Located` dicts and sequences as :class:`LocatedList`; both carry the
1-based line (and column) of each key or item so that validation errors can point into the file.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from batcert.errors import Collector, InputError, Problem


class Located(dict):
    """A mapping with the source position of each key and value."""

    file: str
    line: int
    key_pos: dict[str, tuple[int, int]]
    value_pos: dict[str, tuple[int, int]]


class LocatedList(list):
    """A sequence with the source position of each item."""

    file: str
    line: int
    item_pos: list[tuple[int, int]]


def _pos(node: yaml.Node) -> tuple[int, int]:
    return node.start_mark.line + 1, node.start_mark.column + 1


def _build(node: yaml.Node, file: str, constructor: yaml.SafeLoader, errors: Collector, path: str):
    if isinstance(node, yaml.MappingNode):
        out = Located()
        out.file, out.line = file, _pos(node)[0]
        out.key_pos, out.value_pos = {}, {}
        for key_node, value_node in node.value:
            key = constructor.construct_object(key_node)
            if not isinstance(key, str):
                errors.add(_pos(key_node)[0], path, f"keys must be text, got {key!r}", _pos(key_node)[1])
                continue
            sub = f"{path}.{key}" if path else key
            if key in out:
                errors.add(_pos(key_node)[0], sub, f"duplicate key (first given on line {out.key_pos[key][0]})",
                           _pos(key_node)[1])
                continue
            out.key_pos[key] = _pos(key_node)
            out.value_pos[key] = _pos(value_node)
            out[key] = _build(value_node, file, constructor, errors, sub)
        return out
    if isinstance(node, yaml.SequenceNode):
        seq = LocatedList()
        seq.file, seq.line = file, _pos(node)[0]
        seq.item_pos = []
        for i, item in enumerate(node.value):
            seq.item_pos.append(_pos(item))
            seq.append(_build(item, file, constructor, errors, f"{path}[{i}]"))
        return seq
    return constructor.construct_object(node)


def load_yaml(path: str | Path) -> Located:
    """Read a YAML file whose top level is a mapping; raise :class:`InputError` on any problem."""
    file = str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError([Problem(file, None, "", "file not found")]) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError([Problem(file, None, "", f"cannot read file: {exc}")]) from None
    return load_yaml_text(text, file)


_FAST_LOADER = getattr(yaml, "CSafeLoader", None)  # libyaml: ~10x faster to compose


def _compose(text: str, loader_class) -> yaml.Node | None:
    loader = loader_class(text)
    try:
        return loader.get_single_node()
    finally:
        loader.dispose()


def load_yaml_text(text: str, file: str) -> Located:
    errors = Collector(file)
    try:
        try:
            node = _compose(text, _FAST_LOADER or yaml.SafeLoader)
        except yaml.YAMLError:
            # the pure-Python parser's messages are the documented ones (and the same
            # everywhere): parse again with it to report the problem
            node = _compose(text, yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark else None
        col = mark.column + 1 if mark else None
        problem = exc.problem or str(exc)
        ctx = exc.context_mark
        if exc.context and ctx is not None and ctx.line + 1 != line:  # e.g. an unclosed bracket
            problem += f" ({exc.context} started on line {ctx.line + 1})"
        raise InputError([Problem(file, line, "", f"malformed YAML: {problem}", col)]) from None
    except yaml.YAMLError as exc:
        raise InputError([Problem(file, None, "", f"malformed YAML: {exc}")]) from None
    if node is None:
        raise InputError([Problem(file, 1, "", "the file is empty; expected a mapping of fields")])
    if not isinstance(node, yaml.MappingNode):
        raise InputError([Problem(file, _pos(node)[0], "", "the top level must be a mapping of fields")])
    constructor = yaml.SafeLoader("")
    try:
        data = _build(node, file, constructor, errors, "")
    except yaml.constructor.ConstructorError as exc:
        mark = exc.problem_mark
        errors.add(mark.line + 1 if mark else None, "", f"malformed YAML: {exc.problem}")
        data = Located()
    errors.raise_if_any()
    return data


def where(container: Any, key: str | int) -> tuple[int | None, int | None]:
    """Line and column of a key's value (mapping) or an item (sequence), if known."""
    if isinstance(container, Located) and isinstance(key, str) and key in container.value_pos:
        return container.value_pos[key]
    if isinstance(container, LocatedList) and isinstance(key, int) and key < len(container.item_pos):
        return container.item_pos[key]
    return getattr(container, "line", None), None
