"""``batcert run``: one bat under one or more protocols."""

from __future__ import annotations

from dataclasses import replace

from batcert.commands.inputs import LoadedBat, ProtocolInputs
from batcert.engines import get_engine
from batcert.results.run import RunResult
from batcert.runner.runner import run_protocols


def run(bat: LoadedBat, protocols: list[ProtocolInputs], engine: str = "flexible",
        on_step=None, **engine_options) -> list[RunResult]:
    """Run ``bat`` under every protocol with one engine (``on_step``: see
    :func:`~batcert.runner.bench.drive`)."""
    eng = get_engine(engine, **engine_options)
    return run_protocols([(bat.built, p.protocol, p.ball) for p in protocols], eng,
                         on_step=on_step)


def check_uncertainty(bat: LoadedBat, protocols: list[ProtocolInputs], samples: int,
                      seed: int | None = None) -> None:
    """Before anything runs: the files state an uncertainty and its draws are possible
    (:func:`batcert.uncertainty.propagate.draws`)."""
    from batcert.uncertainty.propagate import DEFAULT_SEED, draws
    draws(bat.built.spec, [p.ball for p in protocols], samples,
          DEFAULT_SEED if seed is None else seed)


def with_uncertainty(bat: LoadedBat, protocols: list[ProtocolInputs], results: list[RunResult],
                     samples: int, seed: int | None = None, engine: str = "flexible",
                     on_progress=None, method: str = "surrogate", bound: float | None = None,
                     **engine_options) -> list[RunResult]:
    """``results`` (of :func:`run`) with the distribution of each result over ``samples``
    Monte Carlo draws of the stated input uncertainties (:mod:`batcert.uncertainty`; ``seed``
    None: its default seed). ``method``: ``"surrogate"`` (a response surface, checked on a
    sample of the draws against the engine, every draw solved when it misses by more than
    ``bound`` [metric unit]; None: each metric's default, 1e-4, or 0.01 m/s for the exit
    speed) or ``"full"`` (every draw solved)."""
    from batcert.uncertainty.propagate import DEFAULT_SEED, Job, monte_carlo
    eng = get_engine(engine, **engine_options)
    jobs = [Job(p.protocol, p.ball, r) for p, r in zip(protocols, results, strict=True)]
    spread = monte_carlo(bat.built, jobs, eng, samples, DEFAULT_SEED if seed is None else seed,
                         on_progress, method, bound)
    return [replace(r, uncertainty=u) for r, u in zip(results, spread, strict=True)]
