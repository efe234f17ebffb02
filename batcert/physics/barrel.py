r"""The hollow barrel as a local spring-mass: the thin-ring n = 2 ("hoop", "trampoline") mode.

A hollow barrel flattens under the ball. batcert represents that flexing by the lowest flexural
mode of a thin ring of the barrel's cross-section, width ``b`` (the "effective width" of barrel
that takes part), as one spring-mass in series with the ball (DESIGN.md Sec. 4; Nathan, Russell &
Smith, "The physics of the trampoline effect in baseball and softball bats", 2004).

Derivation (inextensional thin ring, after Love, *A Treatise on the Mathematical Theory of
Elasticity*, 4th ed., 1927, and Soedel, *Vibrations of Shells and Plates*, 3rd ed., 2004). Mean
radius ``R``, wall ``t``, width ``b``, plane-strain modulus ``E' = E / (1 - nu^2)``, density
``rho``, bending stiffness of the wall ``D = E' b t^3 / 12``. Take the n-th mode with radial
displacement ``w = A cos(n theta)``. An inextensional mid-surface (``w + dv/dtheta = 0``) forces
the tangential displacement ``v = -(A / n) sin(n theta)``. Then

* change of curvature ``(w_thth + w) / R^2``, so the strain energy is
  ``U = (D / 2 R^3) int (w_thth + w)^2 dtheta = (pi D (n^2 - 1)^2 / (2 R^3)) A^2``;
* kinetic energy ``T = (rho b t R / 2) int (w_t^2 + v_t^2) dtheta
  = (pi rho b t R (1 + 1/n^2) / 2) A_t^2``.

With ``A``, the radial displacement at the loaded point ``theta = 0``, as the coordinate, a point
load ``P`` there does work ``P A``, so the mode acts on the ball as a spring and a mass

* ``k = pi D (n^2 - 1)^2 / R^3``, for n = 2: ``k = (9 pi / 12) E' b t^3 / R^3``,
* ``m = pi rho b t R (1 + 1/n^2)``, for n = 2: ``m = (5/4) pi rho b t R``,

and ``omega_n^2 = k / m`` gives the classical inextensional ring frequency (Love; Soedel)

    ``omega_n = (t / R^2) sqrt(E' / (12 rho)) n (n^2 - 1) / sqrt(n^2 + 1)``.

Axial extent (the barrel's (n = 2, m = 1) hoop mode). The lowest hoop mode of a real barrel is
the shell mode with two circumferential waves and one axial half-wave over the barrel (Russell,
"Acoustics and vibration of baseball and softball bats", Acoustics Today 13(4), 2017): radial
displacement ``A cos(2 theta) sin(pi x / L_b)`` over the full-diameter barrel of length ``L_b``.
Integrating the energies above along the barrel, with ``A`` the displacement at the axial position
``x`` of the impact, gives the same spring-mass with ``b = L_b / 2`` divided by
``sin^2(pi x / L_b)``: stiffest and heaviest (no trampoline) at the barrel's ends, most compliant
at its middle. So the default effective width is half the barrel length
(:func:`default_effective_width`), and :func:`barrel_spring_at` applies the axial shape. Both the
width and the shape follow from the geometry; nothing is fitted to a performance result.

Limitations: only the n = 2 term is kept (for a point load on a free ring the n >= 3 terms add
``9 sum_{n>=3} (n^2 - 1)^-2 = 21 %`` to the static compliance, so ``k`` is an upper bound);
the ring has no axial coupling with the rest of the barrel, so ``omega_2`` is a lower bound on a
real barrel's hoop frequency (REFERENCE-DATA.md, "Materials"); ``t << R`` is assumed.
"""

from __future__ import annotations

import numpy as np

from batcert.physics.batmodel import BatModel, Material

N_RING = 2  # circumferential wave number of the hoop mode used


def _ring(outer_radius, wall, material: Material):
    """Mean radius ``R = outer_radius - wall / 2`` [m], wall [m] and ``E'`` [Pa], broadcast."""
    r_out, t = np.broadcast_arrays(np.asarray(outer_radius, dtype=float),
                                   np.asarray(wall, dtype=float))
    if np.any(t <= 0) or np.any(t >= r_out):
        raise ValueError("barrel wall must satisfy 0 < wall < outer radius")
    e_plane = material.youngs_modulus / (1.0 - material.poisson_ratio**2)
    return r_out - 0.5 * t, t, e_plane


def hoop_angular_frequency(outer_radius, wall, material: Material):
    """Angular frequency of the n = 2 ring mode [rad/s] (Love 1927; derivation in module notes).

    Parameters
    ----------
    outer_radius : array_like
        Barrel outer radius [m].
    wall : array_like
        Wall thickness [m].
    material : Material
        Uses ``density`` [kg/m^3], ``youngs_modulus`` [Pa] and ``poisson_ratio`` [-].

    Returns
    -------
    numpy.ndarray
        ``omega_2 = (t / R^2) sqrt(E' / (12 rho)) n (n^2 - 1) / sqrt(n^2 + 1)`` [rad/s], with
        ``R`` the mean radius and ``E' = E / (1 - nu^2)``.
    """
    radius, t, e_plane = _ring(outer_radius, wall, material)
    n = N_RING
    return (t / radius**2) * np.sqrt(e_plane / (12.0 * material.density)) * (
        n * (n * n - 1) / np.sqrt(n * n + 1.0))


def hoop_frequency(outer_radius, wall, material: Material):
    """Frequency of the n = 2 ring (hoop) mode [Hz]; see :func:`hoop_angular_frequency`.

    Parameters
    ----------
    outer_radius : array_like
        Barrel outer radius [m].
    wall : array_like
        Wall thickness [m].
    material : Material
        Barrel material.

    Returns
    -------
    numpy.ndarray
        ``omega_2 / (2 pi)`` [Hz].
    """
    return hoop_angular_frequency(outer_radius, wall, material) / (2.0 * np.pi)


def barrel_spring(outer_radius, wall, material: Material, effective_width):
    """Point-load stiffness and modal mass of the n = 2 ring mode (module notes).

    Parameters
    ----------
    outer_radius : array_like
        Barrel outer radius [m].
    wall : array_like
        Wall thickness [m].
    material : Material
        Barrel material.
    effective_width : array_like
        Axial width ``b`` of barrel taking part in the hoop flexing [m].

    Returns
    -------
    stiffness : numpy.ndarray
        ``k = (9 pi / 12) E' b t^3 / R^3`` [N/m].
    mass : numpy.ndarray
        ``m = (5/4) pi rho b t R`` [kg]; ``sqrt(k / m)`` is :func:`hoop_angular_frequency`.
    """
    radius, t, e_plane = _ring(outer_radius, wall, material)
    b = np.asarray(effective_width, dtype=float)
    if np.any(b <= 0):
        raise ValueError("barrel effective width must be positive")
    n2 = N_RING * N_RING
    stiffness = np.pi * e_plane * (b * t**3 / 12.0) * (n2 - 1) ** 2 / radius**3
    mass = np.pi * material.density * b * t * radius * (1.0 + 1.0 / n2)
    return stiffness, mass


_BARREL_DIAMETER_FRACTION = 0.99  # slices this close to the largest diameter form the barrel
_MIN_AXIAL_SHAPE = 0.05  # below this sin(pi x / L_b) the hoop mode is left out (k, m -> inf)


def barrel_region(bat: BatModel) -> tuple[float, float]:
    """Start and end of the full-diameter hollow barrel, from the knob [m].

    The contiguous run of hollow slices whose outer diameter is within 1 % of the largest,
    around the largest; ``(nan, nan)`` for a solid bat.
    """
    d = np.asarray(bat.outer_diameter, dtype=float)
    hollow = np.asarray(bat.inner_diameter, dtype=float) > 0
    if bat.construction != "hollow" or not np.any(hollow):
        return float("nan"), float("nan")
    full = hollow & (d >= _BARREL_DIAMETER_FRACTION * d[hollow].max())
    i = int(np.argmax(np.where(hollow, d, -np.inf)))
    lo = i
    while lo > 0 and full[lo - 1]:
        lo -= 1
    hi = i
    while hi < d.size - 1 and full[hi + 1]:
        hi += 1
    return float(bat.z_edges[lo]), float(bat.z_edges[hi + 1])


def default_effective_width(bat: BatModel) -> float | None:
    """Half the full-diameter barrel length [m] (the (2, 1) hoop mode's modal width; module
    notes), or None for a solid bat."""
    z0, z1 = barrel_region(bat)
    return None if not np.isfinite(z0) else 0.5 * (z1 - z0)


def axial_shape(bat: BatModel, z_impact) -> np.ndarray:
    """``sin(pi (z - z0) / L_b)`` of the (2, 1) hoop mode at impact positions, 0 off the barrel."""
    z0, z1 = barrel_region(bat)
    z = np.atleast_1d(np.asarray(z_impact, dtype=float))
    if not np.isfinite(z0):
        return np.zeros_like(z)
    x = (z - z0) / (z1 - z0)
    return np.where((x > 0) & (x < 1), np.sin(np.pi * np.clip(x, 0, 1)), 0.0)


def barrel_spring_at(bat: BatModel, z_impact, effective_width=None):
    """Barrel spring-mass at impact positions of a bat, from the slice under each impact.

    Parameters
    ----------
    bat : BatModel
        Uses ``outer_diameter``, ``inner_diameter``, ``material`` and ``barrel_effective_width``.
    z_impact : array_like
        Impact positions from the knob [m], shape (p,).
    effective_width : float, optional
        Overrides ``bat.barrel_effective_width`` [m].

    Returns
    -------
    tuple of numpy.ndarray or None
        ``(stiffness [N/m], mass [kg])``, each of shape (p,): :func:`barrel_spring` with the outer
        radius and wall of the slice holding each impact, divided by the squared axial shape
        ``sin^2(pi x / L_b)`` of the (2, 1) hoop mode (module notes). Off the full-diameter barrel
        (or where the shape is below 0.05) the stiffness is ``inf`` and the mass 0 (no spring).
        ``None`` for a solid bat.

    Raises
    ------
    ValueError
        For a hollow bat without an effective width.
    """
    if bat.construction != "hollow":
        return None
    b = bat.barrel_effective_width if effective_width is None else effective_width
    if b is None:
        b = default_effective_width(bat)
    if b is None:
        raise ValueError(f"hollow bat {bat.name!r} has no hollow barrel")
    z = np.atleast_1d(np.asarray(z_impact, dtype=float))
    edges = np.asarray(bat.z_edges, dtype=float)
    s = np.clip(np.searchsorted(edges, z, side="right") - 1, 0, edges.size - 2)
    r_out = 0.5 * bat.outer_diameter[s]
    inner = 0.5 * bat.inner_diameter[s]
    shape = axial_shape(bat, z)
    hollow = (inner > 0) & (shape >= _MIN_AXIAL_SHAPE)
    stiffness = np.full(z.shape, np.inf)
    mass = np.zeros(z.shape)
    if np.any(hollow):
        k, m = barrel_spring(r_out[hollow], (r_out - inner)[hollow], bat.material, b)
        stiffness[hollow], mass[hollow] = k / shape[hollow] ** 2, m / shape[hollow] ** 2
    return stiffness, mass
