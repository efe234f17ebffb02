"""Benchmark cases on a uniform tube, computed with batcert's shell of revolution, for the
independent finite-element check (scripts/fe_tube_reference.py, test_shell_against_fe.py).

The tube: outer diameter ``D``, wall ``t``, length ``L``, uniform material; its mid-surface radius
is ``(D - t) / 2``. Loads are patches of uniform pressure on the outer surface, ``length`` long
and ``arc`` wide (arc length on the outer surface), represented on the mid-surface by the same
axial and circumferential spread (thin-shell theory reads the mid-surface; the
through-thickness squeeze under the pressure is left out). A patch's force is the resultant of
its pressure, a vector along the patch's centre normal, as in the finite-element reference: the
pressure summed without direction is larger by ``beta / sin(beta)`` (``beta`` the patch's
half-angle), 1.063 for a 40 mm patch on a 2 5/8 in tube.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from batcert.physics.shell import Assembler, HarmonicSystem, ShellOfRevolution, normal_reader, static_solve


@dataclass(frozen=True)
class Tube:
    outer_diameter: float  # [m]
    wall: float  # [m]
    length: float  # [m]
    youngs_modulus: float  # [Pa]
    poisson_ratio: float  # [-]
    density: float  # [kg/m^3]

    def shell(self, ends: tuple[str, str], elements: int = 120) -> ShellOfRevolution:
        z = np.linspace(0.0, self.length, elements + 1)
        r = np.full(z.size, 0.5 * (self.outer_diameter - self.wall))
        ones = np.ones(elements)
        return ShellOfRevolution(z, r, self.wall * ones, self.density * ones,
                                 self.youngs_modulus * ones, self.poisson_ratio, ends)


def frequencies(tube: Tube, n: int, ends: tuple[str, str], count: int = 2,
                elements: int = 120) -> np.ndarray:
    """The lowest ``count`` frequencies of circumferential order ``n`` [Hz]."""
    system = Assembler(tube.shell(ends, elements)).system(n)
    lam = scipy.linalg.eigh(system.stiffness, system.mass, eigvals_only=True,
                            subset_by_index=(0, count - 1), check_finite=False)
    return np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)


def _resultant_scale(half_angle: float) -> float:
    """Scalar pressure sum over vector resultant of a uniform arc of half-angle ``half_angle``."""
    return half_angle / np.sin(half_angle)


def _arc_factor(n: int, half_angle: float) -> float:
    """``int w(theta) cos(n theta)`` for a uniform arc of half-angle ``half_angle`` [rad]."""
    x = n * half_angle
    return 1.0 if x == 0 else float(np.sin(x) / x)


def _patch_load(shell: ShellOfRevolution, system: HarmonicSystem, centre: float,
                length: float, points: int = 40) -> np.ndarray:
    """Consistent load (free dofs) of a unit resultant spread uniformly over ``length``."""
    z = centre - 0.5 * length + (np.arange(points) + 0.5) * length / points
    cols, h = normal_reader(shell, system.n, z)
    f = np.zeros(system.node_dofs * shell.z.size)
    np.add.at(f, cols.ravel(), (h / points).ravel())
    return f[system.free]


def squeeze(tube: Tube, centre: float, length: float, arc: float, orders: int = 60,
            elements: int = 120) -> dict[str, float]:
    """Two equal, opposite patch loads (at theta = 0 and pi) squeezing a free-free tube.

    Returns the approach of the two patch centres and of the patch averages per newton on each
    patch [m/N] and the stiffness 1 / (patch-average approach / 2) of one side [N/m]: the
    force on one patch over the inward displacement averaged over it.
    """
    shell = tube.shell(("open", "open"), elements)
    assembler = Assembler(shell)
    beta = 0.5 * arc / (0.5 * tube.outer_diameter)
    centre_disp = average_disp = 0.0
    for n in range(0, orders + 1, 2):  # odd orders cancel between the two loads
        system = assembler.system(n, support=True)
        factor = scipy.linalg.cho_factor(system.stiffness, check_finite=False)
        f = _patch_load(shell, system, centre, length)
        x = static_solve(system, factor, f[:, None])[:, 0]
        c = _arc_factor(n, beta)
        cols, h = normal_reader(shell, n, np.array([centre]))
        full = np.zeros(system.node_dofs * shell.z.size)
        full[system.free] = x
        centre_disp += 2.0 * c * float(h[0] @ full[cols[0]])  # both loads, read at theta = 0
        average_disp += 2.0 * c * c * float(f @ x)
    centre_disp *= _resultant_scale(beta)
    average_disp *= _resultant_scale(beta)
    return {"centre_approach_per_newton": float(2 * centre_disp),
            "average_approach_per_newton": float(2 * average_disp),
            "stiffness": float(1.0 / average_disp)}


def squeeze_pulse(tube: Tube, centre: float, length: float, arc: float, peak_force: float,
                  duration: float, until: float, orders: int = 40,
                  max_frequency: float = 60_000.0, elements: int = 120) -> dict[str, float]:
    """The largest approach of the patch centres and of the patch averages [m] under a
    half-sine force ``peak_force sin(pi t / duration)`` on each patch of a free-free tube at rest,
    up to time ``until`` [s]: modal superposition of every mode up to ``max_frequency`` in the
    even orders up to ``orders``, undamped, exact (Duhamel) per mode, plus the static response
    of the modes left out (mode-acceleration correction)."""
    shell = tube.shell(("open", "open"), elements)
    assembler = Assembler(shell)
    beta = 0.5 * arc / (0.5 * tube.outer_diameter)
    t = np.linspace(0.0, until, 4001)
    force = np.where(t <= duration, np.sin(np.pi * t / duration), 0.0)
    at_centre_total = np.zeros(t.size)
    average = np.zeros(t.size)
    for n in range(0, orders + 1, 2):
        supported = assembler.system(n, support=True)
        free_sys = supported if n else assembler.system(0)
        c = _arc_factor(n, beta)
        f_s = _patch_load(shell, supported, centre, length) * c
        factor = scipy.linalg.cho_factor(supported.stiffness, check_finite=False)
        x_static = static_solve(supported, factor, f_s[:, None])[:, 0]
        cols, h = normal_reader(shell, n, np.array([centre]))
        full = np.zeros(supported.node_dofs * shell.z.size)
        full[supported.free] = x_static
        read_static = (float(h[0] @ full[cols[0]]), float(f_s @ x_static))
        lam, vec = scipy.linalg.eigh(free_sys.stiffness, free_sys.mass, check_finite=False,
                                     subset_by_value=(-np.inf, (2 * np.pi * max_frequency) ** 2))
        keep = lam > (2 * np.pi) ** 2
        omega, vec = np.sqrt(lam[keep]), vec[:, keep]
        f_m = _patch_load(shell, free_sys, centre, length) * c
        modal_force = vec.T @ f_m  # per unit force
        full_m = np.zeros((free_sys.node_dofs * shell.z.size, omega.size))
        full_m[free_sys.free] = vec
        at_centre = h[0] @ full_m[cols[0]]  # cos(n theta) = 1 at theta = 0
        response = _half_sine_response(omega, duration, t)  # q per unit force, (t, modes)
        q_static = modal_force / omega**2
        # mode acceleration: static response + dynamic part of the kept modes
        dyn = response - np.outer(force, np.ones(omega.size))  # q / q_static - F(t)
        centre_n = read_static[0] * force + (dyn * (q_static * at_centre)).sum(1)
        average_n = read_static[1] * force + (dyn * (q_static * modal_force)).sum(1)
        at_centre_total += 2.0 * centre_n  # two loads
        average += 2.0 * average_n
    scale = 2 * peak_force * _resultant_scale(beta)
    return {"max_centre_approach": float(scale * at_centre_total.max()),
            "max_average_approach": float(scale * average.max())}


def _half_sine_response(omega: np.ndarray, duration: float, t: np.ndarray) -> np.ndarray:
    """Undamped response ``q(t) / q_static`` of oscillators ``omega`` [rad/s] to a unit
    half-sine of ``duration`` [s] from rest (Duhamel integral in closed form)."""
    w = omega[None, :]
    p = np.pi / duration
    tt = t[:, None]
    inside = tt <= duration
    with np.errstate(divide="ignore", invalid="ignore"):
        during = (np.sin(p * tt) - (p / w) * np.sin(w * tt)) / (1 - (p / w) ** 2)
        # after the pulse: free vibration from the state at t = duration
        q1 = (np.sin(p * duration) - (p / w) * np.sin(w * duration)) / (1 - (p / w) ** 2)
        v1 = (p * np.cos(p * duration) - p * np.cos(w * duration)) / (1 - (p / w) ** 2)
        after = q1 * np.cos(w * (tt - duration)) + v1 / w * np.sin(w * (tt - duration))
    return np.where(inside, during, after)
