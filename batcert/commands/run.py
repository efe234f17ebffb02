"""``batcert run``: one bat under one or more protocols."""

from __future__ import annotations

from batcert.commands.inputs import LoadedBat, ProtocolInputs
from batcert.engines import get_engine
from batcert.results.run import RunResult
from batcert.runner.runner import run_protocol


def run(bat: LoadedBat, protocols: list[ProtocolInputs], engine: str = "flexible",
        **engine_options) -> list[RunResult]:
    """Run ``bat`` under every protocol with one engine."""
    eng = get_engine(engine, **engine_options)
    return [run_protocol(bat.built, p.protocol, p.ball, eng) for p in protocols]
