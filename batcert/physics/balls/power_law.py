"""Nathan's (2000) power-law hysteresis in closed form: the restitution exponent, the contact
force and the work along a compression, a rigid-wall impact's largest compression and its
inverse, the peak force.

The law (Nathan, Am. J. Phys. 68 (2000) 979)
--------------------------------------------
The ball is a nonlinear, lossy spring of compression ``u`` [m] (positive = compressed):

* compression (``u`` at its running maximum): ``F = k1 u^alpha``;
* restitution (``u`` below the maximum ``u_m`` reached so far):
  ``F = k2 u^beta = k1 u_m^alpha (u / u_m)^beta``, so both branches meet at ``u_m``, with
  ``beta = (1 + alpha) / e0^2 - 1``;
* ``F = 0`` for ``u <= 0`` (the ball only pushes).

The work done on the ball during compression is ``k1 u_m^(1+alpha) / (1+alpha)``, the work it
returns is ``k1 u_m^(1+alpha) / (1+beta)``; their ratio ``(1+alpha)/(1+beta) = e0^2`` does not
depend on ``u_m``, so against a rigid wall the COR is ``e0`` at every impact speed
(:mod:`batcert.physics.balls.wall_impact`). The ball's parameters and the ``e0`` each impact
gets: :mod:`batcert.physics.balls.hysteresis`.

Units: SI throughout ([m], [N], [s], [kg]).
"""

from __future__ import annotations

import numpy as np

__all__ = ["contact_force", "deformation_work", "equivalent_wall_speed", "max_compression",
           "peak_force", "restitution_exponent"]


def restitution_exponent(alpha, e0):
    """Restitution exponent ``beta = (1 + alpha) / e0^2 - 1`` [-] (Nathan 2000).

    Parameters
    ----------
    alpha : float or array_like
        Compression exponent [-].
    e0 : float or array_like
        Rigid-wall COR the law is to reproduce [-], in (0, 1].

    Returns
    -------
    numpy.ndarray
        ``beta`` [-].

    References
    ----------
    A. M. Nathan, Am. J. Phys. 68 (2000) 979.

    Examples
    --------
    Nathan's ball at 58 m/s (alpha = 1.84, e0 = 0.53): beta = 2.84 / 0.2809 - 1 = 9.11
    (docs/references.md, derived).

    >>> round(float(restitution_exponent(1.84, 0.53)), 2)
    9.11
    """
    e0 = np.asarray(e0, dtype=float)
    if np.any((e0 <= 0) | (e0 > 1)):
        raise ValueError(f"the ball's COR e0 must lie in (0, 1], got {e0}")
    return (1.0 + alpha) / e0**2 - 1.0


def contact_force(u, u_max, k1, alpha, beta):
    """Contact force of the hysteresis law [N] (Nathan 2000).

    Parameters
    ----------
    u : array_like
        Compression [m], positive = compressed.
    u_max : array_like
        Largest compression reached so far [m] (0 before contact). Where ``u >= u_max`` the
        compression branch applies.
    k1 : float
        Compression stiffness [N / m^alpha].
    alpha, beta : float or array_like
        Compression and restitution exponents [-].

    Returns
    -------
    numpy.ndarray
        ``F >= 0`` [N]: ``k1 u^alpha`` on compression, ``k1 u_m^alpha (u/u_m)^beta`` on
        restitution, 0 for ``u <= 0``.
    """
    u = np.clip(np.asarray(u, dtype=float), 0.0, None)
    top = np.maximum(np.asarray(u_max, dtype=float), u)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(top > 0, u / np.where(top > 0, top, 1.0), 0.0)
    return k1 * top**alpha * ratio**beta


def deformation_work(u, u_max, k1, alpha, beta):
    """Net work done on the ball so far, ``integral F du`` along its path [J].

    On compression it is ``k1 u^(1+alpha) / (1+alpha)``; on restitution the energy already
    returned, ``k1 u_m^(1+alpha) (1 - (u/u_m)^(1+beta)) / (1+beta)``, is subtracted. At separation
    (``u = 0``) what is left is the energy the ball dissipated. For a lossless ball
    (``e0 = 1``, ``beta = alpha``) it is the stored elastic energy.
    """
    u = np.clip(np.asarray(u, dtype=float), 0.0, None)
    top = np.maximum(np.asarray(u_max, dtype=float), u)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(top > 0, u / np.where(top > 0, top, 1.0), 0.0)
    stored = k1 * top ** (1.0 + alpha) / (1.0 + alpha)
    returned = k1 * top ** (1.0 + alpha) * (1.0 - ratio ** (1.0 + beta)) / (1.0 + beta)
    return stored - returned


def max_compression(speed, mass, k1, alpha):
    """Largest compression of a ball hitting a rigid wall [m]:
    ``u_m = ((1 + alpha) m v^2 / (2 k1))^(1 / (1 + alpha))`` (energy balance of the compression
    branch). For a ball hitting a body of effective mass ``M``, pass the reduced mass
    ``m M / (m + M)`` and the relative speed.

    Parameters
    ----------
    speed : array_like
        Normal impact speed [m/s].
    mass : float
        Ball (or reduced) mass [kg].
    k1 : float
        Compression stiffness [N / m^alpha].
    alpha : float
        Compression exponent [-].

    Returns
    -------
    numpy.ndarray
        ``u_m`` [m].

    References
    ----------
    A. M. Nathan, Am. J. Phys. 68 (2000) 979 (the compression law).

    Examples
    --------
    Nathan's ball (0.145 kg, k1 = 6.53e7 N/m^1.84) against a rigid wall at 58 m/s compresses
    17.7 mm (docs/references.md, derived):

    >>> round(float(max_compression(58.0, 0.145, 6.53e7, 1.84)) * 1e3, 1)
    17.7
    """
    v = np.abs(np.asarray(speed, dtype=float))
    return ((1.0 + alpha) * mass * v**2 / (2.0 * k1)) ** (1.0 / (1.0 + alpha))


def equivalent_wall_speed(compression, mass, k1, alpha):
    """The rigid-wall impact speed that compresses the ball by ``compression`` [m/s]:
    ``v = sqrt(2 k1 u^(1+alpha) / ((1+alpha) m))``, the inverse of :func:`max_compression`
    (the ball has then stored the same energy, ``k1 u^(1+alpha) / (1+alpha)``).

    Parameters
    ----------
    compression : array_like
        Largest compression of the ball [m].
    mass : float
        Ball mass [kg].
    k1, alpha : float
        Compression law [N/m^alpha], [-].
    """
    u = np.maximum(np.asarray(compression, dtype=float), 0.0)
    return np.sqrt(2.0 * k1 * u ** (1.0 + alpha) / ((1.0 + alpha) * mass))



def peak_force(speed, mass, k1, alpha):
    """Peak force ``k1 u_m^alpha`` of a rigid-wall impact [N] (see :func:`max_compression`)."""
    return k1 * max_compression(speed, mass, k1, alpha) ** alpha
