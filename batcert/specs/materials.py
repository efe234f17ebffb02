"""Named material library. Values and sources; a bat spec may also give a material inline."""

from __future__ import annotations

from batcert.physics.batmodel import Material
from batcert.physics.laminate import OrthotropicPly

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


# Unidirectional plies for laminated walls (batcert.specs.layup), in-plane constants only (the
# shell is plane stress). Published values of one named system differ by 20 % and more with the
# fibre fraction and the source (AS4/3501-6: E1 from 114 to 147 GPa), so each entry states its
# source and fibre fraction; docs/references.md, "Composite plies". No measured loss factor of a
# laminate was found: the loss factors are assumed.
PLIES: dict[str, tuple[OrthotropicPly, str]] = {
    "as4-3501-6": (
        OrthotropicPly("as4-3501-6", 147e9, 10.3e9, 7.0e9, 0.27, 1600.0, 0.005),
        "AS4/3501-6 carbon/epoxy, fibre fraction 0.63: E1 147 GPa, E2 10.3 GPa, G12 7.0 GPa, "
        "nu12 0.27, 1600 kg/m^3 (the table of Daniel & Ishai, Engineering Mechanics of Composite "
        "Materials, 2nd ed., Table A.4, as transcribed in public code; the book itself not "
        "read). Loss factor 0.005 assumed (carbon/epoxy along the fibres: of order 0.1-1 %).",
    ),
    "t700-epoxy": (
        OrthotropicPly("t700-epoxy", 120.05e9, 8.46e9, 3.91e9, 0.317, 1568.0, 0.005),
        "T700SC carbon / LY556 epoxy (filament winding), fibre fraction 0.60: E1 120.05 GPa, "
        "E2 8.46 GPa, G12 3.91 GPa, nu12 0.317 (DLR tankoh2 material card "
        "CFRP_T700SC_LY556.json); density 1568 kg/m^3 by the rule of mixtures from its fibre "
        "(1800) and resin (1220). Loss factor 0.005 assumed.",
    ),
    "e-glass-epoxy": (
        OrthotropicPly("e-glass-epoxy", 41e9, 10.4e9, 4.3e9, 0.28, 1970.0, 0.01),
        "E-glass/epoxy, fibre fraction 0.55: E1 41 GPa, E2 10.4 GPa, G12 4.3 GPa, nu12 0.28, "
        "1970 kg/m^3 (Daniel & Ishai's Table A.4 as transcribed, as for as4-3501-6). Loss "
        "factor 0.01 assumed (glass laminates damp more than carbon ones).",
    ),
}
