"""``batcert validate``: load (and for bats, build) spec files and the files they name (a
protocol's ball; a league's protocols; a study's protocols, balls and bats); every problem is an
InputError."""

from __future__ import annotations

from pathlib import Path

from batcert.commands.inputs import detect_kind, league_protocols, protocol_ball_path, study_inputs
from batcert.model.build import build_bat
from batcert.runner.runner import check_applicable
from batcert.specs.ball import load_ball
from batcert.specs.bat import load_bat
from batcert.specs.league import load_league
from batcert.specs.protocol import load_protocol
from batcert.specs.resolve import KINDS, shipped_names
from batcert.specs.study import load_study

_LOADERS = {
    "protocol": lambda path: load_ball(protocol_ball_path(load_protocol(path))),
    "ball": load_ball,
    "league": lambda path: league_protocols(load_league(path)),
    "study": lambda path: _study_fits(load_study(path)),
    "bat": lambda path: build_bat(load_bat(path)),
    "session": lambda path: _session(path),
    "batter": lambda path: _batter(path),
    "hits": lambda path: _hits(path),
}


def _batter(path) -> None:
    """A batter file loads with its ball."""
    from batcert.commands.inputs import batter_inputs
    batter_inputs(path)


def _hits(path) -> None:
    """A bare hits CSV reads as ``batcert reduce HITS.csv --bat BAT`` reads it."""
    from batcert.specs.session import load_bare_hits
    load_bare_hits(path)


def _session(path) -> None:
    """A lab session loads with its bat, ball and hits (every problem of the hits CSV too)."""
    from batcert.lab.session import load_lab_session
    load_lab_session(path)


def _study_fits(spec) -> None:
    """A study's inputs load, its figures name parameters and quantities that exist, and each
    of its protocols fits each of its default bats."""
    from batcert.sweeps.study_figures import check_figures
    check_figures(spec)
    protocols, bats = study_inputs(spec)
    for bat in bats:
        for p in protocols:
            check_applicable(p.protocol, bat.built)


def shipped_path(value: str) -> str:
    """``value`` itself when it is a file (or looks like a path); otherwise the shipped input of
    that name (``ash-34``, ``ncaa-bbcor``, ``smith2001``) when exactly one kind has it."""
    if Path(value).exists() or "/" in value or value.endswith((".yaml", ".yml")):
        return value
    found = {str(names[value]) for kind in KINDS if value in (names := shipped_names(kind))}
    return found.pop() if len(found) == 1 else value


def validate_file(path: str) -> str:
    """Load (and for bats, build and reconcile) a spec; raise InputError on any problem.
    Returns the file's kind."""
    kind = detect_kind(path)
    _LOADERS[kind](path)
    return kind
