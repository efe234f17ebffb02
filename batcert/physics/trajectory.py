"""The flight of a batted baseball: gravity, drag and Magnus lift, to where it lands.

The aerodynamics are those of A. M. Nathan's trajectory calculator (the Statcast-era spreadsheet
``TrajectoryCalculator-new-3D.xlsx``; its equations and constants as its own output rows show
them, docs/references.md "Trajectory"):

- drag coefficient ``Cd = cd0 + cd_spin * (spin / 1000 rpm) * D`` (Nathan's fit to Statcast);
- lift coefficient ``Cl = cl2 S / (cl0 + cl1 S)``, spin factor ``S = R w D / v`` (``R`` the
  ball's radius, ``v`` its speed through the air);
- spin decay ``D = exp(-t v / (tau v_100))``: a time constant ``tau`` = 30 s at 100 mph, shorter
  when faster; the spin axis keeps its launch direction;
- air density from temperature, pressure, elevation and humidity (:func:`air_density`).

Forces per unit mass: drag ``-c0 Cd v v_vec``, lift ``c0 Cl v (w_hat x v_vec)``, gravity, with
``c0 = rho A / (2 m)``. Here ``c0`` is computed from the ball's own area and mass; the
spreadsheet's ``0.07182 * 0.06261 * rho`` is 0.29 % larger (its kg/m^3 to lb/ft^3 factor is
rounded), which docs/validation.md quantifies. Integration is classical Runge-Kutta (the
spreadsheet steps ``x += v dt + a dt^2/2, v += a dt``; it lands about 0.8 ft short of the
converged flight, docs/validation.md), and the landing point is interpolated by the cubic
through the last two states.

All in SI. Axes: ``x`` toward the first-base side, ``y`` toward centre field, ``z`` up; the
ball starts at ``start`` (the spreadsheet: 2 ft in front of the plate, 3 ft up); distance is
measured along the ground from home plate (the origin), as the spreadsheet does.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MPH = 0.44704  # [m/s]
FT = 0.3048  # [m]
RPM = np.pi / 30.0  # [rad/s]
GRAVITY = 9.80665  # [m/s^2]


@dataclass(frozen=True)
class Aerodynamics:
    """Coefficients of Nathan's trajectory calculator (the spreadsheet's defaults)."""

    cd0: float = 0.3008  # drag coefficient without spin [-]
    cd_spin: float = 0.0292  # added drag per 1000 rpm [-]
    cl0: float = 0.583  # lift law Cl = cl2 S / (cl0 + cl1 S) [-]
    cl1: float = 2.333
    cl2: float = 1.120
    spin_decay_time: float = 30.0  # tau at 100 mph [s]
    spin_decay_speed: float = 100 * MPH  # the speed tau is quoted at [m/s]


NATHAN = Aerodynamics()


@dataclass(frozen=True)
class Baseball:
    """The flying ball: mass and circumference (the spreadsheet's 5.125 oz and 9.125 in)."""

    mass: float = 5.125 * 0.028349523125  # [kg]
    circumference: float = 9.125 * 0.0254  # [m]

    @property
    def radius(self) -> float:
        return self.circumference / (2 * np.pi)

    @property
    def area(self) -> float:
        return np.pi * self.radius**2


def saturation_vapour_pressure(temperature):
    """Saturation vapour pressure over water [Pa] at ``temperature`` [K] (Buck's form, as the
    spreadsheet writes it in mmHg: 4.5841 exp((18.687 - T/234.5) T / (257.14 + T)), T in deg C)."""
    tc = np.asarray(temperature, dtype=float) - 273.15
    mmhg = 4.5841 * np.exp((18.687 - tc / 234.5) * tc / (257.14 + tc))
    return mmhg * 133.322387415


def air_density(temperature=294.261, pressure=29.92 * 3386.389, elevation=0.0,
                relative_humidity=0.5):
    """Density of moist air [kg/m^3] as Nathan's calculator computes it.

    Parameters
    ----------
    temperature : array_like
        Air temperature [K] (the spreadsheet's default 70 F = 294.26 K).
    pressure : array_like
        Barometric pressure reduced to sea level, as a weather report gives it [Pa] (default
        29.92 inHg); the calculator lowers it with the elevation.
    elevation : array_like
        Of the field above sea level [m].
    relative_humidity : array_like
        [0-1].

    Returns
    -------
    numpy.ndarray
        ``rho = 1.2929 (273 K / T) (p exp(-beta h) - 0.3783 RH p_sat) / 760 mmHg`` with
        ``beta = 1.217e-4 /m`` (the spreadsheet's form: dry air of 1.2929 kg/m^3 at 0 deg C and
        760 mmHg, the water vapour's partial pressure weighted by its lower molar mass).
    """
    t = np.asarray(temperature, dtype=float)
    p = np.asarray(pressure, dtype=float) * np.exp(-1.217e-4 * np.asarray(elevation, float))
    moist = p - 0.3783 * np.asarray(relative_humidity, float) * saturation_vapour_pressure(t)
    return 1.2929 * (273.0 / (t - 0.15)) * moist / 101_325.0


@dataclass(frozen=True)
class Flight:
    """Where a batch of batted balls land (arrays over the batch)."""

    distance: np.ndarray  # along the ground from home plate to the landing point [m]
    hang_time: np.ndarray  # launch to landing [s]
    apex: np.ndarray  # greatest height [m]
    landing: np.ndarray  # (n, 2) landing point x, y [m]


def default_spin(launch_angle, direction=0.0, handedness=1.0):
    """Backspin and sidespin [rad/s] of a batted ball whose spin was not measured: the Statcast
    regression Nathan's calculator uses by default,
    ``backspin = -763 + 120 LA + 21 phi s`` and ``sidespin = -849 s - 94 phi`` [rpm] with the
    launch angle ``LA`` and spray angle ``phi`` in degrees and ``s`` = +1 for a right-handed
    batter, -1 for a left-handed one (the calculator's sheet; docs/references.md
    "Trajectory"). The sidespin's sign follows :func:`fly`.

    Parameters
    ----------
    launch_angle, direction : array_like
        [rad], as :func:`fly` takes them.
    handedness : float
        +1 right-handed, -1 left-handed.
    """
    la, phi = np.degrees(launch_angle), np.degrees(direction)
    back = -763.0 + 120.0 * la + 21.0 * phi * handedness
    side = -849.0 * handedness - 94.0 * phi
    return np.asarray(back * RPM, float), np.asarray(side * RPM, float)


def _launch(exit_speed, launch_angle, direction, backspin, sidespin):
    """Initial velocity (n, 3) and spin vector (n, 3) [rad/s] from the launch conditions:
    backspin about the horizontal axis normal to the flight (lifting the ball), sidespin about
    the axis normal to that and to the velocity (positive curves the ball toward -x, the
    third-base side)."""
    v, th, ph = (np.atleast_1d(np.asarray(a, float)) for a in (exit_speed, launch_angle,
                                                                direction))
    back, side = (np.atleast_1d(np.asarray(a, float)) for a in (backspin, sidespin))
    v, th, ph, back, side = np.broadcast_arrays(v, th, ph, back, side)
    vel = np.stack([v * np.cos(th) * np.sin(ph), v * np.cos(th) * np.cos(ph), v * np.sin(th)],
                   axis=-1)
    spin = np.stack([back * np.cos(ph) - side * np.sin(th) * np.sin(ph),
                     -back * np.sin(ph) - side * np.sin(th) * np.cos(ph),
                     side * np.cos(th)], axis=-1)
    return vel, spin


def _acceleration(t, vel, spin, spin_rate, c0, radius, aero: Aerodynamics):
    speed = np.sqrt(np.einsum("ij,ij->i", vel, vel))
    decay = np.exp(-t * speed / (aero.spin_decay_time * aero.spin_decay_speed))
    s = radius * spin_rate * decay / speed
    cl = aero.cl2 * s / (aero.cl0 + aero.cl1 * s)
    cd = aero.cd0 + aero.cd_spin * (spin_rate / (1000 * RPM)) * decay
    lift = c0 * cl * speed / np.where(spin_rate > 0, spin_rate, 1.0)
    drag = -c0 * cd * speed
    wx, wy, wz = spin[:, 0], spin[:, 1], spin[:, 2]
    vx, vy, vz = vel[:, 0], vel[:, 1], vel[:, 2]
    a = np.empty_like(vel)  # drag along -v, lift along (w x v), gravity
    a[:, 0] = drag * vx + lift * (wy * vz - wz * vy)
    a[:, 1] = drag * vy + lift * (wz * vx - wx * vz)
    a[:, 2] = drag * vz + lift * (wx * vy - wy * vx) - GRAVITY
    return a


def fly(exit_speed, launch_angle, backspin, sidespin=0.0, direction=0.0, *,
        air=None, ball: Baseball = Baseball(), aero: Aerodynamics = NATHAN,
        start=(0.0, 2 * FT, 3 * FT), step=0.005, max_time=20.0) -> Flight:
    """Fly a batch of batted balls to the ground (Nathan's aerodynamics, module notes).

    Parameters
    ----------
    exit_speed : array_like
        Ball speed off the bat [m/s].
    launch_angle : array_like
        Above the horizontal [rad].
    backspin, sidespin : array_like
        Spin components [rad/s] (backspin lifts the ball).
    direction : array_like
        Spray angle from the line to centre field, positive to the first-base side [rad].
    air : float, optional
        Air density [kg/m^3]; default :func:`air_density` at its defaults (70 F, 29.92 inHg,
        sea level, 50 %).
    step : float
        Runge-Kutta time step [s]; 5 ms puts the distance within 1e-4 m of the converged one.

    Returns
    -------
    Flight
        Distance from home plate, hang time and apex of each ball.
    """
    rho = air_density() if air is None else float(air)
    vel, spin = _launch(exit_speed, launch_angle, direction, backspin, sidespin)
    n = vel.shape[0]
    pos = np.tile(np.asarray(start, float), (n, 1))
    rate = np.linalg.norm(spin, axis=-1)
    c0 = rho * ball.area / (2 * ball.mass)

    def acc(t: float, v: np.ndarray) -> np.ndarray:
        return _acceleration(t, v, spin, rate, c0, ball.radius, aero)

    t = 0.0
    apex = pos[:, 2].copy()  # at the steps' ends: within g h^2 / 8 = 3e-5 m of the true apex
    landed = np.zeros(n, bool)
    t_land = np.full(n, np.nan)
    where = np.full((n, 2), np.nan)
    while not landed.all():
        if t > max_time:
            raise ValueError(f"a ball is still in the air after {max_time:g} s")
        new_pos, new_vel = _rk4_step(acc, t, pos, vel, step)
        apex = np.where(landed, apex, np.maximum(apex, new_pos[:, 2]))
        down = ~landed & (new_pos[:, 2] <= 0.0)
        if down.any():
            tau, xy = _touchdown(pos[down], vel[down], new_pos[down], new_vel[down], step)
            t_land[down] = t + tau
            where[down] = xy
            landed |= down
        pos, vel, t = new_pos, new_vel, t + step
    return Flight(distance=np.hypot(where[:, 0], where[:, 1]), hang_time=t_land, apex=apex,
                  landing=where)


def _rk4_step(acc, t, pos, vel, h):
    """One classical Runge-Kutta step of x' = v, v' = acc(t, v) (the acceleration does not
    depend on the position)."""
    k1 = acc(t, vel)
    k2 = acc(t + h / 2, vel + h / 2 * k1)
    k3 = acc(t + h / 2, vel + h / 2 * k2)
    k4 = acc(t + h, vel + h * k3)
    new_pos = pos + h / 6 * (vel + 2 * (vel + h / 2 * k1) + 2 * (vel + h / 2 * k2) + vel + h * k3)
    return new_pos, vel + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def _touchdown(p0, v0, p1, v1, h):
    """Time into the step [s] and ground point (x, y) where the cubic Hermite through the
    step's end states reaches z = 0 (bisection on the cubic: the step brackets the root)."""
    lo, hi = np.zeros(len(p0)), np.full(len(p0), h)
    for _ in range(30):  # h / 2^30: well under a nanosecond
        mid = (lo + hi) / 2
        z = _hermite(p0[:, 2], v0[:, 2], p1[:, 2], v1[:, 2], h, mid)
        above = z > 0
        lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
    tau = (lo + hi) / 2
    xy = np.stack([_hermite(p0[:, i], v0[:, i], p1[:, i], v1[:, i], h, tau) for i in (0, 1)],
                  axis=-1)
    return tau, xy


def _hermite(x0, v0, x1, v1, h, t):
    s = t / h
    return ((2 * s**3 - 3 * s**2 + 1) * x0 + (s**3 - 2 * s**2 + s) * h * v0
            + (-2 * s**3 + 3 * s**2) * x1 + (s**3 - s**2) * h * v1)
