"""Named material library. Values and sources; a bat spec may also give a material inline."""

from __future__ import annotations

from batcert.physics.batmodel import Material

# Wood shear modulus: no per-species value was found; use the ratio G/E = 1.05e9 / 1.814e10 = 0.058
# that Nathan (2000, Table I) used for the R161 ash bat.
_WOOD_G_OVER_E = 1.05e9 / 1.814e10

LIBRARY: dict[str, tuple[Material, str]] = {
    "ash": (
        Material("ash", 600.0, 12.0e9, 12.0e9 * _WOOD_G_OVER_E, 0.3, 0.0),
        "White ash: specific gravity about 0.60, E about 12 GPa (handbook static value; bats "
        "measure higher). G from Nathan 2000's G/E ratio. docs/references.md, Materials.",
    ),
    "maple": (
        Material("maple", 630.0, 12.6e9, 12.6e9 * _WOOD_G_OVER_E, 0.3, 0.0),
        "Sugar maple: specific gravity about 0.63, E about 12.6 GPa (USDA Wood Handbook, "
        "clear wood at 12 % moisture; not in docs/references.md, M). G from Nathan 2000's G/E ratio.",
    ),
    "birch": (
        Material("birch", 620.0, 13.9e9, 13.9e9 * _WOOD_G_OVER_E, 0.3, 0.0),
        "Yellow birch: specific gravity 0.62, E 13.9 GPa. docs/references.md, Materials. "
        "G from Nathan 2000's G/E ratio.",
    ),
    "ash-bat": (
        Material("ash-bat", 600.0, 15.0e9, 15.0e9 * _WOOD_G_OVER_E, 0.3, 0.01),
        "Bat-grade ash: E along the grain 15.0 GPa, the 14.7-15.5 GPa (2.14-2.25 Msi) of the "
        "LS-DYNA wood-bat models of Appl. Sci. 12 (2022) 3494, Appendix A (dynamic, stiffer "
        "than the handbook's static 12 GPa; Nathan 2000 needed 18.1 GPa for his R161 to ring at "
        "its measured 165 Hz). Density as handbook ash (reconciled to the bat's mass anyway). "
        "Loss factor 0.01: a wood bat's first mode rings with Q of about 100 (Russell, "
        "acs.psu.edu/drussell/bats, M; derived). G from Nathan 2000's G/E ratio.",
    ),
    "aluminium-7050": (
        Material("aluminium-7050", 2830.0, 71.7e9, 26.9e9, 0.33, 1.0e-4),
        "Aluminium 7050: 2830 kg/m^3, E 71.7 GPa, G 26.9 GPa, Poisson 0.33 (docs/references.md, "
        "H). Loss factor 1e-4: aluminium's flexural loss factor (Cremer & Heckl, Structure-Borne "
        "Sound, 1988, as tabulated by T. Irvine, 'Damping properties of materials', 2004; M).",
    ),
}
