"""How every value is shown: the one set of formatters for Markdown, HTML and the terminal.

Formatters return a :class:`~batcert.units.Display` (SI text with the US customary equivalent,
shown below it in HTML and in brackets as plain text) or plain text. Metric names, decimals and
units come from the metric registry (:data:`batcert.methods.metrics.METRICS`); impact-rule and
aggregate words from theirs. Nothing here computes physics.
"""

from __future__ import annotations

import math
import re
import unicodedata
from collections.abc import Iterator
from datetime import datetime
from typing import Any

from batcert.units import DASH, INCH, Display, show, to_us

MINUS = "\u2212"  # a typographic minus sign for signed values


def signed(text: str) -> str:
    """Python's "-1.2" with a typographic minus sign: "−1.2"."""
    return MINUS + text[1:] if text.startswith("-") else text


def _nz(v: float) -> float:
    return v + 0.0  # turns -0.0 into 0.0


def margin_text(margin: float, digits: int, unit: str = "") -> str:
    """A signed margin at ``digits`` decimals, honest where rounding would hide it: exactly at
    the limit is "0 (at the limit)", and a margin that rounds to zero but is not zero is
    "+<0.0001" (or its negative), never "+0.0000" beside a value that differs from the limit."""
    tail = f" {unit}" if unit else ""
    if margin == 0:
        return f"0{tail} (at the limit)"
    step = 0.5 * 10.0**-digits
    if abs(margin) < step:
        return f"{'+' if margin > 0 else MINUS}<{10.0**-digits:.{digits}f}{tail}"
    return signed(f"{margin:+.{digits}f}{tail}")


# ---------------------------------------------------------------- registry words


def metric_word(metric: str) -> str:
    """The metric's display word ("BBCOR", "exit speed")."""
    from batcert.methods.metrics import METRICS
    return METRICS[metric].display if metric in METRICS else metric


def metric_name(metric: str) -> str:
    """The metric's display word, capitalised for headings ("Exit speed", "BESR")."""
    word = metric_word(metric)
    return word[:1].upper() + word[1:]


def condition_metrics() -> list[tuple[str, str, str]]:
    """The dimensionless metrics a run's condition shows, in registry order: ``(name, field,
    column heading)`` (the exit speed is shown as a speed of its own)."""
    from batcert.methods.metrics import METRICS
    return [(m.name, m.field, m.column or m.display) for m in METRICS.values() if not m.unit]


def rule_word(rule: str) -> str:
    """The impact-location rule's display words ("centre of percussion")."""
    from batcert.methods.rules import IMPACT_RULES
    return IMPACT_RULES[rule].display if rule in IMPACT_RULES else rule


def aggregate_word(aggregate: str) -> str:
    """The aggregate's display word ("mean", "maximum")."""
    from batcert.methods.metrics import AGGREGATES
    return AGGREGATES[aggregate].display if aggregate in AGGREGATES else aggregate


# ---------------------------------------------------------------- values


def metric_value(value: float | None, metric: str, signed_: bool = False) -> Display:
    """A protocol metric value: exit speed in m/s with mph, other metrics dimensionless, with
    the metric's registered number of decimals."""
    from batcert.methods.metrics import METRICS
    if value is None:
        return Display(DASH, None)
    sign = "+" if signed_ else ""
    digits = METRICS[metric].digits if metric in METRICS else 4
    if signed_ and metric == "exit-speed":
        return Display(margin_text(value, digits, "m/s"),
                       "0 mph" if value == 0 else margin_text(to_us(value, "speed"), 1, "mph"))
    if signed_:
        return Display(margin_text(value, digits), None)
    if metric == "exit-speed":
        return Display(signed(f"{_nz(value):{sign}.{digits}f} m/s"),
                       signed(f"{_nz(to_us(value, 'speed')):{sign}.1f} mph"))
    return Display(signed(f"{_nz(value):{sign}.{digits}f}"), None)


def two_significant(value: float, at_least: int = 0) -> int:
    """Decimals that show ``value`` to two significant digits (at least ``at_least``; 0 for
    zero)."""
    if not value:
        return at_least
    return max(at_least, 1 - math.floor(math.log10(abs(value))))


def metric_spread(value: float | None, metric: str, signed_: bool = False) -> Display:
    """A spread or change of a protocol metric (a standard deviation, a sensitivity), to two
    significant digits, with the metric's unit."""
    if value is None:
        return Display(DASH, None)
    if value and abs(value) < 1e-6:  # a rounding-level difference
        text = signed(f"{value:{'+' if signed_ else ''}.1e}")
        return Display(text + (" m/s" if metric == "exit-speed" else ""), None)
    digits = two_significant(value)
    text = signed(f"{_nz(value):{'+' if signed_ else ''}.{digits}f}")
    if metric == "exit-speed":
        return Display(f"{text} m/s", signed(f"{to_us(value, 'speed'):.{digits}f} mph"))
    return Display(text, None)


def plain(value: float | None, digits: int = 3) -> Display:
    """A dimensionless number, e.g. a COR."""
    return Display(DASH if value is None else f"{_nz(value):.{digits}f}", None)


def quantity(value: float | None, dimension: str, digits: int = 3) -> Display:
    """An SI quantity with its US customary equivalent (``units.show``); -0 shows as 0."""
    return show(None if value is None else _nz(value), dimension, digits)


def location(r: float | None, pivot: float, length: float) -> Display:
    """A position on the bat: metres from the pivot, with inches from the tip alongside."""
    if r is None:
        return Display(DASH, None)
    from_tip = length - pivot - r
    where = "from tip" if from_tip >= 0 else "beyond tip"
    return Display(f"{r:.3f} m from pivot", f"{abs(to_us(from_tip, 'length')):.2f} in {where}")


def offset(d: float | None) -> Display:
    """A signed distance along the bat in cm, with inches."""
    if d is None:
        return Display(DASH, None)
    return Display(signed(f"{_nz(d) * 100:+.1f} cm"), signed(f"{_nz(d) / INCH:+.2f} in"))


def percent(p: float | None) -> str:
    """P as a signed percentage; values that round to zero show as 0.00 % (no "-0.00 %")."""
    if p is None:
        return "undefined"
    return "0.00 %" if round(p * 100, 2) == 0 else f"{p * 100:+.2f} %"


def percent_std(s: float | None) -> str:
    """A spread of P (always positive) in per cent."""
    return DASH if s is None else f"{s * 100:.2f} %"


def number(value: Any) -> str:
    """Generic display of a setting or diagnostic value (numbers to 5 significant digits)."""
    if isinstance(value, bool) or value is None:
        return str(value).lower() if value is not None else DASH
    if isinstance(value, float):
        return f"{value:.5g}"
    if isinstance(value, (list, tuple)):
        return ", ".join(number(v) for v in value) or DASH
    return str(value)


# The unit of every setting, diagnostic and correction a report lists (SI), by its flattened
# name, else by its last part, else by its suffix; "" for text, flags and pure numbers.
UNITS: dict[str, str] = {
    "n_modes": "count", "refine": "count", "time_step": "s", "max_contact_time": "s",
    "cor": "ratio", "start": "m from knob", "end": "m from knob", "outer_diameter": "m",
    "wall": "m", "mass_change": "kg", "added_knob_mass": "kg", "added_end_cap_mass": "kg",
    "model_compression_stiffness": "N/m", "measured_compression_stiffness": "N/m",
}
SUFFIX_UNITS = (("_hz", "Hz"), ("_scale", "ratio"), ("_weight_knob", "ratio"),
                ("_weight_tip", "ratio"), ("_weight_min", "ratio"), ("_weight_max", "ratio"))


def unit_of(name: str) -> str:
    """The unit of a listed setting or correction (see :data:`UNITS`)."""
    last = name.rsplit(".", 1)[-1]
    for key in (name, last):
        if key in UNITS:
            return UNITS[key]
    for suffix, unit in SUFFIX_UNITS:
        if last.endswith(suffix):
            return unit
    if name.startswith("barrel.modes_hz"):
        return "Hz"
    return ""


def flatten(data: dict[str, Any], prefix: str = "") -> Iterator[tuple[str, str]]:
    """``{"barrel": {"k": 1}}`` -> ``("barrel.k", "1")``; lists are joined with commas."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            yield from flatten(value, name + ".")
        else:
            yield name, number(value)


# ---------------------------------------------------------------- league rules


# a league rule's unit -> the dimension and SI digits its values and margins are shown with
_RULE_QUANTITIES = {"m/s": ("speed", 2), "kg": ("mass", 3), "N": ("force", 0)}


def rule_value(value: Any, unit: str) -> Display | str:
    """A league rule's value or limit (lengths in mm with inches)."""
    if value is None:
        return DASH
    if isinstance(value, (list, tuple)):
        return ", ".join(str(v) for v in value)
    if isinstance(value, str):
        return value
    if unit == "m":
        return Display(f"{value * 1000:.1f} mm", f"{value / INCH:.3f} in")
    if unit in _RULE_QUANTITIES:
        return show(value, *_RULE_QUANTITIES[unit])
    if unit == "in - oz":
        return Display(f"{value:.2f}", None)
    return Display(f"{value:.4f}", None)


def rule_limit(limit: Any, unit: str, tolerance: float) -> Display | str:
    """A rule's limit, with its tolerance when it has one."""
    shown = rule_value(limit, unit)
    if not tolerance:
        return shown
    if isinstance(shown, Display):
        return Display(f"{shown.si} + {tolerance:g} tolerance", shown.us)
    return f"{shown} + {tolerance:g} tolerance"


def rule_margin(margin: float | None, unit: str) -> Display | str:
    """limit (+ tolerance) minus value; positive passes."""
    if margin is None:
        return DASH
    if unit == "m":
        return Display(margin_text(margin * 1000, 1, "mm"),
                       "0 in" if margin == 0 else margin_text(margin / INCH, 3, "in"))
    if unit == "m/s" and abs(margin) < 0.005:  # at the limit, or within the 0.01 m/s shown
        return Display(margin_text(margin, 2, "m/s"), None)
    if unit in _RULE_QUANTITIES:
        s = show(abs(margin), *_RULE_QUANTITIES[unit])
        sign = MINUS if margin < 0 else "+"
        return Display(sign + s.si, (sign + s.us) if s.us else None)
    return Display(margin_text(margin, 2 if unit == "in - oz" else 4), None)


# ---------------------------------------------------------------- text


def created(text: str) -> str:
    """An ISO 8601 timestamp as "2026-11-22 10:00:00 UTC"."""
    try:
        stamp = datetime.fromisoformat(text.replace("Z", "+00:00"))
    except ValueError:
        return text
    off = stamp.utcoffset()
    zone = "" if off is None else "UTC" if not off else stamp.strftime("%z")
    return f"{stamp:%Y-%m-%d %H:%M:%S} {zone}".strip()


def paragraphs(text: str | None) -> list[str]:
    """Blank-line separated paragraphs of a note, each on one line."""
    blocks = [" ".join(b.split()) for b in (text or "").replace("\r\n", "\n").split("\n\n")]
    return [b for b in blocks if b]


def one_line(text: str | None) -> str:
    return " ".join((text or "").split())


def slugify(text: str, fallback: str = "report") -> str:
    """``"Ash 34 in (R161)"`` -> ``"ash-34-in-r161"``: ASCII, lower case, safe in file names."""
    ascii_text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode("ascii")
    slug = re.sub(r"[^a-z0-9]+", "-", ascii_text.lower()).strip("-")
    return slug or fallback


def identification(values: dict[str, str]) -> str:
    """A bat's identification on one line ("maker Example, model EB-34, serial 123"), or ""."""
    return ", ".join(f"{k} {v}" for k, v in values.items() if v)
