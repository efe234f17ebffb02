"""What `batcert compare` and `batcert league` do, without the CLI: resolve and load every input
first (nothing runs when an input is bad), run the protocols, hand the results to the pure
:func:`batcert.compare.compare` and :func:`batcert.league.evaluate_league`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from batcert.compare import BatEntry, ComparisonResult, bat_labels, compare
from batcert.jobs import ProtocolInputs, load_protocol_any, protocol_inputs
from batcert.league import LeagueResult, bat_facts, evaluate_league, needs_run
from batcert.runner.runner import run_protocol
from batcert.specs.bat import BuiltBat, build_bat, load_bat
from batcert.specs.common import sha256_of
from batcert.specs.league import LeagueSpec, load_league
from batcert.specs.resolve import resolve
from batcert.specs.study import StudySpec, load_study


class EngineUnavailable(LookupError):
    """The requested engine tier is not part of this installation."""


class UsageProblem(ValueError):
    """The command line asks for something impossible (e.g. fewer than two bats)."""


def get_engine_checked(name: str, **options):
    """The engine, or :class:`EngineUnavailable` naming the engines that exist."""
    from batcert.physics.engine import available_engines, get_engine
    try:
        return get_engine(name, **options)
    except KeyError:
        have = ", ".join(available_engines()) or "none"
        raise EngineUnavailable(f"the {name!r} engine is not available in this installation "
                                f"(available: {have}); choose one with --engine") from None


@dataclass(frozen=True)
class LoadedBat:
    path: Path
    built: BuiltBat


def load_bats(values: list[str], relative_to: Path | None = None) -> list[LoadedBat]:
    out = []
    for v in values:
        p = resolve("bat", v, relative_to=relative_to)
        out.append(LoadedBat(p, build_bat(load_bat(p))))
    return out


def load_study_any(value: str) -> StudySpec:
    return load_study(resolve("study", value))


def _same(a: Path, b: Path) -> bool:
    """The same bat file: one path, or identical content (a shipped name resolves to the copy
    installed with the package, which is the same bat as the checkout's file)."""
    return a.resolve() == b.resolve() or sha256_of(a) == sha256_of(b)


def run_comparison(bats: list[str], protocols: list[str], study: str | None = None,
                   reference: str | None = None, engine: str = "flexible") -> ComparisonResult:
    """Run every bat under every protocol (a study's, then any extra ones) and compare them."""
    spec = load_study_any(study) if study else None
    proto_inputs = [protocol_inputs(p) for p in spec.protocols] if spec else []
    proto_inputs += [load_protocol_any(p) for p in protocols]
    if not proto_inputs:
        raise UsageProblem("give at least one --protocol, or a --study")
    ids = [p.protocol.id for p in proto_inputs]
    dup = sorted({i for i in ids if ids.count(i) > 1})
    if dup:
        raise UsageProblem(f"protocol {', '.join(map(repr, dup))} given twice")
    if bats:
        loaded = load_bats(bats)
    elif spec and spec.bats:
        loaded = load_bats([str(p) for p in spec.bats])
    else:
        raise UsageProblem("give the bats to compare (or a study that names default bats)")
    ref = 0
    if reference is not None:
        ref_path = resolve("bat", reference)
        ref = next((i for i, b in enumerate(loaded) if _same(b.path, ref_path)), -1)
        if ref < 0:
            loaded = load_bats([reference]) + loaded
            ref = 0
    if len(loaded) < 2:
        raise UsageProblem("a comparison needs at least two bats")
    eng = get_engine_checked(engine)
    runs = [[run_protocol(b.built, p.protocol, p.ball, eng) for p in proto_inputs]
            for b in loaded]
    labels = bat_labels([b.built.spec.name for b in loaded], [str(b.path) for b in loaded])
    entries = [BatEntry(lab, b.built.spec.name, str(b.path), b.built.spec.sha256,
                        b.built.model.length, b.built.model.construction,
                        b.built.model.material.name) for lab, b in zip(labels, loaded)]
    title = spec.values["title"] if spec else ""
    return compare(runs, ref, bats=entries, title=title, study=spec.id if spec else None,
                   study_reference=spec.values["reference"] if spec else "",
                   study_notes=(spec.values["notes"] or "") if spec else "",
                   claims=spec.claims if spec else ())


def load_league_any(value: str) -> LeagueSpec:
    return load_league(resolve("league", value))


def run_league(league: str, bats: list[str], engine: str = "flexible") -> LeagueResult:
    """Evaluate every rule of a league on every bat; performance rules run their protocol."""
    spec = load_league_any(league)
    loaded = load_bats(bats)
    facts = [bat_facts(b.built) for b in loaded]
    protocols: dict[str, ProtocolInputs] = {}
    for rule in spec.rules:  # load every protocol before running anything
        if rule["kind"] == "performance" and rule["status"] == "modelled":
            path = resolve("protocol", rule["protocol"], relative_to=Path(spec.path))
            protocols[rule["id"]] = load_protocol_any(str(path))
    needed = any(needs_run(r, f) for r in spec.rules for f in facts)
    eng = get_engine_checked(engine) if needed else None
    per_bat = []
    for b, f in zip(loaded, facts):
        runs, cache = {}, {}
        for rule in spec.rules:
            if needs_run(rule, f):
                p = protocols[rule["id"]]
                key = p.protocol.path, p.protocol.id
                if key not in cache:
                    cache[key] = run_protocol(b.built, p.protocol, p.ball, eng)
                runs[rule["id"]] = cache[key]
        per_bat.append((f, runs))
    return evaluate_league(spec, per_bat, eng.name if eng else "none (no performance rule ran)")
