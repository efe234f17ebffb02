"""``batcert league``: every rule of a league on every bat; performance rules run their
protocol (once per bat and protocol). Every input is loaded before anything runs."""

from __future__ import annotations

from dataclasses import replace

from batcert.analysis.league import bat_facts, evaluate_league, needs_run
from batcert.commands.inputs import ProtocolInputs, league_protocols, load_bats, load_league_any
from batcert.engines import get_engine
from batcert.results.league import LeagueResult
from batcert.results.run import RunResult
from batcert.runner.runner import run_protocols
from batcert.specs.resolve import display_path


def run_league(league: str, bats: list[str], engine: str = "flexible",
               on_step=None) -> LeagueResult:
    """Evaluate every rule of a league on every bat."""
    spec = load_league_any(league)
    loaded = load_bats(bats)
    facts = [replace(bat_facts(b.built), path=display_path(b.built.spec.path)) for b in loaded]
    protocols = league_protocols(spec)  # every protocol loaded before anything runs
    needed = any(needs_run(r, f) for r in spec.rules for f in facts)
    eng = get_engine(engine) if needed else None
    # every (bat, protocol) the rules need, once, all solved together
    wanted: dict[tuple[int, str, str], ProtocolInputs] = {}
    for i, f in enumerate(facts):
        for rule in spec.rules:
            if eng is not None and needs_run(rule, f):
                p = protocols[rule.id]
                wanted.setdefault((i, p.protocol.path, p.protocol.id), p)
    results = dict(zip(wanted, run_protocols(
        [(loaded[i].built, p.protocol, p.ball) for (i, _, _), p in wanted.items()], eng,
        on_step=on_step),
        strict=True)) if eng is not None else {}
    per_bat = []
    for i, f in enumerate(facts):
        runs: dict[str, RunResult] = {}
        for rule in spec.rules:
            if eng is not None and needs_run(rule, f):
                p = protocols[rule.id]
                runs[rule.id] = results[(i, p.protocol.path, p.protocol.id)]
        per_bat.append((f, runs))
    result = evaluate_league(spec, per_bat, eng.name if eng else "none (no performance rule ran)",
                             engine_warning=eng.construction_warning if eng else None)
    return replace(result, path=display_path(result.path))
