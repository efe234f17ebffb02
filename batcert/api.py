"""batcert as a library: load bats and protocols, run them, compare, evaluate a league, sweep,
design and reduce lab measurements, from Python. The command line is a layer over these calls
(docs/api.md; every example there runs as a doctest).

Every function takes a shipped name (``"ash-34"``, ``"ncaa-bbcor"``) or a path where an input is
meant, or an object :func:`load_bat` / :func:`load_protocol` returned, and gives a typed result
(``RunResult``, ``ComparisonResult``, ...) whose ``to_dict()`` is the document of
docs/results-json.md. Bad input raises :class:`batcert.errors.InputError` (every problem, with
its file and line), an unknown name :class:`batcert.specs.resolve.NotFound`, an impossible
request :class:`batcert.errors.UsageProblem`.

Results that are costly to rebuild (barrel shells, beam modes, ball fits) are kept in batcert's
cache directory as the command line keeps them (:func:`use_cache`; on by default).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from batcert.commands.inputs import LoadedBat, ProtocolInputs
    from batcert.results.compare import ComparisonResult
    from batcert.results.field import FieldResult
    from batcert.results.lab import LabResult
    from batcert.results.league import LeagueResult
    from batcert.results.run import RunResult
    from batcert.results.sweep import SweepResult

__all__ = ["compare", "design", "field", "league", "load_bat", "load_protocol", "reduce", "run", "sweep",
           "use_cache"]

_chosen = [False]  # whether use_cache was called (else the first call turns the cache on)


def use_cache(on: bool = True) -> None:
    """Keep (``on``) or stop keeping costly intermediate results in batcert's cache directory
    (``$BATCERT_CACHE_DIR``, else ``~/.cache/batcert``; :mod:`batcert.cache`) as well as in
    the process (the active :class:`batcert.workspace.Workspace`). Deleting the directory is
    always safe."""
    from batcert import workspace
    _chosen[0] = True
    if not on:
        workspace.current().attach(None)
        return
    from batcert.cache import disk_stores
    workspace.current().attach(disk_stores())


def _ready() -> None:
    if not _chosen[0]:
        use_cache()


def load_bat(bat: str | Path) -> LoadedBat:
    """A bat file (a path or a shipped name), validated, built and reconciled to its measured
    mass, CG and MOI. ``.built.spec`` is the file's content; ``.built`` the model."""
    from batcert.commands.inputs import load_bat_any
    _ready()
    return load_bat_any(str(bat))


def load_protocol(protocol: str | Path) -> ProtocolInputs:
    """A protocol (a path or a shipped id) with its ball, validated."""
    from batcert.commands.inputs import load_protocol_any
    return load_protocol_any(str(protocol))


def _bat(bat: str | Path | LoadedBat) -> LoadedBat:
    return load_bat(bat) if isinstance(bat, (str, Path)) else bat


def _protocol(protocol: str | Path | ProtocolInputs) -> ProtocolInputs:
    return load_protocol(protocol) if isinstance(protocol, (str, Path)) else protocol


def run(bat: str | Path | LoadedBat, protocol: str | Path | ProtocolInputs,
        engine: str = "flexible") -> RunResult:
    """The model's prediction for ``bat`` under ``protocol``: the metric at the impact point the
    protocol's rule locates, its verdict against the limit, every condition's details."""
    from batcert.commands.run import run as run_protocols
    _ready()
    [result] = run_protocols(_bat(bat), [_protocol(protocol)], engine)
    return result


def compare(bats: Sequence[str | Path], protocols: Sequence[str | Path] = (),
            study: str | None = None, reference: str | None = None,
            engine: str = "flexible", figures: bool = False) -> ComparisonResult:
    """Two or more bats under the same protocols (or a study's), with the relative performance
    of each against the reference (Smith 2001 Eq. 6) and, for a study, its claims checked;
    ``figures``: also the study's figures (sweeps of every bat, a few seconds; without them
    the claims that read a figure are not tested, and say so)."""
    from batcert.commands.compare import run_comparison
    _ready()
    return run_comparison([str(b) for b in bats], [str(p) for p in protocols], study,
                          reference, engine, figures=figures)


def league(league_id: str | Path, bats: Sequence[str | Path],
           engine: str = "flexible") -> LeagueResult:
    """Every rule of a league (shipped id or file) on every bat."""
    from batcert.commands.league import run_league
    _ready()
    return run_league(str(league_id), [str(b) for b in bats], engine)


def field(bats: str | Path | Sequence[str | Path], batters: str | Sequence[str] = "college",
          reference: str | Path = "ash-34", engine: str = "flexible", *,
          pitch_speed: float | None = None, launch_angle: float = 28.0,
          backspin: float | None = None, sidespin: float | None = None,
          temperature: float = 294.261, elevation: float = 0.0) -> FieldResult:
    """What ``bats`` do in play for each batter profile (shipped: ``youth-12u``,
    ``high-school``, ``college``, ``pro``, ``fastpitch``, ``slowpitch``; a batter YAML path;
    ``"all"``): each bat swung at the speed its MOI allows, its best batted-ball speed, sweet
    zone, e_A and carry, and the gains over ``reference``, also under a constant swing speed.
    ``pitch_speed`` [m/s] replaces the profiles' own; ``launch_angle`` [deg]; spins [rpm]
    (default: Nathan's calculator's for the angle); ``temperature`` [K]; ``elevation`` [m]."""
    import math

    from batcert.commands.field import FieldSettings, run_field
    from batcert.physics.trajectory import RPM
    _ready()
    settings = FieldSettings(math.radians(launch_angle),
                             None if backspin is None else backspin * RPM,
                             None if sidespin is None else sidespin * RPM, temperature,
                             elevation, pitch_speed=pitch_speed)
    bat_list = [bats] if isinstance(bats, (str, Path)) else list(bats)
    batter_list = [batters] if isinstance(batters, str) else list(batters)
    return run_field([str(b) for b in bat_list], batter_list, str(reference), engine, settings)


def sweep(bat: str | Path, protocol: str | Path, vary: Sequence[str],
          engine: str = "flexible", workers: int = 1) -> SweepResult:
    """The protocol's result over one or two varied parameters, each ``"PARAM=START:STOP:N"``
    as on the command line (``"wall=80%:120%:5"``, ``"pitch_speed=50m/s:70m/s:3"``)."""
    from batcert.commands.sweep import plan_sweep, run_sweep
    _ready()
    return run_sweep(plan_sweep(str(bat), str(protocol), list(vary), engine=engine),
                     workers=workers)


def design(bat: str | Path, protocol: str | Path, parameter: str,
           range_text: str | None = None, engine: str = "flexible",
           points: int | None = None) -> SweepResult:
    """Every value of ``parameter`` in ``range_text`` (``"40m/s:75m/s"``) where the protocol's
    metric meets its limit: ``.design.roots``."""
    from batcert.commands.sweep import DEFAULT_POINTS, run_design
    _ready()
    return run_design(str(bat), str(protocol), parameter, range_text, engine,
                      DEFAULT_POINTS if points is None else points)


def reduce(session: str | Path, protocol: str | Path, decision_rule: str = "simple",
           engine: str = "flexible", bat: str | Path | None = None) -> LabResult:
    """A lab session's measured hits reduced to a certified value with its uncertainty and a
    verdict under ``decision_rule`` (docs/lab-reduction.md), beside the model's prediction."""
    from batcert.commands.reduce import run_reduce
    _ready()
    return run_reduce(str(session), str(protocol), decision_rule, engine,
                      None if bat is None else str(bat))
