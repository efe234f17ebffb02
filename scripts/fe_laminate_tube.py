#!/usr/bin/env python
"""
fe_laminate_tube.py -- an independent 3-D continuum finite-element reference for a LAMINATED
tube (cross-ply carbon/epoxy wall), against which batcert's thin-shell-of-revolution model of
composite barrels can be validated.  It is the layered counterpart of fe_tube_reference.py
(the isotropic aluminium tube) and reuses that script by importing it: the tensor mesh in
(r, theta, z), the symmetry classes of the 1/8 model, the mode identification, the load
patches, the case runners and the sparse solvers.  What differs is written here:

  * the wall: plies listed from the INNER surface outward, each a transversely isotropic
    carbon/epoxy ply with the fibre (material axis 1) along the tube axis z (0 deg) or around
    the hoop theta (90 deg); material axis 3 is always radial.  Each ply is an integer number
    of element layers (nr per ply), so the ply interfaces are element faces.
  * the stiffness: a general 6x6 material matrix, built in (1,2,3) as the inverse of the
    compliance, rotated to the local cylindrical basis (e_r, e_theta, e_z) per ply, and
    rotated to the Cartesian x, y, z basis at every quadrature point (theta = atan2(y, x));
    element matrices are sum_q B^T D B detJ w (batched numpy, 3x3x3 Gauss, intorder=5).
  * the mass: each ply's density.

It uses nothing of batcert.  It needs scikit-fem (a test dependency), like the isotropic script.

Symmetry.  For 0/90 plies the planes theta = 0, theta = 90 deg and z = 0 are planes of
material symmetry (the cylindrical-basis matrix has no normal/shear coupling and is the same
at every theta), so the 1/8 models with symmetric/antisymmetric conditions stay valid, also
for an unsymmetric layup (the layup varies with r only).  --verify checks this once against a
full 360-deg, full-length free-free model on a coarse mesh.  --selftest checks the assembly:
with isotropic plies it reproduces fe_tube_reference.Tube (stiffness and mass), and with the
real plies it agrees with scikit-fem's own assembly of a form whose stress is computed by a
different route (strain rotated to cylindrical components, 6x6 in Voigt form, stress rotated
back); and the mass of the model is the exact mass of the layered wall (to the accuracy of the
quadratic arcs: 1e-5 with the 15-deg elements of the check).

Cases (the same output quantities and names as fe_tube_reference.py):
  A  free-free modes, n = 2 and 3, the first two axial orders (axial0: z-symmetric,
     axial1: z-antisymmetric)
  B  shear-diaphragm (simply supported) ends, n = 2 and 3, m = 1 and 2; + thin-shell theory of
     the laminate (classical lamination theory, Sanders and Donnell; no transverse shear)
  C  static squeeze by two opposite 40 x 40 mm patches at mid-length (1000 N resultant each):
     approach of the patch centres and patch-average inward displacement
  D  the same squeeze with the patches centred 50 mm from one end

Usage
  python scripts/fe_laminate_tube.py --quick                 # both layups, cases A and C,
                                                             # mesh 'quick' (~25 s per layup)
  python scripts/fe_laminate_tube.py --out raw.json          # full run: --selftest, --verify,
                                                             # cases A-D on meshes quick, M1-nr1
                                                             # and M1 (see LEVELS): ~25 min on
                                                             # 2 cores with SciPy's SuperLU
  python scripts/fe_laminate_tube.py --record raw.json       # write the compact reference
                                                             # (--to PATH to redirect)
  python scripts/fe_laminate_tube.py --verify                # full-360 model vs symmetry classes
  python scripts/fe_laminate_tube.py --selftest              # assembly checks (~80 s)
The raw output (--out) holds fe_tube_reference's quantities, displacements in mm; the compact
reference (--record) holds frequencies in Hz and squeeze displacements in m per 1000 N.
Units inside: SI (m, N, Pa, kg, s).  The solver is fe_tube_reference's (SciPy SuperLU, or MKL
PARDISO where pypardiso is installed).
"""
import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp
from skfem import BilinearForm, CellBasis, ElementHex2, ElementVector, asm

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe_tube_reference as ref  # noqa: E402
from fe_tube_reference import (  # noqa: E402
    CLASSES,
    F_PATCH,
    LEN,
    PATCH_ARC,
    PATCH_LEN,
    RO,
    SOLVER_NAME,
    case_C,
    identify,
    jdump,
    log,
    mode_type,
    modes_class,
)

# ----------------------------------------------------------------------------
# Data.  The ply properties are INPUTS of the check, not claims about a real barrel: the
# comparison is model against model for the same inputs.  AS4/3501-6 carbon/epoxy,
# transversely isotropic about the fibre direction 1 (2, 3 transverse).
# ----------------------------------------------------------------------------
PLY = dict(name='AS4/3501-6 carbon/epoxy (inputs of the check)',
           E1=142.0e9, E2=10.3e9, E3=10.3e9, G12=7.2e9, G13=7.2e9,
           nu12=0.27, nu13=0.27, nu23=0.59, rho=1580.0)
PLY['G23'] = PLY['E2'] / (2 * (1 + PLY['nu23']))          # transverse isotropy

PLY_T = 1.0e-3          # m, every ply
# fibre angle from the tube axis z toward the hoop theta; listed from the INNER surface out
LAYUPS = {
    'cross-ply-sym': [90, 0, 90],
    'cross-ply-unsym': [0, 0, 90],   # unsymmetric: membrane-bending coupling B != 0
}

# mesh levels: nr = element layers per ply; h_th, h_z (target element arc length on the outer
# surface and axial length) as in fe_tube_reference.LEVELS.  'M1-nr1' -> 'M1' refines through
# the wall only, 'quick' -> 'M1-nr1' in the surface only.  M2's h_th, h_z (1.5, 2.5 mm) with
# 2 layers per ply would be 344k dof in the 1/8 model: with SciPy's SuperLU (~8x the 40 s
# factorisation of M1, 13 of them per layup) far beyond the ~40 min this run is kept to.
LEVELS = {
    'quick': dict(nr=1, h_th=4.0e-3, h_z=7.5e-3),
    'M1-nr1': dict(nr=1, h_th=3.0e-3, h_z=5.0e-3),
    'M1': dict(nr=2, h_th=3.0e-3, h_z=5.0e-3),
}

VOIGT = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]   # 11 22 33 23 13 12 (engineering shear)


# ----------------------------------------------------------------------------
# Material
# ----------------------------------------------------------------------------
def compliance_123(m):
    """6x6 compliance in the material axes (1 = fibre), Voigt order 11 22 33 23 13 12."""
    S = np.zeros((6, 6))
    S[0, 0], S[1, 1], S[2, 2] = 1 / m['E1'], 1 / m['E2'], 1 / m['E3']
    S[0, 1] = S[1, 0] = -m['nu12'] / m['E1']
    S[0, 2] = S[2, 0] = -m['nu13'] / m['E1']
    S[1, 2] = S[2, 1] = -m['nu23'] / m['E2']
    S[3, 3], S[4, 4], S[5, 5] = 1 / m['G23'], 1 / m['G13'], 1 / m['G12']
    return S


def to_tensor(D):
    """6x6 (engineering shear strains) -> C_ijkl; (..., 6, 6) -> (..., 3, 3, 3, 3)."""
    C = np.zeros(D.shape[:-2] + (3, 3, 3, 3))
    for p, (i, j) in enumerate(VOIGT):
        for q, (k, m) in enumerate(VOIGT):
            for a, b in ((i, j), (j, i)):
                for c, d in ((k, m), (m, k)):
                    C[..., a, b, c, d] = D[..., p, q]
    return C


def to_voigt(C):
    idx = np.array(VOIGT)
    return C[..., idx[:, 0, None], idx[:, 1, None], idx[None, :, 0], idx[None, :, 1]]


def rotate(D, Q):
    """6x6 matrix D given in basis b, returned in basis a, where Q[..., a, b] = component
    along a of the unit vector b.  Works batched over leading axes."""
    C = to_tensor(D)
    C = np.einsum('...ia,...jb,...kc,...ld,...abcd->...ijkl', Q, Q, Q, Q, C, optimize=True)
    return to_voigt(C)


def ply_matrix_cyl(angle_deg, m=PLY):
    """6x6 stiffness of a ply in the cylindrical basis (r, theta, z).  Fibre (1) at angle phi
    from z toward theta, 2 = the in-surface transverse direction, 3 = radial."""
    ph = np.radians(angle_deg)
    Q = np.zeros((3, 3))           # Q[cyl, material]
    Q[:, 0] = [0.0, np.sin(ph), np.cos(ph)]
    Q[:, 1] = [0.0, np.cos(ph), -np.sin(ph)]
    Q[:, 2] = [1.0, 0.0, 0.0]
    Q[np.abs(Q) < 1e-15] = 0.0     # cos(90 deg) = 6e-17 -> exactly 0
    D = rotate(np.linalg.inv(compliance_123(m)), Q)
    return 0.5 * (D + D.T)


def iso_matrix(lam, mu):
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[np.arange(3), np.arange(3)] += 2 * mu
    D[np.arange(3, 6), np.arange(3, 6)] = mu
    return D


def cyl_to_cart(theta):
    """Q[..., cart, cyl]: columns e_r, e_theta, e_z in Cartesian components."""
    c, s = np.cos(theta), np.sin(theta)
    Q = np.zeros(np.shape(theta) + (3, 3))
    Q[..., 0, 0], Q[..., 1, 0] = c, s
    Q[..., 0, 1], Q[..., 1, 1] = -s, c
    Q[..., 2, 2] = 1.0
    return Q


def plies_of(layup, m=PLY, t=PLY_T):
    """[(thickness, 6x6 in (r, theta, z), density)] from the inner surface outward."""
    for a in layup:
        if a % 90:
            raise ValueError('only 0/90 plies keep theta = 0, 90 deg and z = 0 planes of symmetry')
    return [(t, ply_matrix_cyl(a, m), m['rho']) for a in layup]


# ----------------------------------------------------------------------------
# Model
# ----------------------------------------------------------------------------
class LamTube(ref.Tube):
    """Layered tube segment: plies from the inner surface (r = RO - sum t) outward, nr element
    layers per ply; theta in th_pts, z in z_pts.  Everything but the construction (boundary
    conditions, solvers, load patches, polar components) is fe_tube_reference.Tube's.

    The mesh is Tube.mesh_on's with one radial linspace per ply; only the assembly differs."""

    def __init__(self, plies, th_pts, z_pts, nr, periodic=False, chunk=1000):
        t0 = time.time()
        self.plies = plies
        self.t = sum(p[0] for p in plies)
        r_if = RO - self.t + np.concatenate([[0.0], np.cumsum([p[0] for p in plies])])
        r_if[-1] = RO
        self.r_interfaces = r_if
        r_pts = np.concatenate([r_if[:1]] + [np.linspace(a, b, nr + 1)[1:]
                                             for a, b in zip(r_if[:-1], r_if[1:], strict=True)])
        m1, sb, ed = self.mesh_on(r_pts, th_pts, z_pts, periodic)
        # ply of each element, from the mean radius of its vertices
        rc = m1.p[0, m1.t].mean(axis=0)
        self.ply = np.clip(np.searchsorted(r_if, rc) - 1, 0, len(plies) - 1)
        Dcyl = np.array([p[1] for p in plies])[self.ply]          # (nel, 6, 6)
        rho = np.array([p[2] for p in plies])[self.ply]           # (nel,)
        self.K, self.Ms = self._assemble(sb, ed, Dcyl, rho, chunk)
        self.M = sp.kron(self.Ms, sp.eye(3)).tocsr()
        self.ed = ed
        self.nel = sb.nelems
        self.time_asm = time.time() - t0

    def _assemble(self, sb, ed, Dcyl, rho, chunk):
        nb = 27
        nel = sb.nelems
        N, nn = self.N, self.nn
        G = np.stack([sb.basis[a][0].grad for a in range(nb)])     # (27, 3, nel, nq)
        Phi = np.stack([sb.basis[a][0].value for a in range(nb)])  # (27, nel, nq)
        dx = sb.dx                                                 # (nel, nq)
        xq = sb.global_coordinates().value                         # (3, nel, nq)
        theta = np.arctan2(xq[1], xq[0])
        nq = dx.shape[1]
        # strain rows (xx, yy, zz, yz, xz, xy) <- (derivative j of component k)
        rows = [(0, 0, 0), (1, 1, 1), (2, 2, 2), (3, 2, 1), (3, 1, 2), (4, 2, 0), (4, 0, 2),
                (5, 1, 0), (5, 0, 1)]                               # (strain, j, k)
        Ks, Ms = [], []
        for c0 in range(0, nel, chunk):
            sl = slice(c0, min(nel, c0 + chunk))
            ne = sl.stop - sl.start
            g = G[:, :, sl, :].transpose(2, 3, 1, 0)                  # (e, q, j, a)
            B = np.zeros((ne, nq, 6, nb, 3))
            for s, j, k in rows:
                B[:, :, s, :, k] = g[:, :, j, :]
            B = B.reshape(ne, nq, 6, nb * 3)
            D = rotate(Dcyl[sl, None], cyl_to_cart(theta[sl]))       # (e, q, 6, 6) Cartesian
            DB = np.matmul(D * dx[sl, :, None, None], B)
            Ke = np.matmul(B.reshape(ne, nq * 6, nb * 3).transpose(0, 2, 1),
                           DB.reshape(ne, nq * 6, nb * 3))
            Me = np.einsum('aeq,beq,eq->eab', Phi[:, sl], Phi[:, sl], dx[sl] * rho[sl, None],
                           optimize=True)
            e_d = ed[:, sl].T
            vd = (3 * e_d[:, :, None] + np.arange(3)).reshape(ne, nb * 3)
            Ks.append(sp.coo_matrix((Ke.ravel(), (np.repeat(vd, nb * 3, axis=1).ravel(),
                                                  np.tile(vd, (1, nb * 3)).ravel())),
                                    shape=(N, N)).tocsr())
            Ms.append(sp.coo_matrix((Me.ravel(), (np.repeat(e_d, nb, axis=1).ravel(),
                                                  np.tile(e_d, (1, nb)).ravel())),
                                    shape=(nn, nn)).tocsr())
            del B, DB, Ke, D
        K = sum(Ks[1:], Ks[0]).tocsr()
        return ((K + K.T) * 0.5).tocsr(), sum(Ms[1:], Ms[0]).tocsr()


def eighth_model(plies, lev):
    """fe_tube_reference.eighth_model with the laminated tube and this script's levels."""
    return ref.eighth_model(plies, lev, LamTube, LEVELS)


# ----------------------------------------------------------------------------
# Thin-shell theory of the laminate (classical lamination theory), simply supported
# ----------------------------------------------------------------------------
def abd(plies):
    """A, B, D (3x3 each, order x = z axial, theta, gamma) about the mid-surface r = RO - t/2,
    from each ply's plane-stress stiffness (the inverse of the in-surface block of the inverse
    of its 3-D matrix)."""
    t = sum(p[0] for p in plies)
    zk = np.concatenate([[0.0], np.cumsum([p[0] for p in plies])]) - t / 2
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for (_, Dc, _), z0, z1 in zip(plies, zk[:-1], zk[1:], strict=True):
        ix = [2, 1, 3]                         # zz, theta-theta, theta-z in (r, theta, z) Voigt
        Qb = np.linalg.inv(np.linalg.inv(Dc)[np.ix_(ix, ix)])
        A += Qb * (z1 - z0)
        B += Qb * (z1 ** 2 - z0 ** 2) / 2
        D += Qb * (z1 ** 3 - z0 ** 3) / 3
    return A, B, D


def shell_ss_freqs(plies, n, m, theory='sanders'):
    """Three frequencies [Hz] of the simply supported thin laminated cylinder (mid-surface
    radius R = RO - t/2, length LEN), n circumferential waves, m axial half-waves: the
    Rayleigh-Ritz/Navier solution, exact for the theory when A16 = A26 = B16 = B26 = D16 = D26 = 0
    (cross-ply): u = a cos(al x) cos(n th), v = b sin sin, w = c sin cos, al = m pi / L.
    Strain energy with the full [[A, B], [B, D]] matrix; kinetic energy I0 = sum rho_k t_k
    (no rotary inertia).  With one isotropic ply it is fe_tube_reference.shell_ss_freqs."""
    t = sum(p[0] for p in plies)
    R = RO - t / 2
    al = m * np.pi / LEN
    # rows: coefficients over (a, b, c) of eps_x, eps_th, gamma, kappa_x, kappa_th, 2 kappa_xth
    E6 = np.array([[-al, 0, 0], [0, n / R, 1 / R], [-n / R, al, 0], [0, 0, al ** 2],
                   [0, 0, n ** 2 / R ** 2], [0, 0, 2 * al * n / R]], float)
    if theory == 'sanders':
        E6[4] = [0, n / R ** 2, n ** 2 / R ** 2]
        E6[5] = [n / (2 * R ** 2), 1.5 * al / R, 2 * al * n / R]
    elif theory != 'donnell':
        raise ValueError(theory)
    A, B, D = abd(plies)
    ABD = np.block([[A, B], [B, D]])
    I0 = sum(p[0] * p[2] for p in plies)
    w2 = np.sort(np.linalg.eigvalsh(E6.T @ ABD @ E6)) / I0
    return np.sqrt(w2) / (2 * np.pi)


# ----------------------------------------------------------------------------
# Cases A, B and D (case C is fe_tube_reference's)
# ----------------------------------------------------------------------------
def case_A(model, k=12):
    """free-free: fe_tube_reference.case_A on the classes SS and SA only: AS and AA (the sin
    partners of the same modes, and torsion) are not needed by the picked modes, and leaving
    them out halves the run time."""
    return ref.case_A(model, k=k, classes=('SS', 'SA'))


def case_B(model, k=10):
    """shear-diaphragm ends: fe_tube_reference.case_B with the laminated wall's Sanders and
    Donnell frequencies."""
    return ref.case_B(model, k=k, thin_shell=lambda n, m: {
        th: float(shell_ss_freqs(model.plies, n, m, th)[0]) for th in ['sanders', 'donnell']})


# ----------------------------------------------------------------------------
# Drivers
# ----------------------------------------------------------------------------
def run_layup(name, lev, cases):
    plies = plies_of(LAYUPS[name])
    out = {}
    T0 = time.time()
    model = eighth_model(plies, lev)
    out['mesh'] = ref.mesh_record(model, lev, LEVELS)
    log('  %s %s: 1/8 model %d dof, %d el, asm %.1f s' % (name, lev, model.N, model.nel, model.time_asm))
    if 'A' in cases:
        ref.run_case_A(out, case_A, model)
    if 'B' in cases:
        ref.run_case_B(out, case_B, model, 'Sanders (CLT)', 'sanders')
    if 'C' in cases:
        t0 = time.time()
        out['C'] = case_C(model)[0]
        out['C_time_s'] = time.time() - t0
        log('    C approach %.5f mm, patch-avg %.5f mm' % (out['C']['approach_mm'], out['C']['patch_avg_inward_mm']))
    del model
    if 'D' in cases:
        ref.run_case_D(out, plies, lev, LamTube, LEVELS)
    out['wall_time_s'] = time.time() - T0
    log('    %s %s done in %.1f s' % (name, lev, out['wall_time_s']))
    return out


def verify(layup='cross-ply-unsym', h_th=6.0e-3, h_z=10.0e-3, nr=1, k_full=40):
    """Full 360-deg, full-length free-free model vs the 8 symmetry classes of the 1/8 model
    built with the SAME node positions (uniform theta spacing), as fe_tube_reference.verify."""
    plies = plies_of(LAYUPS[layup])
    nq = int(np.ceil(np.pi / 2 * RO / h_th))
    nzh = int(np.ceil(LEN / 2 / h_z))
    T0 = time.time()
    full = LamTube(plies, np.linspace(0, 2 * np.pi, 4 * nq + 1), np.linspace(-LEN / 2, LEN / 2, 2 * nzh + 1), nr,
                   periodic=True)
    log('verify (%s): full model %d dof (asm %.1f s)' % (layup, full.N, full.time_asm))
    ff, Vf = full.eig(np.zeros(0, int), k_full, sigma=-(2 * np.pi * 300.0) ** 2)
    fullm = []
    for i in range(k_full):
        idd = identify(full, Vf[:, i], cls=None, z_full=True)
        typ = mode_type(ff[i], idd)
        fullm.append(dict(f_Hz=float(ff[i]), n=0 if typ.startswith('torsional') else idd['n'],
                          axial_sign_changes=idd['axial_sign_changes'], type=typ))
    tfull = time.time() - T0
    eighth = LamTube(plies, np.linspace(0, np.pi / 2, nq + 1), np.linspace(0, LEN / 2, nzh + 1), nr)
    symm = []
    for c in CLASSES:
        for zs in ['S', 'A']:
            symm += modes_class(eighth, c, zs, None, k=8)
    symm.sort(key=lambda m: m['f_Hz'])
    fs = np.array([m['f_Hz'] for m in symm])
    rows = []
    for m in fullm:
        j = np.argmin(np.abs(fs - m['f_Hz']))
        rows.append(dict(full=m, sym_f_Hz=float(fs[j]), sym_class=symm[j]['class'], sym_n=symm[j]['n'],
                         sym_axial_sign_changes=symm[j]['axial_sign_changes'],
                         rel_diff=float((m['f_Hz'] - fs[j]) / max(abs(fs[j]), 1.0))))
    # every full-model mode has its partner, and each 1/8-model mode below the highest full-model
    # frequency is used (no spurious or missing symmetry-class modes)
    fmax = fullm[-1]['f_Hz'] * (1 - 1e-6)
    n_sym_below = int(np.sum(fs < fmax))
    n_full_below = int(np.sum(ff < fmax))
    elastic = [r for r in rows if abs(r['full']['f_Hz']) > 1.0]
    # and the two sorted spectra below fmax, pairwise (degenerate pairs included)
    fe_, se_ = np.sort(ff[(ff > 1.0) & (ff < fmax)]), np.sort(fs[(fs > 1.0) & (fs < fmax)])
    sorted_diff = float(np.abs(fe_ / se_ - 1).max()) if fe_.size == se_.size else None
    return dict(layup=layup, mesh=dict(nr_per_ply=nr, h_th=h_th, h_z=h_z, n_theta_full=4 * nq, n_z_full=2 * nzh,
                                       ndof_full=full.N, ndof_eighth=eighth.N),
                time_full_s=tfull, time_total_s=time.time() - T0,
                n_modes_full=k_full, n_elastic=len(elastic),
                max_rel_diff_elastic=float(max(abs(r['rel_diff']) for r in elastic)),
                max_rel_diff_sorted_spectra=sorted_diff,
                f_max_Hz=fullm[-1]['f_Hz'], n_full_below_fmax=n_full_below, n_sym_below_fmax=n_sym_below,
                rows=rows)


def selftest():
    """Assembly checks (see the module docstring)."""
    res = {}
    # 1. material: engineering constants back from the cylindrical 6x6 of 0 and 90 deg plies
    m = PLY
    S0, S90 = np.linalg.inv(ply_matrix_cyl(0)), np.linalg.inv(ply_matrix_cyl(90))   # (r, th, z)
    back = dict(E_z_0=1 / S0[2, 2] / m['E1'], E_th_90=1 / S90[1, 1] / m['E1'], E_r_0=1 / S0[0, 0] / m['E3'],
                E_th_0=1 / S0[1, 1] / m['E2'], nu_zth_0=-S0[2, 1] / S0[2, 2] / m['nu12'],
                nu_thr_0=-S0[1, 0] / S0[1, 1] / m['nu23'], nu_thz_90=-S90[1, 2] / S90[1, 1] / m['nu12'],
                G_thz_0=1 / S0[3, 3] / m['G12'], G_rz_0=1 / S0[4, 4] / m['G13'], G_rth_0=1 / S0[5, 5] / m['G23'],
                G_rth_90=1 / S90[5, 5] / m['G13'], G_rz_90=1 / S90[4, 4] / m['G23'])
    res['engineering_constants_max_rel_err'] = float(max(abs(v - 1) for v in back.values()))
    res['normal_shear_coupling_max'] = float(max(np.abs(ply_matrix_cyl(a)[:3, 3:]).max() for a in (0, 90)))  # Pa
    log('selftest: engineering constants back from the 6x6: max rel err %.1e; normal-shear coupling %.1e' % (
        res['engineering_constants_max_rel_err'], res['normal_shear_coupling_max']))
    th = np.linspace(0, np.pi / 2, 7)
    z = np.linspace(0, LEN / 2, 6)
    # 2. isotropic plies reproduce fe_tube_reference.Tube
    iso = [(PLY_T, iso_matrix(ref.LAM, ref.MU), ref.RHO)] * 3
    a, b = LamTube(iso, th, z, 1), ref.Tube(3 * PLY_T, th, z, 3)
    res['iso_K_rel_diff'] = float(abs(a.K - b.K).max() / abs(b.K).max())
    res['iso_M_rel_diff'] = float(abs(a.M - b.M).max() / abs(b.M).max())
    res['iso_node_max_diff_m'] = float(np.abs(a.mesh.doflocs - b.mesh.doflocs).max())
    log('selftest: isotropic plies vs fe_tube_reference.Tube: K %.1e, M %.1e (relative, max entry)' % (
        res['iso_K_rel_diff'], res['iso_M_rel_diff']))
    # 3. real plies: skfem.asm of a form with the stress computed by another route
    for name, layup in LAYUPS.items():
        plies = plies_of(layup)
        mod = LamTube(plies, th, z, 2)
        Dc = np.array([p[1] for p in plies])
        r_if = mod.r_interfaces

        @BilinearForm
        def form(u, v, w, Dc=Dc, r_if=r_if):
            x = w.x
            Q = np.moveaxis(cyl_to_cart(np.arctan2(x[1], x[0])), (-2, -1), (0, 1))   # (3, 3, nel, nq)
            ply = np.clip(np.searchsorted(r_if, np.hypot(x[0], x[1])) - 1, 0, len(r_if) - 2)
            D = np.moveaxis(Dc[ply], (-2, -1), (0, 1))                               # (6, 6, nel, nq)

            def strain_cyl(g):
                e = 0.5 * (g + np.swapaxes(g, 0, 1))
                return np.einsum('ia...,jb...,ij...->ab...', Q, Q, e)
            ec = strain_cyl(u.grad)
            ev = np.stack([ec[i, j] * (1 if i == j else 2) for i, j in VOIGT])
            sv = np.einsum('pq...,q...->p...', D, ev)
            sc = np.zeros((3, 3) + sv.shape[1:])
            for p, (i, j) in enumerate(VOIGT):
                sc[i, j] = sc[j, i] = sv[p]
            sig = np.einsum('ia...,jb...,ab...->ij...', Q, Q, sc)
            gv = v.grad
            return np.einsum('ij...,ij...->...', sig, 0.5 * (gv + np.swapaxes(gv, 0, 1)))

        ib = CellBasis(mod.mesh, ElementVector(ElementHex2()), intorder=5)
        K2 = asm(form, ib)
        ix = ib.split_indices()
        perm = np.zeros(mod.N, int)
        for i in range(3):
            perm[3 * np.arange(mod.nn) + i] = ix[i]
        d = abs(K2[perm][:, perm] - mod.K).max() / abs(mod.K).max()
        ux = np.zeros(mod.N)
        ux[0::3] = 1
        mass = ux @ mod.M @ ux
        exact = sum(p[2] * np.pi * (r1 ** 2 - r0 ** 2) * LEN / 8
                    for p, r0, r1 in zip(plies, r_if[:-1], r_if[1:], strict=True))
        res[name] = dict(K_rel_diff_vs_skfem_form=float(d), mass_rel_err=float(mass / exact - 1))
        log('selftest %s: |K - K_skfem(stress by rotation of strain)|/|K| = %.1e; mass rel err %.1e' % (
            name, d, mass / exact - 1))
    # 4. the laminated shell formula with one isotropic ply is the isotropic script's
    d = max(abs(shell_ss_freqs([(3e-3, iso_matrix(ref.LAM, ref.MU), ref.RHO)], n, mm, th)[0]
                / ref.shell_ss_freqs(n, mm, 3e-3, th)[0] - 1)
            for n in (2, 3) for mm in (1, 2) for th in ('sanders', 'donnell'))
    res['clt_shell_vs_isotropic_formula_max_rel_diff'] = float(d)
    log('selftest: laminated shell formula vs isotropic one: %.1e' % d)
    return res


def record_level(r):
    """The numbers of one layup and mesh level: frequencies [Hz] with their identification,
    squeezes [m] per 1000 N resultant."""
    rec = {}
    for case, key in (('A', 'free_free'), ('B', 'shear_diaphragm')):
        if case in r:
            rec[key + '_hz'] = {k: v['f_Hz'] for k, v in r[case].items() if v}
            rec[key + '_modes'] = {k: dict(n=v['n'], axial_sign_changes=v['axial_sign_changes'],
                                           symmetry_class=v['class'], E_radial=round(v['E_radial'], 4))
                                   for k, v in r[case].items() if v}
    for case, key in (('C', 'squeeze_mid_m'), ('D', 'squeeze_end_m')):
        if case in r:
            rec[key] = dict(centre_approach=r[case]['approach_mm'] * 1e-3,
                            patch_average_inward=r[case]['patch_avg_inward_mm'] * 1e-3)
    rec['mesh'] = {k: r['mesh'][k] for k in ('ndof', 'nel', 'n_theta_quarter', 'n_z_half')}
    rec['time_s'] = {k: round(v, 1) for k, v in r.items() if k.endswith('time_s')}
    return rec


def flat(rec):
    out = {}
    for k, v in rec.items():
        if k.endswith('_hz') or k.startswith('squeeze'):
            out.update({'%s.%s' % (k, kk): vv for kk, vv in v.items()})
    return out


def record(raw, source):
    """The compact reference (tests/validation/data/fe_laminate_tube.json)."""
    inp = raw['inputs']
    out = dict(
        source=source,
        command=raw['command'],
        date=raw['date'],
        solver=raw['solver'],
        tube=dict(outer_diameter_m=inp['D_out_m'], length_m=inp['L_m']),
        ply_material=dict(inp['ply'], note='inputs of the check: the comparison is model vs model for the same '
                          'inputs; 1 = fibre, 3 = radial, transversely isotropic (2 = 3)'),
        layups={k: dict(angles_deg_inner_to_outer=v, ply_thickness_m=[PLY_T] * len(v), wall_m=PLY_T * len(v),
                        angle_convention='fibre angle from the tube axis z toward the hoop theta')
                for k, v in inp['layups'].items()},
        load=dict(patch_length_m=inp['patch_len_m'], patch_arc_m=inp['patch_arc_m'],
                  static_force_N=inp['F_patch_N'], end_patch_from_end_m=0.050,
                  force_definition='resultant (vector sum) of the uniform pressure on one patch'),
        units=dict(frequencies='Hz', squeeze='m per 1000 N resultant of each patch (the static_force_N)'),
        meshes=inp['levels'],
        results={}, convergence={})
    if 'selftest' in raw:
        out['selftest'] = raw['selftest']
    if 'verify' in raw:
        out['verify_360'] = {k: v for k, v in raw['verify'].items() if k != 'rows'}
    for lay in inp['layups']:
        levels = raw['runs'][lay]
        res = {lev: record_level(r) for lev, r in levels.items()}
        shell = next((r['B_shell_theory_Hz'] for r in levels.values() if 'B_shell_theory_Hz' in r), None)
        if shell:
            out.setdefault('thin_shell_theory_hz', {})[lay] = shell
        out['results'][lay] = res
        order = [lev for lev in LEVELS if lev in res]
        conv = {}
        for c, f in [(order[i], order[j]) for j in range(len(order)) for i in range(j)]:
            fine, coarse = flat(res[f]), flat(res[c])
            conv['%s_vs_%s' % (c, f)] = {k: coarse[k] / v - 1 for k, v in fine.items() if k in coarse}
        out['convergence'][lay] = dict(
            note='relative difference of the coarser level from the finer one, per number', **conv)
    out['total_time_s'] = raw.get('total_time_s')
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--quick', action='store_true', help='both layups, cases A and C, mesh "quick"')
    ap.add_argument('--layups', nargs='*', default=list(LAYUPS))
    ap.add_argument('--levels', nargs='*', default=list(LEVELS))
    ap.add_argument('--cases', default='ABCD')
    ap.add_argument('--no-checks', action='store_true', help='full run without --selftest and --verify')
    ap.add_argument('--verify', action='store_true')
    ap.add_argument('--selftest', action='store_true')
    ap.add_argument('--out', default=None)
    ap.add_argument('--record', metavar='RAW', default=None,
                    help='write the compact reference of a full run (RAW: its --out file)')
    ap.add_argument('--to', default='tests/validation/data/fe_laminate_tube.json',
                    help='with --record: where to write it')
    args = ap.parse_args()
    T0 = time.time()
    if args.record:
        with open(args.record) as fh:
            raw = json.load(fh)
        import skfem
        source = ('scripts/fe_laminate_tube.py, full run of %s (meshes %s) with scikit-fem %s and %s' % (
            raw['date'], ', '.join(raw['inputs']['levels']), skfem.__version__, raw['solver']))
        jdump(record(raw, source), args.to)
        log('wrote %s' % args.to)
        return
    if args.selftest:
        jdump(selftest(), args.out or 'selftest_laminate.json')
        return
    if args.verify:
        v = verify()
        jdump(v, args.out or 'verify_laminate.json')
        for r in v['rows']:
            log('%10.2f  n=%d ch=%d %-40s | sym %10.2f %s n=%d ch=%d  d=%.1e' % (
                r['full']['f_Hz'], r['full']['n'], r['full']['axial_sign_changes'], r['full']['type'],
                r['sym_f_Hz'], r['sym_class'], r['sym_n'], r['sym_axial_sign_changes'], r['rel_diff']))
        log('max |rel diff| (elastic modes) %.1e; modes below %.0f Hz: full %d, symmetry classes %d; '
            'sorted spectra %s' % (v['max_rel_diff_elastic'], v['f_max_Hz'], v['n_full_below_fmax'],
                                   v['n_sym_below_fmax'], v['max_rel_diff_sorted_spectra']))
        return
    levels = ['quick'] if args.quick else args.levels
    cases = 'AC' if args.quick else args.cases
    raw = dict(command=' '.join(['python'] + sys.argv), date=time.strftime('%Y-%m-%d'), solver=SOLVER_NAME,
               inputs=dict(D_out_m=2 * RO, L_m=LEN, patch_len_m=PATCH_LEN, patch_arc_m=PATCH_ARC,
                           F_patch_N=F_PATCH, ply=PLY, ply_t_m=PLY_T,
                           layups={k: LAYUPS[k] for k in args.layups},
                           levels={k: LEVELS[k] for k in levels}),
               runs={})
    fn = args.out or ('results_laminate_quick.json' if args.quick else 'results_laminate_raw.json')
    if not args.quick and not args.no_checks:
        t0 = time.time()
        raw['selftest'] = selftest()
        raw['selftest']['time_s'] = time.time() - t0
        t0 = time.time()
        raw['verify'] = verify()
        log('verify: max |rel diff| %.1e over %d elastic modes (%.0f s)' % (
            raw['verify']['max_rel_diff_elastic'], raw['verify']['n_elastic'], time.time() - t0))
        jdump(raw, fn)
    for name in args.layups:
        raw['runs'][name] = {}
        for lev in levels:
            log('layup %s %s, mesh %s' % (name, LAYUPS[name], lev))
            raw['runs'][name][lev] = run_layup(name, lev, cases)
            jdump(raw, fn)
    raw['total_time_s'] = time.time() - T0
    jdump(raw, fn)
    log('total %.1f s' % raw['total_time_s'])


if __name__ == '__main__':
    main()
