"""The element quadrature of the beam and the shell: 4-point Gauss-Legendre on [0, 1].

Exact for polynomials to degree 7, enough for the products of cubic Hermite functions in the
element matrices. The nodes and weights are those of ``numpy.polynomial.legendre.leggauss(4)``
(Abramowitz & Stegun Table 25.4: ``+-0.339981``, ``+-0.861136``; weights ``0.652145``,
``0.347855``), written out so that a run does not import ``numpy.polynomial`` (5 ms).
"""

from __future__ import annotations

import numpy as np

_NODES = np.array([-0.8611363115940526, -0.33998104358485626, 0.33998104358485626,
                   0.8611363115940526])  # on [-1, 1]
_WEIGHTS = np.array([0.34785484513745357, 0.6521451548625464, 0.6521451548625464,
                     0.34785484513745357])
GAUSS_POINTS = 0.5 * (_NODES + 1.0)  # on [0, 1]
GAUSS_WEIGHTS = 0.5 * _WEIGHTS  # on [0, 1], summing to 1
