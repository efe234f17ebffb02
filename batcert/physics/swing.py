"""How fast a batter swings a bat: the swing speed's dependence on the bat's moment of inertia.

Field studies of batters swinging bats of different moments of inertia fit the bat speed to a
power law of the MOI (DESIGN.md section 7: ``w = C / I^n``, n about 0.25-0.27). Test standards
that set the bat speed from the bat's MOI (USA Softball's batted-ball speed) use such a law with
a reference point: the speed ``v_ref`` a batter reaches with a bat of MOI ``I_ref``.
"""

from __future__ import annotations

import numpy as np


def swing_speed(moi, reference_speed, reference_moi, exponent):
    """Swing speed with a bat of moment of inertia ``moi`` by the power law
    ``v = v_ref (I / I_ref)^-n``.

    Parameters
    ----------
    moi : array_like
        The bat's moment of inertia ``I`` about the axis the law is stated for [kg m^2].
    reference_speed : float
        Speed ``v_ref`` reached with a bat of ``reference_moi`` (a linear speed at a stated
        station [m/s], or an angular speed [rad/s]: the law scales either alike).
    reference_moi : float
        ``I_ref`` [kg m^2], about the same axis as ``moi``.
    exponent : float
        ``n`` [-]: 0 makes the speed independent of the bat.

    Returns
    -------
    numpy.ndarray
        The speed, in the unit of ``reference_speed``.
    """
    moi = np.asarray(moi, dtype=float)
    return reference_speed * (moi / reference_moi) ** (-exponent)
