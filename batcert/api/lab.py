"""The library's lab reduction (docs/lab-reduction.md)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from batcert import arguments as args
from batcert.api.inputs import engine_name, one_named
from batcert.api.setup import ready

if TYPE_CHECKING:
    from batcert.commands.inputs import LoadedBat
    from batcert.results.lab import LabResult


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
    ready()
    return run_reduce(args.name_or_path("session", session, "session"),
                      args.name_or_path("protocol", protocol, "protocol"),
                      args.choice("decision_rule", decision_rule, list(DECISION_RULES)),
                      engine_name(engine), None if bat is None else one_named(bat, "bat", "bat"))
