"""The outcome of each impact of the flexible engine (:mod:`batcert.engines.flexible`) from its
state at separation: the ball's exit speed, the bat's recoil from momentum balance, and the
diagnostics (energies, contact time and force, the barrel's share and deflection).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from batcert.engines.base import ImpactOutcome, Job
from batcert.engines.flexible_system import Extras, rigid_mode_velocities
from batcert.engines.kernel.linear_system import LinearSystem
from batcert.engines.kernel.march import Separation
from batcert.physics import rigid


@dataclass(frozen=True)
class Prepared:
    """A job with its linear system and what its outcome needs, ready to integrate."""

    job: Job
    system: LinearSystem
    extras: Extras



def outcome(ready: Prepared, sep: Separation, ball_loss: str, record_states: bool
            ) -> ImpactOutcome:
    """Exit speed, momentum outcome and diagnostics of one job from its separation state
    (:meth:`~batcert.engines.flexible.FlexibleEngine.solve` lists them)."""
    job, system, extras = ready.job, ready.system, ready.extras
    bat, ball, pivot, batch, support = job.bat, job.ball, job.pivot, job.batch, job.support
    r, vp, w1 = batch.impact_location, batch.pitch_speed, batch.bat_angular_speed
    vb = vp + sep.impulse / ball.mass
    k = rigid.recoil_factor(bat, ball.mass, pivot, r, support)
    w2, cor = rigid.momentum_outcome(bat, ball.mass, pivot, support, r, vp, w1, vb, k)
    om = system.omega
    zeta = system.zeta[:, None]
    q = sep.modal.imag / (om * np.sqrt(1 - zeta**2))
    p = sep.modal.real - zeta * om * q
    energy = 0.5 * (p**2 + (om * q) ** 2)
    diag = {"contact_time": sep.time, "peak_force": sep.peak_force,
            "max_compression": sep.max_compression, "vibrational_energy": energy.sum(1),
            "approach_energy": 0.5 * ball.mass / (1 + k) * batch.relative_speed**2,
            "separated": sep.separated}
    closed = ball.law.separation_loss(ball.mass, sep.max_compression, extras.contact_scale,
                                      batch.relative_speed, ball_loss)
    if closed is not None:  # the energy in closed form, and e0 (Nathan's law)
        diag.update(closed)
    else:  # measured by the integration (the viscoelastic law)
        diag["ball_energy_loss"] = sep.absorbed
    if system.shell_columns is not None:
        diag["barrel_energy"] = energy[:, system.shell_columns].sum(1)
        diag["barrel_energy_share"] = sep.barrel_share
        # the wall's quasi-static deflection under the peak force: the linear wall's limit
        deflection = extras.shell_static * sep.peak_force
        diag["barrel_deflection"] = deflection
        diag["barrel_deflection_ratio"] = deflection / extras.wall
    if record_states:
        diag.update(_states(system, extras, sep, q, p, pivot, w1 * r, w1))
    return ImpactOutcome(exit_speed=vb, bat_angular_speed_after=w2, cor=cor, recoil_factor=k,
                         diagnostics=diag)


def _states(system: LinearSystem, extras: Extras, sep: Separation, q, p, pivot, v_bat, w1):
    """Beam modal velocities and displacements, residual and barrel energies at separation."""
    modes, nb, ns = extras.modes, extras.n_bending, extras.n_shell
    v_rigid = v_bat - sep.impulse / system.rigid_mass  # rigid speed of the contact point
    shell = slice(nb, nb + ns)
    # rigid modes: rotation about the pivot, changed only along phi_r (point force at z)
    qd_r = w1[:, None] * rigid_mode_velocities(modes, pivot)[None, :] + extras.phi[
        :, :modes.n_rigid] * (extras.beam_rigid_mass * (v_rigid - v_bat))[:, None]
    res = slice(nb + ns, nb + ns + 1) if extras.residual_omega > 0 else slice(0, 0)
    return {"modal_velocity": np.concatenate([qd_r, p[:, :nb]], axis=1),
            "bending_displacement": q[:, :nb],
            "barrel_energy": 0.5 * (p[:, shell] ** 2 + (system.omega[:, shell] * q[:, shell]) ** 2
                                    ).sum(1),
            "residual_energy": 0.5 * (p[:, res] ** 2 + (extras.residual_omega
                                                        * q[:, res]) ** 2).sum(1)}
