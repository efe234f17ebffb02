"""The barrel's share of a hollow bat's uncertainty: the range of a protocol's result over the
plausible barrel when no measurement calibrates it.

A hollow bat's barrel comes from its wall, profile and material. When the bat file gives
neither a measured hoop frequency nor a barrel compression test, the wall is the file's
nominal one and the result carries the range over a barrel stiffness scale of x0.8 to x1.25
(about a tenth either way on the hoop frequency: a wall known to about a tenth of its
thickness, the tolerance and construction details, such as inserts and double walls, that a
spec file does not state; an assumption, not a published figure) and a wall loss factor from
1e-4 (bare aluminium, Cremer & Heckl, *Structure-Borne Sound*, 1988, as tabulated by Irvine,
"Damping properties of materials", 2004) to 1e-2 (a heavily damped wall: grip, cap and
coatings; single-wall aluminium bats ring with Q of about 1000-3000, Russell, M). The impact
points stay those the protocol located for the nominal barrel. The general treatment of input
uncertainty is a later, separate capability; this is the barrel's share.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from batcert.results.run import BarrelRange

if TYPE_CHECKING:
    from batcert.methods.metrics import Aggregate, Metric
    from batcert.runner.bench import Bench
    from batcert.runner.conditions import Condition
    from batcert.specs.protocol import LimitSpec

PLAUSIBLE_STIFFNESS = (0.8, 1.25)  # barrel stiffness scales explored [-]
PLAUSIBLE_LOSS = (1e-4, 1e-2)  # wall loss factors explored [-]


def barrel_range_steps(bench: Bench, conds: list[Condition], locations: np.ndarray,
                       metric: Metric, aggregate: Aggregate, limit: LimitSpec | None):
    """The barrel's calibration, or the result's range over the plausible barrel; None for a
    solid bat or an engine without a barrel (rigid). A generator: it yields the variants'
    requests once (an empty list when there are none), is sent their results, and returns
    the :class:`BarrelRange`."""
    built = bench.built
    model = built.model
    if model.construction != "hollow" or not bench.engine.models_barrel:
        yield []
        return None
    from batcert.physics import barrel  # scipy: hollow bats only
    hoop = barrel.hoop_frequency(model)
    measured = built.spec.measured
    measured_hoop = measured.hoop_frequency if measured else None
    compression = measured.barrel_compression if measured else None
    if measured_hoop is not None or compression is not None:
        yield []
        parts = []
        if compression is not None:
            parts.append("a barrel compression test")
        if measured_hoop is not None:
            parts.append(f"a measured hoop frequency of {measured_hoop:.0f} Hz")
        return BarrelRange(True, "calibrated to " + " and ".join(parts), float(hoop or 0.0),
                           measured_hoop, [], [], None, None, [])
    variants = [replace(model, barrel_stiffness_scale=model.barrel_stiffness_scale * s)
                for s in PLAUSIBLE_STIFFNESS]
    variants += [replace(model, material=replace(model.material, loss_factor=eta))
                 for eta in PLAUSIBLE_LOSS]
    answers = yield [replace(bench, built=replace(built, model=v)).request(
        conds, locations[:, None]) for v in variants]
    values = [aggregate.combine(metric.value(final)[:, 0]) for final, _ in answers]
    verdicts = []
    if limit is not None:
        verdicts = sorted({"pass" if limit.max + limit.tolerance - v >= 0 else "fail"
                           for v in values})
    basis = (f"not calibrated by a measurement: range over a barrel stiffness x"
             f"{PLAUSIBLE_STIFFNESS[0]:g}-x{PLAUSIBLE_STIFFNESS[1]:g} and a wall loss factor "
             f"{PLAUSIBLE_LOSS[0]:g}-{PLAUSIBLE_LOSS[1]:g} (hoop frequency "
             f"{hoop * np.sqrt(PLAUSIBLE_STIFFNESS[0]):.0f}-"
             f"{hoop * np.sqrt(PLAUSIBLE_STIFFNESS[1]):.0f} Hz)")
    return BarrelRange(False, basis, float(hoop or 0.0), None, list(PLAUSIBLE_STIFFNESS),
                       list(PLAUSIBLE_LOSS), float(min(values)), float(max(values)), verdicts)
