"""Lines of prose wrapped to the terminal's width with a hanging indent (issue 40): a wrapped
warning or headline continues further in than the line that starts it, so that it still reads as
one item. Words are never broken, so a path or a number longer than the line stands alone on
its line, whole. Styles (``(text, style)`` parts) carry over to the wrapped lines."""

from __future__ import annotations

import re
from collections.abc import Sequence

Part = tuple[str, str]

_TOKEN = re.compile(r"\n|[^\S\n]+|\S+")
NARROWEST = 24  # columns a continuation line keeps at least for its text


def _hang(text: str, hang: int | None, width: int) -> int:
    """The continuation lines' indent: ``hang``, else the first line's indent + 4; never so
    deep that fewer than :data:`NARROWEST` columns are left for the text."""
    lead = len(text) - len(text.lstrip(" "))
    want = lead + 4 if hang is None else hang
    return max(0, min(want, width - NARROWEST))


def wrap_parts(parts: Sequence[Part], width: int, hang: int | None = None) -> list[list[Part]]:
    """``parts`` (one line of styled text, which may hold line feeds) as lines of at most
    ``width`` columns where its words allow, continuation lines indented by ``hang``."""
    text = "".join(t for t, _ in parts)
    if "\n" not in text and len(text) <= width:
        return [list(parts)]
    indent = " " * _hang(text, hang, width)
    lines: list[list[Part]] = []
    line: list[Part] = []
    used, has_word = 0, False

    def flush() -> None:
        while line and line[-1][0].isspace():
            line.pop()
        lines.append(line[:])
        line.clear()

    for part, style in parts:
        for tok in _TOKEN.findall(part):
            if tok == "\n":
                flush()
                used, has_word = 0, False
            elif tok.isspace():
                line.append((tok, style))
                used += len(tok)
            else:
                if has_word and used + len(tok) > width:
                    flush()
                    line.append((indent, ""))
                    used = len(indent)
                line.append((tok, style))
                used += len(tok)
                has_word = True
    flush()
    return lines


def wrap_text(text: str, width: int, hang: int | None = None) -> list[str]:
    """Plain ``text`` as wrapped lines (see :func:`wrap_parts`)."""
    return ["".join(t for t, _ in line) for line in wrap_parts([(text, "")], width, hang)]
