"""Rigid-body impact relations in closed form (Smith 2001, Eqs. 1-7; DESIGN.md section 1).

All functions are vectorised over numpy arrays and work in SI. Sign convention: the bat moves in
the +x direction at the impact point (``w1 * r > 0`` for a swung bat); the pitched ball moves
toward it, so ``pitch_speed < 0``; the batted ball leaves with ``exit_speed > 0``.
"""

from __future__ import annotations

import numpy as np

from batcert.physics.batmodel import BatModel


def recoil_factor_pivoted(ball_mass, moi_pivot, impact_location):
    """Effective-mass ratio of a bat pinned at the pivot, ``k = m r^2 / I``.

    Parameters
    ----------
    ball_mass : float
        Ball mass ``m`` [kg].
    moi_pivot : float
        Bat moment of inertia about the pivot ``I`` [kg m^2].
    impact_location : array_like
        Distance of the impact from the pivot ``r`` [m].

    Returns
    -------
    numpy.ndarray
        ``k`` [-]: the ball's mass over the bat's effective mass ``I / r^2`` at the impact point.

    References
    ----------
    ASTM F2219 (pivoted form); DESIGN.md section 1.
    """
    r = np.asarray(impact_location, dtype=float)
    return ball_mass * r**2 / moi_pivot


def recoil_factor_free(ball_mass, bat_mass, moi_cg, impact_from_cg):
    """Effective-mass ratio of a free bat, ``k = (m / M) (1 + d^2 / k_cg^2)``.

    Parameters
    ----------
    ball_mass, bat_mass : float
        ``m`` and ``M`` [kg].
    moi_cg : float
        Bat moment of inertia about its CG, ``M k_cg^2`` [kg m^2].
    impact_from_cg : array_like
        Distance of the impact point from the bat's CG ``d`` [m].

    Returns
    -------
    numpy.ndarray
        ``k`` [-].

    References
    ----------
    ASTM F2219-23 (free bat); DESIGN.md section 1.
    """
    d = np.asarray(impact_from_cg, dtype=float)
    return (ball_mass / bat_mass) * (1.0 + d**2 * bat_mass / moi_cg)


def collision_efficiency(cor, k):
    """Collision efficiency ``e_A = (e - k) / (1 + k)``.

    Parameters
    ----------
    cor : array_like
        Ball-bat COR ``e`` [-].
    k : array_like
        Effective-mass ratio [-] (:func:`recoil_factor`).

    Returns
    -------
    numpy.ndarray
        ``e_A`` [-]: the exit speed off a stationary bat per unit pitch speed.

    References
    ----------
    ASTM F2219; DESIGN.md section 1.
    """
    return (np.asarray(cor) - k) / (1.0 + k)


def bbcor_from_collision_efficiency(e_a, k):
    """``BBCOR = e_A (1 + k) + k``, the inverse of :func:`collision_efficiency`.

    Parameters
    ----------
    e_a : array_like
        Collision efficiency [-].
    k : array_like
        Effective-mass ratio [-].

    Returns
    -------
    numpy.ndarray
        BBCOR [-].

    References
    ----------
    ASTM F2219; NCAA BBCOR standard (memo of 16 Sep 2008).
    """
    return np.asarray(e_a) * (1.0 + k) + k


def exit_speed(cor, k, pitch_speed, bat_speed):
    """Ball exit speed off a rigid bat, ``v_b = e_A (-v_p) + (1 + e_A) v_bat``.

    Equivalent to Smith 2001 Eqs. 1 and 3 with ``w2`` eliminated:
    ``v_b = [(1 + e) I w1 r + v_p (m r^2 - e I)] / (I + m r^2)`` for a pivoted bat.

    Parameters
    ----------
    cor : array_like
        Ball-bat COR ``e`` [-].
    k : array_like
        Effective-mass ratio [-].
    pitch_speed : array_like
        Ball speed before impact ``v_p`` [m/s], negative toward the bat.
    bat_speed : array_like
        Bat speed at the impact point before impact, ``w1 r`` [m/s].

    Returns
    -------
    numpy.ndarray
        ``v_b`` [m/s], positive away from the bat.

    References
    ----------
    L. V. Smith, Sports Eng. 4 (2001) 205, Eqs. 1 and 3.

    Examples
    --------
    The study's ash bat (I = 0.209 kg m^2) struck 0.55 m from the pivot by a 0.145 kg ball
    pitched at 31 m/s while swinging at 53 rad/s, e = 0.5:

    >>> k = recoil_factor_pivoted(0.145291, 0.209, 0.55)
    >>> round(float(exit_speed(0.5, k, -31.0, 53.0 * 0.55)), 2)
    43.55
    """
    e_a = collision_efficiency(cor, k)
    return -e_a * np.asarray(pitch_speed) + (1.0 + e_a) * np.asarray(bat_speed)


def bat_angular_speed_after(moi_pivot, ball_mass, impact_location, pitch_speed,
                            bat_angular_speed, exit_speed_):
    """Bat angular speed after impact from angular momentum about the pivot.

    ``I w1 + m v_p r = I w2 + m v_b r``, solved for ``w2``.

    Parameters
    ----------
    moi_pivot : float
        ``I`` [kg m^2].
    ball_mass : float
        ``m`` [kg].
    impact_location : array_like
        ``r`` [m from pivot].
    pitch_speed, exit_speed_ : array_like
        ``v_p`` and ``v_b`` [m/s].
    bat_angular_speed : array_like
        ``w1`` [rad/s].

    Returns
    -------
    numpy.ndarray
        ``w2`` [rad/s].

    References
    ----------
    L. V. Smith, Sports Eng. 4 (2001) 205, Eq. 1.
    """
    r = np.asarray(impact_location)
    return np.asarray(bat_angular_speed) + ball_mass * r * (np.asarray(pitch_speed)
                                                            - np.asarray(exit_speed_)) / moi_pivot


def cor_from_speeds(impact_location, pitch_speed, bat_angular_speed, exit_speed_,
                    bat_angular_speed_after_):
    """Ball-bat coefficient of restitution ``e = (w2 r - v_b) / (v_p - w1 r)``.

    Parameters
    ----------
    impact_location : array_like
        ``r`` [m from pivot].
    pitch_speed, exit_speed_ : array_like
        ``v_p`` and ``v_b`` [m/s].
    bat_angular_speed, bat_angular_speed_after_ : array_like
        ``w1`` and ``w2`` [rad/s].

    Returns
    -------
    numpy.ndarray
        ``e`` [-].

    References
    ----------
    L. V. Smith, Sports Eng. 4 (2001) 205, Eq. 3.
    """
    r = np.asarray(impact_location)
    return (np.asarray(bat_angular_speed_after_) * r - exit_speed_) / (
        np.asarray(pitch_speed) - np.asarray(bat_angular_speed) * r)


def besr(impact_location, pitch_speed, bat_angular_speed, exit_speed_):
    """NCAA ball exit speed ratio ``BESR = (v_b - (w1 r + v_p) / 2) / (w1 r - v_p)``.

    Parameters
    ----------
    impact_location : array_like
        ``r`` [m from pivot].
    pitch_speed, exit_speed_ : array_like
        ``v_p`` and ``v_b`` [m/s].
    bat_angular_speed : array_like
        ``w1`` [rad/s].

    Returns
    -------
    numpy.ndarray
        BESR [-]; ``e + 1/2`` for a bat that does not recoil (``w2 = w1``).

    References
    ----------
    L. V. Smith, Sports Eng. 4 (2001) 205, Eq. 2; NCAA BESR protocol (2000-2010).

    Examples
    --------
    The NCAA cap of 97 mph at 70 mph pitch and 66 mph bat speed is BESR 0.728 (Nathan, SABR
    Baseball Research Journal 2003):

    >>> mph = 0.44704
    >>> round(float(besr(1.0, -70 * mph, 66 * mph, 97 * mph)), 3)
    0.728
    """
    v_bat = np.asarray(bat_angular_speed) * np.asarray(impact_location)
    vp = np.asarray(pitch_speed)
    return (np.asarray(exit_speed_) - 0.5 * (v_bat + vp)) / (v_bat - vp)


def collision_efficiency_from_speeds(impact_location, pitch_speed, bat_angular_speed, exit_speed_):
    """Collision efficiency from measured speeds, ``e_A = (v_b - v_bat) / (v_pitch + v_bat)``.

    Parameters
    ----------
    impact_location : array_like
        ``r`` [m from pivot].
    pitch_speed, exit_speed_ : array_like
        ``v_p`` (negative toward the bat, so ``v_pitch = -v_p``) and ``v_b`` [m/s].
    bat_angular_speed : array_like
        ``w1`` [rad/s]; ``v_bat = w1 r``.

    Returns
    -------
    numpy.ndarray
        ``e_A`` [-].

    References
    ----------
    ASTM F2219; DESIGN.md section 1.
    """
    v_bat = np.asarray(bat_angular_speed) * np.asarray(impact_location)
    vp = np.asarray(pitch_speed)
    return (np.asarray(exit_speed_) - v_bat) / (v_bat - vp)


def centre_of_percussion(moi_pivot, mass, cg):
    """Centre of percussion, ``q = I / (M rbar)``.

    Parameters
    ----------
    moi_pivot : float
        ``I`` about the pivot [kg m^2].
    mass : float
        ``M`` [kg].
    cg : float
        ``rbar``, the CG's distance from the pivot [m].

    Returns
    -------
    float
        ``q`` [m from pivot].

    References
    ----------
    L. V. Smith, Sports Eng. 4 (2001) 205, Eq. 4.

    Examples
    --------
    The study's ash bat (906 g, CG 429 mm, MOI 0.209 kg m^2 about a pivot 150 mm from the
    knob):

    >>> round(centre_of_percussion(0.209, 0.906, 0.429), 4)
    0.5377
    """
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
    """Location of maximum exit speed for a rigid pivoted bat,
    ``r_s = v_p / w1 + sqrt(I / m + (v_p / w1)^2)``.

    Parameters
    ----------
    moi_pivot : float
        ``I`` [kg m^2].
    ball_mass : float
        ``m`` [kg].
    pitch_speed : array_like
        ``v_p`` [m/s], negative toward the bat.
    bat_angular_speed : array_like
        ``w1`` [rad/s].

    Returns
    -------
    numpy.ndarray
        ``r_s`` [m from pivot]; nan where ``w1 = 0`` (the exit speed of a stationary rigid bat
        falls monotonically from the pivot).

    References
    ----------
    L. V. Smith, Sports Eng. 4 (2001) 205, Eq. 7.

    Examples
    --------
    At the study's speeds (31 m/s pitch, 53 rad/s swing) Eq. 7 puts the ash bat's sweet spot
    0.749 m from the pivot, beyond its tip (0.710 m): rigid-body dynamics cannot locate it.

    >>> round(float(rigid_sweet_spot(0.209, 0.145291, -31.0, 53.0)), 3)
    0.749
    """
    w1 = np.asarray(bat_angular_speed, dtype=float)
    vp = np.asarray(pitch_speed, dtype=float)
    c = moi_pivot / ball_mass
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        a = np.where(w1 != 0, vp / np.where(w1 != 0, w1, 1.0), np.nan)
        root = np.hypot(np.sqrt(c), a)  # sqrt(c + a^2) without overflow for a slow swing
        # a + root loses every digit when a << 0 (pitch speed >> swing): use c / (root - a)
        return np.where(a < 0, c / (root - a), a + root)
