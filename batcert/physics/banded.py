r"""Banded symmetric matrices: band storage and the band of an inverse.

A barrel's shell problem (:mod:`batcert.physics.shell`) is banded: each node couples only to
its neighbours, so its stiffness has a half-bandwidth of ``2 d - 1`` for ``d`` unknowns per
node. The engine needs the static flexibility ``K^-1`` only between unknowns that one contact
patch can load together, a band of the inverse around its diagonal
(:func:`batcert.physics.barrel.cached_barrel_modes`). That band follows from the Cholesky factor
``K = L L^T`` without the rest of the inverse (Takahashi, Fagan & Chen, "Formation of a sparse
bus impedance matrix and its application to short circuit study", 8th PICA Conference, 1973;
Erisman & Tinney, Commun. ACM 18 (1975) 177): ``Z = K^-1`` satisfies ``L^T Z = L^-1``, whose
upper triangle is zero apart from its diagonal ``1 / L_ii``, so, row by row from the last,

    Z_ij = -sum_{k = i+1}^{i+b} (L_ki / L_ii) Z_kj                         (j > i)
    Z_ii = 1 / L_ii^2 - sum_{k = i+1}^{i+b} (L_ki / L_ii) Z_ki

and every ``Z_kj`` these read lies within the band being computed. Cost: ``n b w`` for a band
of half-width ``w``, against ``n^2 b`` for the whole inverse.

Pure numpy; several matrices of the same size and bandwidth are done together.
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import as_strided


def lower_band(a: np.ndarray, bandwidth: int) -> np.ndarray:
    """Lower band storage of symmetric ``a`` (..., n, n): ``ab[..., k, i] = a[..., i + k, i]``
    for ``k = 0..bandwidth`` (zero past the end), the layout of LAPACK's ``?pbtrf`` with
    ``uplo = 'L'`` and of ``scipy.linalg.cholesky_banded(..., lower=True)``."""
    n = a.shape[-1]
    ab = np.zeros(a.shape[:-2] + (bandwidth + 1, n))
    for k in range(bandwidth + 1):
        ab[..., k, :n - k] = np.diagonal(a, -k, axis1=-2, axis2=-1)
    return ab


def inverse_band(factor: np.ndarray, width: int) -> np.ndarray:
    """The band of ``K^-1`` for each lower banded Cholesky factor in ``factor``.

    Parameters
    ----------
    factor : numpy.ndarray
        Lower band storage of ``L`` (``K = L L^T``), ``factor[o, k, i] = L[i + k, i]``,
        shape (o, b + 1, n), for ``o`` matrices of size ``n`` and half-bandwidth ``b``.
    width : int
        Half-width of the band of the inverse wanted, at least ``b``.

    Returns
    -------
    numpy.ndarray
        ``z[o, i, b + d] = K^-1[i, i + d]`` for ``d = -b..width``, shape (o, n, b + width + 1);
        entries past the matrix's end are zero.
    """
    o, b1, n = factor.shape
    b = b1 - 1
    if width < b:
        raise ValueError(f"the band of the inverse ({width}) must be at least the matrix's ({b})")
    # rows i..n+width of the band of each matrix; a row is one matrix product per matrix
    band = np.zeros((o, n + width + 1, b + width + 1))
    ratio = np.ascontiguousarray((factor[:, 1:, :] / factor[:, None, 0, :]).transpose(2, 0, 1))
    inv_square = 1.0 / factor[:, 0, :] ** 2  # (o, n)
    s_o, s_row, s_col = band.strides
    below = np.arange(1, b + 1)
    for i in range(n - 1, -1, -1):
        lk = ratio[i]  # (o, b): L[i + 1 + k, i] / L[i, i]
        # Z[i + 1 + k, i + 1 + w] (row i + 1 + k, column w - k + b): a strided view of the
        # rows below, no copy
        below_rows = as_strided(band[:, i + 1, b:], shape=(o, b, width),
                                strides=(s_o, s_row - s_col, s_col))
        row = -np.matmul(lk[:, None, :], below_rows)[:, 0, :]  # Z[i, i+1 .. i+width]
        band[:, i, b + 1:] = row
        band[:, i + below, b - below] = row[:, :b]  # Z[i + k, i] = Z[i, i + k]
        band[:, i, b] = inv_square[:, i] - (lk * row[:, :b]).sum(axis=1)
    return np.ascontiguousarray(band[:, :n])
