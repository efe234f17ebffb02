"""The element quadrature, written out (batcert.physics.quadrature), is numpy's Gauss-Legendre."""

import numpy as np

from batcert.physics.quadrature import GAUSS_POINTS, GAUSS_WEIGHTS


def test_the_written_out_rule_is_numpys_leggauss_mapped_to_0_1():
    # bit for bit: the element matrices stay exactly what they were with numpy's rule
    x, w = np.polynomial.legendre.leggauss(4)
    np.testing.assert_array_equal(GAUSS_POINTS, 0.5 * (x + 1.0))
    np.testing.assert_array_equal(GAUSS_WEIGHTS, 0.5 * w)


def test_the_rule_integrates_polynomials_to_degree_7_exactly():
    # int_0^1 s^k ds = 1 / (k + 1) for k <= 7 (to rounding); degree 8 is not exact
    for k in range(8):
        assert abs((GAUSS_WEIGHTS * GAUSS_POINTS**k).sum() - 1.0 / (k + 1)) < 1e-15
    assert abs((GAUSS_WEIGHTS * GAUSS_POINTS**8).sum() - 1.0 / 9) > 1e-6
