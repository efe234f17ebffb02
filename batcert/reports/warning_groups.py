"""A sweep's warnings grouped for the terminal (issue 40): a 15-point sweep gave some twenty
warnings that differ only in a number and in which variant (or condition) gave them ("the
barrel's wall deflects about 1.5 mm ... 0.5 times its thickness (1 of 15 variants: wall=0.0027
m)"). Warnings that are the same but for their numbers and their condition become one line: the
variants it concerns by their values ("wall 60%-90% (4 of 15 variants)"), the conditions, and
each differing number as its range ("1.5 to 2.7 mm"). The result's warnings (its JSON and
reports) keep every warning as it was."""

from __future__ import annotations

import re

from batcert.results.sweep import SweepAxis, SweepResult

# a warning and its variants as batcert.sweeps.sweep words them: "<text> (all 15 variants)",
# "(the variant)", "(2 of 15 variants: wall=0.0027 m; wall=0.00243 m[; and 3 more])"
_WHICH = re.compile(r"^(?P<text>.*) \((?P<which>all \d+ variants|the variant|"
                    r"\d+ of \d+ variants: (?P<names>.*))\)$", re.S)
_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.])")


def _variant_names(result: SweepResult) -> dict[str, int]:
    """Each variant's name as a warning gives it (``wall=0.0027 m, relative_speed=60 m/s``)."""
    def one(a: SweepAxis, v: float) -> str:
        return f"{a.name}={v:.6g}" + (f" {a.unit}" if a.unit and a.unit != "-" else "")
    return {", ".join(one(a, v) for a, v in zip(result.axes, p, strict=True)): i
            for i, p in enumerate(result.points)}


def _split(result: SweepResult, warning: str, names: dict[str, int]):
    """(condition or None, text, variant indices) of a warning; None when its variants are not
    all named (the sweep names four and counts the rest) or it has no variants."""
    m = _WHICH.match(warning)
    if m is None:
        return None
    if m["names"] is None:
        indices = list(range(len(result.points)))
    else:
        listed = m["names"].split("; ")
        if any(n not in names for n in listed):
            return None
        indices = [names[n] for n in listed]
    text, condition = m["text"], None
    for c in result.conditions:
        if text.startswith(f"{c.name}: "):
            condition, text = c.name, text[len(c.name) + 2:]
            break
    return condition, text, indices


def _span(values: list[str]) -> str:
    """Numbers that differ as their range ("1.5 to 2.7"); one that does not, as itself."""
    floats = sorted(set(values), key=float)
    return floats[0] if len(floats) == 1 else f"{floats[0]} to {floats[-1]}"


def _merged(texts: list[str]) -> str:
    """Texts equal but for their numbers, with each number as its range over them."""
    numbers = [_NUMBER.findall(t) for t in texts]
    spans = iter([_span([n[k] for n in numbers]) for k in range(len(numbers[0]))])
    return _NUMBER.sub(lambda _: next(spans), texts[0])


def _axis_value(a: SweepAxis, v: float) -> str:
    if a.percent and a.nominal:
        return f"{v / a.nominal * 100:.4g}%"
    if a.dimension == "length":
        return f"{v * 1e3:.4g} mm"
    return f"{v:.4g}" + (f" {a.unit}" if a.unit and a.unit != "-" else "")


def _position(a: SweepAxis, value: float) -> int:
    return min(range(len(a.values)), key=lambda k: abs(a.values[k] - value))


def _runs(a: SweepAxis, positions: list[int]) -> str:
    """An axis's values at ``positions`` (indices into its values): consecutive ones as a
    range ("60%-90%, 120%")."""
    runs: list[list[int]] = []
    for k in sorted(set(positions)):
        if runs and k == runs[-1][-1] + 1:
            runs[-1].append(k)
        else:
            runs.append([k])
    def span(r: list[int]) -> str:
        first, last = _axis_value(a, a.values[r[0]]), _axis_value(a, a.values[r[-1]])
        if len(r) == 1:
            return first
        unit = first.partition(" ")[2]  # "50-55 m/s", "2.16-2.7 mm"; "60%-90%"
        return f"{first.partition(' ')[0]}-{last}" if unit and last.endswith(unit) \
            else f"{first}-{last}"
    return ", ".join(span(r) for r in runs)


def variants_words(result: SweepResult, indices: list[int]) -> str:
    """Which variants, by their values: "wall 60%-90% (4 of 15 variants)"."""
    n = len(result.points)
    if len(set(indices)) == n:
        return f"all {n} variants" if n > 1 else "the variant"
    axes = [f"{a.name} " + _runs(a, [_position(a, result.points[i][k]) for i in indices])
            for k, a in enumerate(result.axes)
            if len({result.points[i][k] for i in indices}) < len(a.values)]
    count = f"{len(set(indices))} of {n} variants"
    return f"{', '.join(axes)} ({count})" if axes else count


def _by_text(result: SweepResult) -> list[str | list[tuple[str | None, str, list[int]]]]:
    """The warnings in order, those alike but for their numbers (same condition) together; a
    warning that cannot be grouped (its variants not all named) as itself."""
    names = _variant_names(result)
    groups: dict[tuple[str | None, str], list[tuple[str | None, str, list[int]]]] = {}
    out: list[str | list[tuple[str | None, str, list[int]]]] = []
    for w in result.warnings:
        split = _split(result, w, names)
        if split is None:
            out.append(w)
            continue
        key = (split[0], _NUMBER.sub("#", split[1]))
        if key not in groups:
            groups[key] = []
            out.append(groups[key])
        groups[key].append(split)
    return out


def grouped_warnings(result: SweepResult) -> list[str]:
    """The sweep's warnings for the terminal, those alike grouped (see the module's doc); the
    same group in several conditions with the same variants is one line naming them."""
    order = [c.name for c in result.conditions]
    merged: dict[tuple[str, str], list[str]] = {}  # (variants, text) -> its conditions
    for item in _by_text(result):
        if isinstance(item, str):
            merged.setdefault(("", item), [])
            continue
        indices = sorted({i for _, _, idx in item for i in idx})
        text = _merged([t for _, t, _ in item])
        conditions = merged.setdefault((variants_words(result, indices), text), [])
        conditions += [item[0][0]] if item[0][0] else []
    out = []
    for (which, text), conditions in merged.items():
        if not which:
            out.append(text)
            continue
        lead = ("every condition: " if len(conditions) == len(order) > 1
                else "".join(f"{c}, " for c in conditions[:-1]) + f"{conditions[-1]}: "
                if conditions else "")
        out.append(f"{which}: {lead}{text}")
    return out
