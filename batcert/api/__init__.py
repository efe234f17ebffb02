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
from batcert.api.design import design, sweep
from batcert.api.inputs import (
    engine_name,
    flag,
    loaded_bat,
    loaded_protocol,
    named,
    one_named,
    uncertainty_options,
)
from batcert.api.lab import reduce
from batcert.api.setup import ready, use_cache

if TYPE_CHECKING:
    from batcert.commands.inputs import LoadedBat, ProtocolInputs
    from batcert.results.compare import ComparisonResult
    from batcert.results.field import FieldResult
    from batcert.results.league import LeagueResult
    from batcert.results.run import RunResult

__all__ = ["compare", "design", "field", "league", "load_bat", "load_protocol", "reduce", "run", "sweep",
           "use_cache"]

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
    ready()
    return loaded_bat(bat)


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
    return loaded_protocol(protocol)










def run(bat: str | Path | LoadedBat, protocol: str | Path | ProtocolInputs,
        engine: str = "flexible", *, uncertainty: int | None = None, seed: int | None = None,
        uncertainty_method: str | None = None,
        uncertainty_bound: float | None = None) -> RunResult:
    """The model's prediction for ``bat`` under ``protocol``: the metric at the impact point the
    protocol's rule locates, its verdict against the limit, every condition's details.

    Parameters
    ----------
    bat : str, Path or LoadedBat
        A shipped name, a bat file, or what :func:`load_bat` returned.
    protocol : str, Path or ProtocolInputs
        A shipped id, a protocol file, or what :func:`load_protocol` returned.
    engine : {"flexible", "rigid"}
        The flexible beam-and-shell engine (default) or the rigid closed forms.
    uncertainty : int, optional
        Also the result's distribution over this many Monte Carlo draws of the uncertainties
        the bat and ball files state (``.uncertainty``; docs/uncertainty.md).
    seed : int, optional
        The draws' seed (default 20011).
    uncertainty_method : {"surrogate", "full"}, optional
        ``"surrogate"`` (default): a response surface serves the draws, checked against the
        engine on a sample of them; ``"full"``: every draw solved by the engine.
    uncertainty_bound : float, optional
        The surface's largest allowed difference on the checked draws, in the metric's unit
        (default: 1e-4, or 0.01 m/s for exit speed); beyond it every draw is solved by
        the engine.

    Returns
    -------
    RunResult
        ``.value`` (the metric: exit speed [m/s] or dimensionless), ``.verdict``, ``.margin``,
        ``.conditions`` (each set-up's speeds [m/s], [rad/s], impact location [m from the
        pivot], exit speed, COR, BPF, BESR, BBCOR, e_A), ``.mass_properties``; a MODEL
        PREDICTION, with the metric's known offset (``.model_offset``).

    References
    ----------
    Smith (2001), Eqs. 1-7; JCGM 101:2008 (the Monte Carlo); docs/validation.md.
    """
    from batcert.commands.run import check_uncertainty, with_uncertainty
    from batcert.commands.run import run as run_protocols
    ready()
    engine = engine_name(engine)
    options = uncertainty_options(uncertainty, seed, uncertainty_method, uncertainty_bound)
    loaded, protocols = loaded_bat(bat), [loaded_protocol(protocol)]
    if options is None:
        return run_protocols(loaded, protocols, engine)[0]
    samples, seed, method, bound = options
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
    ready()
    bat_names = named(bats, "bats", "bat")
    protocol_names = args.names_or_paths("protocols", protocols, "protocol", 0)
    if study is not None:
        args.name_or_path("study", study, "study")
    ref = None if reference is None else one_named(reference, "reference", "bat")
    return run_comparison(bat_names, protocol_names, study, ref, engine_name(engine),
                          figures=flag("figures", figures))



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
    ready()
    return run_league(args.name_or_path("league_id", league_id, "league"),
                      named(bats, "bats", "bat", 1), engine_name(engine))


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
    ready()
    back, side = args.spin("backspin", backspin), args.spin("sidespin", sidespin)
    settings = FieldSettings(math.radians(args.launch_angle(launch_angle)),
                             None if back is None else back * RPM,
                             None if side is None else side * RPM,
                             args.temperature(temperature), args.elevation(elevation),
                             pitch_speed=args.pitch_speed(pitch_speed))
    bat_list = named(bats if isinstance(bats, Sequence) and not isinstance(bats, str)
                      else [bats], "bats", "bat", 1)
    batter_list = args.names_or_paths("batters", [batters] if isinstance(batters, (str, Path))
                                      else batters, "batter", 1)
    return run_field(bat_list, batter_list, one_named(reference, "reference", "bat"),
                     engine_name(engine), settings)


