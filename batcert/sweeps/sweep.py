"""Sweeps: one protocol run on every variant of a bat or a protocol, in engine batches.

A :class:`Plan` holds the nominal case, the varied axes and every grid point. Its points are cut
into :class:`Chunk` s of :func:`chunk_size` variants (a number that depends only on how many
variants there are), the same whatever runs them, so a chunk's variants share engine batches
(:func:`batcert.runner.runner.run_protocols`) and the results do not depend on the worker count
or the scheduler: an engine batch's last bits depend on what shares it. A batch costs about
40 ms besides its impacts, so a variant solved alone costs about twice what one of eight solved
together does. :func:`evaluate_chunk` (a top-level function: processes and dask workers pickle
it) turns a chunk into rows, one per variant, of plain JSON numbers; :func:`collect` turns the
rows into a :class:`~batcert.results.sweep.SweepResult`. Where the chunks run is
:mod:`batcert.sweeps.execute`'s business.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

from batcert.errors import InputError
from batcert.model.build import BuiltBat, build_bat
from batcert.results.run import RunResult
from batcert.results.sweep import (
    CONDITION_FIELDS,
    VARIANT_FIELDS,
    NominalRun,
    SweepAxis,
    SweepCondition,
    SweepResult,
)
from batcert.specs.ball import BallSpec
from batcert.specs.resolve import display_path
from batcert.sweeps.variants import Axis, Case, ParameterError
from batcert.units import si_unit
from batcert.version import __version__

CHUNK_SIZE = 4  # variants per chunk (the unit of work of a worker, and of resuming) ...
LARGE_CHUNK_SIZE = 8  # ... and in a sweep of LARGE_SWEEP variants or more
LARGE_SWEEP = 256  # (32 chunks or more: several for each of 16 workers)
MAX_VARIANTS = 100_000  # variants of one sweep, all axes together (a grid multiplies them):
# about 7 h of the flexible engine on one core, and the grid's points, chunks and rows in memory
Row = dict[str, Any]


@dataclass(frozen=True)
class Chunk:
    """Variants to evaluate together: their indices and grid points."""

    index: int
    base: Case
    built: BuiltBat  # the nominal bat (nominal values of the parameters)
    ball: BallSpec
    engine: str
    names: tuple[str, ...]  # the varied parameters
    points: tuple[tuple[int, tuple[float, ...]], ...]  # (variant index, value per axis [SI])
    created: str


@dataclass(frozen=True)
class Plan:
    base: Case
    built: BuiltBat
    ball: BallSpec
    engine: str
    axes: tuple[Axis, ...]
    created: str

    @property
    def points(self) -> list[tuple[float, ...]]:
        """Every grid point, the first axis outermost (row-major)."""
        return list(itertools.product(*(a.values for a in self.axes)))

    def chunks(self) -> list[Chunk]:
        pts = list(enumerate(self.points))
        names = tuple(a.name for a in self.axes)
        size = chunk_size(len(pts))
        return [Chunk(k // size, self.base, self.built, self.ball, self.engine, names,
                      tuple(pts[k:k + size]), self.created)
                for k in range(0, len(pts), size)]

    def nominal_chunk(self) -> Chunk:
        """The nominal bat as its file describes it, as a chunk without points
        (:func:`evaluate_chunk`)."""
        return Chunk(-1, self.base, self.built, self.ball, self.engine,
                     tuple(a.name for a in self.axes), (), self.created)

    def check(self) -> None:
        """Every variant can be made (before any work): a value a parameter cannot take for
        this bat or protocol raises :class:`ParameterError`, as does a grid of more than
        :data:`MAX_VARIANTS` variants (refused before a point is made)."""
        variants = math.prod(len(a.values) for a in self.axes)
        if variants > MAX_VARIANTS:
            sizes = " x ".join(f"{len(a.values)} ({a.name})" for a in self.axes)
            raise ParameterError(f"--vary: {sizes} = {variants} variants; a sweep has at most "
                                 f"{MAX_VARIANTS}: use fewer values")
        changes = {a.parameter.changes for a in self.axes}
        if {"geometry", "measured"} <= changes:
            raise ParameterError("a geometric or material parameter and a measured property "
                                 "cannot vary together: a geometric variant's mass properties "
                                 "come from its geometry, not from measurements")
        if len({a.name for a in self.axes}) < len(self.axes):
            raise ParameterError("each parameter may be varied once")
        for point in self.points:
            variant_case(self.base, self.built, [a.name for a in self.axes], point)


def variant_case(base: Case, built: BuiltBat, names, point) -> Case:
    from batcert.sweeps.variants import PARAMETERS
    case = base
    for name, value in zip(names, point, strict=True):
        case = PARAMETERS[name].apply(case, built, value)
    return case


def _row(index: int, result: RunResult) -> Row:
    mp, barrel = result.mass_properties, result.barrel
    row: Row = {"index": index, "error": None, "value": result.value, "margin": result.margin,
                "verdict": result.verdict, "mass": mp.mass, "length": mp.length, "cg": mp.cg,
                "moi_pivot": mp.moi_pivot, "cop": mp.cop,
                "value_low": barrel.value_low if barrel else None,
                "value_high": barrel.value_high if barrel else None,
                "hoop_frequency": barrel.hoop_frequency if barrel else None,
                "warnings": result.warnings, "settings": result.engine_settings,
                "conditions": {c.name: {k: getattr(c, k) for k in CONDITION_FIELDS}
                               for c in result.conditions}}
    return row


def _failed(index: int, reason: str) -> Row:
    return {"index": index, "error": reason}


def whole_row(row: Any, index: int, conditions: tuple[str, ...]) -> bool:
    """Whether ``row`` (read back from a sweep's journal) is a whole row of variant ``index``
    as :func:`run_cases` makes it, under a protocol of ``conditions``: a failed variant's reason,
    or every field :func:`collect` reads, of its kind."""
    def number(x: Any) -> bool:
        return x is None or (isinstance(x, (int, float)) and not isinstance(x, bool))

    if not isinstance(row, dict) or row.get("index") != index or isinstance(row["index"], bool):
        return False
    if "error" not in row or row["error"] is not None:
        return isinstance(row.get("error"), str)
    got = row.get("conditions")
    return (all(number(row.get(k, "")) for k in VARIANT_FIELDS)
            and isinstance(row.get("verdict", ""), (str, type(None)))
            and isinstance(row.get("settings"), dict)
            and isinstance(row.get("warnings"), list)
            and all(isinstance(w, str) for w in row["warnings"])
            and isinstance(got, dict)
            and all(isinstance(got.get(c), dict) for c in conditions)
            and all(number(v) or isinstance(v, bool) for c in conditions
                    for v in got[c].values()))


def _reason(exc: InputError) -> str:
    return "; ".join(p.message for p in exc.problems)


def run_cases(cases: list[tuple[int, Case]], ball: BallSpec, engine_name: str, created: str
              ) -> list[Row]:
    """Build each case's bat and run its protocol, all in shared engine batches; a case that
    cannot be built or solved gets a row with its reason (and the others still run)."""
    from batcert.engines import get_engine
    from batcert.runner.runner import check_applicable, run_protocols
    engine = get_engine(engine_name)
    rows: dict[int, Row] = {}
    jobs = []
    for i, case in cases:
        try:
            built = build_bat(case.bat)
            check_applicable(case.protocol, built)
        except InputError as exc:
            rows[i] = _failed(i, _reason(exc))
            continue
        jobs.append((i, built, case.protocol))
    try:
        results = run_protocols([(b, p, ball) for _, b, p in jobs], engine, created)
        rows.update({i: _row(i, r) for (i, _, _), r in zip(jobs, results, strict=True)})
    except InputError:  # one variant has no finite solution: run them one by one to say which
        for i, b, p in jobs:
            try:
                rows[i] = _row(i, run_protocols([(b, p, ball)], engine, created)[0])
            except InputError as exc:
                rows[i] = _failed(i, _reason(exc))
    return [rows[i] for i, _ in cases]


def evaluate_chunk(chunk: Chunk) -> list[Row]:
    """The rows of one chunk's variants, solved together; a chunk without points is the
    nominal bat as its file describes it (:func:`nominal_run`), one row. Top-level, so that
    process and dask workers can run it."""
    cases = [(i, variant_case(chunk.base, chunk.built, chunk.names, point))
             for i, point in chunk.points] or [(-1, chunk.base)]
    return run_cases(cases, chunk.ball, chunk.engine, chunk.created)


# ---- collecting ---------------------------------------------------------------------------

def variant_name(plan: Plan, index: int) -> str:
    """A variant by its values, as on the command line: ``pitch_speed=55 m/s, wall=0.0027 m``
    (SI)."""
    return ", ".join(f"{a.name}={v:.6g}" + (f" {si_unit(a.parameter.dimension)}"
                                             if a.parameter.dimension
                                             else f" {a.parameter.unit}" if a.parameter.unit
                                             else "")
                     for a, v in zip(plan.axes, plan.points[index], strict=True))


def _which(plan: Plan, indices: list[int], shown: int = 4) -> str:
    """Which variants a warning came from: all of them, or the first few by name."""
    n = len(plan.points)
    if len(indices) == n:
        return f"all {n} variants" if n > 1 else "the variant"
    names = "; ".join(variant_name(plan, i) for i in indices[:shown])
    more = f"; and {len(indices) - shown} more" if len(indices) > shown else ""
    return f"{len(indices)} of {n} variants: {names}{more}"


def _notes(plan: Plan) -> list[str]:
    changes = {a.parameter.changes for a in plan.axes}
    bat = plan.base.bat
    notes = [f"{a.name}: {a.parameter.doc}" for a in plan.axes]
    if "geometry" in changes and bat.measured is not None:
        notes.append("The variants' mass properties come from their geometry (profile, wall "
                     "and material): the measured values (mass, CG, MOI, frequencies, barrel "
                     "compression) were measured on the nominal bat and apply only to it. The "
                     "nominal bat as measured is shown for contrast, with the corrections its "
                     "measurements made to the geometry.")
    if "geometry" in changes and bat.construction == "hollow":
        notes.append("Without a measured hoop frequency or compression the variants' barrels "
                     "are uncalibrated: each carries its range over the plausible barrel "
                     "(value_low to value_high).")
    if "measured" in changes:
        notes.append("The other measured properties stay as the bat file gives them; the model "
                     "is reconciled (and calibrated) to each variant's values.")
    return notes


def _construction_warning(plan: Plan) -> str | None:
    """The engine's warning (:func:`batcert.engines.construction_warning`) when the sweep
    varies what its results do not depend on, once for the sweep."""
    from batcert.engines import construction_warning
    varied = [a.name for a in plan.axes if a.parameter.construction]
    text = construction_warning(plan.engine) if varied else None
    if text is None:
        return None
    return f"{text} (varied: {', '.join(varied)}, which shows only in the mass properties, if at all)"


def chunk_size(variants: int) -> int:
    """The variants of a chunk in a sweep of ``variants`` (module notes): 1 to 8 variants
    together take 67 to 38 ms per variant of a wall sweep, 16 and 32 together 43 and 52 ms
    (larger batches leave the processor's cache); small chunks give more of them to share
    among workers, large ones less fixed cost per variant."""
    return LARGE_CHUNK_SIZE if variants >= LARGE_SWEEP else CHUNK_SIZE


def needs_nominal(plan: Plan) -> bool:
    """Whether the sweep's result shows the nominal bat as its file describes it: when the
    variants drop its measurements (a geometric parameter) and it has some."""
    return any(a.parameter.changes == "geometry" for a in plan.axes) \
        and plan.base.bat.measured is not None


def nominal_run(plan: Plan, row: Row | None = None) -> NominalRun | None:
    """The nominal bat with its measurements, when the sweep's variants drop them
    (:func:`needs_nominal`); ``row``: its row when already solved (:meth:`Plan.nominal_chunk`,
    which gives the same numbers)."""
    if not needs_nominal(plan):
        return None
    if row is None:
        row = evaluate_chunk(plan.nominal_chunk())[0]
    from batcert.model.mass import mass_properties
    mp = mass_properties(plan.built, plan.base.protocol.pivot)
    return NominalRun(row.get("value"), row.get("margin"), row.get("verdict"),
                      mp.reconciliation, mp.corrections, mp.geometry_mass, mp.measured_mass,
                      row["error"])


def collect(plan: Plan, rows: list[Row], nominal: NominalRun | None) -> SweepResult:
    """The sweep's result from every variant's row (in any order)."""
    by_index = {r["index"]: r for r in rows}
    points = plan.points
    ordered = [by_index[i] for i in range(len(points))]
    p = plan.base.protocol
    series = {k: [r.get(k) for r in ordered] for k in VARIANT_FIELDS}
    conditions = []
    for c in p.conditions:
        got = [r["conditions"][c.name] if r["error"] is None else {} for r in ordered]
        rigid = any(g.get("rigid_sweet_spot") is not None for g in got)
        conditions.append(SweepCondition(c.name, rigid,
                                         {k: [g.get(k) for g in got] for k in CONDITION_FIELDS}))
    seen: dict[str, list[int]] = {}  # each warning and the variants that gave it
    for i, r in enumerate(ordered):
        for w in r.get("warnings", []):
            if not w.startswith("the barrel was not calibrated") and i not in seen.get(w, []):
                seen.setdefault(w, []).append(i)
    warnings = [f"{w} ({_which(plan, idx)})" for w, idx in sorted(seen.items())]
    blind = _construction_warning(plan)
    if blind:
        warnings.insert(0, blind)
    failed = sum(r["error"] is not None for r in ordered)
    if failed:
        warnings.insert(0, f"{failed} of {len(ordered)} variants have no result (see errors)")
    settings: dict[str, Any] = next((r["settings"] for r in ordered if r["error"] is None), {})
    axes = [SweepAxis(a.name, a.parameter.dimension,
                      si_unit(a.parameter.dimension) if a.parameter.dimension
                      else a.parameter.unit or "-",
                      a.parameter.changes, a.parameter.doc, a.nominal, list(a.values),
                      a.percent, a.parameter.label) for a in plan.axes]
    bat = plan.base.bat
    inputs = [{"role": "bat", "name": bat.name, "path": display_path(bat.path),
               "sha256": bat.sha256},
              {"role": "protocol", "name": p.id, "path": display_path(p.path), "sha256": p.sha256},
              {"role": "ball", "name": plan.ball.name, "path": display_path(plan.ball.path),
               "sha256": plan.ball.sha256}]
    return SweepResult(
        bat=bat.name, bat_path=display_path(bat.path), protocol=p.id, protocol_title=p.title,
        metric=p.metric, aggregate=p.aggregate, limit=p.limit.max if p.limit else None,
        tolerance=p.limit.tolerance if p.limit else 0.0, engine=plan.engine,
        engine_settings=settings, axes=axes, points=[list(x) for x in points], series=series,
        verdicts=[r.get("verdict") for r in ordered], errors=[r["error"] for r in ordered],
        conditions=conditions, nominal=nominal, notes=_notes(plan), warnings=warnings,
        inputs=inputs, batcert_version=__version__, created=plan.created,
        bat_identification=_identification(bat))


def _identification(spec) -> dict[str, str]:
    from batcert.runner.runner import identification
    return identification(spec)
