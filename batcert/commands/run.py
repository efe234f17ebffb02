"""``batcert run``: one bat under one or more protocols."""

from __future__ import annotations

from batcert.commands.inputs import LoadedBat, ProtocolInputs
from batcert.engines import get_engine
from batcert.results.run import RunResult
from batcert.runner.runner import run_protocols


def run(bat: LoadedBat, protocols: list[ProtocolInputs], engine: str = "flexible",
        on_step=None, **engine_options) -> list[RunResult]:
    """Run ``bat`` under every protocol with one engine (``on_step``: see
    :func:`~batcert.runner.runner.drive`)."""
    eng = get_engine(engine, **engine_options)
    return run_protocols([(bat.built, p.protocol, p.ball) for p in protocols], eng,
                         on_step=on_step)
