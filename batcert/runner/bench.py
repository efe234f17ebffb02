"""A bat on the test bench and the lockstep driver of protocol runs: what the engine is asked.

A protocol run is written as *steps* (a generator that yields the requests it needs solved
together and is sent back their results); :func:`drive` advances many runs in lockstep and
solves each step's requests in one engine call. :class:`Bench` is what every request of one run
shares (bat, ball, engine, pivot, support). The runner (:mod:`batcert.runner.runner`), the
location search (:mod:`~batcert.runner.locate`), the barrel range, sampled bats and the lab's
calibration build on these; this module imports none of them.
"""

from __future__ import annotations

from collections.abc import Callable, Generator
from dataclasses import dataclass
from typing import Any

import numpy as np

from batcert.engines.base import Engine, ImpactBatch, ImpactOutcome, Job
from batcert.methods.metrics import ImpactMetrics, impact_metrics
from batcert.model.build import BuiltBat
from batcert.physics.balls import LAWS
from batcert.runner.conditions import Condition
from batcert.specs.ball import BallSpec

__all__ = ["Bench", "Request", "Solved", "Steps", "drive"]


@dataclass(frozen=True)
class Bench:
    """A bat on the test bench: what every engine batch of one protocol run shares."""

    built: BuiltBat
    ball: BallSpec
    engine: Engine
    pivot: float  # [m from knob]
    support: str  # pinned | free
    modes: Any = None  # the bat's modes when given (a sampled bat's Ritz modes), else computed

    def request(self, conds: list[Condition], locations: np.ndarray) -> Request:
        """Every condition at its row of ``locations`` (shape (n_cond, n_loc)), as one batch."""
        r = np.asarray(locations, float)
        vp, w1 = zip(*(c.speeds(row) for c, row in zip(conds, r, strict=True)), strict=True)
        return Request(self, r.shape, ImpactBatch(r.ravel(), np.stack(vp).ravel(),
                                                  np.stack(w1).ravel()))

    def solve(self, conds: list[Condition], locations: np.ndarray
              ) -> tuple[ImpactMetrics, dict[str, np.ndarray]]:
        """Solve one request now: the metrics and the engine's diagnostics, shaped like
        ``locations``."""
        req = self.request(conds, locations)
        return req.finish(self.engine.solve_many([req.job()])[0])


@dataclass(frozen=True)
class Request:
    """One batch a protocol run needs solved; :func:`drive` solves the requests of many runs
    together."""

    bench: Bench
    shape: tuple[int, ...]
    batch: ImpactBatch

    def job(self) -> Job:
        b = self.bench
        return Job(b.built.model, b.ball.model, b.pivot, self.batch, b.support, b.modes)

    def finish(self, out: ImpactOutcome, ball_cor: np.ndarray | None = None
               ) -> tuple[ImpactMetrics, dict[str, np.ndarray]]:
        """The metrics of the solved batch; ``ball_cor``: the ball's rigid-wall COR at each
        impact's relative speed when already known (:func:`_ball_cors`)."""
        batch, ball = self.batch, self.bench.ball.model
        cor_at = ball.cor if ball_cor is None else (lambda _: ball_cor)
        m = impact_metrics(batch.impact_location, batch.pitch_speed, batch.bat_angular_speed,
                           out.exit_speed, out.bat_angular_speed_after, out.cor, cor_at,
                           out.recoil_factor)
        diag = {k: np.asarray(v).reshape(self.shape) for k, v in out.diagnostics.items()}
        return m.reshape(self.shape), diag


# A protocol run as steps: a generator that yields the requests it needs solved together and
# is sent back their results, in order, until it returns its value.
Solved = tuple[ImpactMetrics, dict[str, np.ndarray]]
Steps = Generator[list[Request], list[Solved], Any]


def drive(runs: list[Steps], engine: Engine,
          on_step: Callable[[int, int, int], None] | None = None) -> list[Any]:
    """Advance every run in lockstep, solving all the requests of one step in a single engine
    call (:meth:`Engine.solve_many`): a comparison's bats and protocols share their sweeps,
    refinements and final impacts. Returns each run's value, in order. ``on_step(step,
    runs_active, impacts)`` is told of each step before it is solved (progress displays)."""
    values: list[Any] = [None] * len(runs)
    pending: dict[int, list[Request]] = {}
    for i, run in enumerate(runs):
        try:
            pending[i] = next(run)
        except StopIteration as stop:
            values[i] = stop.value
    step = 0
    while pending:
        order = [(i, req) for i, reqs in pending.items() for req in reqs]
        step += 1
        if on_step is not None:
            on_step(step, len(pending), sum(req.batch.impact_location.size for _, req in order))
        outcomes = engine.solve_many([req.job() for _, req in order])
        answers: dict[int, list[Solved]] = {i: [] for i in pending}
        cors = _ball_cors([req for _, req in order])
        for (i, req), out, cor in zip(order, outcomes, cors, strict=True):
            answers[i].append(req.finish(out, cor))
        for i in list(pending):
            try:
                pending[i] = runs[i].send(answers[i])
            except StopIteration as stop:
                values[i] = stop.value
                del pending[i]
    return values


def _ball_cors(requests: list[Request]) -> list[np.ndarray | None]:
    """The balls' rigid-wall COR at each request's relative speeds, where a step has many
    balls whose COR is integrated (the drawn balls of a Monte Carlo, each a law of its own):
    one batched integration (:func:`~batcert.physics.balls.impact1d.wall_cors`) instead of a
    table per ball; None where a ball's own ``cor`` serves (few balls: its cached table; a
    closed form)."""
    from batcert.physics.balls.impact1d import MANY_BALLS, wall_cors

    out: list[np.ndarray | None] = [None] * len(requests)
    integrated = [k for k, req in enumerate(requests)
                  if not LAWS[req.bench.ball.model.law.name].closed_form_cor]
    distinct: dict[tuple, int] = {}
    for k in integrated:
        ball = requests[k].bench.ball.model
        distinct.setdefault((ball.law, float(ball.mass)), len(distinct))
    if len(distinct) <= MANY_BALLS:
        return out
    for law_class in {type(law) for law, _ in distinct}:
        members = [k for k in integrated
                   if type(requests[k].bench.ball.model.law) is law_class]
        balls = [key for key in distinct if type(key[0]) is law_class]
        index = {key: j for j, key in enumerate(balls)}
        speeds = [np.abs(requests[k].batch.relative_speed) for k in members]
        which = np.concatenate([np.full(v.size, index[(requests[k].bench.ball.model.law,
                                                        float(requests[k].bench.ball.model.mass))])
                                for k, v in zip(members, speeds, strict=True)])
        unique, inverse = np.unique(np.stack([which, np.concatenate(speeds)], axis=1), axis=0,
                                    return_inverse=True)
        cor = wall_cors(balls, unique[:, 0].astype(int), unique[:, 1])[np.asarray(inverse).ravel()]
        start = 0
        for k, v in zip(members, speeds, strict=True):
            out[k] = cor[start:start + v.size]
            start += v.size
    return out
