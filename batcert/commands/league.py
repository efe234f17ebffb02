"""``batcert league``: every rule of a league on every bat; performance rules run their
protocol (once per bat and protocol). Every input is loaded before anything runs."""

from __future__ import annotations

from pathlib import Path

from batcert.analysis.league import bat_facts, evaluate_league, needs_run
from batcert.commands.inputs import ProtocolInputs, load_bats, load_league_any, load_protocol_any
from batcert.engines import get_engine
from batcert.results.league import LeagueResult
from batcert.results.run import RunResult
from batcert.runner.runner import run_protocol


def run_league(league: str, bats: list[str], engine: str = "flexible") -> LeagueResult:
    """Evaluate every rule of a league on every bat."""
    spec = load_league_any(league)
    loaded = load_bats(bats)
    facts = [bat_facts(b.built) for b in loaded]
    protocols: dict[str, ProtocolInputs] = {}
    for rule in spec.rules:  # load every protocol before running anything
        if rule.kind == "performance" and rule.status == "modelled" and rule.protocol:
            protocols[rule.id] = load_protocol_any(rule.protocol, relative_to=Path(spec.path))
    needed = any(needs_run(r, f) for r in spec.rules for f in facts)
    eng = get_engine(engine) if needed else None
    per_bat = []
    for b, f in zip(loaded, facts, strict=True):
        runs: dict[str, RunResult] = {}
        cache: dict[tuple[str, str], RunResult] = {}
        for rule in spec.rules:
            if eng is not None and needs_run(rule, f):
                p = protocols[rule.id]
                key = p.protocol.path, p.protocol.id
                if key not in cache:
                    cache[key] = run_protocol(b.built, p.protocol, p.ball, eng)
                runs[rule.id] = cache[key]
        per_bat.append((f, runs))
    return evaluate_league(spec, per_bat, eng.name if eng else "none (no performance rule ran)")
