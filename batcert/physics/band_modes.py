r"""The modes below a cut of a banded generalized eigenproblem ``K x = lam M x`` (a barrel
shell's order, :mod:`batcert.physics.shell`) without a dense eigen-solve.

A wall of 87 nodes has 431 unknowns per order and half-bandwidth 9, and the engine wants the
few modes below a frequency cut (1 to 21 of them). The dense solve reduces the whole matrix
to tridiagonal form (``4/3 n^3``, about 11 ms an order); here:

- **How many** (:func:`count_below`): Sylvester's law of inertia, the number of eigenvalues
  below ``lam`` is the number of negative eigenvalues of ``K - lam M``, read from its block
  ``L D L^T`` factorisation over the nodes (the matrix is block tridiagonal: an element joins
  two nodes). This is the Sturm sequence check of finite-element eigen-solvers (Bathe, *Finite
  Element Procedures*, 1996, Sec. 11.4.3), no pivoting, ``n d^2`` work.
- **Which** (:func:`lowest_modes`): Lanczos on the shifted and inverted operator
  ``(K - sigma M)^-1 M`` in the ``M`` inner product, with full reorthogonalisation (Ericsson &
  Ruhe, Math. Comp. 35 (1980) 1251; Parlett, *The Symmetric Eigenvalue Problem*, 1998,
  ch. 13), the shifted matrix factored once in band form (LAPACK ``dpbtrf``). The extreme
  eigenvalues of the inverse, the lowest of the problem, converge first; the iteration stops
  when as many Ritz values as the count lie below the cut, each with a residual under
  :data:`TOLERANCE` of its value.

Anything that does not settle (a count the iteration does not reach, a singular block at the
cut) is left to the caller's dense solve (None). tests/physics/test_band_modes.py holds the
frequencies and shapes to the dense solve's.
"""

from __future__ import annotations

import numpy as np

TOLERANCE = 1e-12  # a Ritz pair's residual relative to its value at which it is taken
SEED = 20_011  # the start vector's random seed (any fixed number: the modes are reproducible)
# nodes per step of the count's block factorisation (measured on aluminium-34's wall: 1, 4,
# 8, 12 nodes 12, 6, 10, 10 ms for its six orders)
GROUP_NODES = 4
CHECK_EVERY = 4  # Lanczos steps between convergence checks (each an eigen-solve of the tridiagonal)


def count_below(shifted: np.ndarray, free: np.ndarray, node_dofs: int, n_nodes: int
                ) -> int | None:
    """The number of negative eigenvalues of the symmetric ``shifted`` (``K - lam M`` on the
    free dofs ``free`` of ``n_nodes`` nodes of ``node_dofs`` unknowns each, coupled between
    neighbouring nodes only); None if a pivot block is singular (``lam`` an eigenvalue, to
    rounding). The factorisation runs over groups of :data:`GROUP_NODES` nodes (still block
    tridiagonal: fewer, larger steps)."""
    a = np.asarray(shifted, dtype=float)
    group = (np.asarray(free) // node_dofs) // GROUP_NODES  # each free unknown's group
    bounds = np.searchsorted(group, np.arange(-(-n_nodes // GROUP_NODES) + 1))
    negative = 0
    d = a[bounds[0]:bounds[1], bounds[0]:bounds[1]]
    try:
        for lo, mid, hi in zip(bounds[:-2], bounds[1:-1], bounds[2:], strict=True):
            negative += int((np.linalg.eigvalsh(d) < 0).sum())
            c = a[lo:mid, mid:hi]  # the coupling of this group to the next
            d = a[mid:hi, mid:hi] - c.T @ np.linalg.solve(d, c)
            d = 0.5 * (d + d.T)
    except np.linalg.LinAlgError:
        return None
    return negative + int((np.linalg.eigvalsh(d) < 0).sum())


def lowest_modes(k: np.ndarray, m: np.ndarray, cut: float, bandwidth: int, count: int
                 ) -> tuple[np.ndarray, np.ndarray] | None:
    """The ``count`` eigenpairs of ``k x = lam m x`` below ``cut`` [the eigenvalue's unit]:
    ``lam`` ascending, (count,), and mass-normalised vectors, (m, count); ``k`` and ``m``
    symmetric with half-bandwidth ``bandwidth``, ``m`` positive definite. None if the
    iteration does not find them (module notes)."""
    import scipy.linalg  # hollow bats only, as the dense solve it replaces

    n = k.shape[0]
    sigma = -0.01 * cut  # below every eigenvalue (a free order's rigid mode is at 0)
    try:
        factor = scipy.linalg.cholesky_banded(_upper_band(k - sigma * m, bandwidth),
                                              check_finite=False)
    except np.linalg.LinAlgError:
        return None
    solve = scipy.linalg.lapack.dpbtrs
    least = 1.0 / (cut - sigma)  # the inverse's eigenvalues above this are wanted
    steps = min(n, 4 * count + 40)
    q_all, mq_all = np.zeros((n, steps)), np.zeros((n, steps))
    alpha, beta = np.zeros(steps), np.zeros(steps)
    r = np.random.default_rng(SEED).standard_normal(n)
    mr = m @ r
    norm = float(np.sqrt(r @ mr))
    for j in range(steps):
        q, mq = r / norm, mr / norm
        q_all[:, j], mq_all[:, j] = q, mq
        solved, info = solve(factor, mq[:, None])  # LAPACK dpbtrs (the wrapper checks cost more)
        if info:
            return None
        w = solved[:, 0]
        alpha[j] = w @ mq
        w -= alpha[j] * q + (beta[j - 1] * q_all[:, j - 1] if j else 0.0)
        for _ in range(2):  # full reorthogonalisation, twice (Parlett 1998, Sec. 6.9)
            w -= q_all[:, :j + 1] @ (mq_all[:, :j + 1].T @ w)
        mr = m @ w
        norm = beta[j] = float(np.sqrt(max(w @ mr, 0.0)))
        r = w
        if norm == 0.0:  # an invariant subspace: the next step would divide by zero
            steps = j + 1
        elif j + 1 < count or (j + 1 - count) % CHECK_EVERY and j + 1 < steps:
            continue
        theta, s = scipy.linalg.eigh_tridiagonal(alpha[:j + 1], beta[:j], check_finite=False)
        wanted = theta >= least
        residual = np.abs(norm * s[-1, :])
        if wanted.sum() == count and np.all(residual[wanted] <= TOLERANCE * theta[wanted]):
            lam = sigma + 1.0 / theta[wanted]
            vectors = q_all[:, :j + 1] @ s[:, wanted]
            order = np.argsort(lam)
            return lam[order], vectors[:, order]
        if j + 1 == steps:
            break
    return None


def _upper_band(a: np.ndarray, bandwidth: int) -> np.ndarray:
    """Upper band storage of symmetric ``a`` (n, n) (LAPACK ``dpbtrf``'s, ``lower=False``):
    ``ab[bandwidth + i - j, j] = a[i, j]`` for ``j - bandwidth <= i <= j``."""
    n = a.shape[0]
    ab = np.zeros((bandwidth + 1, n))
    for d in range(bandwidth + 1):
        ab[bandwidth - d, d:] = np.diagonal(a, d)
    return ab
