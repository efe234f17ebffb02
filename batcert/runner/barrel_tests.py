"""The barrel compression test and the accelerated break-in (ABI) of a composite barrel, as a
protocol runs them (:mod:`batcert.runner.runner`) and as a lab reduces a measured one.

Compression: the force on one flat platen when two opposite platens, ``platen_width`` long,
centred ``position`` from the tip, have approached by ``deflection``; the barrel is linear
(:func:`batcert.physics.barrel.compression_stiffness`), so the force is the stiffness times the
deflection.

ABI (NCAA; the steps as issue 26 states them, the NCAA document itself not read, see
docs/physics.md): the initial compression is measured; if it has already fallen by more than
``skip_drop`` of the new bat's, the bat is not rolled (a model is of a new bat, so only a
measured history, :func:`measured_history`, can be skipped); else it is rolled pass by pass, the
compression read after each, until it has fallen by at least ``target_drop`` of the initial;
then the performance test. A pass is emulated as ``damage_per_pass`` more damage of the plies'
matrix-dominated moduli (:func:`batcert.model.break_in.broken_in_model`): an assumption, as no
measured relation between rolling and damage was found. The first :data:`ONE_BY_ONE` passes are
read one by one; a protocol that allows more (``max_passes``, up to 10,000, with a tiny damage per
pass: minutes of readings) has the first pass that reaches the target found by bisection over the
passes after them (the compression falls with every pass), at most ``max_passes``, and the
record's outcome says which passes were read.
"""

from __future__ import annotations

from dataclasses import dataclass
from math import ceil

from batcert.model.break_in import breaks_in, broken_in_model
from batcert.physics.barrel import compression_stiffness
from batcert.physics.batmodel import BatModel
from batcert.results.run import BreakInResult, BreakInStep, CompressionResult
from batcert.specs.barrel_tests import BreakInSpec, CompressionTestSpec

ONE_BY_ONE = 100  # passes read one by one (a reading: about 0.1 s); after them, a bisection


def compression(model: BatModel, test: CompressionTestSpec) -> CompressionResult:
    """The barrel compression test on ``model`` (module notes), with its verdict against the
    test's ``min`` where one is given."""
    try:
        k = compression_stiffness(model, model.length - test.position, test.platen_width)
    except ValueError as exc:
        raise ValueError(f"barrel compression test: {exc}") from None
    force = k * test.deflection
    margin = None if test.min is None else force - test.min
    verdict = None if margin is None else ("pass" if margin >= 0 else "fail")
    return CompressionResult(test.position, test.platen_width, test.deflection, force, k,
                             test.min, margin, verdict, test.source or "")


@dataclass(frozen=True)
class Emulated:
    """An emulated ABI: its record, and the bat after it (the bat before, if not rolled)."""

    record: BreakInResult
    model: BatModel
    compression: CompressionResult  # the compression test on ``model``


def emulate(model: BatModel, test: CompressionTestSpec, rule: BreakInSpec) -> Emulated:
    """The ABI on ``model`` (module notes). A bat whose plies do not break in (a metal wall)
    is not rolled, and its record says so."""
    if model.wall_damage != 0.0:
        raise ValueError("the break-in is emulated on a new bat")
    new = compression(model, test)
    initial = new.force
    steps = [BreakInStep(0, 0.0, initial, 0.0)]
    if not breaks_in(model, model.length - test.position):
        return Emulated(_record(rule, False, "the barrel's wall under the platens has no ply "
                                "that breaks in (not a composite barrel): the ABI does not "
                                "apply", steps, False), model, new)
    # a model is of a new bat, whose compression has not fallen: the skip rule acts on measured
    # histories (measured_history)
    # the last pass that may be rolled: the protocol's limit, and a damage below 1
    last = min(rule.max_passes, ceil(1.0 / rule.damage_per_pass))
    while last * rule.damage_per_pass >= 1.0:
        last -= 1
    for n in range(1, min(last, ONE_BY_ONE) + 1):
        rolled, after = _roll(model, test, rule, n, initial, steps)
        if after.force <= (1.0 - rule.target_drop) * initial:
            return Emulated(_record(rule, True, f"rolled {n} passes until the compression "
                                    f"fell {100 * steps[-1].drop:.2f} % (target "
                                    f"{100 * rule.target_drop:g} %)", steps, False), rolled,
                            after)
    if last > ONE_BY_ONE:
        return _bisect(model, test, rule, initial, steps, last)
    raise _not_reached(rule, steps)


def _roll(model: BatModel, test: CompressionTestSpec, rule: BreakInSpec, n: int, initial: float,
          steps: list[BreakInStep]) -> tuple[BatModel, CompressionResult]:
    """The bat after ``n`` passes and its compression, the reading added to ``steps``."""
    damage = n * rule.damage_per_pass
    rolled = broken_in_model(model, damage)
    after = compression(rolled, test)
    steps.append(BreakInStep(n, damage, after.force, 1.0 - after.force / initial))
    return rolled, after


def _bisect(model: BatModel, test: CompressionTestSpec, rule: BreakInSpec, initial: float,
            steps: list[BreakInStep], last: int) -> Emulated:
    """The first pass after :data:`ONE_BY_ONE` that reaches the target, at most ``last``, by
    bisection (the compression falls with every pass): a few readings instead of thousands;
    the readings are the record's steps, in pass order."""
    probes: list[BreakInStep] = []
    lo, (hi, found) = ONE_BY_ONE, (last, _roll(model, test, rule, last, initial, probes))
    if probes[-1].drop < rule.target_drop:
        raise _not_reached(rule, steps + probes)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        rolled, after = _roll(model, test, rule, mid, initial, probes)
        if after.force <= (1.0 - rule.target_drop) * initial:
            hi, found = mid, (rolled, after)
        else:
            lo = mid
    steps += sorted((s for s in probes if s.passes <= hi), key=lambda s: s.passes)
    outcome = (f"rolled {hi} passes until the compression fell {100 * steps[-1].drop:.2f} % "
               f"(target {100 * rule.target_drop:g} %); read one by one up to pass "
               f"{ONE_BY_ONE}, then the first pass to reach the target found by bisection "
               f"({len(probes)} readings, the protocol's limit {rule.max_passes} passes)")
    return Emulated(_record(rule, True, outcome, steps, False), *found)


def _not_reached(rule: BreakInSpec, steps: list[BreakInStep]) -> ValueError:
    return ValueError(f"the emulated break-in did not lower the barrel's compression by "
                      f"{100 * rule.target_drop:g} % within {steps[-1].passes} passes (last "
                      f"{100 * steps[-1].drop:.2f} %): its plies' matrix moduli carry too "
                      "little of the barrel's compression stiffness")


def _record(rule: BreakInSpec, applies: bool, outcome: str, steps: list[BreakInStep],
            skipped: bool, measured: bool = False) -> BreakInResult:
    return BreakInResult(applies=applies, skipped=skipped, outcome=outcome,
                         steps=steps, target_drop=rule.target_drop, skip_drop=rule.skip_drop,
                         damage_per_pass=rule.damage_per_pass, source=rule.source or "",
                         measured=measured)


def measured_history(forces: list[float], new_force: float | None,
                     rule: BreakInSpec) -> BreakInResult:
    """A lab's measured ABI: the compression before rolling and after each pass [N], and the
    new bat's where known; checked against the rule (skip, or a final drop of at least
    ``target_drop``)."""
    if not forces:
        raise ValueError("a measured break-in needs at least the initial compression")
    initial = forces[0]
    steps = [BreakInStep(i, None, f, 1.0 - f / initial) for i, f in enumerate(forces)]
    if new_force is not None and 1.0 - initial / new_force > rule.skip_drop:
        outcome = (f"compression already {100 * (1 - initial / new_force):.1f} % below the new "
                   "bat's: rolling skipped (skip rule)")
        return _record(rule, True, outcome, steps, True, measured=True)
    drop = steps[-1].drop
    if drop < rule.target_drop:
        outcome = (f"the last reading is {100 * drop:.2f} % below the initial: the procedure "
                   f"needs at least {100 * rule.target_drop:g} %, so the break-in is incomplete")
    else:
        outcome = f"rolled {len(forces) - 1} passes; compression fell {100 * drop:.2f} %"
    return _record(rule, True, outcome, steps, False, measured=True)

