#!/usr/bin/env python
"""
fe_ball_contact.py -- an independent 3-D finite-element reference for the contact FOOTPRINT of
an elastic ball pressed onto a rigid barrel (a circular cylinder) or onto a rigid flat, against
which batcert's footprint rule (Hertz's elliptical contact, batcert/physics/balls/footprint.py)
is checked in the small-strain regime (tests/validation/test_fe_ball_contact_reproduces.py,
data in tests/validation/data/fe_ball_contact.json).

It uses no contact theory (Hertz's formulas are evaluated only to be compared with) and nothing
of batcert; it needs scikit-fem (a test dependency) and SciPy (SuperLU).

Everything here is quasi-static, small-strain, frictionless, linear elasticity:
  * ball       : a sphere of radius R_b = 36.9 mm (9 1/8 in circumference), homogeneous and
                 isotropic, E = 10 MPa (the footprint against a rigid surface does not depend
                 on E; forces scale with it), nu = 0.3 and 0.45
  * counterface: a rigid circular cylinder, axis along x, radius R_c = 33.3375 mm (a 2 5/8 in
                 barrel) or 28.575 mm (a 2 1/4 in softball barrel), or a rigid flat; it touches
                 the ball's bottom pole P = (0, -R_b, 0) before loading
  * loading    : the quasi-static analogue of an impact: a uniform body force along -y (the
                 ball's deceleration) pushes the ball on the counterface and is balanced by the
                 contact reactions.  The compression u, the mean displacement of the ball (its
                 centre of mass's) toward the counterface, is prescribed; the body force comes
                 out, and F = body force per volume x the ball's volume is the contact force
  * symmetry   : quarter model x >= 0, z >= 0 (u_x = 0 on x = 0, u_z = 0 on z = 0); the one
                 rigid motion left, the translation along y, is taken up by the contact: the
                 pole, in contact with zero gap at any load, has u_y = 0 (its reaction is
                 checked to be compressive)
  * elements   : 27-node tri-quadratic hexahedra (scikit-fem ElementHex2) on an ISOPARAMETRIC
                 quadratic mesh (MeshHex2): every node, mid-side ones included, is placed by the
                 exact map below, so all surface nodes lie on the sphere; 3x3x3 Gauss
                 quadrature (intorder=5); element matrices formed with numpy from the
                 scikit-fem basis (checked against skfem.asm by --selftest)
  * mesh       : graded toward P with element size proportional to the distance from P.
                 The quarter ball is the image, under the inversion about the top pole Q
                 (radius 2 R_b), of the half-space that touches the ball at P; the inversion
                 maps the tangent plane at P onto the sphere, the symmetry planes onto
                 themselves, and is conformal (shapes are kept) with unit scale at P.  In the
                 half-space the mesh is polar about P: the octant of directions is split into
                 3 structured patches (n x n elements each, equiangular), layers are
                 geometric in the distance rho from P (aspect ratio 1 near the contact, up to
                 FAR_ASPECT far from it), a small "cube + 3 shells" octant ball fills
                 rho < rho0, and the region around Q is a second such octant ball, built in
                 the half-space of the inversion about P.  Nodes shared by blocks are merged.
                 Levels: n = 4 ('quick'), 6 (M1), 8 (M2); see LEVELS
  * contact    : unilateral, frictionless, node-to-rigid-surface on the ball's surface nodes
                 near P (the candidates: inside (1.2 + 2.5 x the angular step) times the largest
                 Hertz ellipse of the run; checked that every surface face touching the contact
                 has only candidate nodes); the gap is measured along y to the counterface at
                 the node's undeformed (x, z) (small-displacement gap) and the reaction is
                 along y.  Solved by a primal-dual active-set (Signorini) iteration on the
                 condensed problem: the compliance C_ij = u_y at candidate i per unit force
                 along y at candidate j (one sparse solve per candidate, SuperLU, in
                 parallel by fork), the response to the body force, and the mean-displacement
                 constraint.  Active nodes get u_y = -gap; nodes with a tensile reaction are
                 dropped, penetrating ones added, until a fixed point.  The converged state is
                 re-solved on the full model as a check (mean displacement, gaps, reactions)
  * pressure   : from the nodal contact reactions lambda_i (N, along y):
                 F = 4 sum(lambda) (full ball);  <f>_p = sum(lambda_i f(x_i, s_i)) / sum(lambda);
                 a_eq = sqrt(5 <x^2>_p) along the cylinder's axis and b_eq = sqrt(5 <s^2>_p)
                 around it, s the arc length on the cylinder from the contact centre
                 (s = R_c asin(z / R_c); s = z on the flat), for Hertz's ellipsoidal pressure
                 exactly the semi-axes (if the reactions are the consistent nodal loads of a
                 pressure p on flat Q2 faces, sum lambda_i x_i^2 is exactly the integral of
                 p x^2; the same measures on the deformed positions are reported for reference).
                 The marginals (pressure integrated across,
                 per unit length, binned along x and along s, 20 bins) use the field
                 p = sum_i (lambda_i / A_i) N_i on the surface (A_i = integral of N_i; it carries
                 the same total force), integrated by 5x5-point Gauss per surface face
  * Hertz      : for the same u (Hertz's approach of distant points, set equal to the
                 centre-of-mass approach): A = 1/(2 R_b), B = A + 1/(2 R_c);
                 B/A = ((1/(1-e^2)) E(e) - K(e)) / (K(e) - E(e)), e^2 = 1 - (b/a)^2,
                 a^2 = u (K - E) / (A K e^2), b = a sqrt(1 - e^2), F = (2/3) pi a u E* / K,
                 E* = E / (1 - nu^2); flat: a = b = sqrt(R_b u), F = (4/3) E* sqrt(R_b) u^1.5.
                 Reported with the FE/Hertz ratios of a_eq, b_eq, F, the extents, b/a, and two
                 that separate the approach from the rest: the Hertz approach that would give
                 the FE's a_eq (over u), and F over Hertz's force at the FE's a_eq

Cases: counterfaces 'cyl_2.625in', 'cyl_2.25in', 'flat'; u/R_b = 0.01, 0.02, 0.04, 0.07,
0.10, 0.15; nu = 0.3 and 0.45 (all three counterfaces, as they share the compliance);
meshes M1 and M2.  --quick: the coarse mesh, 'cyl_2.625in', u/R_b = 0.02 and 0.07, nu = 0.3.

Usage
  python scripts/fe_ball_contact.py --out raw.json       # full run: M1 and M2, nu 0.3 and
                                                         # 0.45, plus the --quick case (33 min
                                                         # on 2 cores, 16 GB: M1 2 x 2.2 min,
                                                         # M2 2 x 14 min)
  python scripts/fe_ball_contact.py --record raw.json    # write the compact reference the
                                                         # tests read (--to PATH to redirect;
                                                         # --quick-run Q.json: record that
                                                         # --quick run instead of raw's)
  python scripts/fe_ball_contact.py --quick              # coarse mesh, one cylinder, two
                                                         # compressions (~12 s); --out PATH
  python scripts/fe_ball_contact.py --selftest           # assembly check against skfem.asm
Units inside: SI (m, N, Pa).  Reported: mm, N.
"""
import os

# SuperLU's many small dense kernels (the multi-right-hand-side solves) run several times
# slower with OpenBLAS's threads than without; the 2 cores go to 2 worker processes instead
os.environ.setdefault('OPENBLAS_NUM_THREADS', '1')
import argparse
import json
import logging
import multiprocessing
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from scipy.optimize import brentq
from scipy.spatial import cKDTree
from scipy.special import ellipe, ellipk
from skfem import CellBasis, ElementHex2, MeshHex, MeshHex2
from skfem.assembly import Dofs

# ----------------------------------------------------------------------------
# Data
# ----------------------------------------------------------------------------
R_B = 36.9e-3                     # m, ball radius (9 1/8 in circumference: 36.89 mm)
E_MOD = 10.0e6                    # Pa (footprint independent of it; F proportional to it)
NUS = (0.3, 0.45)
COUNTERFACES = {                  # name -> cylinder radius [m] (inf: flat)
    'cyl_2.625in': 2.625 / 2 * 0.0254,    # 33.3375 mm
    'cyl_2.25in': 2.25 / 2 * 0.0254,      # 28.575 mm
    'flat': np.inf,
}
U_OVER_R = (0.01, 0.02, 0.04, 0.07, 0.10, 0.15)
QUICK = dict(level='quick', nu=0.3, counterfaces=('cyl_2.625in',), u_over_r=(0.02, 0.07))
P_POLE = np.array([0.0, -R_B, 0.0])   # bottom pole: the contact centre
Q_POLE = np.array([0.0, R_B, 0.0])    # top pole
TH_CONTACT = 0.70     # rad: polar angle (from P) up to which layers keep aspect ratio 1
TH_RAMP = 0.50        # rad: over which the layers' aspect ratio grows to FAR_ASPECT
FAR_ASPECT = 2.0
TH_MAX = 0.75 * np.pi  # polar layers end there; the cap around Q is the second octant ball
CAND_MARGIN = (1.2, 2.5)  # candidate region: (1.2 + 2.5 x the angular step) x the largest
                          # Hertz semi-axes (the contact, and the faces around it, inside)
N_BINS = 20

# mesh levels: n = elements along each side of the 3 direction patches (angular step
# pi/(4n) rad); rho0 = radius of the octant ball around P (half-space coordinates)
LEVELS = {
    'quick': dict(n=4, rho0=2.5e-3),
    'M1': dict(n=6, rho0=2.0e-3),
    'M2': dict(n=8, rho0=1.5e-3),
}


def log(*a):
    print(*a, flush=True)


def jdefault(o):
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(type(o))


def jdump(obj, fn):
    with open(fn, 'w') as fh:
        json.dump(obj, fh, indent=1, default=jdefault)


def lame(nu):
    return E_MOD * nu / ((1 + nu) * (1 - 2 * nu)), E_MOD / (2 * (1 + nu))


# ----------------------------------------------------------------------------
# Mesh
# ----------------------------------------------------------------------------
def _tan_q(s):
    """equiangular coordinate on a cube face: s in [0, 1] -> tan(pi s / 4)."""
    return np.tan(0.25 * np.pi * s)


def _face_point(face, s, t, equiangular):
    """Point of the unit cube's face 'X' (a1 = 1), 'Z' (a2 = 1) or 'N' (a3 = 1) at face
    coordinates (s, t); local octant axes: a1 along x, a2 along z, a3 along the pole's
    outward normal (away from the ball)."""
    one = np.ones_like(s)
    f = _tan_q if equiangular else (lambda v: v)
    if face == 'X':
        return np.array([one, f(s), f(t)])
    if face == 'Z':
        return np.array([f(s), one, f(t)])
    return np.array([f(s), f(t), one])


def _direction(face, s, t):
    v = _face_point(face, s, t, True)
    return v / np.linalg.norm(v, axis=0)


def _from_p_halfspace(a):
    """Half-space below the tangent plane at P (local octant coordinates a, see _face_point)
    -> ball, by the inversion about Q of radius 2 R_b (an involution; P is fixed)."""
    h = np.array([a[0], -R_B - a[2], a[1]]) - Q_POLE[:, None]
    return Q_POLE[:, None] + 4 * R_B ** 2 * h / np.sum(h * h, axis=0)


def _from_q_halfspace(b):
    """The same about the top pole: half-space above the tangent plane at Q -> ball, by the
    inversion about P.  The two inversions map the hemisphere rho = rho_max about P onto the
    hemisphere rho = 4 R_b^2 / rho_max about Q, direction (a1, a2, a3) onto the same (b1, b2, b3)."""
    h = np.array([b[0], R_B + b[2], b[1]]) - P_POLE[:, None]
    return P_POLE[:, None] + 4 * R_B ** 2 * h / np.sum(h * h, axis=0)


def rho_layers(n, rho0):
    """Radii (half-space distance from P) of the polar layers, from rho0 to rho_max, the image
    of the polar angle TH_MAX (rho = 2 R_b tan(theta / 2) on the surface)."""
    dl = 0.25 * np.pi / n
    th = [2 * np.arctan(rho0 / (2 * R_B))]
    while th[-1] < TH_MAX - 1e-12:
        t = th[-1]
        f = 1.0 + (FAR_ASPECT - 1.0) * np.clip((t - TH_CONTACT) / TH_RAMP, 0.0, 1.0)
        rho = 2 * R_B * np.tan(t / 2) * np.exp(dl * f)
        th.append(2 * np.arctan(rho / (2 * R_B)))
    th = np.array(th)
    if th[-1] - TH_MAX > 0.5 * (th[-1] - th[-2]):
        th = th[:-1]
    th[-1] = TH_MAX
    return 2 * R_B * np.tan(th / 2)


def mesh_blocks(n, rho0):
    """Structured blocks: (parameter grids, map to the ball).  Parameters in [0, 1] except the
    layer index of the polar blocks."""
    u = np.linspace(0.0, 1.0, n + 1)
    layers = rho_layers(n, rho0)
    rho_q = 4 * R_B ** 2 / layers[-1]
    nsh = max(2, n // 2)
    blocks = []
    for r0, to_ball in ((rho0, _from_p_halfspace), (rho_q, _from_q_halfspace)):
        c = r0 / 2          # inner cube [0, c]^3, 3 shells from its faces to the sphere rho = r0
        blocks.append(((u, u, u), lambda L, c=c, to_ball=to_ball: to_ball(c * L)))
        for face in 'XZN':
            def shell(L, face=face, c=c, r0=r0, to_ball=to_ball):
                s, t, w = L
                return to_ball((1 - w) * c * _face_point(face, s, t, False)
                               + w * r0 * _direction(face, s, t))
            blocks.append(((u, u, np.linspace(0.0, 1.0, nsh + 1)), shell))
    log_r = np.log(layers)
    k = np.arange(layers.size, dtype=float)
    for face in 'XZN':
        def polar(L, face=face):
            s, t, w = L
            return _from_p_halfspace(np.exp(np.interp(w, k, log_r)) * _direction(face, s, t))
        blocks.append(((u, u, k), polar))
    return blocks, layers, rho_q


def build_mesh(n, rho0):
    """Isoparametric 27-node hexahedral mesh of the quarter ball, graded toward P."""
    blocks, layers, rho_q = mesh_blocks(n, rho0)
    phys = []
    for grids, to_ball in blocks:
        m = MeshHex.init_tensor(*grids)
        loc = m._mapping().F(ElementHex2.doflocs.T)            # (3, nel, 27) parameters
        phys.append(to_ball(loc.reshape(3, -1)).reshape(loc.shape))
    ph = np.concatenate(phys, axis=1)
    nel = ph.shape[1]
    # merge the vertices shared by blocks (coincident to rounding)
    V = ph[:, :, :8].reshape(3, -1).T
    parent = np.arange(V.shape[0])
    for i, j in cKDTree(V).query_pairs(1e-10, output_type='ndarray'):
        ri, rj = parent[i], parent[j]
        while parent[ri] != ri:
            ri = parent[ri]
        while parent[rj] != rj:
            rj = parent[rj]
        if ri != rj:
            parent[max(ri, rj)] = min(ri, rj)
    for i in range(parent.size):
        r = i
        while parent[r] != r:
            r = parent[r]
        parent[i] = r
    uniq, inv = np.unique(parent, return_inverse=True)
    t = np.ascontiguousarray(inv.reshape(nel, 8).T)
    dofs = Dofs(MeshHex(np.ascontiguousarray(V[uniq].T), t), ElementHex2())
    ed = dofs.element_dofs
    X = np.zeros((3, dofs.N))
    X[:, ed.ravel()] = ph.transpose(0, 2, 1).reshape(3, -1)
    mismatch = float(np.abs(X[:, ed] - ph.transpose(0, 2, 1)).max())
    assert mismatch < 1e-12, mismatch     # every shared node placed identically by its blocks
    mesh = MeshHex2(np.ascontiguousarray(X), t)
    info = dict(n=n, rho0_mm=rho0 * 1e3, n_layers=layers.size - 1, rho_q_mm=rho_q * 1e3,
                layer_radii_mm=layers * 1e3, nel=nel, nodes=dofs.N, ndof=3 * dofs.N,
                node_mismatch_m=mismatch)
    return mesh, info


# ----------------------------------------------------------------------------
# Model: K, body-force vector, constraints
# ----------------------------------------------------------------------------
class Ball:
    """The quarter ball: mesh, stiffness K (DOF 3*node + component), w_a = integral of N_a."""

    def __init__(self, lev, nu, mesh=None, info=None, chunk=1500):
        t0 = time.time()
        L = LEVELS[lev]
        if mesh is None:
            mesh, info = build_mesh(L['n'], L['rho0'])
        self.mesh, self.info, self.nu = mesh, dict(info), nu
        basis = CellBasis(mesh, ElementHex2(), intorder=5)
        self.X = basis.doflocs
        assert np.allclose(self.X, mesh.doflocs)
        nn = basis.N
        self.nn, self.N = nn, 3 * nn
        nb = 27
        G = np.stack([basis.basis[a][0].grad for a in range(nb)])      # (27, 3, nel, nq)
        Phi = np.stack([basis.basis[a][0].value for a in range(nb)])   # (27, nel, nq)
        dx = basis.dx
        detj = mesh._mapping().detDF(basis.X)
        self.info['jacobian_sign_consistent'] = bool(np.all(detj.min(axis=1) * detj.max(axis=1) > 0))
        self.info['min_detJ_ratio'] = float(np.min(np.abs(detj).min(axis=1) / np.abs(detj).max(axis=1)))
        assert self.info['jacobian_sign_consistent']
        ed = basis.element_dofs
        self.ed = ed
        lam, mu = lame(nu)
        K = sp.csr_matrix((self.N, self.N))
        for c0 in range(0, basis.nelems, chunk):
            sl = slice(c0, min(basis.nelems, c0 + chunk))
            D = G[:, :, sl, :].transpose(2, 3, 0, 1).reshape(-1, dx.shape[1], nb * 3)
            # S[e, (a, i), (b, j)] = sum_q dx dN_a/dx_i dN_b/dx_j
            S = np.einsum('eqk,eql->ekl', D, dx[sl, :, None] * D, optimize=True)
            S = S.reshape(-1, nb, 3, nb, 3)
            grad_dot = np.einsum('eaibi->eab', S)                 # sum_q dx grad N_a . grad N_b
            Ke = (lam * S + mu * S.transpose(0, 1, 4, 3, 2)
                  + mu * grad_dot[:, :, None, :, None] * np.eye(3)[None, None, :, None, :])
            ne = Ke.shape[0]
            vd = (3 * ed[:, sl].T[:, :, None] + np.arange(3)).reshape(ne, nb * 3)
            K = K + sp.coo_matrix((Ke.reshape(ne, -1).ravel(),
                                   (np.repeat(vd, nb * 3, axis=1).ravel(), np.tile(vd, (1, nb * 3)).ravel())),
                                  shape=(self.N, self.N)).tocsr()
            del S, Ke, D
        self.K = ((K + K.T) * 0.5).tocsr()
        w = np.zeros(nn)
        np.add.at(w, ed.ravel(), np.einsum('aeq,eq->ae', Phi, dx).ravel())
        self.w = w                                   # integral of N_a over the quarter ball
        self.volume = float(w.sum())
        self.info['volume_rel_err'] = self.volume / (np.pi / 3 * R_B ** 3) - 1
        # constraints: symmetry planes and the pole's u_y
        tol = 1e-12
        x, y, z = self.X
        self.pole = int(np.argmin(np.linalg.norm(self.X - P_POLE[:, None], axis=0)))
        assert np.linalg.norm(self.X[:, self.pole] - P_POLE) < tol
        fixed = np.concatenate([3 * np.nonzero(np.abs(x) < tol)[0],
                                3 * np.nonzero(np.abs(z) < tol)[0] + 2, [3 * self.pole + 1]])
        free = np.ones(self.N, bool)
        free[fixed] = False
        self.free = np.nonzero(free)[0]
        self.pos = -np.ones(self.N, int)
        self.pos[self.free] = np.arange(self.free.size)
        self.on_sphere = np.abs(np.linalg.norm(self.X, axis=0) - R_B) < 1e-9 * R_B
        self.time_asm = time.time() - t0

    def factor(self):
        t0 = time.time()
        Kf = self.K[self.free][:, self.free].tocsc()
        self.lu = spl.splu(Kf, permc_spec='MMD_AT_PLUS_A')
        self.time_factor = time.time() - t0
        self.fill = int(self.lu.L.nnz + self.lu.U.nnz)
        # response to a downward body force of 1 N in total on the quarter (uniform per volume)
        fb = np.zeros(self.N)
        fb[1::3] = -self.w / self.volume
        self.fb = fb
        self.ub = self.solve(fb)

    def solve(self, f):
        """Displacement (all DOFs) for the load f with the constraints above."""
        u = np.zeros(self.N)
        u[self.free] = self.lu.solve(f[self.free])
        return u

    def mean_uy(self, u):
        return float(self.w @ u[1::3]) / self.volume


# the compliance columns are computed in forked workers that share the factor
_SHARED = {}


def _columns(idx):
    lu, rows = _SHARED['lu'], _SHARED['rows']
    B = np.zeros((lu.shape[0], len(idx)))
    B[rows[idx], np.arange(len(idx))] = 1.0
    return lu.solve(B)[rows, :]


def compliance(ball, cand, procs, chunk=48):
    """C[i, j] = u_y at candidate i per unit upward force at candidate j."""
    rows = ball.pos[3 * cand + 1]
    assert np.all(rows >= 0)
    _SHARED.update(lu=ball.lu, rows=rows)
    pieces = [np.arange(i, min(i + chunk, cand.size)) for i in range(0, cand.size, chunk)]
    C = np.empty((cand.size, cand.size))
    if procs > 1:
        with multiprocessing.get_context('fork').Pool(procs) as pool:
            for idx, cols in zip(pieces, pool.imap(_columns, pieces), strict=True):
                C[:, idx] = cols
    else:
        for idx in pieces:
            C[:, idx] = _columns(idx)
    _SHARED.clear()
    asym = float(np.abs(C - C.T).max() / np.abs(C).max())
    return 0.5 * (C + C.T), asym


# ----------------------------------------------------------------------------
# Hertz (for comparison only)
# ----------------------------------------------------------------------------
def hertz(u, rc, nu):
    """Semi-axes a (along the cylinder's axis), b (around it) [m] and force [N] of Hertz's
    contact of the sphere R_b on a rigid cylinder rc (inf: flat) at the approach u."""
    es = E_MOD / (1 - nu ** 2)
    A = 1 / (2 * R_B)
    B = A + (0.0 if np.isinf(rc) else 1 / (2 * rc))
    if np.isinf(rc):
        a = np.sqrt(R_B * u)
        return dict(a=a, b=a, F=4.0 / 3.0 * es * np.sqrt(R_B) * u ** 1.5, e2=0.0)

    def shape(m):
        k, e = ellipk(m), ellipe(m)
        return (e / (1 - m) - k) / (k - e) - B / A
    m = brentq(shape, 1e-12, 1 - 1e-14, xtol=1e-15, rtol=1e-15)
    k, e = ellipk(m), ellipe(m)
    a = np.sqrt(u * (k - e) / (A * k * m))
    return dict(a=a, b=a * np.sqrt(1 - m), F=2 * np.pi / 3 * a * u * es / k, e2=m)


def hertz_at_a(a, rc, nu):
    """Hertz's approach and force for the semi-axis a along the cylinder's axis."""
    h1 = hertz(1.0, rc, nu)                      # a^2 and F^(2/3) are proportional to u
    u = (a / h1['a']) ** 2
    return dict(u=u, F=h1['F'] * u ** 1.5)


def arc(z, rc):
    """Arc length on the counterface from the contact centre at lateral position z."""
    return z if np.isinf(rc) else rc * np.arcsin(np.clip(z / rc, -1, 1))


def gap(X, rc):
    """Initial gap along y from the points X to the counterface below (y = -R_b at z = 0)."""
    if np.isinf(rc):
        return X[1] + R_B
    return X[1] - (-R_B - rc + np.sqrt(rc ** 2 - X[2] ** 2))


# ----------------------------------------------------------------------------
# Contact: active-set iteration on the condensed problem
# ----------------------------------------------------------------------------
def signorini(C, ubc, beta, g, u0, active0, max_it=200):
    """Candidates' reactions lam >= 0 and the quarter's total body force Fq such that
    u = Fq ubc + C lam satisfies u + g >= 0, lam (u + g) = 0 and the mean displacement
    Fq beta - ubc . lam = -u0 (beta = mean u_y per unit total body force, reciprocity gives
    the reactions' part).  Primal-dual active set; Murty's least-index rule if it cycles."""
    nc = g.size
    A = active0.copy()
    tol = 1e-10 * u0
    seen = set()
    murty = False
    for it in range(1, max_it + 1):
        ia = np.nonzero(A)[0]
        M = np.empty((ia.size + 1, ia.size + 1))
        M[:-1, :-1] = C[np.ix_(ia, ia)]
        M[:-1, -1] = ubc[ia]
        M[-1, :-1] = -ubc[ia]
        M[-1, -1] = beta
        sol = np.linalg.solve(M, np.concatenate([-g[ia], [-u0]]))
        lam = np.zeros(nc)
        lam[ia] = sol[:-1]
        Fq = sol[-1]
        u = Fq * ubc + C[:, ia] @ sol[:-1]
        drop = A & (lam < 0)
        add = ~A & (u + g < -tol)
        if not (drop.any() or add.any()):
            return lam, Fq, u, A, it, murty
        if not murty:
            Anew = (A & ~drop) | add
            key = np.packbits(Anew).tobytes()
            if key in seen:
                murty = True
            seen.add(key)
        if murty:
            i = np.nonzero(drop | add)[0][0]
            Anew = A.copy()
            Anew[i] = ~A[i]
        A = Anew
    raise RuntimeError('active set did not converge in %d iterations' % max_it)


def candidates(ball, rcs, u_max):
    """Surface nodes near P (without P) inside a multiple of the largest Hertz ellipses."""
    ell = [hertz(u_max, rc, ball.nu) for rc in rcs]
    f = CAND_MARGIN[0] + CAND_MARGIN[1] * 0.25 * np.pi / ball.info['n']
    x, y, z = ball.X
    inside = np.zeros(ball.nn, bool)
    for h in ell:
        inside |= (x / (f * h['a'])) ** 2 + (z / (f * h['b'])) ** 2 <= 1
    sel = ball.on_sphere & (y < 0) & inside
    sel[ball.pole] = False
    return np.nonzero(sel)[0]


class Surface:
    """The ball's surface faces around the candidates, integrated with 5x5 Gauss points per
    face: the trace of the element's 27 shape functions on the face (the face is a reference
    cube face, found from its 9 nodes on the sphere) and the isoparametric area element."""

    def __init__(self, ball, cand):
        ed = ball.ed
        on = ball.on_sphere[ed]                                    # (27, nel)
        rmax = 1.05 * np.linalg.norm(ball.X[:, cand] - P_POLE[:, None], axis=0).max()
        dist = np.linalg.norm(ball.X - P_POLE[:, None], axis=0)
        near = np.all(np.where(on, dist[ed], 0.0) < rmax, axis=0)
        els = np.nonzero((on.sum(axis=0) > 0) & near)[0]
        assert np.all(on[:, els].sum(axis=0) == 9), 'an element touches the sphere by a face only'
        ref = ElementHex2.doflocs                                  # (27, 3) reference dof locations
        gp, gw = np.polynomial.legendre.leggauss(5)
        gp, gw = 0.5 * (gp + 1), 0.5 * gw
        elem = ElementHex2()
        self.dofs, self.phi, self.pos, self.dA = [], [], [], []
        self.face_nodes = [ed[on[:, e], e] for e in els]
        # the reference face (axis, side) of each: the coordinate its 9 nodes share
        keys = []
        for e in els:
            r = ref[on[:, e]]
            axis = int(np.nonzero(np.ptp(r, axis=0) == 0)[0][0])
            keys.append((axis, r[0, axis]))
        keys = np.array(keys)
        for axis in range(3):
            for side in (0.0, 1.0):
                sel = els[(keys[:, 0] == axis) & (keys[:, 1] == side)]
                if sel.size == 0:
                    continue
                free_ax = [k for k in range(3) if k != axis]
                Xr = np.zeros((3, gp.size ** 2))
                Xr[free_ax[0]] = np.repeat(gp, gp.size)
                Xr[free_ax[1]] = np.tile(gp, gp.size)
                Xr[axis] = side
                wq = np.outer(gw, gw).ravel()
                vals = [elem.lbasis(Xr, j) for j in range(27)]
                phi = np.array([v[0] for v in vals])                   # (27, nq)
                dphi = np.array([v[1] for v in vals])                  # (27, 3, nq)
                Xn = ball.X[:, ed[:, sel]]                             # (3, 27, ne)
                t1 = np.einsum('dje,jq->deq', Xn, dphi[:, free_ax[0]])
                t2 = np.einsum('dje,jq->deq', Xn, dphi[:, free_ax[1]])
                self.dofs.append(ed[:, sel])
                self.phi.append(phi)
                self.pos.append(np.einsum('dje,jq->deq', Xn, phi))
                self.dA.append(np.linalg.norm(np.cross(t1, t2, axis=0), axis=0) * wq)
        self.area = np.zeros(ball.nn)                              # A_i = integral of N_i
        for d, phi, dA in zip(self.dofs, self.phi, self.dA, strict=True):
            np.add.at(self.area, d.ravel(), np.einsum('jq,eq->je', phi, dA).ravel())
        self.total_area = float(sum(dA.sum() for dA in self.dA))

    def field(self, pn):
        """(positions (3, m), values, area weights) at all Gauss points of the nodal field pn."""
        pos = np.concatenate([p.reshape(3, -1) for p in self.pos], axis=1)
        val = np.concatenate([np.einsum('je,jq->eq', pn[d], phi).ravel()
                              for d, phi in zip(self.dofs, self.phi, strict=True)])
        dA = np.concatenate([dA.ravel() for dA in self.dA])
        return pos, val, dA


def bin_average_parabola(edges, a):
    """Mean over each bin of Hertz's marginal per unit force, (3 / (4 a)) (1 - (x/a)^2)."""
    lo, hi = np.clip(edges[:-1], 0, a), np.clip(edges[1:], 0, a)
    integral = 3 / (4 * a) * ((hi - lo) - (hi ** 3 - lo ** 3) / (3 * a ** 2))
    return integral / np.diff(edges)


def contact_outputs(ball, cand, lam, Fq, rc, surf, u_full):
    """Footprint measures of one converged state (full-ball values)."""
    idx = np.concatenate([[ball.pole], cand])
    reac = np.concatenate([[Fq - lam.sum()], lam])          # the pole's from equilibrium
    act = reac > 0
    X = ball.X[:, idx]
    x, s = X[0], arc(X[2], rc)
    tot = reac.sum()
    mx2, ms2 = (reac * x ** 2).sum() / tot, (reac * s ** 2).sum() / tot
    mx4, ms4 = (reac * x ** 4).sum() / tot, (reac * s ** 4).sum() / tot
    on_x0, on_z0 = np.abs(X[0]) < 1e-12, np.abs(X[2]) < 1e-12
    n_full = int(np.sum(act * np.where(on_x0 & on_z0, 1, np.where(on_x0 | on_z0, 2, 4))))

    def edge(line, coord):
        """last contact node along a symmetry line and half-way to the next node"""
        o = np.argsort(coord[line])
        c, a = coord[line][o], act[line][o]
        last = np.nonzero(a)[0].max()
        assert last + 1 < c.size, 'candidate region too small'
        return c[last], 0.5 * (c[last] + c[last + 1])
    # the candidates must surround the contact: every face touching it has only candidates
    inside = np.zeros(ball.nn, bool)
    inside[idx] = True
    touch = np.zeros(ball.nn, bool)
    touch[idx[act]] = True
    for nodes in surf.face_nodes:
        assert not touch[nodes].any() or inside[nodes].all(), 'candidate region too small'
    x_last, x_edge = edge(on_z0, x)
    s_last, s_edge = edge(on_x0, s)
    # deformed positions (the footprint's shape in the deformed state, for reference)
    ud = u_full.reshape(-1, 3)[idx]
    xd, sd = x + ud[:, 0], arc(X[2] + ud[:, 2], rc)
    # marginals: field p = sum (lambda_i / A_i) N_i over the surface faces
    pn = np.zeros(ball.nn)
    assert np.all(surf.area[idx[act]] > 0)
    pn[idx[act]] = reac[act] / surf.area[idx[act]]
    Xq, pq, dA = surf.field(pn)
    xe = np.linspace(0, 1.25 * x_edge, N_BINS + 1)
    se = np.linspace(0, 1.25 * s_edge, N_BINS + 1)
    fq = pq * dA
    qx = 2 * np.histogram(Xq[0], bins=xe, weights=fq)[0] / np.diff(xe)
    qs = 2 * np.histogram(arc(Xq[2], rc), bins=se, weights=fq)[0] / np.diff(se)
    F = 4 * tot
    return dict(
        F_N=F, n_contact_nodes_quarter=int(act.sum()), n_contact_nodes_full=n_full,
        a_eq_mm=np.sqrt(5 * mx2) * 1e3, b_eq_mm=np.sqrt(5 * ms2) * 1e3,
        x4_over_x2sq=mx4 / mx2 ** 2, s4_over_s2sq=ms4 / ms2 ** 2,
        x_max_mm=x[act].max() * 1e3, s_max_mm=s[act].max() * 1e3,
        x_last_on_axis_mm=x_last * 1e3, x_edge_mm=x_edge * 1e3,
        s_last_on_axis_mm=s_last * 1e3, s_edge_mm=s_edge * 1e3,
        a_eq_deformed_mm=np.sqrt(5 * (reac * xd ** 2).sum() / tot) * 1e3,
        b_eq_deformed_mm=np.sqrt(5 * (reac * sd ** 2).sum() / tot) * 1e3,
        pole_reaction_N=4 * reac[0],
        marginal_total_check=2 * (qx * np.diff(xe)).sum() / F,
        marginal_x=dict(edges_mm=xe * 1e3, q_over_F_per_mm=qx / F * 1e-3),
        marginal_s=dict(edges_mm=se * 1e3, q_over_F_per_mm=qs / F * 1e-3),
    )


def run_level(lev, nus, counterfaces, u_over_r, procs, mesh=None, info=None):
    out = {}
    for nu in nus:
        T0 = time.time()
        ball = Ball(lev, nu, mesh, info)
        mesh, info = ball.mesh, ball.info
        log('%s nu=%.2f: %d el, %d dof, vol err %.1e, asm %.1f s' % (
            lev, nu, ball.info['nel'], ball.N, ball.info['volume_rel_err'], ball.time_asm))
        ball.factor()
        log('  factor %.1f s (L+U %.3g nonzeros)' % (ball.time_factor, ball.fill))
        rcs = [COUNTERFACES[c] for c in counterfaces]
        cand = candidates(ball, rcs, max(u_over_r) * R_B)
        t0 = time.time()
        C, asym = compliance(ball, cand, procs)
        t_c = time.time() - t0
        log('  compliance of %d candidates: %.1f s (asymmetry %.1e)' % (cand.size, t_c, asym))
        ubc = ball.ub[3 * cand + 1]
        beta = ball.mean_uy(ball.ub)
        surf = Surface(ball, cand)
        res = dict(mesh=dict(level=lev, **ball.info), n_candidates=int(cand.size),
                   time_asm_s=ball.time_asm, time_factor_s=ball.time_factor,
                   time_compliance_s=t_c, factor_nnz=ball.fill, compliance_asymmetry=asym,
                   cases={})
        for name in counterfaces:
            rc = COUNTERFACES[name]
            g = gap(ball.X[:, cand], rc)
            A = np.zeros(cand.size, bool)
            rows = []
            for ur in u_over_r:
                u0 = ur * R_B
                if not A.any():
                    A = g < 0.5 * u0
                lam, Fq, uc, A, its, murty = signorini(C, ubc, beta, g, u0, A)
                # check: the converged state on the full model
                f = Fq * ball.fb
                f[3 * cand + 1] += lam
                uf = ball.solve(f)
                chk = dict(iterations=its, murty=murty,
                           mean_disp_rel_err=-ball.mean_uy(uf) / u0 - 1,
                           active_gap_max_rel=float(np.abs(uf[3 * cand[A] + 1] + g[A]).max() / u0),
                           min_gap_rel=float((uf[3 * cand + 1] + g).min() / u0),
                           min_reaction_N=float(lam[A].min()) if A.any() else 0.0)
                r = dict(u_over_R=ur, u_mm=u0 * 1e3)
                r.update(contact_outputs(ball, cand, lam, Fq, rc, surf, uf))
                h = hertz(u0, rc, nu)
                r['hertz'] = dict(a_mm=h['a'] * 1e3, b_mm=h['b'] * 1e3, F_N=h['F'], e2=h['e2'])
                ha = hertz_at_a(r['a_eq_mm'] * 1e-3, rc, nu)
                r['ratio_to_hertz'] = dict(a_eq=r['a_eq_mm'] / r['hertz']['a_mm'],
                                           b_eq=r['b_eq_mm'] / r['hertz']['b_mm'],
                                           F=r['F_N'] / h['F'],
                                           x_edge=r['x_edge_mm'] / r['hertz']['a_mm'],
                                           s_edge=r['s_edge_mm'] / r['hertz']['b_mm'],
                                           b_over_a=(r['b_eq_mm'] / r['a_eq_mm']) / (h['b'] / h['a']),
                                           hertz_approach_for_a_eq=ha['u'] / u0,
                                           F_at_same_a_eq=r['F_N'] / ha['F'])
                for key in ('marginal_x', 'marginal_s'):
                    ed = np.array(r[key]['edges_mm']) * 1e-3
                    sax = h['a'] if key == 'marginal_x' else h['b']
                    aeq = (r['a_eq_mm'] if key == 'marginal_x' else r['b_eq_mm']) * 1e-3
                    r[key]['hertz_parabola_per_mm'] = bin_average_parabola(ed, sax) * 1e-3
                    r[key]['parabola_same_moment_per_mm'] = bin_average_parabola(ed, aeq) * 1e-3
                r['check'] = chk
                rows.append(r)
                log('  %-12s u/R=%.2f F=%8.2f N  n=%4d  a_eq=%6.3f (H %6.3f) b_eq=%6.3f (H %6.3f) mm'
                    '  its %d  chk %.1e %.1e' % (
                        name, ur, r['F_N'], r['n_contact_nodes_quarter'], r['a_eq_mm'],
                        r['hertz']['a_mm'], r['b_eq_mm'], r['hertz']['b_mm'], its,
                        chk['mean_disp_rel_err'], chk['active_gap_max_rel']))
                assert abs(chk['mean_disp_rel_err']) < 1e-8 and chk['active_gap_max_rel'] < 1e-8
                assert chk['min_gap_rel'] > -1e-8 and r['pole_reaction_N'] > 0
            res['cases'][name] = rows
        res['time_s'] = time.time() - T0
        out['%.2f' % nu] = res
        del ball, C
    return out, mesh, info


# ----------------------------------------------------------------------------
# Record
# ----------------------------------------------------------------------------
ROW_KEYS = ('u_over_R', 'u_mm', 'F_N', 'n_contact_nodes_quarter', 'n_contact_nodes_full',
            'a_eq_mm', 'b_eq_mm', 'x4_over_x2sq', 's4_over_s2sq', 'x_max_mm', 's_max_mm',
            'x_edge_mm', 's_edge_mm', 'a_eq_deformed_mm', 'b_eq_deformed_mm', 'hertz',
            'ratio_to_hertz')


def compact_row(r, marginals):
    out = {k: r[k] for k in ROW_KEYS}
    if marginals:
        for key in ('marginal_x', 'marginal_s'):
            m = r[key]
            out[key] = dict(edges_mm=m['edges_mm'], fe_q_over_F_per_mm=m['q_over_F_per_mm'],
                            hertz_parabola_per_mm=m['hertz_parabola_per_mm'],
                            parabola_same_moment_per_mm=m['parabola_same_moment_per_mm'])
    return out


def _sig(obj, digits=7):
    """obj with its floats to `digits` significant digits (the compact file's size)."""
    if isinstance(obj, dict):
        return {k: _sig(v, digits) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_sig(v, digits) for v in obj]
    if isinstance(obj, float) and np.isfinite(obj) and obj != 0:
        return float('%.*g' % (digits, obj))
    return obj


def record(raw, quick):
    """The compact reference (tests/validation/data/fe_ball_contact.json): meta (set-up, meshes,
    mesh convergence, run times), results per mesh, nu and counterface (the marginals on the finest
    mesh only), to 7 significant digits, and the --quick numbers in full, which the slow test
    re-runs."""
    inp = raw['inputs']
    levels = [lev for lev in ('M1', 'M2') if lev in raw['levels']]
    finest = levels[-1]
    results = {}
    for lev in levels:
        results[lev] = {}
        for nu, res in raw['levels'][lev].items():
            results[lev]['nu=' + nu] = {name: [compact_row(r, lev == finest) for r in rows]
                                        for name, rows in res['cases'].items()}
    conv = {}
    qs = ('F_N', 'a_eq_mm', 'b_eq_mm')
    if len(levels) == 2:
        per = {}
        for nu, res in raw['levels']['M2'].items():
            per['nu=' + nu] = {}
            for name, rows in res['cases'].items():
                r1 = raw['levels']['M1'][nu]['cases'][name]
                per['nu=' + nu][name] = {q: [a[q] / b[q] - 1 for a, b in zip(r1, rows, strict=True)]
                                         for q in qs}
        m2 = {r['u_over_R']: r for r in raw['levels']['M2']['%.2f' % QUICK['nu']]['cases'][
            QUICK['counterfaces'][0]]}
        conv = dict(
            note=('relative differences M1/M2 - 1 per compression (u/R_b as in results), and '
                  'quick/M2 - 1 at the quick run\'s compressions'),
            max_abs_M1_vs_M2={q: max(abs(v) for c in per.values() for d in c.values() for v in d[q])
                              for q in qs},
            M1_vs_M2=per,
            quick_vs_M2={q: [r[q] / m2[r['u_over_R']][q] - 1 for r in quick['rows']] for q in qs})
    meshes = {}
    for lev in levels:
        res = next(iter(raw['levels'][lev].values()))
        m = res['mesh']
        meshes[lev] = dict(n=m['n'], rho0_mm=m['rho0_mm'], n_layers=m['n_layers'], elements=m['nel'],
                           nodes=m['nodes'], dof=m['ndof'], candidates=res['n_candidates'],
                           volume_rel_err=m['volume_rel_err'], min_detJ_ratio=m['min_detJ_ratio'])
    qm = quick['mesh']
    meshes['quick'] = dict(n=qm['n'], rho0_mm=qm['rho0_mm'], n_layers=qm['n_layers'], elements=qm['nel'],
                           nodes=qm['nodes'], dof=qm['ndof'], candidates=quick['n_candidates'],
                           volume_rel_err=qm['volume_rel_err'], min_detJ_ratio=qm['min_detJ_ratio'])
    times = {lev: {nu: res['time_s'] for nu, res in raw['levels'][lev].items()} for lev in levels}
    meta = dict(
        source=('scripts/fe_ball_contact.py, full run (meshes %s, nu %s) with scikit-fem %s, '
                'SciPy %s (SuperLU)' % (' and '.join(levels), ' and '.join(inp['nus']),
                                        inp['skfem'], inp['scipy'])),
        date='2026-11-26',
        geometry=dict(ball_radius_mm=round(R_B * 1e3, 9), counterfaces_radius_mm={
            k: (None if np.isinf(v) else round(v * 1e3, 9)) for k, v in COUNTERFACES.items()},
            cylinder_axis='x (along the bat)', approach_direction='-y'),
        material=dict(youngs_modulus_Pa=E_MOD, poisson_ratios=[float(v) for v in inp['nus']],
                      note='footprint independent of E; forces proportional to E'),
        loading=('uniform body force along -y balanced by the contact; compression u = mean '
                 'displacement (centre of mass) toward the counterface, prescribed'),
        contact=('frictionless, unilateral, node-to-rigid-surface on surface nodes; gap along y '
                 'at the undeformed (x, z); reactions along y; primal-dual active set on the '
                 'condensed compliance, converged to a fixed point, re-checked on the full model'),
        pressure=('a_eq = sqrt(5 <x^2>), b_eq = sqrt(5 <s^2>), <.> weighted by the nodal reactions, '
                  's = arc length on the counterface; marginals from the field sum (lambda_i/A_i) N_i '
                  'integrated per face (5x5 Gauss), binned (20 bins), full-ball force per unit '
                  'length divided by F [1/mm]; Hertz parabola bin-averaged with Hertz a (or b) and '
                  'with a_eq (b_eq)'),
        elements='27-node isoparametric hexahedra, 3x3x3 Gauss, quarter model',
        meshes=meshes,
        solver='SciPy SuperLU (MMD_AT_PLUS_A), one solve per contact candidate for the compliance',
        mesh_convergence=conv,
        run_time_s=dict(full_run_total=raw['total_time_s'], per_level_and_nu=times,
                        quick=quick['total_time_s']),
        hertz_shape_x4_over_x2sq=15 / 7,
    )
    return dict(meta=_sig(meta), results=_sig(results),
                quick=dict(level=QUICK['level'], nu=QUICK['nu'], counterface=QUICK['counterfaces'][0],
                           rows=[{k: r[k] for k in ('u_over_R', 'u_mm', 'F_N', 'n_contact_nodes_quarter',
                                                    'a_eq_mm', 'b_eq_mm', 'x_max_mm', 's_max_mm')}
                                 for r in quick['rows']]))


def run_quick(procs):
    T0 = time.time()
    res, _, _ = run_level(QUICK['level'], (QUICK['nu'],), QUICK['counterfaces'], QUICK['u_over_r'], procs)
    r = res['%.2f' % QUICK['nu']]
    return dict(mesh=r['mesh'], n_candidates=r['n_candidates'],
                rows=r['cases'][QUICK['counterfaces'][0]], total_time_s=time.time() - T0)


def selftest():
    """Stiffness of the quick mesh against skfem.asm(linear_elasticity)."""
    from skfem import ElementVector, asm
    from skfem.models.elasticity import linear_elasticity
    ball = Ball('quick', 0.3)
    ib = CellBasis(ball.mesh, ElementVector(ElementHex2()), intorder=5)
    K2 = asm(linear_elasticity(*lame(0.3)), ib)
    ix = ib.split_indices()
    perm = np.zeros(ball.N, int)
    for i in range(3):
        perm[3 * np.arange(ball.nn) + i] = ix[i]
    d = abs(K2[perm][:, perm] - ball.K).max() / abs(ball.K).max()
    rigid = np.zeros(ball.N)
    rigid[1::3] = 1
    log('selftest: |K_mine - K_skfem| / |K| = %.2e; |K 1_y| / |K| = %.1e; volume error %.1e' % (
        d, abs(ball.K @ rigid).max() / abs(ball.K).max(), ball.info['volume_rel_err']))
    return dict(K_rel_diff=float(d))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--quick', action='store_true', help='coarse mesh, one cylinder, two compressions')
    ap.add_argument('--levels', nargs='*', default=['M1', 'M2'])
    ap.add_argument('--selftest', action='store_true')
    ap.add_argument('--procs', type=int, default=min(2, os.cpu_count() or 1),
                    help='processes for the compliance solves')
    ap.add_argument('--out', default=None)
    ap.add_argument('--record', metavar='RAW', default=None,
                    help='write the compact reference of a full run (RAW: its --out file)')
    ap.add_argument('--quick-run', metavar='QUICK', default=None,
                    help='with --record: a --quick run to record instead of the one in RAW')
    ap.add_argument('--to', default='tests/validation/data/fe_ball_contact.json',
                    help='with --record: where to write it')
    args = ap.parse_args()
    logging.getLogger('skfem').setLevel(logging.ERROR)   # its notes on array layouts
    T0 = time.time()
    if args.record:
        raw = json.load(open(args.record))
        quick = json.load(open(args.quick_run))['quick'] if args.quick_run else raw['quick']
        jdump(record(raw, quick), args.to)
        log('wrote %s' % args.to)
        return
    if args.selftest:
        selftest()
        return
    if args.quick:
        q = run_quick(args.procs)
        jdump(dict(quick=q, total_time_s=time.time() - T0), args.out or 'fe_ball_contact_quick.json')
        log('total %.1f s' % (time.time() - T0))
        return
    import scipy
    import skfem
    out = dict(inputs=dict(R_b_m=R_B, E_Pa=E_MOD, nus=['%.2f' % v for v in NUS],
                           counterfaces={k: (None if np.isinf(v) else v) for k, v in COUNTERFACES.items()},
                           u_over_R=U_OVER_R, levels=LEVELS, far_aspect=FAR_ASPECT,
                           th_contact=TH_CONTACT, th_ramp=TH_RAMP, th_max=TH_MAX,
                           cand_margin=CAND_MARGIN, skfem=skfem.__version__, scipy=scipy.__version__),
               levels={})
    fn = args.out or 'fe_ball_contact_raw.json'
    for lev in args.levels:
        out['levels'][lev], _, _ = run_level(lev, NUS, tuple(COUNTERFACES), U_OVER_R, args.procs)
        jdump(out, fn)
    out['quick'] = run_quick(args.procs)
    out['total_time_s'] = time.time() - T0
    jdump(out, fn)
    log('total %.1f s' % out['total_time_s'])


if __name__ == '__main__':
    main()
