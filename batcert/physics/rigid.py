"""Rigid-body impact relations in closed form (Smith 2001, Eqs. 1-7; DESIGN.md section 1).

All functions are vectorised over numpy arrays and work in SI. Sign convention: the bat moves in
the +x direction at the impact point (``w1 * r > 0`` for a swung bat); the pitched ball moves
toward it, so ``pitch_speed < 0``; the batted ball leaves with ``exit_speed > 0``.
"""

from __future__ import annotations

import numpy as np

from batcert.physics.batmodel import BatModel


def recoil_factor_pivoted(ball_mass, moi_pivot, impact_location):
    """Effective-mass ratio k = m r^2 / I of a bat pinned at the pivot [-].

    Parameters
    ----------
    ball_mass : float — [kg]
    moi_pivot : float — bat moment of inertia about the pivot [kg m^2]
    impact_location : array_like — distance from the pivot [m]
    """
    r = np.asarray(impact_location, dtype=float)
    return ball_mass * r**2 / moi_pivot


def recoil_factor_free(ball_mass, bat_mass, moi_cg, impact_from_cg):
    """Effective-mass ratio k = (m / M) (1 + d^2 / k_cg^2) of a free bat [-].

    ``impact_from_cg`` is the impact point's distance from the bat's CG [m];
    ``moi_cg`` the bat's moment of inertia about its CG [kg m^2].
    """
    d = np.asarray(impact_from_cg, dtype=float)
    return (ball_mass / bat_mass) * (1.0 + d**2 * bat_mass / moi_cg)


def collision_efficiency(cor, k):
    """e_A = (e - k) / (1 + k) [-] (ASTM F2219; DESIGN.md section 1)."""
    return (np.asarray(cor) - k) / (1.0 + k)


def bbcor_from_collision_efficiency(e_a, k):
    """BBCOR = e_A (1 + k) + k [-], the inverse of :func:`collision_efficiency`."""
    return np.asarray(e_a) * (1.0 + k) + k


def exit_speed(cor, k, pitch_speed, bat_speed):
    """Ball exit speed v_b = e_A (-v_p) + (1 + e_A) v_bat [m/s].

    Equivalent to Smith 2001 Eqs. 1 and 3 with w2 eliminated:
    ``v_b = [(1 + e) I w1 r + v_p (m r^2 - e I)] / (I + m r^2)`` for a pivoted bat.

    Parameters
    ----------
    cor : array_like — ball-bat COR e [-]
    k : array_like — effective-mass ratio [-]
    pitch_speed : array_like — ball speed before impact v_p [m/s], negative toward the bat
    bat_speed : array_like — bat speed at the impact point before impact, w1 r [m/s]
    """
    e_a = collision_efficiency(cor, k)
    return -e_a * np.asarray(pitch_speed) + (1.0 + e_a) * np.asarray(bat_speed)


def bat_angular_speed_after(moi_pivot, ball_mass, impact_location, pitch_speed,
                            bat_angular_speed, exit_speed_):
    """w2 from angular momentum about the pivot (Smith 2001 Eq. 1) [rad/s]:
    ``I w1 + m v_p r = I w2 + m v_b r``."""
    r = np.asarray(impact_location)
    return np.asarray(bat_angular_speed) + ball_mass * r * (np.asarray(pitch_speed)
                                                            - np.asarray(exit_speed_)) / moi_pivot


def cor_from_speeds(impact_location, pitch_speed, bat_angular_speed, exit_speed_,
                    bat_angular_speed_after_):
    """Ball-bat COR e = (w2 r - v_b) / (v_p - w1 r) (Smith 2001 Eq. 3) [-]."""
    r = np.asarray(impact_location)
    return (np.asarray(bat_angular_speed_after_) * r - exit_speed_) / (
        np.asarray(pitch_speed) - np.asarray(bat_angular_speed) * r)


def besr(impact_location, pitch_speed, bat_angular_speed, exit_speed_):
    """NCAA ball exit speed ratio (Smith 2001 Eq. 2) [-]:
    ``BESR = (v_b - (w1 r + v_p) / 2) / (w1 r - v_p)``."""
    v_bat = np.asarray(bat_angular_speed) * np.asarray(impact_location)
    vp = np.asarray(pitch_speed)
    return (np.asarray(exit_speed_) - 0.5 * (v_bat + vp)) / (v_bat - vp)


def collision_efficiency_from_speeds(impact_location, pitch_speed, bat_angular_speed, exit_speed_):
    """e_A = (v_b - v_bat) / (v_pitch + v_bat) with v_pitch = -v_p and v_bat = w1 r [-]."""
    v_bat = np.asarray(bat_angular_speed) * np.asarray(impact_location)
    vp = np.asarray(pitch_speed)
    return (np.asarray(exit_speed_) - v_bat) / (v_bat - vp)


def centre_of_percussion(moi_pivot, mass, cg):
    """q = I / (M rbar), distance from the pivot [m] (Smith 2001 Eq. 4)."""
    return moi_pivot / (mass * cg)


def recoil_factor(bat: BatModel, ball_mass: float, pivot: float, impact_location, support: str):
    """Effective-mass ratio k of the bat at the impact point for its support [-]:
    pinned ``m r^2 / I_pivot``; free ``(m / M)(1 + d^2 / k_cg^2)``."""
    r = np.asarray(impact_location, dtype=float)
    if support == "pinned":
        return recoil_factor_pivoted(ball_mass, bat.moi_about(pivot), r)
    if support == "free":
        return recoil_factor_free(ball_mass, bat.mass, bat.moi_about(bat.balance_point),
                                  r + pivot - bat.balance_point)
    raise ValueError(f"unknown support {support!r}")


def momentum_outcome(bat: BatModel, ball_mass: float, pivot: float, support: str,
                     impact_location, pitch_speed, bat_angular_speed, exit_speed_, k=None):
    """Bat angular speed after impact [rad/s] and the ball-bat COR [-] from momentum balance.

    The impulse on the bat is ``m (v_p - v_b)``; the bat's speed at the impact point changes by
    ``k (v_p - v_b)`` with the support's recoil factor ``k``. Pinned: ``w2`` is Smith 2001 Eq. 1
    and ``e`` Eq. 3. Free: ``w2`` is the free bat's angular velocity after impact,
    ``w1 + m (v_p - v_b) d / I_cg`` (``d`` the impact point's distance from the CG), and ``e`` is
    Eq. 3 with the impact point's speed after impact in place of ``w2 r``. ``k`` may be passed
    when the caller already has it (:func:`recoil_factor`).
    """
    r = np.asarray(impact_location, dtype=float)
    vp, w1, vb = (np.asarray(a, dtype=float) for a in (pitch_speed, bat_angular_speed, exit_speed_))
    k = recoil_factor(bat, ball_mass, pivot, r, support) if k is None else np.asarray(k, float)
    point_after = w1 * r + k * (vp - vb)
    cor = (point_after - vb) / (vp - w1 * r)
    if support == "pinned":
        w2 = bat_angular_speed_after(bat.moi_about(pivot), ball_mass, r, vp, w1, vb)
    else:
        d = r + pivot - bat.balance_point
        w2 = w1 + ball_mass * (vp - vb) * d / bat.moi_about(bat.balance_point)
    return w2, cor


def rigid_sweet_spot(moi_pivot, ball_mass, pitch_speed, bat_angular_speed):
    """Location of maximum exit speed for a rigid pivoted bat (Smith 2001 Eq. 7) [m from pivot]:
    ``r_s = v_p / w1 + sqrt(I / m + (v_p / w1)^2)``. Undefined (nan) when w1 = 0: the exit speed
    of a stationary rigid bat then falls monotonically from the pivot."""
    w1 = np.asarray(bat_angular_speed, dtype=float)
    vp = np.asarray(pitch_speed, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(w1 != 0, vp / np.where(w1 != 0, w1, 1.0), np.nan)
        return a + np.sqrt(moi_pivot / ball_mass + a**2)
