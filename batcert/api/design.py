"""The library's sweeps and inverse design (docs/sweeps.md)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from batcert import arguments as args
from batcert.api.inputs import engine_name, one_named, texts
from batcert.api.setup import ready

if TYPE_CHECKING:
    from batcert.commands.inputs import LoadedBat
    from batcert.results.sweep import SweepResult


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
    ready()
    n = args.workers(workers)
    plan = plan_sweep(one_named(bat, "bat", "bat"), args.name_or_path("protocol", protocol,
                                                                         "protocol"),
                      texts("vary", vary), engine=engine_name(engine))
    return run_sweep(plan, workers=n)



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
    ready()
    if not isinstance(parameter, str):
        raise args.ArgumentError("parameter", f"expected a parameter's name, got {parameter!r}")
    if range_text is not None and not isinstance(range_text, str):
        raise args.ArgumentError("range_text", f"expected 'A:B' with units, got {range_text!r}")
    return run_design(one_named(bat, "bat", "bat"),
                      args.name_or_path("protocol", protocol, "protocol"), parameter,
                      range_text, engine_name(engine),
                      DEFAULT_POINTS if points is None else args.whole("points", points))
