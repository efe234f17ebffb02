"""Loading the inputs of a command: bats, protocols with their balls, studies and leagues, by
shipped name or path. Every input is loaded (and every bat built) before anything runs."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from batcert.model.build import BuiltBat, build_bat
from batcert.specs.ball import BallSpec, load_ball
from batcert.specs.bat import load_bat
from batcert.specs.common import sha256_of
from batcert.specs.protocol import ProtocolSpec, load_protocol
from batcert.specs.resolve import NotFound, resolve
from batcert.specs.yamlio import load_yaml

if TYPE_CHECKING:
    from batcert.specs.batter import BatterSpec
    from batcert.specs.league import LeagueSpec
    from batcert.specs.study import StudySpec


@dataclass(frozen=True)
class ProtocolInputs:
    """A loaded protocol with its ball."""

    protocol: ProtocolSpec
    ball: BallSpec


@dataclass(frozen=True)
class LoadedBat:
    path: Path
    built: BuiltBat


def load_bat_any(value: str, relative_to: Path | None = None) -> LoadedBat:
    """A bat from a path or a shipped name (e.g. ``ash-34``), built and reconciled."""
    path = resolve("bat", value, relative_to=relative_to)
    return LoadedBat(path, build_bat(load_bat(path)))


def load_bats(values: list[str], relative_to: Path | None = None) -> list[LoadedBat]:
    return [load_bat_any(v, relative_to) for v in values]


def protocol_ball_path(protocol: ProtocolSpec) -> Path:
    """The protocol's ball file; an unknown ball is invalid input in the protocol file (its
    ``ball:`` line), not a usage error."""
    try:
        return resolve("ball", protocol.ball, relative_to=Path(protocol.path))
    except NotFound as exc:
        raise protocol.problem("ball", str(exc)) from None


def load_ball_lot(path: str | Path) -> BallSpec:
    """A ball file, its lot calibrated on its reference bat where it names one
    (:mod:`batcert.runner.lot`)."""
    from batcert.runner.lot import calibrated_lot
    return calibrated_lot(load_ball(path))


def protocol_inputs(protocol: ProtocolSpec) -> ProtocolInputs:
    """A loaded protocol with its ball."""
    return ProtocolInputs(protocol, load_ball_lot(protocol_ball_path(protocol)))


def load_protocol_any(value: str, relative_to: Path | None = None) -> ProtocolInputs:
    """A protocol from a path or a shipped id (e.g. ``proposed``), with its ball."""
    return protocol_inputs(load_protocol(resolve("protocol", value, relative_to=relative_to)))


def load_study_any(value: str) -> StudySpec:
    from batcert.specs.study import load_study  # not on a run's path
    from batcert.sweeps.study_figures import check_figures

    spec = load_study(resolve("study", value))
    check_figures(spec)
    return spec


def load_league_any(value: str) -> LeagueSpec:
    from batcert.specs.league import load_league  # not on a run's path

    return load_league(resolve("league", value))


def league_protocols(spec: LeagueSpec) -> dict[str, ProtocolInputs]:
    """The protocol (with its ball) of each modelled rule that runs one, by rule id; a name or
    path that does not resolve is invalid input at the rule's ``protocol:`` line."""
    from batcert.specs.league import runs_protocol  # not on a run's path
    out: dict[str, ProtocolInputs] = {}
    for i, rule in enumerate(spec.rules):
        if runs_protocol(rule.kind) and rule.status == "modelled" and rule.protocol:
            try:
                path = resolve("protocol", rule.protocol, relative_to=Path(spec.path))
            except NotFound as exc:
                raise spec.source.problem(f"rules[{i}].protocol", str(exc)) from None
            out[rule.id] = protocol_inputs(load_protocol(path))
    return out


@dataclass(frozen=True)
class BatterInputs:
    """A loaded batter profile with its ball."""

    batter: BatterSpec
    ball: BallSpec


def batter_inputs(path: str | Path) -> BatterInputs:
    """A batter file with its ball; an unknown ball is invalid input at its ``ball:`` line."""
    from batcert.specs.batter import load_batter  # not on a run's path
    spec = load_batter(path)
    try:
        ball = resolve("ball", spec.ball, relative_to=Path(spec.path))
    except NotFound as exc:
        raise spec.source.problem("ball", str(exc)) from None
    return BatterInputs(spec, load_ball_lot(ball))


def load_batter_any(value: str) -> BatterInputs:
    """A batter profile from a path or a shipped name (e.g. ``college``), with its ball."""
    return batter_inputs(resolve("batter", value))


def study_inputs(spec: StudySpec) -> tuple[list[ProtocolInputs], list[LoadedBat]]:
    """A study's protocols with their balls, and its default bats, loaded and built."""
    return [protocol_inputs(p) for p in spec.protocols], load_bats([str(b) for b in spec.bats])


def same_file(a: Path, b: Path) -> bool:
    """The same input: one path, or identical content (a shipped name resolves to the copy
    installed with the package, which is the same bat as the checkout's file)."""
    return a.resolve() == b.resolve() or sha256_of(a) == sha256_of(b)


def detect_kind(path: str) -> str:
    """Guess a spec file's kind from its keys (bat, ball, protocol, league, study, lab
    session), or ``hits`` for a lab's hits CSV (by its name, as ``batcert reduce`` tells it)."""
    from batcert.specs.session import is_hits_csv
    if is_hits_csv(path):
        return "hits"
    data = load_yaml(path)
    if "hits" in data:
        return "session"
    if "swing" in data and "pitch_speed" in data:
        return "batter"
    if "conditions" in data or "metric" in data:
        return "protocol"
    if "rules" in data:
        return "league"
    if "protocols" in data:
        return "study"
    if "construction" in data or "profile" in data:
        return "bat"
    if "cor" in data or "contact" in data:
        return "ball"
    return "bat"
