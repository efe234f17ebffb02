"""Monte Carlo propagation of stated input uncertainties through the engine (JCGM 101).

By default the draws' results come from a response surface in the drawn inputs
(:mod:`batcert.uncertainty.surrogate`), fitted on a few dozen draws solved by the engine as
below; every run solves :data:`~batcert.uncertainty.surrogate.SURROGATE_CHECKED` of the actual
draws (the extremes and some at random) with the engine too, reports the surface's largest
difference from them, and solves every draw with the engine when it exceeds the bound
(``method="full"`` always does).

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
the mean and the first) are run again as ``run`` runs a bat (new modes, the whole search; all
in the same engine batches), and the largest difference from the reported result (the
surface's, or the stencil's) is reported (``full_run_difference``). It includes the full search's own
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
from batcert.results.run import InputUncertainty, PredictedUncertainty, Propagation, RunResult
from batcert.runner.bench import Bench, drive
from batcert.runner.runner import decide, run_protocols
from batcert.runner.sampled import drawn_result, fit_steps
from batcert.specs.ball import BallSpec
from batcert.specs.bat import BatSpec
from batcert.specs.protocol import ProtocolSpec
from batcert.specs.resolve import display_path
from batcert.uncertainty.inputs import StatedInput, draw, sampled, stated_inputs
from batcert.uncertainty.surrogate import (
    ResponseSurface,
    axial,
    checked_draws,
    default_bound,
    most_runs,
    second_stage,
    strong_inputs,
)

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
                on_progress: Callable[[int, int], None] | None = None,
                method: str = "surrogate", bound: float | None = None
                ) -> list[PredictedUncertainty]:
    """The distribution of every job's result over ``samples`` draws of the stated input
    uncertainties of ``built``'s bat file and the jobs' ball files, one
    :class:`PredictedUncertainty` per job. ``method``: ``"full"`` solves every draw with the
    engine; ``"surrogate"`` (when it costs fewer engine runs) a response surface
    (:mod:`batcert.uncertainty.surrogate`), checked on a sample of the draws, and every draw
    when the surface misses the engine there by more than ``bound`` [metric unit; None: each
    job's metric's :func:`~batcert.uncertainty.surrogate.default_bound`].
    ``on_progress(done, total)`` counts the draws the engine solves."""
    bounds = np.array([default_bound(j.protocol.metric) if bound is None else bound
                       for j in jobs])
    balls = [j.ball for j in jobs]
    inputs, z = draws(built.spec, balls, samples, seed)
    cost = most_runs(len(inputs))
    use_surface = method == "surrogate" and cost < samples
    solver = _Solver(built, jobs, engine, inputs, on_progress, cost if use_surface else samples)
    if use_surface:
        values, propagation = _by_surface(solver, z, seed, bounds)
    else:
        values = solver.solve(z, _draw_name(range(samples)))
        reason = "" if method == "full" else (
            f"{samples} draws are not more than the {cost} engine runs the surface may take")
        propagation = [Propagation("full", method, solver.done, 0, 0, None, float(b), reason)
                       for b in bounds]
    checked = _checked_draws(values)
    drawn = []
    for i in checked:
        bat, drawn_balls = sampled(built.spec, balls, inputs, z[i])
        bat_built = build_bat(bat)
        drawn += [(bat_built, j.protocol, ball) for j, ball in zip(jobs, drawn_balls, strict=True)]
    exact = np.array([r.value for r in run_protocols(drawn, engine, created="")]).reshape(
        len(checked), len(jobs))  # the full runs, all in the same engine batches
    error = np.abs(exact - values[checked]).max(axis=0)
    words = solver.method if propagation[0].method == "full" else _surface_words(
        propagation[0], solver.method)
    return [_summary(j, inputs, z, values[:, k], seed, float(error[k]), len(checked),
                     float(solver.shift[k]), words, propagation[k])
            for k, j in enumerate(jobs)]


def _draw_name(numbers) -> list[str]:
    return [f"draw {i + 1}" for i in numbers]


def _by_surface(solver: _Solver, z: np.ndarray, seed: int, bound: np.ndarray
                ) -> tuple[np.ndarray, list[Propagation]]:
    """The draws' results by the response surface, and how it was checked; every draw solved
    by the engine when the surface misses the engine by more than ``bound`` (one per job) on
    its checked draws, or a design point cannot be built (said in the propagation's reason). Two engine
    batches: the axial points, then the second stage with the checked draws (chosen on the
    axial points' quadratic, whose extremes are the whole surface's but for the cubic terms
    and the interactions)."""
    first = axial(z)
    try:
        axial_values = solver.solve(first, _point_names(0, first.shape[0]))
    except InputError as exc:
        return _fall_back(solver, z, bound, 0, 0, None, _unbuilt(exc))
    strong = strong_inputs(axial_values)
    more = second_stage(z, strong)
    checked = checked_draws(z, ResponseSurface.fit(first, axial_values, [False] * z.shape[1])(z),
                            seed)
    solver.total = solver.done + len(more) + len(checked)
    try:
        second = solver.solve(np.concatenate([more, z[checked]]), _point_names(
            first.shape[0], len(more)) + _draw_name(checked))
    except InputError as exc:
        return _fall_back(solver, z, bound, first.shape[0], 0, None, _unbuilt(exc))
    points = np.concatenate([first, more])
    surface = ResponseSurface.fit(points, np.concatenate([axial_values, second[:len(more)]]),
                                  strong)
    predicted = surface(z)
    difference = np.abs(predicted[checked] - second[len(more):]).max(axis=0)
    if np.all(difference <= bound):
        return predicted, [Propagation("surrogate", "surrogate", solver.done, points.shape[0],
                                       len(checked), float(d), float(b))
                           for d, b in zip(difference, bound, strict=True)]
    worst = int(np.argmax(difference / bound))
    reason = (f"the response surface missed the engine by {difference[worst]:.2g} on "
              f"{len(checked)} checked draws{_of(solver, worst)}, more than the bound "
              f"{bound[worst]:g}")
    return _fall_back(solver, z, bound, points.shape[0], len(checked), difference, reason)


def _unbuilt(exc: InputError) -> str:
    return ("a design point of the response surface (or a checked draw) cannot be built: "
            + exc.problems[0].message)


def _point_names(first: int, count: int) -> list[str]:
    return [f"the response surface's design point {first + i + 1}" for i in range(count)]


def _of(solver: _Solver, k: int) -> str:
    return f" (protocol {solver.jobs[k].protocol.id})" if len(solver.jobs) > 1 else ""


def _fall_back(solver: _Solver, z: np.ndarray, bound: np.ndarray, points: int, checked: int,
               difference: np.ndarray | None, reason: str
               ) -> tuple[np.ndarray, list[Propagation]]:
    solver.total = solver.done + z.shape[0]
    values = solver.solve(z, _draw_name(range(z.shape[0])))
    return values, [Propagation("full", "surrogate", solver.done, points, checked,
                                None if difference is None else float(difference[k]),
                                float(bound[k]), reason) for k in range(len(solver.jobs))]


def _surface_words(p: Propagation, each: str) -> str:
    return ("a response surface in the inputs' standard uncertainties (quadratic in each, "
            "cubic in the strong ones, with their interactions; every draw's result from it), "
            "fitted on "
            f"{p.design_points} design points and checked on {p.checked_draws} of the draws; "
            f"the engine's runs: {each}")


class _Solver:
    """Draws (rows of standard uncertainties) solved by the engine: each drawn bat built like
    the bat file and solved on the stencils around the nominal impact points, in chunks."""

    def __init__(self, built: BuiltBat, jobs: list[Job], engine: Engine,
                 inputs: list[StatedInput], on_progress: Callable[[int, int], None] | None,
                 total: int) -> None:
        self.built, self.jobs, self.engine, self.inputs = built, jobs, engine, inputs
        self.reducer = _Reducer(built, engine)
        self.method = self.reducer.method
        self.nominal = drive([fit_steps(b, j.protocol, j.nominal) for b, j in zip(
            _benches(built, jobs, engine, inputs, np.zeros((1, len(inputs))), self.reducer,
                     ["the nominal inputs"])[0], jobs, strict=True)], engine)
        self.shift = np.zeros(len(jobs))  # the largest move of a draw's impact point [m]
        self.on_progress, self.done, self.total = on_progress, 0, total
        # a drawn wall is a new barrel (about 0.25 s): smaller chunks keep the progress moving
        self.chunk = WALL_CHUNK if any(s.field == "wall" for s in inputs) else CHUNK
        self._progress()

    def _progress(self) -> None:
        if self.on_progress:
            self.on_progress(self.done, self.total)

    def solve(self, z: np.ndarray, names: list[str]) -> np.ndarray:
        """Each row's result under each job, shape (rows, jobs); ``names``: each row's, for an
        error (``draw 12``)."""
        jobs = self.jobs
        values = np.zeros((z.shape[0], len(jobs)))
        for start in range(0, z.shape[0], self.chunk):
            rows = z[start:start + self.chunk]
            fits = drive([fit_steps(b, j.protocol, j.nominal)
                          for benches in _benches(self.built, jobs, self.engine, self.inputs,
                                                  rows, self.reducer,
                                                  names[start:start + self.chunk])
                          for b, j in zip(benches, jobs, strict=True)], self.engine)
            for k, fit in enumerate(fits):
                i, n = divmod(k, len(jobs))
                values[start + i, n], x = drawn_result(jobs[n].protocol, jobs[n].nominal,
                                                       self.nominal[n], fit)
                self.shift[n] = max(self.shift[n],
                                    float(np.abs(x - self.nominal[n].centre).max()))
            self.done += rows.shape[0]
            self._progress()
        return values


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
             rows: np.ndarray, reducer: _Reducer, names: list[str]) -> list[list[Bench]]:
    """For each row of draws ``rows``, its bat and balls on the bench of each job (``names``:
    each row's, for an error: ``draw 12``, ``the nominal inputs``)."""
    drawn, balls = [], []
    for i, row in enumerate(rows):
        bat, row_balls = sampled(built.spec, [j.ball for j in jobs], inputs, row)
        try:
            drawn.append(build_bat(bat))
        except InputError as exc:
            raise InputError([replace(p, message=f"{p.message} (in {names[i]} of the Monte "
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
             error: float, checked: int, shift: float, method: str, propagation: Propagation
             ) -> PredictedUncertainty:
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
        values=[float(v) for v in values], note=note, propagation=propagation)
