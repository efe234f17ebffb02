"""Unit tests of the modes' coupling to the ball over its compression
(batcert.engines.kernel.coupling): the tabulated group factors, the stacking of several systems'
groups, and the compression's extrapolation over a step."""

from __future__ import annotations

import numpy as np
import pytest

from batcert.engines.kernel.coupling import Coupling, extrapolate, stack

LABELS = ("beam", ("shell", 2), "residual")


def coupling(rows: int = 2, points: int = 5, first_start: int = 0) -> Coupling:
    """Three groups (3 beam, 2 shell-order-2 and 1 residual columns); row ``i``'s factor of
    group ``g`` at point ``k`` is ``1 + (i + 1) (g + 1) (0.1 k + 0.02 k^2)`` (points 0.5 mm
    apart in row 0, 1 mm in row 1...): distinct per row, group and segment."""
    k = np.arange(points)
    table = np.array([[1.0 + (i + 1) * (g + 1) * (0.1 * k + 0.02 * k**2) for g in range(3)]
                      for i in range(rows)])
    spacing = 5e-4 * (1 + np.arange(rows))
    return Coupling(LABELS, (0, 3, 5, 6), table, spacing)


def test_at_is_the_table_at_its_points():
    c = coupling()
    for k in range(5):
        np.testing.assert_array_equal(c.at(k * c.spacing), c.table[:, :, k])
    assert c.size == 3


def test_at_interpolates_linearly_between_points():
    c = coupling()
    # a quarter and two thirds of the way through segments 1 and 2 of rows 0 and 1
    u = np.array([1.25, 2 + 2 / 3]) * c.spacing
    lo = np.stack([c.table[0, :, 1], c.table[1, :, 2]])
    hi = np.stack([c.table[0, :, 2], c.table[1, :, 3]])
    t = np.array([0.25, 2 / 3])[:, None]
    np.testing.assert_allclose(c.at(u), lo + t * (hi - lo), rtol=1e-14)  # rounding of u / spacing
    # linear in u within a segment: the midpoint of two points is their mean
    a, b = c.at(np.array([1.1, 2.2]) * c.spacing), c.at(np.array([1.9, 2.8]) * c.spacing)
    np.testing.assert_allclose(c.at(np.array([1.5, 2.5]) * c.spacing), 0.5 * (a + b), rtol=1e-14)


def test_at_holds_beyond_the_table():
    c = coupling()
    np.testing.assert_array_equal(c.at(np.array([4.0, 4.0]) * c.spacing), c.table[:, :, -1])
    np.testing.assert_array_equal(c.at(np.array([7.3, 100.0]) * c.spacing), c.table[:, :, -1])
    # a negative compression (no contact) reads the first point
    np.testing.assert_array_equal(c.at(np.array([-1e-3, -1.0])), c.table[:, :, 0])


def test_slope_is_the_segments_slope():
    c = coupling()
    for k in range(4):
        for frac in (0.0, 0.3, 0.99):
            u = (k + frac) * c.spacing
            expected = (c.table[:, :, k + 1] - c.table[:, :, k]) / c.spacing[:, None]
            np.testing.assert_allclose(c.slope(u), expected, rtol=1e-14)
    # the slope is the derivative of `at` inside a segment (central difference of a line)
    u, du = 1.4 * c.spacing, 1e-3 * c.spacing
    fd = (c.at(u + du) - c.at(u - du)) / (2 * du[:, None])
    np.testing.assert_allclose(c.slope(u), fd, rtol=1e-9)  # rounding of the difference


def test_rows_keeps_rows():
    c = coupling(rows=4)
    kept = c.rows(np.array([3, 1]))
    assert kept.labels == c.labels and kept.starts == c.starts
    np.testing.assert_array_equal(kept.table, c.table[[3, 1]])
    np.testing.assert_array_equal(kept.spacing, c.spacing[[3, 1]])
    u = np.array([0.7, 2.5, 1.1, 3.9]) * c.spacing
    np.testing.assert_array_equal(kept.at(u[[3, 1]]), c.at(u)[[3, 1]])
    # a mask and a slice too
    np.testing.assert_array_equal(c.rows(np.array([True, False, True, False])).table,
                                  c.table[[0, 2]])
    assert c.rows(slice(1, 3)).table.shape == (2, 3, 5)


def test_stack_aligns_groups_by_label():
    # system 1: the three groups, 2 rows, 5 points; system 2: beam (2 columns) and shell order
    # 3 (4 columns), 1 row, 6 points; system 3: no coupling, 4 columns, 3 rows
    one = coupling(rows=2, points=5)
    table2 = np.stack([np.full((1, 6), 2.0), np.linspace(1.0, 0.5, 6)[None, :]], axis=1)
    two = Coupling(("beam", ("shell", 3)), (0, 2, 6), table2, np.array([2e-3]))
    got, cols = stack([one, None, two], [6, 4, 6], [2, 3, 1])
    # the union of labels, beam first, shell orders ascending, residual last; each group as
    # wide as its widest: beam 4 (the uncoupled system), shell 2: 2, shell 3: 4, residual 1
    assert got.labels == ("beam", ("shell", 2), ("shell", 3), "residual")
    assert got.starts == (0, 4, 6, 10, 11)
    np.testing.assert_array_equal(cols[0], [0, 1, 2, 4, 5, 10])
    np.testing.assert_array_equal(cols[1], [0, 1, 2, 3])
    np.testing.assert_array_equal(cols[2], [0, 1, 6, 7, 8, 9])
    # rows in the systems' order; the longest table's points, shorter ones held at their end
    assert got.table.shape == (6, 4, 6)
    np.testing.assert_array_equal(got.spacing, [5e-4, 1e-3, 1.0, 1.0, 1.0, 2e-3])
    np.testing.assert_array_equal(got.table[:2, [0, 1, 3], :5], one.table)
    np.testing.assert_array_equal(got.table[:2, [0, 1, 3], 5], one.table[:, :, -1])
    np.testing.assert_array_equal(got.table[:2, 2], 1.0)  # no shell order 3 in system 1
    np.testing.assert_array_equal(got.table[2:5], 1.0)  # no coupling: factors of one
    np.testing.assert_array_equal(got.table[5, [0, 2]], two.table[0])
    np.testing.assert_array_equal(got.table[5, [1, 3]], 1.0)
    # the stacked coupling reads each system's factors in its own groups
    u = np.array([1e-3, 3e-4, 0.5, 2.0, 7.0, 5e-3])
    rho = got.at(u)
    np.testing.assert_allclose(rho[:2][:, [0, 1, 3]], one.at(u[:2]), rtol=1e-14)
    np.testing.assert_allclose(rho[5, [0, 2]], two.at(u[5:])[0], rtol=1e-14)
    np.testing.assert_array_equal(rho[2:5], 1.0)


def test_stack_keeps_a_systems_column_order():
    # groups given in another column order (residual first) keep their columns' places
    table = np.ones((1, 2, 3))
    c = Coupling(("residual", "beam"), (0, 1, 4), table, np.array([1e-3]))
    got, cols = stack([c], [4], [1])
    assert got.labels == ("beam", "residual") and got.starts == (0, 3, 4)
    np.testing.assert_array_equal(cols[0], [3, 0, 1, 2])


def test_stack_without_coupling():
    got, cols = stack([None, None], [3, 5], [2, 1])
    assert got is None
    # one beam group as wide as the widest system; each system's columns from the start
    np.testing.assert_array_equal(cols[0], [0, 1, 2])
    np.testing.assert_array_equal(cols[1], [0, 1, 2, 3, 4])


def cubic(t, c):
    return c[0] + c[1] * t + c[2] * t**2 + c[3] * t**3


def dcubic(t, c):
    return c[1] + 2 * c[2] * t + 3 * c[3] * t**2


@pytest.mark.parametrize("h", [1e-7, 3.8e-6, 1e-3])
def test_extrapolate_is_exact_for_cubics(h):
    # the cubic Hermite interpolant of a cubic's values and rates at t = -h and 0 is the cubic
    # itself, so half and whole a step ahead are exact to rounding: random cubics whose terms
    # are each up to 1e-2 m over |t| <= h on top of 5e-2 m (positive: no clipping); the whole
    # step's weights (5, 2, -4, 4) amplify rounding to ~15 eps of 5e-2 m (measured <= 6e-17 m)
    rng = np.random.default_rng(7)
    scale = np.array([5e-2, 1e-2 / h, 1e-2 / h**2, 1e-2 / h**3])[:, None]
    c = scale * np.vstack([np.ones(50), rng.uniform(-1.0, 1.0, (3, 50))])
    half, whole = extrapolate(cubic(-h, c), dcubic(-h, c), cubic(0.0, c), dcubic(0.0, c), h)
    np.testing.assert_allclose(half, cubic(0.5 * h, c), rtol=0, atol=1e-15)
    np.testing.assert_allclose(whole, cubic(h, c), rtol=0, atol=1e-15)
    # a quartic is not extrapolated exactly (the rule is cubic)
    q = lambda t: 5e-2 + 1e-2 * (t / h) ** 4  # noqa: E731
    dq = lambda t: 4e-2 * t**3 / h**4  # noqa: E731
    _, whole = extrapolate(q(-h), dq(-h), q(0.0), dq(0.0), h)
    assert abs(whole - q(h)) > 1e-3


def test_extrapolate_of_lower_degrees():
    h = 2e-6
    for c in ([3e-3, 0, 0, 0], [3e-3, 10.0, 0, 0], [3e-3, 10.0, -2e6, 0]):
        c = np.array(c, dtype=float)[:, None]
        half, whole = extrapolate(cubic(-h, c), dcubic(-h, c), cubic(0.0, c), dcubic(0.0, c), h)
        np.testing.assert_allclose(half, cubic(h / 2, c), rtol=1e-13)
        np.testing.assert_allclose(whole, cubic(h, c), rtol=1e-13)


def test_extrapolate_clips_at_zero():
    # a ball leaving fast: the compression continued past zero is held at zero
    h = 1e-5
    u_prev, du_prev, u, du = (np.array([2e-4]), np.array([-20.0]), np.array([1e-5]),
                              np.array([-20.0]))
    half, whole = extrapolate(u_prev, du_prev, u, du, h)
    # the line u = 1e-5 - 20 t would give 1e-5 - 1e-4 < 0 and 1e-5 - 2e-4 < 0
    assert half[0] == 0.0 and whole[0] == 0.0
    # positive continuations are untouched
    half, whole = extrapolate(np.array([1e-3]), np.array([0.0]), np.array([1e-3]), np.array([0.0]), h)
    assert half[0] == pytest.approx(1e-3, rel=1e-14) and whole[0] == pytest.approx(1e-3, rel=1e-14)
