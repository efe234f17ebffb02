"""Starting points of a ball fit (:mod:`batcert.physics.balls.fit`), read off the data: the
exponent from how the contact times fall with speed, the stiffness from a time, a force or the
compression, and a few relaxation times around the contact time."""

from __future__ import annotations

from typing import Any

import numpy as np

from batcert.physics.balls.fit_coordinates import theta_of
from batcert.physics.balls.viscoelastic import TwoTimeViscoelastic, Viscoelastic


def starts(tests: tuple[Any, ...], mass: float,
           cls: type[Viscoelastic] = Viscoelastic) -> list[np.ndarray]:
    """Starting points for a fit to ``tests`` (``fit.BallTest``) read off the data: the exponent
    from how the times fall with speed (an elastic power-law spring's contact time goes as
    ``v^(-(a-1)/(a+1))``), the stiffness from a time, a force or the compression, a few
    relaxation times around a fifth of a contact time; for two relaxation times, the slow one
    near the contact time of slow impacts and the fast one a tenth to a third of a fast
    impact's."""
    times = sorted((t.condition, t.value) for t in tests
                   if t.kind in ("collision_time", "contact_time"))
    a = 1.8
    if len(times) >= 2 and times[-1][0] > times[0][0]:
        slope = -np.log(times[-1][1] / times[0][1]) / np.log(times[-1][0] / times[0][0])
        a = float(np.clip((1 + slope) / (1 - slope), 1.2, 2.6)) if slope < 0.9 else 2.6
    k = 6.5e7  # a baseball's order (Nathan 2000's k1)
    t_scale = 1e-3
    if times:
        v, t = times[len(times) // 2]
        t = t / 0.85 if any(x.kind == "collision_time" for x in tests) else t
        # contact_time_estimate = 3 u_m / v = t  ->  u_m = t v / 3  ->  k
        um = t * v / 3.0
        k = (1 + a) * mass * v**2 / (2.0 * um ** (1 + a))
        t_scale = t
    else:
        comp = [x for x in tests if x.kind == "compression"]
        forces = [x for x in tests if x.kind == "peak_force"]
        if comp:
            k = comp[0].value / (0.5 * comp[0].condition) ** a / 0.4
        elif forces:
            v, f = forces[0].condition, forces[0].value
            um = ((1 + a) * mass * v**2 / 2.0 / f) ** 1.0  # F u_m ~ (1+a) E for a power law
            k = f / um**a
    starts = []
    if cls is TwoTimeViscoelastic:
        slow = max(t for _, t in times) if times else t_scale
        fast = min(t for _, t in times) if times else t_scale
        for fast_frac in (0.02, 0.15):
            for share in (0.9, 0.5):
                for r in (0.1, 0.3):
                    law = TwoTimeViscoelastic(k * (2.0 if r == 0.3 else 3.0), a, r, 0.5 * slow,
                                              share, fast_frac * fast)
                    starts.append(theta_of(law))
        return starts
    for tau_frac in (0.2, 0.05, 0.6):
        for r in (0.4, 0.15):
            one = Viscoelastic(k * (1.6 if r == 0.4 else 2.5), a, r, tau_frac * t_scale)
            starts.append(theta_of(one))
    return starts
