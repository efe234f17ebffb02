"""Calibrate the bat's stiffness to a measured first bending frequency.

Handbook moduli of wood are static values; bats measure stiffer (Nathan 2000 tuned E to the
R161's measured fundamental; docs/references.md, Materials). When a bat spec gives the measured
free-free first bending frequency, the bending stiffness EI and the shear stiffness kappa G A are
scaled by one factor ``s`` (keeping G/E), so every frequency scales with ``sqrt(s)`` and the
fundamental matches exactly: ``s = (f_measured / f_model)^2``.
"""

from __future__ import annotations

from dataclasses import replace

from batcert.errors import ModelError
from batcert.physics.batmodel import BatModel
from batcert.units import INCH

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


BARREL_STIFFNESS_BOUNDS = (0.25, 4.0)
BARREL_MASS_BOUNDS = (0.5, 2.0)


def calibrate_barrel(bat: BatModel, hoop_frequency: float | None = None,
                     compression: dict | None = None) -> tuple[BatModel, dict[str, float]]:
    """Return the bat with its barrel shell calibrated to what a lab measured, and the
    correction applied.

    A measured hoop frequency alone scales the shell's Young's modulus by
    ``s_k = (f_measured / f_model)^2`` (the wall's mass kept), so the model's lowest n = 2
    frequency matches it. A barrel compression test (force on a platen at a stated approach)
    sets ``s_k`` from the static stiffness instead (:func:`batcert.physics.barrel.compression_stiffness`);
    a hoop frequency given with it then sets the shell's mass scale ``s_m`` so that the
    frequency matches too. Corrections outside x0.25-x4 (stiffness) or x0.5-x2 (mass) are
    refused: they say the wall, profile or material of the file is not the bat's.
    """
    from batcert.physics import barrel

    f_model = barrel.hoop_frequency(bat)
    if f_model is None:
        raise ModelError("measured", "only a hollow bat has a barrel to calibrate")
    corr: dict[str, float] = {"model_hoop_frequency_hz": f_model}
    s_k, s_m = 1.0, 1.0
    if compression is not None:
        z = bat.length - compression["position"]
        shell = barrel.barrel_shell(bat)
        half = 0.5 * compression["platen_width"]
        if shell is None or z - half < shell.z[0] or z + half > shell.z[-1]:
            span = "" if shell is None else (
                f" (the hollow wall runs {(bat.length - shell.z[-1]) / INCH:.1f}-"
                f"{(bat.length - shell.z[0]) / INCH:.1f} in from the tip)")
            raise ModelError("measured.barrel_compression.position",
                             f"the platens ({(compression['position'] - half) / INCH:.1f}-"
                             f"{(compression['position'] + half) / INCH:.1f} in from the tip) do "
                             f"not lie on the hollow wall{span}")
        k_model = barrel.compression_stiffness(bat, z, compression["platen_width"])
        k_measured = compression["force"] / compression["deflection"]
        s_k = k_measured / k_model
        corr.update(model_compression_stiffness=k_model,
                    measured_compression_stiffness=k_measured)
        _check_scale("measured.barrel_compression", s_k, BARREL_STIFFNESS_BOUNDS,
                     f"matching {k_measured:.4g} N/m needs the wall's stiffness x {s_k:.2f} "
                     f"(model {k_model:.4g} N/m)")
        if hoop_frequency is not None:
            s_m = s_k * (f_model / hoop_frequency) ** 2
            _check_scale("measured.hoop_frequency", s_m, BARREL_MASS_BOUNDS,
                         f"with the stiffness from the compression test, matching "
                         f"{hoop_frequency:.0f} Hz needs the wall's mass x {s_m:.2f}")
    elif hoop_frequency is not None:
        s_k = (hoop_frequency / f_model) ** 2
        _check_scale("measured.hoop_frequency", s_k, BARREL_STIFFNESS_BOUNDS,
                     f"matching {hoop_frequency:.0f} Hz needs the wall's stiffness x {s_k:.2f} "
                     f"(model hoop frequency {f_model:.0f} Hz)")
    if hoop_frequency is not None:
        corr["measured_hoop_frequency_hz"] = hoop_frequency
    corr.update(barrel_stiffness_scale=s_k, barrel_mass_scale=s_m)
    model = replace(bat, barrel_stiffness_scale=bat.barrel_stiffness_scale * s_k,
                    barrel_mass_scale=bat.barrel_mass_scale * s_m)
    return model, corr


def _check_scale(field: str, scale: float, bounds: tuple[float, float], what: str) -> None:
    lo, hi = bounds
    if not lo <= scale <= hi:
        raise ModelError(field, f"{what}; allowed x{lo}-x{hi}: check the measurement, the "
                         "wall, the profile and the material")
