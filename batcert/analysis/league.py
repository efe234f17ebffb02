"""League rule evaluation (pure): bat facts and protocol results in, per-rule verdicts out.

Each rule of a league file (:mod:`batcert.specs.league`) has a kind of
:data:`batcert.specs.kinds.RULE_KINDS` (how the kind reads its ``limit``, which other fields it
needs, its unit; the league schema reads them there), evaluated by its function in
:data:`EVALUATIONS`. Verdicts: ``pass``,
``fail``, ``not-applicable`` (the rule covers other bats, e.g. a BBCOR rule for non-wood bats on a
wood bat) and ``not-modelled`` (the league file says batcert cannot evaluate the rule yet, or the
bat file lacks what the rule needs). A not-modelled rule never counts as a pass: a bat passes a
league only when every rule passes or does not apply."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from batcert.results.league import BatLeagueResult, LeagueResult, RuleResult
from batcert.results.run import RunResult
from batcert.results.serialise import utc_now
from batcert.specs.kinds import RULE_KINDS
from batcert.specs.league import runs_protocol
from batcert.specs.materials import PLIES
from batcert.units import INCH, OUNCE
from batcert.version import __version__

if TYPE_CHECKING:
    from batcert.model.build import BuiltBat
    from batcert.specs.league import LeagueSpec, RuleSpec

_REL = 1e-9  # comparisons allow this relative rounding (a 2.61 in barrel meets a 2.61 in limit)

# Library materials by class; inline materials are classed from words in their name.
MATERIAL_CLASS = {"ash": "wood", "ash-bat": "wood", "maple": "wood", "birch": "wood",
                  "aluminium-7050": "metal", **{name: "composite" for name in PLIES}}
_CLASS_WORDS = {
    "wood": ("wood", "ash", "maple", "birch", "bamboo", "hickory", "beech"),
    "metal": ("aluminium", "aluminum", "alloy", "steel", "titanium", "scandium"),
    "composite": ("composite", "carbon", "fibre", "fiber", "glass", "resin"),
}


def material_class(name: str) -> tuple[str | None, str]:
    """Class (wood, metal, composite or None) of a material and how it was decided."""
    if name in MATERIAL_CLASS:
        return MATERIAL_CLASS[name], f"library material {name!r}"
    words = set(re.findall(r"[a-z]+", name.lower()))
    found = {cls for cls, keys in _CLASS_WORDS.items() if words & set(keys)}
    if len(found) == 1:
        cls = found.pop()
        return cls, f"the word {sorted(words & set(_CLASS_WORDS[cls]))[0]!r} in the material name"
    return None, f"material {name!r} names no single class (wood, metal, composite)"


@dataclass(frozen=True)
class BatFacts:
    """What league rules read from a bat model (SI)."""

    name: str
    path: str
    sha256: str
    length: float  # [m]
    mass: float  # [kg] (the reconciled model, equal to the measured mass when one is given)
    barrel_diameter: float  # largest outer diameter [m]
    min_diameter: float  # smallest outer diameter [m]
    construction: str  # solid | hollow
    material: str
    material_class: str | None  # wood | metal | composite | None when unknown
    material_class_basis: str

    @property
    def drop(self) -> float:
        """Length in inches minus weight in ounces [-] (a 34 in, 31 oz bat has drop 3)."""
        return self.length / INCH - self.mass / OUNCE


def bat_facts(built: BuiltBat) -> BatFacts:
    """Facts of a :class:`~batcert.model.build.BuiltBat` (reads the reconciled model)."""
    m = built.model
    name, cls, basis = barrel_material(m)
    return BatFacts(built.spec.name, built.spec.path, built.spec.sha256, m.length, m.mass,
                    float(m.outer_diameter.max()), float(m.outer_diameter.min()),
                    m.construction, name, cls, basis)


def barrel_material(m) -> tuple[str, str | None, str]:
    """The material of the barrel (the widest slice; league rules on material concern it),
    its class and how that was decided: a layup's plies there (composite if any ply is, so a
    hybrid with a composite barrel is composite), else the bat's material."""
    i = int(m.outer_diameter.argmax())
    stack = m.layup.stack_of(i) if m.layup is not None else None
    if stack is None:
        return (m.material.name, *material_class(m.material.name))
    names = list(dict.fromkeys(layer.ply.name for wall in stack.walls for layer in wall))
    classes = {material_class(n)[0] for n in names}
    cls = "composite" if "composite" in classes else (classes.pop() if len(classes) == 1
                                                      else None)
    walls = f", {len(stack.walls)} walls" if len(stack.walls) > 1 else ""
    return (f"{' + '.join(names)} layup{walls}", cls,
            f"the barrel's layup ({', '.join(names)}{walls})")


# ---------------------------------------------------------------- evaluators


def _at_limit(margin: float, limit: float) -> float:
    """``margin``, or exactly 0 where it is only the rounding of the limit's own arithmetic
    (within ``_REL`` of it): a bat at exactly drop 3 is at the limit, not 7e-15 short."""
    return 0.0 if abs(margin) <= _REL * max(abs(limit), 1.0) else margin


def _at_most(value: float, limit: float, tol: float = 0.0) -> tuple[str, float]:
    margin = _at_limit(limit + tol - value, limit)
    return ("pass" if margin >= 0.0 else "fail"), margin


def _max_length(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    verdict, margin = _at_most(f.length, rule.limit)
    return RuleResult(rule.id, "", rule.kind, f.length, rule.limit, verdict, "m",
                      margin=margin)


def _max_drop(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    verdict, margin = _at_most(f.drop, rule.limit)
    return RuleResult(rule.id, "", rule.kind, f.drop, rule.limit, verdict, "in - oz",
                      margin=margin,
                      note=f"length {f.length / INCH:.2f} in, weight {f.mass / OUNCE:.2f} oz")


def _max_mass(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    verdict, margin = _at_most(f.mass, rule.limit)
    return RuleResult(rule.id, "", rule.kind, f.mass, rule.limit, verdict, "kg", margin=margin,
                      note=f"weight {f.mass / OUNCE:.2f} oz")


def _max_barrel(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    verdict, margin = _at_most(f.barrel_diameter, rule.limit)
    return RuleResult(rule.id, "", rule.kind, f.barrel_diameter, rule.limit, verdict,
                      "m", margin=margin, note="largest outer diameter of the profile")


def _min_diameter(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    margin = _at_limit(f.min_diameter - rule.limit, rule.limit)
    verdict = "pass" if margin >= 0.0 else "fail"
    return RuleResult(rule.id, "", rule.kind, f.min_diameter, rule.limit, verdict, "m",
                      margin=margin, note="smallest outer diameter of the profile")


def _construction(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    verdict = "pass" if f.construction == rule.required else "fail"
    return RuleResult(rule.id, "", rule.kind, f.construction, rule.required, verdict)


def _material(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    allowed = list(rule.allowed or [])
    value = f"{f.material} ({f.material_class or 'class unknown'})"
    if f.material in allowed or (f.material_class is not None and f.material_class in allowed):
        verdict, note = "pass", f"classed from {f.material_class_basis}"
    elif f.material_class is None:
        verdict, note = "not-modelled", (f"{f.material_class_basis}; name a library material "
                                         "or put the class in the material's name")
    else:
        verdict, note = "fail", f"classed from {f.material_class_basis}"
    return RuleResult(rule.id, "", rule.kind, value, allowed, verdict, note=note)


def _performance(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    if run is None:
        raise ValueError(f"rule {rule.id!r} needs the result of protocol {rule.protocol!r}")
    verdict, margin = _at_most(run.value, rule.limit, rule.tolerance)
    unit = "m/s" if run.metric == "exit-speed" else ""
    note = (f"{run.metric} ({run.aggregate} of {len(run.conditions)} condition"
            f"{'s' if len(run.conditions) != 1 else ''}) under {run.protocol}, engine "
            f"{run.engine}; the league's limit replaces the protocol's own")
    return RuleResult(rule.id, "", rule.kind, run.value, rule.limit, verdict, unit,
                      tolerance=rule.tolerance, margin=margin, protocol=run.protocol,
                      metric=run.metric, note=note, model_offset=run.model_offset)


def _min_compression(rule: RuleSpec, f: BatFacts, run: RunResult | None) -> RuleResult:
    if run is None:
        raise ValueError(f"rule {rule.id!r} needs the result of protocol {rule.protocol!r}")
    c = run.compression
    if c is None:
        return RuleResult(rule.id, "", rule.kind, None, rule.limit, "not-modelled", "N",
                          protocol=run.protocol,
                          note=f"protocol {run.protocol} has no barrel compression test, or "
                               "the bat has no hollow barrel")
    margin = _at_limit(c.force - rule.limit, rule.limit)
    after = " after the break-in" if run.break_in is not None and run.break_in.applies else ""
    note = (f"model: force on one platen at {c.deflection * 1e3:.3f} mm approach, platens "
            f"{c.platen_width * 1e3:.1f} mm wide {c.position * 1e3:.1f} mm from the tip"
            f"{after}, under {run.protocol}")
    return RuleResult(rule.id, "", rule.kind, c.force, rule.limit,
                      "pass" if margin >= 0 else "fail", "N", margin=margin,
                      protocol=run.protocol, note=note)


# how each kind of rule (:data:`batcert.specs.kinds.RULE_KINDS`: its name, meaning, limit
# and unit) is evaluated on a bat; None: it cannot be
EVALUATIONS: dict[str, Callable[[RuleSpec, BatFacts, RunResult | None], RuleResult] | None] = {
    "max-length": _max_length,
    "max-drop": _max_drop,
    "max-mass": _max_mass,
    "max-barrel-diameter": _max_barrel,
    "min-diameter": _min_diameter,
    "construction": _construction,
    "material": _material,
    "performance": _performance,
    "min-barrel-compression": _min_compression,
    "other": None,
}


def applies(rule: RuleSpec, f: BatFacts) -> bool | None:
    """Whether the rule covers this bat; None when the material class needed is unknown."""
    lo, hi = rule.applies_from_length, rule.applies_below_length
    if (lo is not None and f.length < lo * (1 - _REL)) or (hi is not None and f.length >= hi):
        return False
    scope = rule.applies_to
    if scope == "all":
        return True
    if f.material_class is None:
        return None
    return (f.material_class == "wood") == (scope == "wood")


def needs_run(rule: RuleSpec, f: BatFacts) -> bool:
    """Whether evaluating ``rule`` on this bat needs a protocol run."""
    return runs_protocol(rule.kind) and rule.status == "modelled" and applies(rule, f) is True


def _scope_text(rule: RuleSpec, f: BatFacts) -> str:
    parts = []
    if rule.applies_to != "all":
        parts.append(f"{rule.applies_to} bats")
    if rule.applies_from_length is not None:
        parts.append(f"bats of {rule.applies_from_length / INCH:g} in or longer")
    if rule.applies_below_length is not None:
        parts.append(f"bats shorter than {rule.applies_below_length / INCH:g} in")
    kind = f.material_class or "of unknown material class"
    return f"applies to {' and '.join(parts)}; this bat is {kind}, {f.length / INCH:.2f} in"


def _clean(text: str | None) -> str:
    return " ".join((text or "").split())


def evaluate_rule(rule: RuleSpec, f: BatFacts, run: RunResult | None = None) -> RuleResult:
    """One rule on one bat. Scope first (not-applicable), then not-modelled, then the check."""
    scope = applies(rule, f)
    common: dict[str, Any] = {"title": _clean(rule.title) or rule.id,
              "applies_to": rule.applies_to, "source": _clean(rule.source),
              "confidence": rule.confidence or "",
              "unit": RULE_KINDS[rule.kind].unit if isinstance(rule.limit, float)
              else ""}
    limit = rule.limit
    if scope is False:
        return RuleResult(rule.id, kind=rule.kind, value=None, limit=limit,
                          verdict="not-applicable", note=_scope_text(rule, f), **common)
    if rule.status == "not-modelled":
        return RuleResult(rule.id, kind=rule.kind, value=None, limit=limit,
                          verdict="not-modelled", note=_clean(rule.reason),
                          protocol=rule.protocol, **common)
    if scope is None:
        return RuleResult(rule.id, kind=rule.kind, value=None, limit=limit,
                          verdict="not-modelled", note=f"applies to {rule.applies_to} bats, "
                          f"but {f.material_class_basis}", **common)
    evaluate = EVALUATIONS[rule.kind]
    assert evaluate is not None  # the league schema refuses a modelled rule of kind 'other'
    out = evaluate(rule, f, run)
    out.title, out.applies_to = common["title"], common["applies_to"]
    out.source, out.confidence = common["source"], common["confidence"]
    out.note = "; ".join(n for n in (out.note, _clean(rule.note)) if n)
    return out


def evaluate_bat(rules: Sequence[RuleSpec], f: BatFacts, runs: dict[str, RunResult],
                 engine_warning: str | None = None) -> BatLeagueResult:
    """All rules on one bat; ``runs`` maps a performance rule's id to its protocol result;
    ``engine_warning``: what the engine's results do not show of a bat
    (:attr:`batcert.engines.base.Engine.construction_warning`), added when a rule ran."""
    results = [evaluate_rule(r, f, runs.get(r.id)) for r in rules]
    warnings = [f"{rid} ({run.protocol}): {w}" for rid, run in runs.items() for w in run.warnings]
    if runs and engine_warning:
        warnings.append(engine_warning)
    facts = {"length": f.length, "mass": f.mass, "drop": f.drop,
             "barrel_diameter": f.barrel_diameter, "min_diameter": f.min_diameter,
             "construction": f.construction, "material": f.material,
             "material_class": f.material_class}
    return BatLeagueResult(f.name, f.path, f.sha256, facts, results, warnings)


def evaluate_league(league: LeagueSpec, bats: Sequence[tuple[BatFacts, dict[str, RunResult]]],
                    engine: str, created: str | None = None,
                    engine_warning: str | None = None) -> LeagueResult:
    """Evaluate a :class:`~batcert.specs.league.LeagueSpec` on several bats (``engine_warning``:
    :func:`evaluate_bat`'s)."""
    return LeagueResult(
        league=league.id, title=league.title, reference=league.reference, version=league.version,
        description=league.description or "", notes=league.notes or "", path=league.path,
        sha256=league.sha256, engine=engine,
        bats=[evaluate_bat(league.rules, f, runs, engine_warning) for f, runs in bats],
        batcert_version=__version__,
        created=created or utc_now())
