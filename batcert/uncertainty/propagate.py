"""Monte Carlo propagation of stated input uncertainties through the engine (JCGM 101).

Each draw (:func:`batcert.uncertainty.inputs.draw`) is a bat and a ball file with the drawn
values, built like any bat (:func:`batcert.model.build.build_bat`: reconciliation to the drawn
mass properties, calibration to a drawn frequency) and run under the protocol. Two things keep
a thousand draws within seconds, each checked against the full computation in the tests:

- The bending modes of a drawn bat are found by Rayleigh-Ritz on the nominal bat's modes
  (:mod:`batcert.physics.ritz`; :data:`BASIS_MODES` of them) instead of a new
  eigenproblem. A draw that changes the beam's stiffness (the wall, a drawn first bending
  frequency) solves its own static flexibility for the residual compliance.
- Each draw is solved on a five-point stencil around each nominal impact point; its impact
  point and result follow from the parabolas through them (:mod:`batcert.runner.sampled`)
  instead of a search of the whole window.

Every run checks both against the full computation: :data:`CHECKED` draws (the farthest from
the mean and the first) are run again as ``run`` runs a bat (new modes, the whole search), and
the largest difference is reported (``full_run_difference``). It includes the full search's own
scatter: the model's flat exit-speed maximum is located only to about 0.5 mm, which moves BPF
at the sweet spot of a hollow bat by up to about 1e-3 (docs/validation.md, section 5).

A hollow bat's barrel is computed once and scaled for a drawn mass or hoop frequency (exact);
a drawn wall is a new barrel, which costs about a quarter of a second per draw. The draws are
solved in chunks of :data:`CHUNK`, all protocols and draws of a chunk in the same engine
batches (:func:`batcert.runner.bench.drive`), and their set-up is shared: the chunk's Ritz
eigenproblems are solved as one stack (:func:`~batcert.physics.ritz.reduced_modes_many`), and
the engine builds the linear systems of the drawn bats and balls together, their barrel read
once on the wall they share (:mod:`batcert.engines.flexible_family`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from batcert.engines.base import Engine
from batcert.errors import InputError, UsageProblem
from batcert.model.build import BuiltBat, build_bat
from batcert.results.run import InputUncertainty, PredictedUncertainty, RunResult
from batcert.runner.bench import Bench, drive
from batcert.runner.runner import decide, run_protocols
from batcert.runner.sampled import drawn_result, fit_steps
from batcert.specs.ball import BallSpec
from batcert.specs.bat import BatSpec
from batcert.specs.protocol import ProtocolSpec
from batcert.specs.resolve import display_path
from batcert.uncertainty.inputs import StatedInput, draw, sampled, stated_inputs

BASIS_MODES = 48  # nominal bending modes spanning a drawn bat's modes (Ritz basis)
CHUNK = 125  # draws solved together (memory and progress)
WALL_CHUNK = 8  # the same when each draw builds its own barrel
DEFAULT_SEED = 20011  # the default random seed (any fixed number: draws are reproducible)


@dataclass(frozen=True)
class Job:
    """One protocol's nominal run, to be repeated over the draws."""

    protocol: ProtocolSpec
    ball: BallSpec
    nominal: RunResult


class NoStatedUncertainty(UsageProblem):
    """``--uncertainty`` on files that state none."""


def monte_carlo(built: BuiltBat, jobs: list[Job], engine: Engine, samples: int,
                seed: int = DEFAULT_SEED,
                on_progress: Callable[[int, int], None] | None = None
                ) -> list[PredictedUncertainty]:
    """The distribution of every job's result over ``samples`` draws of the stated input
    uncertainties of ``built``'s bat file and the jobs' ball files, one
    :class:`PredictedUncertainty` per job. ``on_progress(draws_done, draws)``."""
    balls = [j.ball for j in jobs]
    inputs, z = draws(built.spec, balls, samples, seed)
    reducer = _Reducer(built, engine)
    nominal = drive([fit_steps(b, j.protocol, j.nominal) for b, j in zip(
        _benches(built, jobs, engine, inputs, np.zeros((1, len(inputs))), reducer, -1)[0],
        jobs, strict=True)], engine)
    values = np.zeros((samples, len(jobs)))
    shift = np.zeros(len(jobs))  # the largest move of a draw's impact point [m]
    if on_progress:
        on_progress(0, samples)
    # a drawn wall is a new barrel (about 0.25 s): smaller chunks keep the progress moving
    chunk = WALL_CHUNK if any(s.field == "wall" for s in inputs) else CHUNK
    for start in range(0, samples, chunk):
        rows = z[start:start + chunk]
        fits = drive([fit_steps(b, j.protocol, j.nominal)
                      for benches in _benches(built, jobs, engine, inputs, rows, reducer, start)
                      for b, j in zip(benches, jobs, strict=True)], engine)
        for k, fit in enumerate(fits):
            i, n = divmod(k, len(jobs))
            values[start + i, n], x = drawn_result(jobs[n].protocol, jobs[n].nominal,
                                                   nominal[n], fit)
            shift[n] = max(shift[n], float(np.abs(x - nominal[n].centre).max()))
        if on_progress:
            on_progress(start + rows.shape[0], samples)
    checked = _checked_draws(values)
    exact = np.zeros((len(checked), len(jobs)))
    for k, i in enumerate(checked):
        bat, drawn_balls = sampled(built.spec, balls, inputs, z[i])
        drawn = build_bat(bat)
        exact[k] = [r.value for r in run_protocols(
            [(drawn, j.protocol, ball) for j, ball in zip(jobs, drawn_balls, strict=True)],
            engine, created="")]
    error = np.abs(exact - values[checked]).max(axis=0)
    return [_summary(j, inputs, z, values[:, k], seed, float(error[k]), len(checked),
                     float(shift[k]), reducer.method) for k, j in enumerate(jobs)]


def draws(bat: BatSpec, balls: list[BallSpec], samples: int, seed: int
          ) -> tuple[list[StatedInput], np.ndarray]:
    """The stated inputs of ``bat`` and ``balls`` and their draws (:func:`draw`); refuses files
    that state no uncertainty (:class:`NoStatedUncertainty`) and draws of impossible values
    (an :class:`InputError`), so that a command can check before it runs anything."""
    inputs = stated_inputs(bat, balls)
    if not inputs:
        raise NoStatedUncertainty(
            f"--uncertainty: neither {display_path(bat.path)} nor the ball file states an "
            "uncertainty; give one with the value, e.g. 'mass: 863 g +/- 1 g' (docs/uncertainty.md)")
    return inputs, draw(inputs, samples, seed)


CHECKED = 4  # draws solved again by the full run (the check of the reductions)


def _checked_draws(values: np.ndarray) -> list[int]:
    """The draws whose result is checked against a full run: the farthest from the mean
    (where the reductions are the least exact) and the first ones."""
    far = np.argsort(-np.abs(values - values.mean(axis=0)).max(axis=1))[:CHECKED // 2]
    first = [i for i in range(values.shape[0]) if i not in set(far)][:CHECKED - len(far)]
    return sorted({int(i) for i in far} | set(first))


class _Reducer:
    """The modes of drawn bats by Ritz on the nominal bat's modes (flexible engine only)."""

    def __init__(self, built: BuiltBat, engine: Engine) -> None:
        self.built, self.engine = built, engine
        self.bases: dict[tuple[str, float], Any] = {}
        self.flexible = engine.name == "flexible"
        self.method = ("each draw built like the bat file (reconciled and calibrated to the drawn "
                       "values) and run with the " + engine.name + " engine on a five-point "
                       "stencil around each nominal impact point, its impact point and result "
                       "following from the parabolas through them")
        if self.flexible:
            self.method += (f"; bending modes by Rayleigh-Ritz on the nominal bat's "
                            f"{BASIS_MODES} modes")

    def modes(self, models: list, support: str, pivot: float) -> list:
        """The modes of the drawn bats ``models`` (one Ritz solve for them all), or None for
        each where the engine computes its own."""
        if not self.flexible:
            return [None] * len(models)
        from batcert.physics.ritz import reduced_modes_many, ritz_basis
        key = (support, float(pivot))
        flexible: Any = self.engine  # a FlexibleEngine (checked above)
        if key not in self.bases:
            self.bases[key] = ritz_basis(self.built.model, support, pivot, BASIS_MODES,
                                         flexible.refine)[0]
        return reduced_modes_many(self.bases[key], models, flexible.n_modes)


def _benches(built: BuiltBat, jobs: list[Job], engine: Engine, inputs: list[StatedInput],
             rows: np.ndarray, reducer: _Reducer, first: int) -> list[list[Bench]]:
    """For each row of draws ``rows``, its bat and balls on the bench of each job (``first``:
    the first row's draw number, -1 for the nominal inputs)."""
    drawn, balls = [], []
    for i, row in enumerate(rows):
        bat, row_balls = sampled(built.spec, [j.ball for j in jobs], inputs, row)
        try:
            drawn.append(build_bat(bat))
        except InputError as exc:
            where = "the nominal inputs" if first < 0 else f"draw {first + i + 1}"
            raise InputError([replace(p, message=f"{p.message} (in {where} of the Monte "
                                      "Carlo, from the stated uncertainties)")
                              for p in exc.problems]) from None
        balls.append(row_balls)
    modes = {(j.protocol.support, j.protocol.pivot): reducer.modes(
        [d.model for d in drawn], j.protocol.support, j.protocol.pivot) for j in jobs}
    return [[Bench(d, ball, engine, j.protocol.pivot, j.protocol.support,
                   modes[(j.protocol.support, j.protocol.pivot)][i])
             for j, ball in zip(jobs, row_balls, strict=True)]
            for i, (d, row_balls) in enumerate(zip(drawn, balls, strict=True))]


def _summary(job: Job, inputs: list[StatedInput], z: np.ndarray, values: np.ndarray, seed: int,
             error: float, checked: int, shift: float, method: str) -> PredictedUncertainty:
    n = values.size
    design = np.column_stack([np.ones(n), z])
    coef, *_ = np.linalg.lstsq(design, values, rcond=None)
    slopes = coef[1:]
    fitted = design @ coef
    spread = float(((values - values.mean()) ** 2).sum())
    r2 = 1.0 - float(((values - fitted) ** 2).sum()) / spread if spread > 0 else 1.0
    total = float((slopes**2).sum())
    limit = job.protocol.limit
    passes = None
    if limit is not None:
        passes = float(np.mean([decide(float(v), limit)[1] == "pass" for v in values]))
    nominal = job.nominal
    note = ""
    if nominal.barrel is not None and not nominal.barrel.calibrated:
        note = ("the barrel is not calibrated: the distribution is for the nominal barrel; the "
                "plausible barrel's range (reported separately) is not in it")
    std = float(values.std(ddof=1)) if n > 1 else 0.0
    return PredictedUncertainty(
        samples=n, seed=seed, method=method,
        inputs=[InputUncertainty(s.file, display_path(s.path), s.field, s.line, s.dimension,
                                 list(s.nominal), list(s.u), s.distribution, float(c),
                                 float(c**2 / total) if total > 0 else 0.0)
                for s, c in zip(inputs, slopes, strict=True)],
        mean=float(values.mean()), standard_deviation=std, median=float(np.median(values)),
        interval_low=float(np.percentile(values, 2.5)),
        interval_high=float(np.percentile(values, 97.5)),
        minimum=float(values.min()), maximum=float(values.max()),
        mean_standard_error=std / np.sqrt(n), linear_r2=float(r2),
        pass_probability=passes,
        pass_probability_standard_error=None if passes is None
        else float(np.sqrt(passes * (1 - passes) / n)),
        nominal_value=float(nominal.value), full_run_difference=error, checked_draws=checked,
        largest_location_shift=shift,
        values=[float(v) for v in values], note=note)
