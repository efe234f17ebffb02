"""The ball's fit kept by the active workspace (:mod:`batcert.workspace`): a fit takes about a
second, and a ball file is read by every run. The fit itself is :mod:`batcert.physics.balls.fit`.
"""

from __future__ import annotations

import numpy as np

from batcert import workspace
from batcert.physics.balls.fit import FITTED, BallFit, BallTest, Fixed, fit_ball
from batcert.physics.balls.viscoelastic import Viscoelastic


def cached_fit(tests: tuple[BallTest, ...], mass: float, radius: float,
               fixed: Fixed = (), law: str = Viscoelastic.name) -> BallFit:
    """:func:`fit_ball`, kept by the active workspace (kind ``ball-fit``, also in its disk
    store where one is attached): a fit takes a second or more, a ball file is read by every
    run."""
    tests = tuple(tests)
    fixed = tuple((str(k), float(v)) for k, v in fixed)
    cls = FITTED[law]
    return workspace.current().call("ball-fit", _fit, tests, float(mass), float(radius), fixed,
                                    law, save=_fit_arrays,
                                    load=lambda a: _fit_from(a, tests, cls))


def _fit(tests: tuple[BallTest, ...], mass: float, radius: float, fixed: Fixed,
         law: str) -> BallFit:
    return fit_ball(tests, mass, radius, fixed, law)


def _fit_arrays(f: BallFit) -> dict:
    names = f.law.PARAMETERS
    return {"law": np.array([getattr(f.law, p) for p in names]), "model": np.array(f.model),
            "residuals": np.array(f.residuals), "chi2": np.array([f.chi2, f.dof]),
            "uncertainty": np.array([f.uncertainty[p] for p in names]),
            "direction": np.array(f.lot_direction),
            "held": np.array([p in f.held for p in names])}


def _fit_from(a: dict, tests: tuple[BallTest, ...], cls: type[Viscoelastic]) -> BallFit | None:
    names = cls.PARAMETERS
    if len(a["model"]) != len(tests) or len(a["law"]) != len(names):
        return None
    law = cls(*(float(x) for x in a["law"]))
    return BallFit(law, tests, tuple(float(x) for x in a["model"]),
                   tuple(float(x) for x in a["residuals"]), float(a["chi2"][0]),
                   int(a["chi2"][1]), dict(zip(names, (float(x) for x in a["uncertainty"]),
                                               strict=True)),
                   tuple(float(x) for x in a["direction"]),
                   tuple(p for p, h in zip(names, a["held"], strict=True) if h))
