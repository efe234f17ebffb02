"""The phi functions of exponential time differencing, shared by the modal stepping
(:mod:`batcert.engines.kernel.march`, complex modal exponents) and the viscoelastic ball's branch
(:mod:`batcert.physics.balls.viscoelastic`, a real relaxation rate)."""

from __future__ import annotations

import numpy as np

_SMALL = 0.5  # below this |z| the Taylor series (30 terms: to rounding), else closed forms


def phi_functions(z):
    """``phi_1``, ``phi_2``, ``phi_3`` of exponential integrators at real or complex ``z``
    [-], of ``z``'s kind.

    ``phi_k(z) = sum_j z^j / (j + k)!``: ``phi_1 = (e^z - 1)/z``, ``phi_2 = (e^z - 1 - z)/z^2``,
    ``phi_3 = (e^z - 1 - z - z^2/2)/z^3`` (Cox & Matthews 2002). Taylor series for
    ``|z| < 0.5`` (no cancellation), closed forms elsewhere (``expm1`` for real ``z``).
    """
    z = np.asarray(z)
    z = z.astype(complex if np.iscomplexobj(z) else float)
    small = np.abs(z) < _SMALL
    zs = np.where(small, z, 0.0)
    series = []
    for k in (1, 2, 3):
        total = np.zeros_like(z)
        term = np.full_like(z, 1.0 / np.prod(np.arange(1, k + 1)))
        for j in range(1, 30):
            total += term
            term = term * zs / (j + k)
        series.append(total)
    zb = np.where(small, 1.0, z)
    em1 = np.exp(zb) - 1 if np.iscomplexobj(z) else np.expm1(zb)
    closed = [em1 / zb, (em1 - zb) / zb**2, (em1 - zb - zb**2 / 2) / zb**3]
    return tuple(np.where(small, s, c) for s, c in zip(series, closed, strict=True))
