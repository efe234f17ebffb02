"""Reduction of measured hits on a pivoted bat: from ball speeds (and, for the BPF method, the
bat's speed after impact) to e_A, BBCOR, BESR, the COR and BPF (docs/lab-reduction.md derives
every formula from the balance of angular momentum about the pivot).

Pure and vectorised: arrays of hits in, arrays out, SI units. The sign convention is the lab's:
``inbound_speed`` and ``rebound_speed`` are magnitudes (the ball approaches, then leaves); the
bat is at rest before impact (a ball-cannon test, ASTM F2219 / NCAA BBCOR).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from batcert.physics import rigid


@dataclass(frozen=True)
class HitReduction:
    """Every reduced quantity of a batch of hits (arrays of one shape)."""

    collision_efficiency: np.ndarray  # e_A = v_r / v_i [-]
    recoil_factor: np.ndarray  # k = m r^2 / I [-]
    bbcor: np.ndarray  # e_A (1 + k) + k [-]
    besr: np.ndarray  # Smith 2001 Eq. 2 with w1 = 0: e_A + 1/2 [-]
    bat_angular_speed_after: np.ndarray  # from angular momentum (Smith 2001 Eq. 1) [rad/s]
    ball_cor: np.ndarray  # the ball's rigid-wall COR at the inbound speed [-]
    bpf: np.ndarray  # BBCOR / ball_cor (Smith 2001 Eq. 5, e from momentum) [-]
    measured_cor: np.ndarray  # (r w2 + v_r) / v_i from a measured w2, NaN without one [-]
    measured_bpf: np.ndarray  # measured_cor / ball_cor (the BPF method), NaN without w2 [-]


# the fields that need the ball's COR (the rest do not read ``ball_cor_at``)
BALL_COR_FIELDS = ("ball_cor", "bpf", "measured_bpf")


def reduce_hits(inbound_speed, rebound_speed, impact_location, moi_pivot, ball_mass,
                ball_cor_at: Callable[[np.ndarray], np.ndarray | float] | None,
                bat_angular_speed_after=None) -> HitReduction:
    """Reduce hits on a pivoted bat at rest.

    Parameters
    ----------
    inbound_speed, rebound_speed : array_like
        Ball speed before and after impact, magnitudes [m/s].
    impact_location : array_like
        ``r`` [m from the pivot].
    moi_pivot : float or array_like
        The bat's MOI about the pivot, ``I`` [kg m^2] (an array broadcasts: Monte Carlo draws).
    ball_mass : float or array_like
        ``m`` [kg].
    ball_cor_at : callable or None
        The ball's rigid-wall COR at an impact speed [m/s] (the ball lot's); None where only
        the fields that do not need it are wanted (:data:`BALL_COR_FIELDS` are then NaN).
    bat_angular_speed_after : array_like, optional
        ``w2`` measured after impact [rad/s] (BPF method); NaN where not measured.

    Returns
    -------
    HitReduction
        ``e_A = v_r / v_i``; ``k = m r^2 / I``; ``BBCOR = e_A (1 + k) + k``; ``BESR = e_A + 1/2``;
        ``w2 = m r (v_i + v_r) / I``; ``BPF = BBCOR / e_b(v_i)``; and from a measured ``w2``,
        ``e = (r w2 + v_r) / v_i`` and its BPF (docs/lab-reduction.md, Eqs. R1-R7).

    References
    ----------
    ASTM F2219 (collision efficiency, BBCOR); L. V. Smith, Sports Eng. 4 (2001) 205, Eqs. 1-5.
    """
    v_i = np.asarray(inbound_speed, float)
    v_r = np.asarray(rebound_speed, float)
    r = np.asarray(impact_location, float)
    # Smith's axis: the pitch moves toward the bat (negative), the ball leaves along +x (v_b =
    # v_r) and the struck bat turns the pitch's way (w2 < 0); the lab states magnitudes
    pitch, zero = -v_i, np.zeros_like(v_i)
    e_a = rigid.collision_efficiency_from_speeds(r, pitch, zero, v_r)
    k = rigid.recoil_factor_pivoted(ball_mass, moi_pivot, r)
    w2 = -rigid.bat_angular_speed_after(moi_pivot, ball_mass, r, pitch, zero, v_r)
    e_b = (np.full_like(v_i, np.nan) if ball_cor_at is None
           else np.asarray(ball_cor_at(v_i), float))
    bbcor = rigid.bbcor_from_collision_efficiency(e_a, k)
    measured = np.full_like(v_i, np.nan) if bat_angular_speed_after is None \
        else np.asarray(bat_angular_speed_after, float)
    e_measured = rigid.cor_from_speeds(r, pitch, zero, v_r, -measured)
    return HitReduction(e_a, k, bbcor, rigid.besr(r, pitch, zero, v_r), w2, e_b, bbcor / e_b,
                        e_measured, e_measured / e_b)
