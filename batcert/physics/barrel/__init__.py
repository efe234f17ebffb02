r"""A hollow bat's barrel as a thin shell of revolution: its modes, its compliance under the
ball, its hoop frequency and its compression stiffness.

:mod:`~batcert.physics.barrel.wall`: the shell and its modes; :mod:`~batcert.physics.barrel.patch`:
the wall under the ball's patch; :mod:`~batcert.physics.barrel.lab`: what a lab measures of
it (hoop frequency, compression stiffness). Their public names are here.

The wall of a hollow bat (every contiguous hollow slice around the largest diameter: handle,
taper, barrel) is a shell of revolution (:mod:`batcert.physics.shell`) with the bat's mid-surface
radius, wall and reconciled density along it, and its ends held round by the knob and the end
cap (``closed``) or left open (``BatModel.barrel_end``). Its deformation is expanded in
circumferential orders: ``n = 1`` moves each cross-section as a whole and is the beam's bending
(:mod:`batcert.physics.beam`), so the barrel contributes the orders ``n = 0`` (breathing) and
``n >= 2`` (ovalling and higher). These are orthogonal to the beam's motion, so the two add
without counting any mass twice.

The ball presses on a patch (:mod:`batcert.physics.balls.footprint`): along the bat the
parabolic weight over ``2 a`` of the beam's contact patch, around it the same weight over the
arc ``2 b`` of the outer surface (half-angle ``beta = b / R_outer``). Order ``n`` feels the
load through the factor ``c_n = 3 j_1(n beta) / (n beta)``
(:func:`~batcert.physics.balls.footprint.circumferential_factor`).

What the engine uses per impact (:func:`barrel_response`): the modes of orders
``0, 2 .. dynamic_orders`` below ``max_frequency`` as extra modes of the bat (gain
``c_n W_j`` averaged over the patch), and the quasi-static compliance of everything left out
(higher modes of those orders, and the orders up to ``static_orders``), a spring in series with
the ball like the beam's residual compliance. Nothing here is fitted: the shell comes from the
profile, the wall and the material; a measured hoop frequency or barrel compression scales its
stiffness (and mass) through ``BatModel.barrel_stiffness_scale`` / ``barrel_mass_scale``
(:mod:`batcert.model.calibrate`).
"""

from batcert.physics.barrel.lab import compression_stiffness, hoop_frequency
from batcert.physics.barrel.patch import (
    BarrelPatch,
    BarrelResponse,
    PatchLoads,
    barrel_patch,
    barrel_response,
    patch_half_angle,
)
from batcert.physics.barrel.shared import shared_wall
from batcert.physics.barrel.wall import (
    DYNAMIC_ORDERS,
    MAX_FREQUENCY,
    NOMINAL_CUT,
    PATCH_SPAN,
    STATIC_ORDERS,
    BarrelModes,
    barrel_shell,
    cached_barrel_modes,
    compute_barrel_modes,
    shell_modes,
    wall_of,
)

__all__ = ["DYNAMIC_ORDERS", "MAX_FREQUENCY", "NOMINAL_CUT", "PATCH_SPAN", "STATIC_ORDERS",
           "BarrelModes", "BarrelPatch", "BarrelResponse", "PatchLoads", "barrel_patch",
           "barrel_response", "barrel_shell", "cached_barrel_modes", "compression_stiffness",
           "compute_barrel_modes", "hoop_frequency", "patch_half_angle", "shared_wall",
           "shell_modes", "wall_of"]
