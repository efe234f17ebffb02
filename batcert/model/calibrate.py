"""Calibrate the bat's stiffness to a measured first bending frequency.

Handbook moduli of wood are static values; bats measure stiffer (Nathan 2000 tuned E to the
R161's measured fundamental; REFERENCE-DATA.md, Materials). When a bat spec gives the measured
free-free first bending frequency, the bending stiffness EI and the shear stiffness kappa G A are
scaled by one factor ``s`` (keeping G/E), so every frequency scales with ``sqrt(s)`` and the
fundamental matches exactly: ``s = (f_measured / f_model)^2``.
"""

from __future__ import annotations

from dataclasses import replace

from batcert.errors import ModelError
from batcert.physics.batmodel import BatModel

STIFFNESS_SCALE_BOUNDS = (0.25, 4.0)


def calibrate_stiffness(bat: BatModel, first_bending_frequency: float, pivot: float
                        ) -> tuple[BatModel, dict[str, float]]:
    """Return the bat with EI and kappa G A scaled so that its free-free fundamental equals
    ``first_bending_frequency`` [Hz], and the correction applied."""
    from batcert.physics.modes import compute_modes

    f_model = float(compute_modes(bat, "free", pivot, n_modes=2).frequencies_hz[0])
    scale = (first_bending_frequency / f_model) ** 2
    lo, hi = STIFFNESS_SCALE_BOUNDS
    if not lo <= scale <= hi:
        raise ModelError("measured.first_bending_frequency",
                         f"matching {first_bending_frequency:.0f} Hz needs the material's stiffness "
                         f"x {scale:.2f} (model fundamental {f_model:.0f} Hz; allowed x{lo}-x{hi}): "
                         "check the frequency (free-free, first bending mode), the profile and E")
    model = replace(bat, bending_stiffness=bat.bending_stiffness * scale,
                    shear_stiffness=bat.shear_stiffness * scale)
    return model, {"stiffness_scale": scale, "model_first_frequency_hz": f_model,
                   "measured_first_frequency_hz": first_bending_frequency}
