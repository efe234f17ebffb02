"""Reading the terminal's wrapped lines back as items (issue 40: prose wraps at the width with a
hanging indent). A line indented by four or more spaces continues the item above it: a
warning's ("  warning: " then 11 spaces), a headline's (its indent + 4). Only for output with
no aligned table in it, whose cells may be indented as deeply."""

from __future__ import annotations


def items(text: str) -> list[str]:
    """``text``'s lines with each wrapped item joined back into one line."""
    out: list[str] = []
    for line in text.splitlines():
        if out and line.startswith("    ") and line.strip():
            out[-1] += " " + line.strip()
        else:
            out.append(line)
    return out


def too_wide(text: str, width: int = 80) -> list[str]:
    """The lines of ``text`` wider than ``width`` but for an unbreakable word (a path) too long
    for any line."""
    return [line for line in text.splitlines()
            if len(line) > width and len(max(line.split(), key=len)) <= width - 20]
