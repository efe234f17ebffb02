"""YAML loading that remembers where every key and value came from.

Mappings load as :class:`Located` dicts and sequences as :class:`LocatedList`; both carry the
1-based line (and column) of each key or item so that validation errors can point into the file.
"""

from __future__ import annotations

import os
import stat
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


# Bounds on what a spec file may hold. The shipped files are a few kilobytes, a few levels deep
# and about a hundred values; these limits are far above any real bat or protocol and keep a
# hostile file (an alias "billion laughs", a recursive alias, thousands of nested brackets, a
# multi-megabyte file) from hanging or crashing the loader.
MAX_BYTES = 2_000_000  # file size
MAX_DEPTH = 32  # nested mappings and lists
MAX_VALUES = 100_000  # keys, items and values after aliases are expanded


class _Limit(Exception):
    def __init__(self, node: yaml.Node, message: str):
        self.node, self.message = node, message


class _Walk:
    """Budget and path of one :func:`_build` walk (for alias bombs and recursive aliases)."""

    def __init__(self) -> None:
        self.values = 0
        self.path: set[int] = set()

    def enter(self, node: yaml.Node, depth: int) -> None:
        self.values += 1
        if self.values > MAX_VALUES:
            raise _Limit(node, f"more than {MAX_VALUES:,} values once aliases are expanded "
                         "(an alias bomb?); a spec file needs a few hundred at most")
        if depth > MAX_DEPTH:
            raise _Limit(node, f"nested more than {MAX_DEPTH} levels deep")
        if id(node) in self.path:
            raise _Limit(node, "an alias that contains itself (recursive alias)")


def _build(node: yaml.Node, file: str, constructor: yaml.SafeLoader, errors: Collector, path: str,
           walk: _Walk | None = None, depth: int = 0):
    walk = walk or _Walk()
    walk.enter(node, depth)
    if isinstance(node, (yaml.MappingNode, yaml.SequenceNode)):
        walk.path.add(id(node))
        try:
            return _build_collection(node, file, constructor, errors, path, walk, depth)
        finally:
            walk.path.discard(id(node))
    return constructor.construct_object(node)


def _build_collection(node: yaml.Node, file: str, constructor: yaml.SafeLoader, errors: Collector,
                      path: str, walk: _Walk, depth: int):
    if isinstance(node, yaml.MappingNode):
        out = Located()
        out.file, out.line = file, _pos(node)[0]
        out.key_pos, out.value_pos = {}, {}
        for key_node, value_node in node.value:
            walk.enter(key_node, depth + 1)
            key = constructor.construct_object(key_node) if isinstance(key_node, yaml.ScalarNode) \
                else None
            if not isinstance(key, str):
                errors.add(_pos(key_node)[0], path, "keys must be text, got "
                           f"{key!r}" if key is not None else "keys must be text", _pos(key_node)[1])
                continue
            sub = f"{path}.{key}" if path else key
            if key in out:
                errors.add(_pos(key_node)[0], sub, f"duplicate key (first given on line {out.key_pos[key][0]})",
                           _pos(key_node)[1])
                continue
            out.key_pos[key] = _pos(key_node)
            out.value_pos[key] = _pos(value_node)
            out[key] = _build(value_node, file, constructor, errors, sub, walk, depth + 1)
        return out
    if isinstance(node, yaml.SequenceNode):
        seq = LocatedList()
        seq.file, seq.line = file, _pos(node)[0]
        seq.item_pos = []
        for i, item in enumerate(node.value):
            seq.item_pos.append(_pos(item))
            seq.append(_build(item, file, constructor, errors, f"{path}[{i}]", walk, depth + 1))
        return seq
    raise TypeError(f"not a collection: {node!r}")


def load_yaml(path: str | Path) -> Located:
    """Read a YAML file whose top level is a mapping; raise :class:`InputError` on any problem."""
    file = str(path)
    raw = read_input(path, MAX_BYTES, "a YAML file",
                     "a spec file is a few kilobytes (is this the right file?)")
    return load_yaml_text(decode_text(raw, file), file)


def read_input(path: str | Path, max_bytes: int, what: str, typical: str) -> bytes:
    """The bytes of the input file ``path`` (``what`` it should be, e.g. "a YAML file"),
    refused with one :class:`Problem` when it is missing, unreadable, not a regular file (a
    FIFO, a device, a socket: checked before opening, and the file is opened without waiting
    for a writer, so nothing blocks) or larger than ``max_bytes`` (at most ``max_bytes + 1``
    bytes are read, so a file that never ends cannot fill the memory); ``typical`` says how
    large such a file usually is. The one place input files are read."""
    file = str(path)

    def refuse(message: str) -> InputError:
        return InputError([Problem(file, None, "", message)])

    def too_large() -> InputError:
        return refuse(f"larger than {max_bytes / 1e6:g} MB; {typical}")

    try:
        info = os.stat(path)
        if stat.S_ISDIR(info.st_mode):
            raise refuse(f"is a directory; give {what}")
        if not stat.S_ISREG(info.st_mode):
            raise refuse(f"is not a regular file (a FIFO, a device or a socket); give {what}")
        if info.st_size > max_bytes:
            raise too_large()
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_BINARY", 0))
        with os.fdopen(fd, "rb") as handle:
            if not stat.S_ISREG(os.fstat(handle.fileno()).st_mode):  # swapped since the stat
                raise refuse(f"is not a regular file; give {what}")
            raw = handle.read(max_bytes + 1)
    except FileNotFoundError:
        raise refuse("file not found") from None
    except OSError as exc:
        raise refuse(f"cannot read file: {exc.strerror or exc}") from None
    if len(raw) > max_bytes:  # grew since the stat
        raise too_large()
    return raw


def decode_text(raw: bytes, file: str) -> str:
    """UTF-8 text (a byte-order mark is allowed); a byte that is not UTF-8 is an error at its
    line and column, naming the byte."""
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise InputError([Problem(file, 1, "", "UTF-16 text; save the file as UTF-8")])
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        start = exc.start
        line = raw.count(b"\n", 0, start) + 1
        col = start - (raw.rfind(b"\n", 0, start) + 1) + 1
        byte = raw[start:start + 1].hex()
        raise InputError([Problem(file, line, "", f"byte 0x{byte} is not UTF-8 text (a Latin-1 "
                                  "or Windows-1252 file?); save the file as UTF-8", col)]
                         ) from None


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
    except yaml.reader.ReaderError as exc:  # a control character such as NUL
        at = text.count("\n", 0, exc.position) + 1
        col_at = exc.position - (text.rfind("\n", 0, exc.position) + 1) + 1
        what = f"U+{exc.character:04X}" if isinstance(exc.character, int) else repr(exc.character)
        raise InputError([Problem(file, at, "", f"control character {what} is not allowed in "
                                  "a YAML file", col_at)]) from None
    except RecursionError:
        raise InputError([Problem(file, None, "", f"nested too deeply (more than {MAX_DEPTH} "
                                  "levels are refused)")]) from None
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
    except _Limit as exc:
        line, col = _pos(exc.node)
        raise InputError([Problem(file, line, "", f"refused: {exc.message}", col)]) from None
    errors.raise_if_any()
    return data


def where(container: Any, key: str | int) -> tuple[int | None, int | None]:
    """Line and column of a key's value (mapping) or an item (sequence), if known."""
    if isinstance(container, Located) and isinstance(key, str) and key in container.value_pos:
        return container.value_pos[key]
    if isinstance(container, LocatedList) and isinstance(key, int) and key < len(container.item_pos):
        return container.item_pos[key]
    return getattr(container, "line", None), None
