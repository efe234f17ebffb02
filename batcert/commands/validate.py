"""``batcert validate``: load (and for bats, build) spec files and the files they name (a
protocol's ball; a league's protocols; a study's protocols, balls and bats); every problem is an
InputError."""

from __future__ import annotations

from batcert.commands.inputs import detect_kind, league_protocols, protocol_ball_path, study_inputs
from batcert.model.build import build_bat
from batcert.specs.ball import load_ball
from batcert.specs.bat import load_bat
from batcert.specs.league import load_league
from batcert.specs.protocol import load_protocol
from batcert.specs.study import load_study

_LOADERS = {
    "protocol": lambda path: load_ball(protocol_ball_path(load_protocol(path))),
    "ball": load_ball,
    "league": lambda path: league_protocols(load_league(path)),
    "study": lambda path: study_inputs(load_study(path)),
    "bat": lambda path: build_bat(load_bat(path)),
}


def validate_file(path: str) -> str:
    """Load (and for bats, build and reconcile) a spec; raise InputError on any problem.
    Returns the file's kind."""
    kind = detect_kind(path)
    _LOADERS[kind](path)
    return kind
