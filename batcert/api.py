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
    as well as in the process.

    Parameters
    ----------
    on : bool
        Keep them in ``$BATCERT_CACHE_DIR``, else ``~/.cache/batcert`` (:mod:`batcert.cache`),
        besides the active :class:`batcert.workspace.Workspace`. Deleting the directory is
        always safe.
    """
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
    """A bat file, validated, built and reconciled to its measured mass, CG and MOI.

    Parameters
    ----------
    bat : str or Path
        A shipped name (``"ash-34"``) or the path of a bat YAML (docs/inputs.md).

    Returns
    -------
    LoadedBat
        ``.built.spec`` is the file's content in SI units; ``.built.model`` the beam model
        (lengths [m], masses [kg], MOI [kg m^2]). Any function here takes it where a bat goes.

    Raises
    ------
    batcert.InputError
        Every problem of the file, with its line; ``batcert.NotFound`` for an unknown name.

    References
    ----------
    docs/reconciliation.md (the reconciliation to measured mass properties).
    """
    _ready()
    return _bat(bat)


def load_protocol(protocol: str | Path) -> ProtocolInputs:
    """A protocol with its ball, validated.

    Parameters
    ----------
    protocol : str or Path
        A shipped id (``"ncaa-bbcor"``, ``"proposed"``) or the path of a protocol YAML.

    Returns
    -------
    ProtocolInputs
        ``.protocol`` (conditions with speeds [m/s] and [rad/s], pivot [m], impact rule,
        metric, limit) and ``.ball`` (its ball, the lot calibrated where the ball file says).

    References
    ----------
    L. V. Smith, "Evaluating baseball bat performance", Sports Engineering 4 (2001) 205-214
    (the set-ups and metrics); docs/inputs.md (the fields).
    """
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
    of each against the reference and, for a study, its claims checked.

    Parameters
    ----------
    bats : sequence of str, Path or LoadedBat
        At least two bats.
    protocols : sequence of str or Path
        The protocols to run each bat under (or give ``study``).
    study : str, optional
        A study file or shipped id (``"smith2001"``): its protocols, bats and claims.
    reference : str, Path or LoadedBat, optional
        The bat every other is compared with (default: the first, or the study's).
    engine : {"flexible", "rigid"}
    figures : bool
        Also the study's figures (sweeps of every bat, a few seconds; without them the claims
        that read a figure are not tested, and say so).

    Returns
    -------
    ComparisonResult
        Per protocol and condition each bat's metric and its relative performance
        ``P = (P_a - P_w) / P_w`` [-] against the reference; the claims' verdicts.

    References
    ----------
    Smith (2001), Eq. 6 (relative performance); docs/validation.md, section 4 (the replay).
    """
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
    """Every rule of a league on every bat.

    Parameters
    ----------
    league_id : str or Path
        A shipped league (``"ncaa"``, ``"usssa"``, ...) or a league YAML.
    bats : sequence of str, Path or LoadedBat
    engine : {"flexible", "rigid"}
        For the rules that run a protocol (a model prediction, labelled so).

    Returns
    -------
    LeagueResult
        Each bat's verdict and every rule's: measured value (lengths [m], drop in inches minus
        ounces), limit, pass, fail, not applicable or not modelled, with the metric's known
        offset where a protocol decides.

    References
    ----------
    The league file's own ``reference`` (its rule book); docs/validation.md (the offsets).
    """
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
    """What ``bats`` do in play for each batter profile: each bat swung at the speed its MOI
    allows, its best batted-ball speed, sweet zone, e_A and carry, and the gains over
    ``reference``, also under a constant swing speed.

    Parameters
    ----------
    bats : str, Path, LoadedBat or a sequence of them
    batters : str or sequence of str
        Shipped profiles (``youth-12u``, ``high-school``, ``college``, ``pro``,
        ``fastpitch``, ``slowpitch``), batter YAML paths, or ``"all"``.
    reference : str, Path or LoadedBat
        The bat the gains are measured against (default ``ash-34``).
    engine : {"flexible", "rigid"}
    pitch_speed : float or str, optional
        [m/s], or with its unit (``"85 mph"``); replaces the profiles' own.
    launch_angle : float
        [deg] above the horizontal.
    backspin, sidespin : float, optional
        [rpm]; default: Nathan's trajectory calculator's for the launch angle.
    temperature : float or str
        [K], or with its unit (``"70F"``).
    elevation : float or str
        [m], or with its unit (``"5280 ft"``).

    Returns
    -------
    FieldResult
        Per batter and bat: swing speed [m/s], batted-ball speed [m/s], carry [m] and the
        gains over the reference (predictions, labelled so).

    References
    ----------
    A. M. Nathan, "Dynamics of the baseball-bat collision", Am. J. Phys. 68 (2000) 979;
    Nathan's trajectory calculator (the flight); docs/validation.md, section 4b.
    """
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
    """The protocol's result over one or two varied parameters.

    Parameters
    ----------
    bat : str, Path or LoadedBat
    protocol : str or Path
    vary : sequence of str
        One or two ``"PARAM=START:STOP:N"`` as on the command line (``"wall=80%:120%:5"``,
        ``"pitch_speed=50m/s:70m/s:3"``); the parameters are docs/sweeps.md's table.
    engine : {"flexible", "rigid"}
    workers : int
        Processes to share the variants (1: this one).

    Returns
    -------
    SweepResult
        Every variant's value of each parameter [SI], the metric, its verdict and margin, each
        condition's exit speed [m/s], COR, impact location [m] and the mass properties.

    References
    ----------
    docs/sweeps.md.
    """
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
    """Every value of ``parameter`` where the protocol's metric meets its limit.

    Parameters
    ----------
    bat : str, Path or LoadedBat
    protocol : str or Path
        It must set a limit.
    parameter : str
        A sweep parameter's name (docs/sweeps.md), e.g. ``"wall"``.
    range_text : str, optional
        Where to look, ``"A:B"`` with units or as percent of nominal (``"40m/s:75m/s"``,
        ``"50%:150%"``, the default).
    engine : {"flexible", "rigid"}
    points : int, optional
        Points of the margin curve that brackets the roots (default 9).

    Returns
    -------
    SweepResult
        The margin curve, and ``.design.roots``: each value [SI] with its bracket, the mass
        [kg] and the drop there.

    References
    ----------
    R. P. Brent, Algorithms for Minimization without Derivatives (1973), ch. 4 (the root);
    docs/sweeps.md.
    """
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
    verdict, beside the model's prediction.

    Parameters
    ----------
    session : str or Path
        A session YAML (docs/lab-reduction.md), or a bare hits CSV with ``bat``.
    protocol : str or Path
        Its metric (BBCOR, BESR, BPF or e_A), location rule and limit.
    decision_rule : {"simple", "guarded"}
        ``simple``: the limit as written; ``guarded``: the value plus its expanded uncertainty
        must be within it.
    engine : {"flexible", "rigid"}
        Of the model's prediction drawn beside the measurement.
    bat : str, Path or LoadedBat, optional
        For a bare hits CSV only.

    Returns
    -------
    LabResult
        The certified value [-], its combined and expanded (95 %) uncertainties, the
        conformance probability, every hit reduced, the certificate's ISO/IEC 17025 record,
        and the ball lot's calibration (an input) where the session names a reference bat.

    References
    ----------
    ASTM F2219 (the reduction); JCGM 100:2008 and JCGM 101:2008 (the uncertainty); JCGM
    106:2012 (the decision); ISO/IEC 17025:2017, 7.8 (the record).
    """
    from batcert.commands.reduce import DECISION_RULES, run_reduce
    _ready()
    return run_reduce(args.name_or_path("session", session, "session"),
                      args.name_or_path("protocol", protocol, "protocol"),
                      args.choice("decision_rule", decision_rule, list(DECISION_RULES)),
                      _engine(engine), None if bat is None else _one_named(bat, "bat", "bat"))
