"""batcert as a library: load bats and protocols, run them, compare, evaluate a league, sweep,
design and reduce lab measurements, from Python. The command line is a layer over these calls
(docs/api.md; every example there runs as a doctest).

Every function takes a shipped name (``"ash-34"``, ``"ncaa-bbcor"``) or a path where an input is
meant, or an object :func:`load_bat` / :func:`load_protocol` returned, and gives a typed result
(``RunResult``, ``ComparisonResult``, ...) whose ``to_dict()`` is the document of
docs/results-json.md. Quantities may be strings with their units (``pitch_speed="85 mph"``) or
SI floats. Every argument is checked as the command line checks it (:mod:`batcert.arguments`),
and every error is a :class:`batcert.BatcertError`: bad input in a file
:class:`batcert.InputError` (every problem, with its file and line), an unknown name
:class:`batcert.NotFound`, an argument or request that cannot mean anything
:class:`batcert.UsageProblem` (its message starts with the argument's name).

Results that are costly to rebuild (barrel shells, beam modes, ball fits) are kept in batcert's
cache directory as the command line keeps them (:func:`use_cache`; on by default).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from batcert import arguments as args

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
    _ready()
    return _bat(bat)


def load_protocol(protocol: str | Path) -> ProtocolInputs:
    """A protocol (a path or a shipped id) with its ball, validated."""
    return _protocol(protocol)


def _loaded_types():
    from batcert.commands.inputs import LoadedBat, ProtocolInputs
    return LoadedBat, ProtocolInputs


def _bat(bat) -> LoadedBat:
    from batcert.commands.inputs import LoadedBat, load_bat_any
    return _loaded(bat, "bat", "protocol", LoadedBat, load_bat_any)


def _protocol(protocol) -> ProtocolInputs:
    from batcert.commands.inputs import ProtocolInputs, load_protocol_any
    return _loaded(protocol, "protocol", "bat", ProtocolInputs, load_protocol_any)


def _loaded(value, kind: str, other: str, loaded: type, load):
    """A loaded ``kind`` (bat or protocol) from a name, a path or what ``load_<kind>`` returned
    (an instance of ``loaded``); a shipped ``other`` given in its place (arguments swapped) is
    said to be one."""
    from batcert.specs.resolve import NotFound
    read = args.name_or_path(kind, value, kind, loaded)
    if not isinstance(read, str):
        return read
    try:
        return load(read)
    except NotFound:
        _swapped(kind, read, kind, other)
        raise


def _swapped(name: str, value: str, kind: str, other: str) -> None:
    """An :class:`~batcert.arguments.ArgumentError` when ``value``, not a ``kind``, is a
    shipped ``other`` (the arguments given in the wrong order)."""
    from batcert.specs.resolve import shipped_names
    if value in shipped_names(other):
        raise args.ArgumentError(name, f"{value!r} is a shipped {other}, not a {kind}: are the "
                                 "arguments in the wrong order?")


def _named(values, name: str, kind: str, at_least: int = 0) -> list[str]:
    """Names or paths for the commands that take them: a loaded bat stands for its file."""
    loaded = _loaded_types()[0]
    if isinstance(values, loaded):
        values = [values]
    if isinstance(values, Sequence) and not isinstance(values, str):
        values = [str(v.path) if isinstance(v, loaded) else v for v in values]
    return args.names_or_paths(name, values, kind, at_least)


def _one_named(value, name: str, kind: str) -> str:
    loaded = _loaded_types()[0]
    return str(value.path) if isinstance(value, loaded) else args.name_or_path(name, value, kind)


def _engine(engine) -> str:
    from batcert.engines import available_engines
    return args.choice("engine", engine, available_engines())


def run(bat: str | Path | LoadedBat, protocol: str | Path | ProtocolInputs,
        engine: str = "flexible", *, uncertainty: int | None = None, seed: int | None = None,
        uncertainty_method: str | None = None,
        uncertainty_bound: float | None = None) -> RunResult:
    """The model's prediction for ``bat`` under ``protocol``: the metric at the impact point the
    protocol's rule locates, its verdict against the limit, every condition's details.
    ``uncertainty=N``: also the result's distribution over N Monte Carlo draws of the
    uncertainties the bat and ball files state (``.uncertainty``; docs/uncertainty.md), with
    ``seed`` (default 20011), ``uncertainty_method`` (``"surrogate"``, the default: a response
    surface checked against the engine on a sample of the draws; ``"full"``: every draw solved
    by the engine) and ``uncertainty_bound`` (the surface's largest allowed difference on the
    checked draws, in the metric's unit; default 1e-4), as ``run --uncertainty N`` takes
    them."""
    from batcert.commands.run import check_uncertainty, with_uncertainty
    from batcert.commands.run import run as run_protocols
    _ready()
    engine = _engine(engine)
    options = {"seed": seed, "uncertainty_method": uncertainty_method,
               "uncertainty_bound": uncertainty_bound}
    for name, value in options.items():
        if value is not None and uncertainty is None:
            raise args.ArgumentError(name, "needs uncertainty=N (the Monte Carlo's draws)")
    loaded, protocols = _bat(bat), [_protocol(protocol)]
    if uncertainty is None:
        return run_protocols(loaded, protocols, engine)[0]
    samples = args.whole("uncertainty", uncertainty)
    seed = None if seed is None else args.whole("seed", seed)
    method = args.choice("uncertainty_method", "surrogate" if uncertainty_method is None
                         else uncertainty_method, args.UNCERTAINTY_METHODS)
    bound = (None if uncertainty_bound is None
             else args.positive("uncertainty_bound", uncertainty_bound))
    check_uncertainty(loaded, protocols, samples, seed)
    results = run_protocols(loaded, protocols, engine)
    return with_uncertainty(loaded, protocols, results, samples, seed, engine, method=method,
                            bound=bound)[0]


def compare(bats: Sequence[str | Path | LoadedBat], protocols: Sequence[str | Path] = (),
            study: str | None = None, reference: str | Path | LoadedBat | None = None,
            engine: str = "flexible", figures: bool = False) -> ComparisonResult:
    """Two or more bats under the same protocols (or a study's), with the relative performance
    of each against the reference (Smith 2001 Eq. 6) and, for a study, its claims checked;
    ``figures``: also the study's figures (sweeps of every bat, a few seconds; without them
    the claims that read a figure are not tested, and say so)."""
    from batcert.commands.compare import run_comparison
    _ready()
    bat_names = _named(bats, "bats", "bat")
    protocol_names = args.names_or_paths("protocols", protocols, "protocol", 0)
    if study is not None:
        args.name_or_path("study", study, "study")
    ref = None if reference is None else _one_named(reference, "reference", "bat")
    return run_comparison(bat_names, protocol_names, study, ref, _engine(engine),
                          figures=_flag("figures", figures))


def _flag(name: str, value) -> bool:
    if not isinstance(value, bool):
        raise args.ArgumentError(name, f"expected True or False, got {value!r}")
    return value


def league(league_id: str | Path, bats: Sequence[str | Path | LoadedBat],
           engine: str = "flexible") -> LeagueResult:
    """Every rule of a league (shipped id or file) on every bat."""
    from batcert.commands.league import run_league
    _ready()
    return run_league(args.name_or_path("league_id", league_id, "league"),
                      _named(bats, "bats", "bat", 1), _engine(engine))


def field(bats: str | Path | LoadedBat | Sequence[str | Path | LoadedBat],
          batters: str | Sequence[str] = "college",
          reference: str | Path | LoadedBat = "ash-34", engine: str = "flexible", *,
          pitch_speed: float | str | None = None, launch_angle: float = 28.0,
          backspin: float | None = None, sidespin: float | None = None,
          temperature: float | str = 294.261, elevation: float | str = 0.0) -> FieldResult:
    """What ``bats`` do in play for each batter profile (shipped: ``youth-12u``,
    ``high-school``, ``college``, ``pro``, ``fastpitch``, ``slowpitch``; a batter YAML path;
    ``"all"``): each bat swung at the speed its MOI allows, its best batted-ball speed, sweet
    zone, e_A and carry, and the gains over ``reference``, also under a constant swing speed.
    ``pitch_speed`` [m/s, or ``"85 mph"``] replaces the profiles' own; ``launch_angle`` [deg];
    spins [rpm] (default: Nathan's calculator's for the angle); ``temperature`` [K, or
    ``"70F"``]; ``elevation`` [m, or ``"5280 ft"``]."""
    import math

    from batcert.commands.field import FieldSettings, run_field
    from batcert.physics.trajectory import RPM
    _ready()
    back, side = args.spin("backspin", backspin), args.spin("sidespin", sidespin)
    settings = FieldSettings(math.radians(args.launch_angle(launch_angle)),
                             None if back is None else back * RPM,
                             None if side is None else side * RPM,
                             args.temperature(temperature), args.elevation(elevation),
                             pitch_speed=args.pitch_speed(pitch_speed))
    bat_list = _named(bats if isinstance(bats, Sequence) and not isinstance(bats, str)
                      else [bats], "bats", "bat", 1)
    batter_list = args.names_or_paths("batters", [batters] if isinstance(batters, (str, Path))
                                      else batters, "batter", 1)
    return run_field(bat_list, batter_list, _one_named(reference, "reference", "bat"),
                     _engine(engine), settings)


def sweep(bat: str | Path | LoadedBat, protocol: str | Path, vary: Sequence[str],
          engine: str = "flexible", workers: int = 1) -> SweepResult:
    """The protocol's result over one or two varied parameters, each ``"PARAM=START:STOP:N"``
    as on the command line (``"wall=80%:120%:5"``, ``"pitch_speed=50m/s:70m/s:3"``)."""
    from batcert.commands.sweep import plan_sweep, run_sweep
    _ready()
    n = args.workers(workers)
    plan = plan_sweep(_one_named(bat, "bat", "bat"), args.name_or_path("protocol", protocol,
                                                                         "protocol"),
                      _texts("vary", vary), engine=_engine(engine))
    return run_sweep(plan, workers=n)


def _texts(name: str, values) -> list[str]:
    """A list of strings (``vary``); a single string is taken as a list of one."""
    items = [values] if isinstance(values, str) else values
    if not isinstance(items, Sequence) or not all(isinstance(v, str) for v in items):
        raise args.ArgumentError(name, f"expected a list of 'PARAM=START:STOP:N' strings, got "
                                 f"{values!r}"[:300])
    return list(items)


def design(bat: str | Path | LoadedBat, protocol: str | Path, parameter: str,
           range_text: str | None = None, engine: str = "flexible",
           points: int | None = None) -> SweepResult:
    """Every value of ``parameter`` in ``range_text`` (``"40m/s:75m/s"``) where the protocol's
    metric meets its limit: ``.design.roots``."""
    from batcert.commands.sweep import DEFAULT_POINTS, run_design
    _ready()
    if not isinstance(parameter, str):
        raise args.ArgumentError("parameter", f"expected a parameter's name, got {parameter!r}")
    if range_text is not None and not isinstance(range_text, str):
        raise args.ArgumentError("range_text", f"expected 'A:B' with units, got {range_text!r}")
    return run_design(_one_named(bat, "bat", "bat"),
                      args.name_or_path("protocol", protocol, "protocol"), parameter,
                      range_text, _engine(engine),
                      DEFAULT_POINTS if points is None else args.whole("points", points))


def reduce(session: str | Path, protocol: str | Path, decision_rule: str = "simple",
           engine: str = "flexible", bat: str | Path | LoadedBat | None = None) -> LabResult:
    """A lab session's measured hits reduced to a certified value with its uncertainty and a
    verdict under ``decision_rule`` (docs/lab-reduction.md), beside the model's prediction."""
    from batcert.commands.reduce import DECISION_RULES, run_reduce
    _ready()
    return run_reduce(args.name_or_path("session", session, "session"),
                      args.name_or_path("protocol", protocol, "protocol"),
                      args.choice("decision_rule", decision_rule, list(DECISION_RULES)),
                      _engine(engine), None if bat is None else _one_named(bat, "bat", "bat"))
