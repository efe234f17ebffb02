"""Find shipped protocols, balls, leagues, batters and example bats by name, from a checkout or a wheel.

In a wheel the shipped YAML lives in ``batcert/shipped/`` (copied there at build time, see
pyproject.toml); in a source checkout it is read from the top-level ``protocols/`` and ``bats/``.
A value that names an existing file (or ends in .yaml/.yml) is taken as a path.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from pathlib import Path

from batcert.errors import BatcertError

_PACKAGE = Path(__file__).resolve().parents[1]
_CHECKOUT = _PACKAGE.parent

KINDS = {
    "protocol": ("protocols",),
    "ball": ("protocols/balls",),
    "league": ("protocols/leagues",),
    "bat": ("bats",),
    "study": ("protocols/studies",),
    "batter": ("protocols/batters",),
}


def shipped_dirs(kind: str) -> list[Path]:
    out = []
    for sub in KINDS[kind]:
        for root in (_PACKAGE / "shipped", _CHECKOUT):
            d = root / sub
            if d.is_dir() and d not in out:
                out.append(d)
    return out


def shipped_names(kind: str) -> dict[str, Path]:
    """Shipped files of ``kind`` by name. The studies' folder also holds the protocols a study
    uses; only the studies (a top-level ``protocols:`` list) count as studies."""
    names: dict[str, Path] = {}
    for d in shipped_dirs(kind):
        for p in sorted(d.glob("*.yaml")):
            if kind == "study" and not _top_level_key(p, "protocols"):
                continue
            names.setdefault(p.stem, p)
    return names


def _top_level_key(path: Path, key: str) -> bool:
    try:
        text = path.read_text(encoding="utf-8")
    except OSError:
        return False
    return any(line.startswith(f"{key}:") for line in text.splitlines())


class NotFound(BatcertError, LookupError):
    """No shipped input of that name and no such file (with the shipped names)."""


# where resolve() says which of two differing copies of a shipped file it used (the command
# line sets it to print a note; None: silent)
_notify: Callable[[str], None] | None = None


def set_notifier(notify: Callable[[str], None] | None) -> None:
    """Have :func:`resolve` tell ``notify`` when a shipped name finds a differing copy in the
    source checkout the command runs in, and which one it used."""
    global _notify
    _notify = notify


def _checkout_of_cwd() -> Path | None:
    """The batcert source checkout the working directory is in (a folder above it, or itself,
    whose pyproject.toml names the project batcert), or None."""
    try:
        here = Path.cwd().resolve()
    except OSError:
        return None
    for d in (here, *here.parents):
        try:
            text = (d / "pyproject.toml").read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            continue
        return d if 'name = "batcert"' in text else None
    return None


def _prefer_checkout(kind: str, value: str, found: Path) -> Path:
    """A shipped name found in the installed package: the working directory's checkout's copy
    instead when it differs (an edit in progress), said through the notifier."""
    checkout = _checkout_of_cwd()
    if checkout is None or checkout.resolve() == _CHECKOUT.resolve():
        return found
    for sub in KINDS[kind]:
        mine = checkout / sub / found.name
        try:
            if mine.is_file() and mine.read_bytes() != found.read_bytes():
                if _notify is not None:
                    _notify(f"{kind} {value}: using this checkout's {sub}/{found.name}, which "
                            f"differs from the installed batcert's copy ({found})")
                return mine
        except OSError:
            return found
    return found


def resolve(kind: str, value: str, relative_to: Path | None = None) -> Path:
    """Path of a shipped name or a user path; raise :class:`NotFound` with the choices. A
    shipped name run inside a batcert source checkout whose copy of the file differs from the
    installed one resolves to the checkout's copy (and says so, :func:`set_notifier`)."""
    candidate = Path(value)
    if relative_to is not None and not candidate.is_absolute():
        rel = relative_to.parent / candidate
        if _names_a_file(rel):
            return rel
    if _names_a_file(candidate):
        return candidate
    names = shipped_names(kind)
    if value in names:
        return _prefer_checkout(kind, value, names[value])
    folded = {n.casefold(): n for n in names}  # shipped names compare case-insensitively
    if value.casefold() in folded:
        return _prefer_checkout(kind, value, names[folded[value.casefold()]])
    if candidate.suffix in (".yaml", ".yml") or "/" in value:
        raise NotFound(f"{kind} file not found: {value}")
    close = suggest(value, list(names))
    hint = f"; did you mean '{close}'?" if close else ""
    raise NotFound(f"unknown {kind} {value!r} (shipped: {', '.join(names) or 'none'}){hint}")


def _names_a_file(path: Path) -> bool:
    """A regular file, or something else that is there and is not a folder (a FIFO, a
    device), which the loader then refuses by name rather than as "not found"."""
    return path.is_file() or (path.exists() and not path.is_dir())


def suggest(value: str, names: list[str]) -> str | None:
    """The shipped name a mistyped ``value`` most likely meant: one that starts with what was
    typed before its first dash or digit ("alu-34" -> "aluminium-34"), else the closest by
    spelling; None when nothing is close."""
    import difflib
    import re
    typed = value.casefold()
    stem = re.split(r"[-_\d]", typed, maxsplit=1)[0]
    if stem:
        starts = [n for n in names if n.casefold().startswith(stem)]
        if starts:
            return max(starts, key=lambda n: difflib.SequenceMatcher(
                None, typed, n.casefold()).ratio())
    close = difflib.get_close_matches(typed, [n.casefold() for n in names], n=1, cutoff=0.5)
    return next((n for n in names if n.casefold() == close[0]), None) if close else None


def display_path(path: str | Path) -> str:
    """How reports name an input file: ``shipped:protocols/proposed.yaml`` for a file that
    ships with batcert (wherever it is installed); a user's file by the path as given, an
    absolute one inside the working directory relative to it (``bats/my-bat.yaml``)."""
    p = Path(path).resolve()
    sub = _shipped_dirs().get(p.parent)
    if sub is not None:
        return f"shipped:{sub}/{p.name}"
    if Path(path).is_absolute():
        try:
            return str(Path(path).relative_to(Path.cwd()))
        except (ValueError, OSError):
            pass
    return str(path)


def resolve_display(shown: str) -> Path:
    """The file behind a :func:`display_path` name: ``shipped:SUB/NAME`` in the first shipped
    folder ``SUB`` that holds it, else the path itself."""
    if not shown.startswith("shipped:"):
        return Path(shown)
    sub, _, name = shown[len("shipped:"):].rpartition("/")
    for base, folder in _shipped_dirs().items():
        if folder == sub and (base / name).is_file():
            return base / name
    return Path(shown)


@functools.lru_cache(maxsize=1)
def _shipped_dirs() -> dict[Path, str]:
    """The resolved folders that shipped files live in, each with its name in
    :func:`display_path` (an installed package's first, then a checkout's)."""
    dirs: dict[Path, str] = {}
    for root in (_PACKAGE / "shipped", _CHECKOUT):
        for subs in KINDS.values():
            for sub in subs:
                base = (root / sub).resolve()
                if base.is_dir():
                    dirs.setdefault(base, sub)
    return dirs
