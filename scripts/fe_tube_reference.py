#!/usr/bin/env python
"""
fe_tube_reference.py -- an independent 3-D continuum finite-element reference for a uniform
aluminium tube, against which batcert's thin-shell barrel model is validated
(tests/validation/test_shell_against_fe.py, docs/validation.md section 3).

It uses no shell theory and nothing of batcert; it needs scikit-fem (a test dependency), and
optionally pypardiso (MKL's sparse solver, about 4x faster on the fine mesh; SciPy's SuperLU
otherwise, with the same numbers).

Everything here is 3-D linear elasticity:
  * geometry  : tube, outer diameter 2.625 in, wall t, length 0.300 m
  * material  : Al 7050, E = 71.7 GPa, nu = 0.33, rho = 2830 kg/m^3
  * elements  : 27-node tri-quadratic hexahedra (scikit-fem ElementHex2) on an
                ISOPARAMETRIC quadratic mesh (MeshHex2): the mid-side nodes lie
                exactly on the cylinders r = const, so the curved geometry is
                represented to O(h^3), not faceted.
  * quadrature: 3x3x3 Gauss (intorder=5) for stiffness, mass and loads.
  * assembly  : element matrices are formed with numpy (batched B^T D B) from the
                scikit-fem basis (shape-function gradients, detJ, weights, dofs);
                this was checked to agree with skfem.asm(linear_elasticity) to
                5e-16 (see --selftest) and is ~4x faster.
  * symmetry  : the mesh is a tensor mesh in (r, theta, z).  Most runs use an
                1/8 model (theta in [0, 90 deg], z in [0, L/2], z measured from
                mid-length) with symmetric (S) or antisymmetric (A) conditions on
                the planes theta=0 (y=0), theta=90 deg (x=0) and z=0.  The
                symmetry classes were verified against a full 360-deg, full-length
                model (--verify: 34 elastic modes up to 10.3 kHz agree to 3.5e-11).

Cases:
  A  free-free modes (n=2,3; first two axial orders), plus n=0/1 listing
  B  shear-diaphragm (simply supported) ends; n=2,3 with m=1,2; + thin-shell
     theory (Flugge, with Sanders and Donnell-Mushtari as cross-checks)
  C  static squeeze by two opposite 40x40 mm patches at mid-length (1000 N each: the
     resultant, a vector along the line of the patch centres, of a uniform pressure)
  D  same squeeze with the patches centred 50 mm from one end
  E  half-sine pulse (10 kN, 1 ms) on the mid-length patches, modal superposition
     (with and without static correction) + Newmark cross-check

Usage
  python scripts/fe_tube_reference.py --out raw.json      # full run: walls 2.0-4.0 mm, meshes
                                                          # M1 and M2 (about an hour on 2 cores)
  python scripts/fe_tube_reference.py --record raw.json   # write the compact reference the
                                                          # tests read (--to PATH to redirect)
  python scripts/fe_tube_reference.py --quick --wall 3.0  # cases A and C, coarse mesh (~15 s)
  python scripts/fe_tube_reference.py --verify            # full-360 model vs symmetry classes
  python scripts/fe_tube_reference.py --selftest          # assembly check against skfem.asm
  python scripts/fe_tube_reference.py --stress            # peak von Mises of case C per 1000 N
Units inside: SI (m, N, Pa, kg, s).  Reported: Hz, mm, N/m.
"""
import argparse
import json
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from skfem import CellBasis, ElementHex2, ElementVector, FacetBasis, Functional, LinearForm, MeshHex, MeshHex2, asm

# ----------------------------------------------------------------------------
# Data
# ----------------------------------------------------------------------------
E_MOD = 71.7e9          # Pa
NU = 0.33
RHO = 2830.0            # kg/m^3
LAM = E_MOD * NU / ((1 + NU) * (1 - 2 * NU))
MU = E_MOD / (2 * (1 + NU))
D_OUT = 2.625 * 0.0254  # 66.675 mm
RO = D_OUT / 2          # outer radius
LEN = 0.300             # tube length
PATCH_LEN = 0.040       # axial length of a load patch
PATCH_ARC = 0.040       # arc length of a load patch measured on the outer surface
TH_P = PATCH_ARC / 2 / RO   # half-angle of the patch (rad) = 0.59993 rad = 34.37 deg
F_PATCH = 1000.0        # N, resultant of one patch (cases C, D)
F0_PULSE = 10.0e3       # N, peak resultant of one patch (case E)
T_PULSE = 1.0e-3        # s
T_END = 2.0e-3          # s
# uniform pressure normal to the outer surface, chosen so that the resultant of
# one patch (which points along -x for the patch at theta=0) is F:
#   F = p * PATCH_LEN * 2*RO*sin(TH_P)    (projected width = chord 37.64 mm)
P_PER_N = 1.0 / (PATCH_LEN * 2 * RO * np.sin(TH_P))   # Pa per N of resultant

# mesh levels: nr = elements through the wall, h_th = target element arc length
# on the outer surface, h_z = target axial element length.  Patch edges, the
# quarter-length station and the planes of symmetry are always element edges.
LEVELS = {
    'quick': dict(nr=2, h_th=4.0e-3, h_z=7.5e-3),
    'M1': dict(nr=2, h_th=3.0e-3, h_z=5.0e-3),
    'M2': dict(nr=3, h_th=1.5e-3, h_z=2.5e-3),
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


def grid(bps, h):
    """Node coordinates through the breakpoints bps with spacing <= ~h."""
    pts = [bps[0]]
    for a, b in zip(bps[:-1], bps[1:], strict=True):
        n = max(1, int(np.ceil((b - a) / h - 1e-9)))
        pts.extend(np.linspace(a, b, n + 1)[1:])
    return np.array(pts)


# ----------------------------------------------------------------------------
# Sparse SPD solver: Intel MKL PARDISO via pypardiso if installed (~10x faster
# factorisation than SuperLU on these meshes), else SciPy SuperLU.
# ----------------------------------------------------------------------------
try:
    import ctypes

    import pypardiso

    class SPDSolver:
        """PARDISO (mtype=2, real SPD) factorisation of a sparse SPD matrix."""

        def __init__(self, A):
            A = sp.triu(sp.csr_matrix(A), format='csr')
            A.sort_indices()
            self.A = A
            self.n = A.shape[0]
            self.ps = pypardiso.PyPardisoSolver(mtype=2)
            self.ia = (A.indptr + 1).astype(np.int32)
            self.ja = (A.indices + 1).astype(np.int32)
            self._call(12, np.zeros((self.n, 1), order='F'))

        def _call(self, phase, b):
            ps = self.ps
            b = np.asfortranarray(b, dtype=float)
            x = np.zeros_like(b)
            err = ctypes.c_int32(0)
            i32 = ctypes.POINTER(ctypes.c_int32)
            f64 = ctypes.POINTER(ctypes.c_double)
            ps.set_iparm(12, 0)
            ps._mkl_pardiso(ps.pt.ctypes.data_as(ctypes.POINTER(ps._pt_type[0])),
                            ctypes.byref(ctypes.c_int32(1)), ctypes.byref(ctypes.c_int32(1)),
                            ctypes.byref(ctypes.c_int32(2)), ctypes.byref(ctypes.c_int32(phase)),
                            ctypes.byref(ctypes.c_int32(self.n)), self.A.data.ctypes.data_as(f64),
                            self.ia.ctypes.data_as(i32), self.ja.ctypes.data_as(i32),
                            ps.perm.ctypes.data_as(i32),
                            ctypes.byref(ctypes.c_int32(1 if b.ndim == 1 else b.shape[1])),
                            ps.iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)),
                            b.ctypes.data_as(f64), x.ctypes.data_as(f64), ctypes.byref(err))
            if err.value != 0:
                raise RuntimeError('PARDISO error %d' % err.value)
            return x

        def solve(self, b):
            return np.ascontiguousarray(self._call(33, b))

        def __del__(self):
            try:
                self._call(-1, np.zeros((self.n, 1), order='F'))
            except Exception:
                pass

    SOLVER_NAME = 'MKL PARDISO (pypardiso), mtype=2'
except ImportError:  # pragma: no cover
    class SPDSolver:
        def __init__(self, A):
            self.lu = spl.splu(sp.csc_matrix(A), permc_spec='MMD_AT_PLUS_A')

        def solve(self, b):
            return self.lu.solve(np.ascontiguousarray(b))

    SOLVER_NAME = 'SciPy SuperLU (MMD_AT_PLUS_A)'


# ----------------------------------------------------------------------------
# Model: mesh + K + M
# ----------------------------------------------------------------------------
class Tube:
    """Tube segment r in [RO-t, RO], theta in th_pts, z in z_pts (z from mid-length).

    DOF numbering: 3*node + component (x, y, z)."""

    def __init__(self, t, th_pts, z_pts, nr, periodic=False, chunk=4000):
        t0 = time.time()
        self.t = t
        _, sb, ed = self.mesh_on(np.linspace(RO - t, RO, nr + 1), th_pts, z_pts, periodic)
        nn = self.nn
        # ---- element matrices (batched), chunked over elements ----
        nb = 27
        nel = sb.nelems
        G = np.stack([sb.basis[a][0].grad for a in range(nb)])   # (27,3,nel,nq)
        Phi = np.stack([sb.basis[a][0].value for a in range(nb)])  # (27,nel,nq)
        dx = sb.dx                                               # (nel,nq)
        eye3 = np.eye(3)
        Ks, Ms = [], []
        for c0 in range(0, nel, chunk):
            sl = slice(c0, min(nel, c0 + chunk))
            Dm = G[:, :, sl, :].transpose(2, 3, 0, 1).reshape(-1, dx.shape[1], nb * 3)
            W = dx[sl, :, None] * Dm
            A = np.einsum('eqk,eql->ekl', Dm, W, optimize=True).reshape(-1, nb, 3, nb, 3)
            tr = np.einsum('eakbk->eab', A)
            Ke = (LAM * A + MU * A.transpose(0, 1, 4, 3, 2)
                  + MU * tr[:, :, None, :, None] * eye3[None, None, :, None, :])
            Me = RHO * np.einsum('aeq,beq,eq->eab', Phi[:, sl], Phi[:, sl], dx[sl], optimize=True)
            ne = Ke.shape[0]
            e_d = ed[:, sl].T                                        # (ne,27)
            vd = (3 * e_d[:, :, None] + np.arange(3)).reshape(ne, nb * 3)
            Ks.append(sp.coo_matrix((Ke.reshape(ne, -1).ravel(),
                                     (np.repeat(vd, nb * 3, axis=1).ravel(),
                                      np.tile(vd, (1, nb * 3)).ravel())),
                                    shape=(self.N, self.N)).tocsr())
            Ms.append(sp.coo_matrix((Me.ravel(),
                                     (np.repeat(e_d, nb, axis=1).ravel(),
                                      np.tile(e_d, (1, nb)).ravel())),
                                    shape=(nn, nn)).tocsr())
            del A, Ke, Dm, W
        self.K = sum(Ks[1:], Ks[0]).tocsr()
        self.Ms = sum(Ms[1:], Ms[0]).tocsr()            # scalar mass matrix
        self.M = sp.kron(self.Ms, sp.eye(3)).tocsr()     # vector mass matrix
        self.K = ((self.K + self.K.T) * 0.5).tocsr()
        self.ed = ed
        self.nel = nel
        self.time_asm = time.time() - t0

    def mesh_on(self, r_pts, th_pts, z_pts, periodic=False):
        """The isoparametric 27-node mesh of the tensor grid (r_pts, th_pts, z_pts): sets
        mesh, sb, r, th, z, nn, N (and keep, periodic); returns the linear tensor mesh, the
        basis and the scalar element dofs."""
        m1 = MeshHex.init_tensor(r_pts, th_pts, z_pts)
        m2 = MeshHex2.from_mesh(m1)
        P = m2.doflocs                              # (r, theta, z) of all 27-node dofs
        X = np.vstack([P[0] * np.cos(P[1]), P[0] * np.sin(P[1]), P[2]])
        self.mesh = MeshHex2(X, m2.t)                # isoparametric curved mesh
        sb = CellBasis(self.mesh, ElementHex2(), intorder=5)
        self.sb = sb
        assert np.allclose(sb.doflocs, X)
        ed = sb.element_dofs.copy()                 # (27, nel) scalar dofs
        nn = sb.N
        r, th, z = P[0].copy(), P[1].copy(), P[2].copy()
        if periodic:  # merge theta = 2 pi nodes into theta = 0 nodes
            dup = np.isclose(th, 2 * np.pi)
            base = np.isclose(th, 0.0)
            def key(i):
                return (round(r[i] * 1e9), round(z[i] * 1e9))
            lut = {key(i): i for i in np.nonzero(base)[0]}
            mp = np.arange(nn)
            for i in np.nonzero(dup)[0]:
                mp[i] = lut[key(i)]
            keep = np.nonzero(~dup)[0]
            newidx = -np.ones(nn, int)
            newidx[keep] = np.arange(keep.size)
            ed = newidx[mp[ed]]
            r, th, z = r[keep], th[keep], z[keep]
            nn = keep.size
            self.keep = keep
        self.r, self.th, self.z = r, th, z
        self.nn = nn
        self.N = 3 * nn
        return m1, sb, ed

    # ---- helpers ----
    def dofs(self, mask, comps):
        nodes = np.nonzero(mask)[0]
        return np.concatenate([3 * nodes + c for c in comps]) if nodes.size else np.zeros(0, int)

    def polar(self, u):
        """radial, circumferential, axial nodal displacements."""
        ux, uy, uz = u[0::3], u[1::3], u[2::3]
        c, s = np.cos(self.th), np.sin(self.th)
        return ux * c + uy * s, -ux * s + uy * c, uz

    def bc(self, th0=None, th90=None, zmid=None, zend=None, zstart=None):
        """Fixed DOFs.  th0/th90/zmid in {'S','A',None}; zend/zstart in {'SD',None}.
        plane theta=0 (y=0):  S -> u_y=0           A -> u_x=u_z=0
        plane theta=90 (x=0): S -> u_x=0           A -> u_y=u_z=0
        plane z=0 (mid):      S -> u_z=0           A -> u_x=u_y=0
        end face 'SD' (shear diaphragm): u_r=u_theta=0 <=> u_x=u_y=0, u_z free"""
        fx = []
        tol = 1e-9
        on0 = np.abs(self.th) < tol
        on90 = np.abs(self.th - np.pi / 2) < tol
        onz = np.abs(self.z) < tol
        if th0 == 'S':
            fx.append(self.dofs(on0, [1]))
        elif th0 == 'A':
            fx.append(self.dofs(on0, [0, 2]))
        if th90 == 'S':
            fx.append(self.dofs(on90, [0]))
        elif th90 == 'A':
            fx.append(self.dofs(on90, [1, 2]))
        if zmid == 'S':
            fx.append(self.dofs(onz, [2]))
        elif zmid == 'A':
            fx.append(self.dofs(onz, [0, 1]))
        if zend == 'SD':
            fx.append(self.dofs(np.abs(self.z - self.z.max()) < tol, [0, 1]))
        if zstart == 'SD':
            fx.append(self.dofs(np.abs(self.z - self.z.min()) < tol, [0, 1]))
        if not fx:
            return np.zeros(0, int)
        return np.unique(np.concatenate(fx))

    def free(self, fixed):
        mask = np.ones(self.N, bool)
        mask[fixed] = False
        return np.nonzero(mask)[0]

    # ---- solvers ----
    def eig(self, fixed, k, sigma):
        free_dofs = self.free(fixed)
        Kf = self.K[free_dofs][:, free_dofs].tocsc()
        Mf = self.M[free_dofs][:, free_dofs].tocsc()
        lu = SPDSolver(Kf - sigma * Mf)            # sigma < 0  ->  SPD
        op = spl.LinearOperator(Kf.shape, matvec=lambda x: lu.solve(x).ravel(), dtype=float)
        w, v = spl.eigsh(Kf, k=k, M=Mf, sigma=sigma, which='LM', OPinv=op, tol=1e-10)
        o = np.argsort(w)
        w, v = w[o], v[:, o]
        V = np.zeros((self.N, k))
        V[free_dofs] = v                                  # M-orthonormal mode shapes
        f = np.sign(w) * np.sqrt(np.abs(w)) / (2 * np.pi)
        return f, V

    def static(self, fixed, F):
        free_dofs = self.free(fixed)
        lu = SPDSolver(self.K[free_dofs][:, free_dofs])
        U = np.zeros((self.N,) + F.shape[1:])
        U[free_dofs] = lu.solve(F[free_dofs]).reshape(U[free_dofs].shape)
        return U, lu, free_dofs

    # ---- loads ----
    def patch(self, zc, p):
        """Patch on the outer surface centred at theta=0 (this model holds theta>=0),
        axial extent zc +- PATCH_LEN/2 clipped to the model.  Returns load vector for
        a uniform inward pressure p [Pa] and the vector a such that a.u = integral of
        the inward normal displacement over the patch (in this model)."""
        m = self.mesh
        mid = m.p[:, m.facets].mean(axis=1)
        thm = np.arctan2(mid[1], mid[0])
        # facets lying ON the outer surface: all 4 corner vertices at r = RO
        rv = np.hypot(m.p[0, m.facets], m.p[1, m.facets])      # (4, nfacets)
        sel = ((rv.min(axis=0) > RO - 1e-7) & (np.abs(thm) < TH_P)
               & (np.abs(mid[2] - zc) < PATCH_LEN / 2))
        facets = np.intersect1d(np.nonzero(sel)[0], m.boundary_facets())
        fb = FacetBasis(m, ElementHex2(), facets=facets, intorder=5)
        area = asm(Functional(lambda w: 1.0 + 0 * w.x[0]), fb)
        a = np.zeros(self.N)
        for i in range(3):
            ai = asm(LinearForm(lambda v, w, i=i: -w.n[i] * v), fb)
            if hasattr(self, 'keep'):
                ai = ai[self.keep]
            a[i::3] = ai
        return p * a, a, area, facets.size


# ----------------------------------------------------------------------------
# Mode identification
# ----------------------------------------------------------------------------
KMAX = 8


def circ_fourier(th, ur, cls):
    """Fourier amplitudes c_k (k=0..KMAX) of ur(theta) around the full circle.
    th in [0, 90deg] for a quarter model (cls=(s0, s90), s=+1 even, -1 odd) or
    th in [0, 2pi) for the full model (cls=None)."""
    o = np.argsort(th)
    th, ur = th[o], ur[o]
    if cls is not None:
        s0, s90 = cls
        t2 = np.pi - th[::-1]
        u2 = s90 * ur[::-1]
        thh = np.concatenate([th, t2[1:]])            # [0, pi]
        uh = np.concatenate([ur, u2[1:]])
        t3 = 2 * np.pi - thh[::-1]
        u3 = s0 * uh[::-1]
        thf = np.concatenate([thh, t3[1:]])           # [0, 2pi]
        uf = np.concatenate([uh, u3[1:]])
    else:
        thf = np.concatenate([th, [2 * np.pi]])
        uf = np.concatenate([ur, ur[:1]])
    c = []
    for k in range(KMAX + 1):
        a = np.trapezoid(uf * np.cos(k * thf), thf) / np.pi
        b = np.trapezoid(uf * np.sin(k * thf), thf) / np.pi
        if k == 0:
            a /= 2
        c.append(np.hypot(a, b))
    return np.array(c)


def harmonic_profile(model, ur, n, outer, cls):
    """Axial profile W_n(z) of harmonic n of u_r on the outer surface."""
    zs = np.unique(np.round(model.z[outer], 12))
    W = []
    for zz in zs:
        s = outer & (np.abs(model.z - zz) < 1e-9)
        th = model.th[s]
        o = np.argsort(th)
        th, u = th[o], ur[s][o]
        if cls is None:
            thf, uf = np.concatenate([th, [2 * np.pi]]), np.concatenate([u, u[:1]])
            a = np.trapezoid(uf * np.cos(n * thf), thf)
            b = np.trapezoid(uf * np.sin(n * thf), thf)
            W.append((a, b))
        else:
            fn = np.cos if cls[0] > 0 else np.sin
            W.append((np.trapezoid(u * fn(n * th), th), 0.0))
    W = np.array(W)
    if cls is None:  # project on the dominant phase
        ph = W[np.argmax(np.hypot(W[:, 0], W[:, 1]))]
        ph = ph / np.linalg.norm(ph)
        W = W @ ph
    else:
        W = W[:, 0]
    return zs, W


def sign_changes(W, rel=0.02):
    W = np.asarray(W)
    big = W[np.abs(W) > rel * np.abs(W).max()]
    return int(np.sum(np.sign(big[1:]) != np.sign(big[:-1])))


def identify(model, u, cls=None, zsym=None, z_full=False):
    """Describe a mode: dominant n (mid and quarter length), axial sign changes of
    the n-th harmonic of u_r along the whole length, kinetic-energy fractions."""
    ur, ut, uz = model.polar(u)
    Ms = model.Ms
    er, et, ez = ur @ Ms @ ur, ut @ Ms @ ut, uz @ Ms @ uz
    tot = er + et + ez
    outer = np.abs(model.r - RO) < 1e-9
    res = dict(E_radial=er / tot, E_circ=et / tot, E_axial=ez / tot)
    # share of circumferential kinetic energy in the theta-uniform (n=0) part:
    # u_theta(r,z) averaged over theta at each (r,z) position
    key = np.round(model.r * 1e7) * 1e7 + np.round((model.z + 1) * 1e7)
    _, inv = np.unique(key, return_inverse=True)
    if cls is None or cls[0] < 0:   # torsion possible (u_theta even about theta=0)
        wgt = np.asarray(Ms.sum(axis=1)).ravel()
        mean = np.bincount(inv, ut * wgt) / np.maximum(np.bincount(inv, wgt), 1e-300)
        ut0 = mean[inv]
        res['E_circ_n0'] = float((ut0 @ Ms @ ut0) / max(et, 1e-300))
    else:
        res['E_circ_n0'] = 0.0
    if z_full:  # full-length model, z in [-L/2, L/2]
        zq = [0.0, -LEN / 4]
    else:
        zq = [0.0, LEN / 4]
    spec = {}
    for name, zz in zip(['mid', 'quarter'], zq, strict=True):
        s = outer & (np.abs(model.z - zz) < 1e-9)
        spec[name] = circ_fourier(model.th[s], ur[s], cls)
    # dominant n: from the station with the larger overall amplitude
    cm, cq = spec['mid'], spec['quarter']
    ref = cm if cm.max() >= cq.max() else cq
    n = int(np.argmax(ref))
    # a station at an axial node (e.g. mid-length of a z-antisymmetric mode) has no
    # radial motion: report None there
    res['n_mid'] = int(np.argmax(cm)) if cm.max() > 1e-6 * ref.max() else None
    res['n_quarter'] = int(np.argmax(cq)) if cq.max() > 1e-6 * ref.max() else None
    res['n'] = n
    res['spec_mid'] = (cm / max(ref.max(), 1e-300)).round(3).tolist()
    res['spec_quarter'] = (cq / max(ref.max(), 1e-300)).round(3).tolist()
    zs, W = harmonic_profile(model, ur, n, outer, cls)
    if not z_full:  # reflect over z = 0
        s = 1.0 if zsym == 'S' else -1.0
        zs = np.concatenate([-zs[::-1], zs[1:]])
        W = np.concatenate([s * W[::-1], W[1:]])
    res['axial_sign_changes'] = sign_changes(W)
    imid = np.argmin(np.abs(zs))
    res['W_end_over_max'] = float(W[-1] / np.abs(W).max()) if np.abs(W).max() > 0 else 0.0
    res['W_mid_over_max'] = float(W[imid] / np.abs(W).max()) if np.abs(W).max() > 0 else 0.0
    return res


def mode_type(f, idd):
    if abs(f) < 1.0:
        return 'rigid body'
    n = idd['n']
    er, et, ez = idd['E_radial'], idd['E_circ'], idd['E_axial']
    if max(er, et) < 0.5 and ez >= 0.5:
        # axial motion dominant
        return 'axial/longitudinal' if n == 0 or er < 0.02 else 'axial-dominant n=%d' % n
    if et > 0.9 and er < 0.05:
        return 'torsional (n=0, u_theta ~ uniform around)' if idd['E_circ_n0'] > 0.9 else 'circumferential-dominant'
    if n == 0:
        return 'breathing/radial n=0'
    if n == 1 and er + et > 0.5:
        return 'beam bending/shear (n=1)'
    return 'shell n=%d, %d axial sign change(s)' % (n, idd['axial_sign_changes'])


# ----------------------------------------------------------------------------
# Thin-shell theory (simply supported = shear diaphragm), independent reference
# ----------------------------------------------------------------------------
def shell_ss_freqs(n, m, t, theory='flugge'):
    """Three frequencies [Hz] of the simply supported thin cylinder (mean radius
    R=(D-t)/2, thickness t, length LEN) for n circumferential waves and m axial
    half-waves.  Exact for the shell theory (the SS mode functions
    u=A cos(m pi x/L) cos n th, v=B sin sin, w=C sin cos are exact eigenfunctions).
    Nondimensional: lam = m pi R/L, k = t^2/(12R^2), Omega^2 = rho(1-nu^2)R^2 w^2/E;
    det(C - Omega^2 free_dofs) = 0.
    'flugge' : Flugge operator as tabulated by Leissa, Vibration of Shells,
               NASA SP-288 (1973), ch.2 (Donnell-Mushtari operator + k*[L_mod]).
    'donnell', 'sanders': matrices derived here from the shell strain energy
               U = K/2 int(ex^2+et^2+2nu ex et+(1-nu)/2 g^2)
                 + D/2 int(kx^2+kt^2+2nu kx kt+(1-nu)/2 chi^2)
               with Donnell or Sanders strain-displacement relations."""
    R = (D_OUT - t) / 2
    nu = NU
    lam = m * np.pi * R / LEN
    k = t ** 2 / (12 * R ** 2)
    if theory == 'flugge':
        C = np.zeros((3, 3))
        C[0, 0] = lam ** 2 + 0.5 * (1 - nu) * (1 + k) * n ** 2
        C[0, 1] = 0.5 * (1 + nu) * lam * n
        C[0, 2] = nu * lam + k * (lam ** 3 - 0.5 * (1 - nu) * lam * n ** 2)
        C[1, 1] = 0.5 * (1 - nu) * (1 + 3 * k) * lam ** 2 + n ** 2
        C[1, 2] = n + 0.5 * k * (3 - nu) * lam ** 2 * n
        C[2, 2] = 1 + k * (lam ** 4 + 2 * lam ** 2 * n ** 2 + n ** 4 - 2 * n ** 2 + 1)
        C = np.triu(C) + np.triu(C, 1).T
    else:
        # coefficient vectors over (A, B, C); S-type: sin(lam xi) cos(n th), T-type
        ex = np.array([-lam, 0, 0.])
        et = np.array([0, n, 1.])
        g = np.array([-n, lam, 0.])
        kx = np.array([0, 0, lam ** 2])
        if theory == 'donnell':
            kt = np.array([0, 0, n ** 2])
            chi = np.array([0, 0, 2 * lam * n])
        elif theory == 'sanders':
            kt = np.array([0, n, n ** 2])
            chi = np.array([0.5 * n, 1.5 * lam, 2 * lam * n])
        else:
            raise ValueError(theory)

        def q(a, b, c):
            return (np.outer(a, a) + np.outer(b, b) + nu * (np.outer(a, b) + np.outer(b, a))
                    + 0.5 * (1 - nu) * np.outer(c, c))
        C = q(ex, et, g) + k * q(kx, kt, chi)
    Om2 = np.sort(np.linalg.eigvalsh(C))
    w = np.sqrt(Om2 * E_MOD / (RHO * (1 - nu ** 2) * R ** 2))
    return w / (2 * np.pi)


# ----------------------------------------------------------------------------
# Model factories
# ----------------------------------------------------------------------------
def eighth_model(t, lev, tube=None, levels=None):
    """theta in [0, 90 deg], z in [0, L/2] from mid-length; patch edges, and the
    quarter-length station z=L/4 are element boundaries.  `tube` is the mesh class and
    `levels` the mesh levels (default Tube and LEVELS; fe_laminate_tube passes its laminated
    tube, `t` then its plies, and its own levels)."""
    L = (levels or LEVELS)[lev]
    th = grid([0.0, TH_P, np.pi / 2], L['h_th'] / RO)
    z = grid([0.0, PATCH_LEN / 2, LEN / 4, LEN / 2], L['h_z'])
    return (tube or Tube)(t, th, z, L['nr'])


def quarter_full_length_model(t, lev, zc, tube=None, levels=None):
    """theta in [0, 90 deg], z in [-L/2, L/2]; patch centred at z=zc (tube, levels: as
    eighth_model)."""
    L = (levels or LEVELS)[lev]
    th = grid([0.0, TH_P, np.pi / 2], L['h_th'] / RO)
    bz = sorted(set([-LEN / 2, -LEN / 4, 0.0, zc - PATCH_LEN / 2, zc + PATCH_LEN / 2, LEN / 2]))
    z = grid(bz, L['h_z'])
    return (tube or Tube)(t, th, z, L['nr'])


# symmetry classes of the quarter model: name -> (bc at theta=0, bc at theta=90,
# parities of u_r (s0, s90)).  Harmonics contained:
CLASSES = {
    'SS': ('S', 'S', (1, 1)),     # cos(n th), n = 0, 2, 4, ...
    'SA': ('S', 'A', (1, -1)),    # cos(n th), n = 1, 3, 5, ...
    'AS': ('A', 'S', (-1, 1)),    # sin(n th), n = 1, 3, 5, ...
    'AA': ('A', 'A', (-1, -1)),   # sin(n th), n = 0(torsion), 2, 4, ...
}


def modes_class(model, cname, zsym, ends, k=12):
    b0, b90, par = CLASSES[cname]
    fixed = model.bc(th0=b0, th90=b90, zmid=zsym, zend=ends)
    sigma = -(2 * np.pi * 300.0) ** 2
    f, V = model.eig(fixed, k, sigma)
    out = []
    for i in range(k):
        idd = identify(model, V[:, i], cls=par, zsym=zsym)
        idd['f_Hz'] = float(f[i])
        idd['class'] = '%s-z%s' % (cname, zsym)
        idd['type'] = mode_type(f[i], idd)
        if idd['type'].startswith('torsional'):
            idd['n'] = 0          # u_r ~ 0: the u_r spectrum is meaningless
        out.append(idd)
    return out


def pick(modes, n, nchg):
    c = [m for m in modes if m['n'] == n and m['axial_sign_changes'] == nchg
         and abs(m['f_Hz']) > 1.0]
    return min(c, key=lambda m: m['f_Hz']) if c else None


# ----------------------------------------------------------------------------
# Case runners
# ----------------------------------------------------------------------------
def case_A(model, k=12, classes=('SS', 'SA', 'AS', 'AA')):
    """free-free: n=2 (class SS), n=3 (class SA); z-sym (even axial orders) and
    z-anti (odd).  AS/AA hold the degenerate sin partners and torsion (listed; a caller that
    needs only the picked modes may leave them out of ``classes``)."""
    allm = []
    for c in classes:
        for zs in ['S', 'A']:
            allm += modes_class(model, c, zs, None, k=k)
    allm.sort(key=lambda m: m['f_Hz'])
    res = {}
    for n, c in [(2, 'SS'), (3, 'SA')]:
        ms = [m for m in allm if m['class'].startswith(c)]
        r1 = pick(ms, n, 0)
        r2 = pick(ms, n, 1)
        res['n%d_axial0' % n] = r1
        res['n%d_axial1' % n] = r2
    return res, allm


def case_B(model, k=10, thin_shell=None):
    """shear-diaphragm ends at z=+-L/2; m odd <-> z-sym, m even <-> z-anti.  With them the
    thin-shell frequencies of each (n, m): ``thin_shell(n, m)`` -> {theory: Hz}, by default
    the isotropic wall's Flugge, Sanders and Donnell values."""
    allm = []
    for c in ['SS', 'SA']:
        for zs in ['S', 'A']:
            allm += modes_class(model, c, zs, 'SD', k=k)
    allm.sort(key=lambda m: m['f_Hz'])
    res = {}
    for n, c in [(2, 'SS'), (3, 'SA')]:
        ms = [mm for mm in allm if mm['class'].startswith(c)]
        for m in (1, 2):
            res['n%d_m%d' % (n, m)] = pick(ms, n, m - 1)
    if thin_shell is None:
        def thin_shell(n, m):
            return {th: float(shell_ss_freqs(n, m, model.t, th)[0])
                    for th in ['flugge', 'sanders', 'donnell']}
    shell = {'n%d_m%d' % (n, m): thin_shell(n, m) for n in (2, 3) for m in (1, 2)}
    return res, allm, shell


def squeeze_outputs(model, u, a, area, Fpatch_model, Fpatch, zc):
    """Outputs of a squeeze: approach of the patch centres, pressure-weighted mean
    inward radial displacement, work-conjugate displacement, stiffness."""
    outer = np.abs(model.r - RO) < 1e-9
    ur, ut, uz = model.polar(u)
    ic = np.nonzero(outer & (np.abs(model.th) < 1e-9) & (np.abs(model.z - zc) < 1e-9))[0][0]
    i90 = np.nonzero(outer & (np.abs(model.th - np.pi / 2) < 1e-9) & (np.abs(model.z - zc) < 1e-9))[0][0]
    inward_c = -ur[ic]
    avg = (a @ u) / area                      # pressure-weighted (uniform p) = area mean
    work_disp = (Fpatch_model @ u) / (Fpatch * area / (model.patch_area_full))
    return dict(
        centre_inward_mm=inward_c * 1e3,
        approach_mm=2 * inward_c * 1e3,
        patch_avg_inward_mm=avg * 1e3,
        stiffness_F_over_avg_N_per_m=Fpatch / avg,
        work_conjugate_disp_mm=work_disp * 1e3,
        stiffness_F_over_workdisp_N_per_m=Fpatch / work_disp,
        stiffness_F_over_approach_N_per_m=Fpatch / (2 * inward_c),
        outward_at_90deg_mm=ur[i90] * 1e3,
        diameter_increase_at_90deg_mm=2 * ur[i90] * 1e3,
    )


def case_C(model):
    fixed = model.bc(th0='S', th90='S', zmid='S')   # removes all rigid-body modes
    p = F_PATCH * P_PER_N
    f, a, area, nf = model.patch(0.0, p)
    model.patch_area_full = PATCH_LEN * PATCH_ARC
    Fx = f[0::3].sum()
    U, lu, free_dofs = model.static(fixed, f)
    out = squeeze_outputs(model, U, a, area, f, F_PATCH, 0.0)
    out.update(pressure_MPa=p / 1e6, resultant_check_N=-4 * Fx,
               patch_area_check_mm2=4 * area * 1e6, n_patch_facets_model=int(nf))
    return out, f, a, area, U, lu, free_dofs, fixed


def case_D(t, lev, tube=None, levels=None):
    zc = LEN / 2 - 0.050
    model = quarter_full_length_model(t, lev, zc, tube, levels)
    fixed = model.bc(th0='S', th90='S')
    # the only remaining rigid-body mode is translation along z: fix u_z of one node
    outer = np.abs(model.r - RO) < 1e-9
    i0 = np.nonzero(outer & (np.abs(model.th - np.pi / 2) < 1e-9) & (np.abs(model.z) < 1e-9))[0][0]
    fixed = np.unique(np.concatenate([fixed, [3 * i0 + 2]]))
    p = F_PATCH * P_PER_N
    f, a, area, nf = model.patch(zc, p)
    model.patch_area_full = PATCH_LEN * PATCH_ARC
    U, lu, free_dofs = model.static(fixed, f)
    out = squeeze_outputs(model, U, a, area, f, F_PATCH, zc)
    out.update(resultant_check_N=-2 * f[0::3].sum(), reaction_uz_check_N=float((model.K @ U)[3 * i0 + 2]),
               patch_centre_z_from_end_mm=(LEN / 2 - zc) * 1e3,
               patch_area_check_mm2=2 * area * 1e6, ndof=model.N, nel=model.nel,
               t_asm_s=model.time_asm)
    return out


def halfsine_modal(w, g, tt, Tp=T_PULSE):
    """Undamped SDOF x''+w^2 x = g sin(pi t/Tp) (0<=t<=Tp), 0 after; x(0)=x'(0)=0.
    w: (nm,), g: (nm,), tt: (nt,) -> (nm, nt).  Exact (Duhamel) solution."""
    Om = np.pi / Tp
    W = w[:, None]
    G = g[:, None]
    den = W ** 2 - Om ** 2
    # (near-)resonant guard: w == Om is not met here (checked below)
    assert np.all(np.abs(den) > 1e-6 * W ** 2)
    t1 = np.minimum(tt, Tp)[None, :]
    x1 = G / den * (np.sin(Om * t1) - Om / W * np.sin(W * t1))
    xT = G[:, 0] / den[:, 0] * (np.sin(Om * Tp) - Om / w * np.sin(w * Tp))
    vT = G[:, 0] / den[:, 0] * (Om * np.cos(Om * Tp) - Om * np.cos(w * Tp))
    tau = np.maximum(tt - Tp, 0)[None, :]
    x2 = xT[:, None] * np.cos(W * tau) + (vT / w)[:, None] * np.sin(W * tau)
    return np.where(tt[None, :] <= Tp, x1, x2)


def case_E(model, f1, a, area, lu, free_dofs, fixed, nmodes=120, newmark=True, dt=1.0e-6):
    """Modal superposition (exact Duhamel per mode) on the 1/8 model (SS, z-sym):
    only modes symmetric about theta=0, theta=90 deg and z=0 are excited."""
    t0 = time.time()
    f0 = f1 * (F0_PULSE / F_PATCH)
    outer = np.abs(model.r - RO) < 1e-9
    ic = np.nonzero(outer & (np.abs(model.th) < 1e-9) & (np.abs(model.z) < 1e-9))[0][0]
    # output functionals: approach = -2 u_x(centre); patch mean inward disp = a.u/area
    cA = np.zeros(model.N)
    cA[3 * ic] = -2.0
    cB = a / area
    # static solution for the peak load
    us = np.zeros(model.N)
    us[free_dofs] = lu.solve(f0[free_dofs]).ravel()
    ys = np.array([cA @ us, cB @ us])
    fr, V = model.eig(fixed, nmodes, sigma=-(2 * np.pi * 300.0) ** 2)
    w = 2 * np.pi * fr
    g = V.T @ f0
    tt = np.linspace(0.0, T_END, 20001)           # 0.1 us output resolution
    X = halfsine_modal(w, g, tt)
    s = np.where(tt <= T_PULSE, np.sin(np.pi * tt / T_PULSE), 0.0)
    C = np.vstack([cA @ V, cB @ V])               # (2, nm)
    conv = []
    for nm in sorted(set([1, 2, 3, 5, 10, 20, 40, 80, nmodes])):
        if nm > nmodes:
            continue
        yd = C[:, :nm] @ X[:nm]                                 # mode displacement
        ya = ys[:, None] * s[None, :] + C[:, :nm] @ (X[:nm] - (g[:nm] / w[:nm] ** 2)[:, None] * s[None, :])
        conv.append(dict(nmodes=nm, f_max_Hz=float(fr[nm - 1]),
                         approach_max_mm_modedisp=float(yd[0].max() * 1e3),
                         patchavg_max_mm_modedisp=float(yd[1].max() * 1e3),
                         approach_max_mm_staticcorr=float(ya[0].max() * 1e3),
                         patchavg_max_mm_staticcorr=float(ya[1].max() * 1e3)))
    ya = ys[:, None] * s[None, :] + C @ (X - (g / w ** 2)[:, None] * s[None, :])
    imax = np.argmax(ya[0])
    jmax = np.argmax(ya[1])
    # participation: which modes carry the response
    contrib = np.abs(C[0] * g / w ** 2)
    top = np.argsort(contrib)[::-1][:6]
    res = dict(
        approach_max_mm=float(ya[0, imax] * 1e3), t_at_approach_max_ms=float(tt[imax] * 1e3),
        patchavg_max_mm=float(ya[1, jmax] * 1e3), t_at_patchavg_max_ms=float(tt[jmax] * 1e3),
        approach_min_mm=float(ya[0].min() * 1e3),
        static_approach_at_F0_mm=float(ys[0] * 1e3), static_patchavg_at_F0_mm=float(ys[1] * 1e3),
        DAF_approach=float(ya[0, imax] / ys[0]), DAF_patchavg=float(ya[1, jmax] / ys[1]),
        nmodes=nmodes, highest_mode_Hz=float(fr[-1]), convergence=conv,
        dominant_modes=[dict(f_Hz=float(fr[i]), static_share=float(C[0, i] * g[i] / w[i] ** 2 / ys[0]))
                        for i in top],
    )
    res['t_modal_s'] = time.time() - t0
    if newmark:
        t1 = time.time()
        # direct integration, Newmark average acceleration (beta=1/4, gamma=1/2)
        Kf = model.K[free_dofs][:, free_dofs].tocsc()
        Mf = model.M[free_dofs][:, free_dofs].tocsc()
        Keff = (Kf + 4.0 / dt ** 2 * Mf).tocsc()
        luN = SPDSolver(Keff)
        nst = int(round(T_END / dt))
        u = np.zeros(free_dofs.size)
        v = np.zeros(free_dofs.size)
        acc = np.zeros(free_dofs.size)
        fI = f0[free_dofs]
        cAI, cBI = cA[free_dofs], cB[free_dofs]
        hist = np.zeros((nst + 1, 2))
        for j in range(1, nst + 1):
            tj = j * dt
            sj = np.sin(np.pi * tj / T_PULSE) if tj <= T_PULSE else 0.0
            rhs = sj * fI + Mf @ (4.0 / dt ** 2 * u + 4.0 / dt * v + acc)
            un = luN.solve(rhs).ravel()
            an = 4.0 / dt ** 2 * (un - u) - 4.0 / dt * v - acc
            v = v + 0.5 * dt * (acc + an)
            u, acc = un, an
            hist[j] = [cAI @ u, cBI @ u]
        res['newmark'] = dict(dt_us=dt * 1e6, approach_max_mm=float(hist[:, 0].max() * 1e3),
                              t_at_approach_max_ms=float(np.argmax(hist[:, 0]) * dt * 1e3),
                              patchavg_max_mm=float(hist[:, 1].max() * 1e3),
                              t_s=time.time() - t1)
    return res


# ----------------------------------------------------------------------------
# Drivers
# ----------------------------------------------------------------------------
def brief(m):
    if m is None:
        return None
    return {k: m[k] for k in ['f_Hz', 'class', 'n', 'n_mid', 'n_quarter', 'axial_sign_changes',
                              'spec_mid', 'spec_quarter', 'E_radial', 'E_circ', 'E_axial',
                              'W_end_over_max', 'W_mid_over_max', 'type']}


def mesh_record(model, lev, levels=None):
    """The mesh of a 1/8 model as run records it (levels: as eighth_model)."""
    return dict(level=lev, ndof=model.N, nel=model.nel, **(levels or LEVELS)[lev],
                n_theta_quarter=int(len(np.unique(model.th.round(12))) - 1) // 2,
                n_z_half=int(len(np.unique(model.z.round(12))) - 1) // 2,
                t_asm_s=model.time_asm)


def run_case_A(out, solve, model, **kw):
    """Case A (free-free modes) by `solve(model, **kw)`, recorded into `out` and logged."""
    t0 = time.time()
    res, allm = solve(model, **kw)
    out['A'] = {kk: brief(v) for kk, v in res.items()}
    out['A_all_modes'] = [dict(f_Hz=m['f_Hz'], cls=m['class'], n=m['n'], axial_sign_changes=m['axial_sign_changes'],
                               type=m['type'], E_r=round(m['E_radial'], 3), E_t=round(m['E_circ'], 3),
                               E_z=round(m['E_axial'], 3)) for m in allm]
    out['A_time_s'] = time.time() - t0
    for kk, v in res.items():
        log('    A %-12s %s' % (kk, 'NOT IDENTIFIED' if v is None else '%.1f Hz (%s)' % (v['f_Hz'], v['class'])))


def run_case_B(out, solve, model, theory_label, theory_key, **kw):
    """Case B (shear-diaphragm modes) by `solve(model, **kw)`, recorded into `out` and logged
    beside the thin-shell theory `theory_key` of its output."""
    t0 = time.time()
    res, allm, shell = solve(model, **kw)
    out['B'] = {kk: brief(v) for kk, v in res.items()}
    out['B_shell_theory_Hz'] = shell
    out['B_all_modes'] = [dict(f_Hz=m['f_Hz'], cls=m['class'], n=m['n'], axial_sign_changes=m['axial_sign_changes'],
                               type=m['type']) for m in allm]
    out['B_time_s'] = time.time() - t0
    for kk, v in res.items():
        log('    B %-8s FE %s  %s %.1f Hz' % (kk, 'NOT IDENTIFIED' if v is None else '%.1f Hz' % v['f_Hz'],
                                             theory_label, shell[kk][theory_key]))


def run_case_D(out, t, lev, tube=None, levels=None):
    """Case D (the full-length static squeeze) recorded into `out` and logged."""
    t0 = time.time()
    out['D'] = case_D(t, lev, tube, levels)
    out['D_time_s'] = time.time() - t0
    log('    D approach %.5f mm, patch-avg %.5f mm' % (out['D']['approach_mm'], out['D']['patch_avg_inward_mm']))


def run_wall(t, lev, cases, k=12):
    out = {}
    T0 = time.time()
    model = eighth_model(t, lev)
    out['mesh'] = mesh_record(model, lev)
    log('  t=%.1f mm %s: 1/8 model %d dof, %d el, asm %.1f s' % (t * 1e3, lev, model.N, model.nel, model.time_asm))
    if 'A' in cases:
        run_case_A(out, case_A, model, k=k)
    if 'B' in cases:
        run_case_B(out, case_B, model, 'Flugge', 'flugge', k=10)
    if 'C' in cases or 'E' in cases:
        t0 = time.time()
        resC, f1, a, area, U, lu, free_dofs, fixed = case_C(model)
        out['C'] = resC
        out['C_time_s'] = time.time() - t0
        log('    C approach %.5f mm, patch-avg %.5f mm, k = %.4e N/m' % (
            resC['approach_mm'], resC['patch_avg_inward_mm'], resC['stiffness_F_over_avg_N_per_m']))
    if 'D' in cases:
        run_case_D(out, t, lev)
    if 'E' in cases:
        t0 = time.time()
        out['E'] = case_E(model, f1, a, area, lu, free_dofs, fixed, newmark=(lev == 'M1'),
                          nmodes=(40 if lev == 'M2' else 120))
        out['E_time_s'] = time.time() - t0
        log('    E max approach %.5f mm at %.3f ms, max patch-avg %.5f mm' % (
            out['E']['approach_max_mm'], out['E']['t_at_approach_max_ms'], out['E']['patchavg_max_mm']))
    out['wall_time_s'] = time.time() - T0
    return out


def peak_von_mises(model, u):
    """Largest von Mises stress [Pa] over all Gauss points (3x3x3 per element) and
    where it occurs (r, theta, z).  Gauss points lie inside the elements, so the
    true surface peak is somewhat higher; this is an indication only."""
    sb = model.sb
    if hasattr(model, 'keep'):
        raise NotImplementedError
    G = np.stack([sb.interpolate(u[i::3]).grad for i in range(3)])   # (3 comp, 3 der, nel, nq)
    eps = 0.5 * (G + G.transpose(1, 0, 2, 3))
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    sig = 2 * MU * eps
    for i in range(3):
        sig[i, i] += LAM * tr
    s = sig
    vm = np.sqrt(0.5 * ((s[0, 0] - s[1, 1]) ** 2 + (s[1, 1] - s[2, 2]) ** 2 + (s[2, 2] - s[0, 0]) ** 2)
                 + 3 * (s[0, 1] ** 2 + s[1, 2] ** 2 + s[2, 0] ** 2))
    e, q = np.unravel_index(np.argmax(vm), vm.shape)
    x = sb.global_coordinates().value[:, e, q]
    return float(vm[e, q]), dict(r_mm=float(np.hypot(x[0], x[1]) * 1e3),
                                 theta_deg=float(np.degrees(np.arctan2(x[1], x[0]))), z_mm=float(x[2] * 1e3))


def stress_run(walls, lev):
    """Peak von Mises of the static mid-length squeeze (case C) per 1000 N."""
    res = {}
    for w in walls:
        model = eighth_model(w * 1e-3, lev)
        out, f, a, area, U, lu, free_dofs, fixed = case_C(model)
        vm, where = peak_von_mises(model, U)
        res['%.1f' % w] = dict(level=lev, peak_von_mises_MPa_per_1000N=vm / 1e6, where=where)
        log('  t=%.1f mm %s: peak von Mises (Gauss pts) %.1f MPa per 1000 N at %s' % (w, lev, vm / 1e6, where))
    return res


def verify(t=3.0e-3, h_th=4.0e-3, h_z=7.5e-3, nr=2, k_full=40):
    """Full 360-deg, full-length free-free model vs the 8 symmetry classes of the
    1/8 model built with the SAME node positions (uniform theta spacing)."""
    nq = int(np.ceil(np.pi / 2 * RO / h_th))
    nzh = int(np.ceil(LEN / 2 / h_z))
    thq = np.linspace(0, np.pi / 2, nq + 1)
    zh = np.linspace(0, LEN / 2, nzh + 1)
    T0 = time.time()
    full = Tube(t, np.linspace(0, 2 * np.pi, 4 * nq + 1), np.linspace(-LEN / 2, LEN / 2, 2 * nzh + 1), nr,
                periodic=True)
    log('verify: full model %d dof (asm %.1f s)' % (full.N, full.time_asm))
    ff, Vf = full.eig(np.zeros(0, int), k_full, sigma=-(2 * np.pi * 300.0) ** 2)
    fullm = []
    for i in range(k_full):
        idd = identify(full, Vf[:, i], cls=None, z_full=True)
        if mode_type(ff[i], idd).startswith('torsional'):
            idd['n'] = 0
        fullm.append(dict(f_Hz=float(ff[i]), n=idd['n'], axial_sign_changes=idd['axial_sign_changes'],
                          type=mode_type(ff[i], idd), spec_mid=idd['spec_mid'], spec_quarter=idd['spec_quarter']))
    tfull = time.time() - T0
    eighth = Tube(t, thq, zh, nr)
    symm = []
    for c in CLASSES:
        for zs in ['S', 'A']:
            symm += modes_class(eighth, c, zs, None, k=8)
    symm.sort(key=lambda m: m['f_Hz'])
    fs = np.array([m['f_Hz'] for m in symm])
    # match each full-model mode to the nearest symmetric-model frequency
    rows = []
    for m in fullm:
        j = np.argmin(np.abs(fs - m['f_Hz']))
        rows.append(dict(full=m, sym_f_Hz=float(fs[j]), sym_class=symm[j]['class'], sym_n=symm[j]['n'],
                         sym_axial_sign_changes=symm[j]['axial_sign_changes'],
                         rel_diff=float((m['f_Hz'] - fs[j]) / max(abs(fs[j]), 1.0))))
    return dict(mesh=dict(t_mm=t * 1e3, nr=nr, n_theta_full=4 * nq, n_z_full=2 * nzh, ndof_full=full.N,
                          ndof_eighth=eighth.N), time_full_s=tfull, rows=rows)


def selftest():
    t = 3e-3
    th = np.linspace(0, np.pi / 2, 7)
    z = np.linspace(0, LEN / 2, 6)
    m = Tube(t, th, z, 2)
    from skfem.models.elasticity import linear_elasticity
    ib = CellBasis(m.mesh, ElementVector(ElementHex2()), intorder=5)
    K2 = asm(linear_elasticity(LAM, MU), ib)
    ix = ib.split_indices()
    perm = np.zeros(m.N, int)
    for i in range(3):
        perm[3 * np.arange(m.nn) + i] = ix[i]
    d = abs(K2[perm][:, perm] - m.K).max() / abs(m.K).max()
    ux = np.zeros(m.N)
    ux[0::3] = 1
    mass = ux @ m.M @ ux
    exact = RHO * np.pi * (RO ** 2 - (RO - t) ** 2) * LEN / 8
    log('selftest: |K_mine-K_skfem|/|K| = %.2e ; mass %.8e vs exact %.8e' % (d, mass, exact))
    return dict(K_rel_diff=float(d), mass_rel_err=float(mass / exact - 1))


def record(raw, source, quick=None):
    """The compact reference the tests read (tests/validation/data/fe_tube_reference.json):
    per wall and mesh level, the frequencies [Hz], squeeze displacements [mm] and pulse maxima
    [mm] that batcert's shell model is compared with."""
    inp = raw['inputs']
    out = dict(
        source=source,
        tube=dict(outer_diameter_m=inp['D_out_m'], length_m=inp['L_m'],
                  youngs_modulus_Pa=inp['E_Pa'], poisson_ratio=inp['nu'],
                  density_kg_m3=inp['rho']),
        load=dict(patch_length_m=inp['patch_len_m'], patch_arc_m=inp['patch_arc_m'],
                  static_force_N=inp['F_patch_N'], end_patch_from_end_m=0.050,
                  pulse_peak_force_N=inp['F0_pulse_N'], pulse_duration_s=inp['T_pulse_s'],
                  pulse_until_s=T_END,
                  force_definition='resultant (vector sum) of the uniform pressure on one patch'),
        meshes=inp['levels'],
        walls={})
    for key, levels in raw.items():
        if key in ('inputs', 'total_time_s'):
            continue
        wall = {}
        for lev, r in levels.items():
            rec = {}
            if 'A' in r:
                rec['free_free_hz'] = {k: v['f_Hz'] for k, v in r['A'].items() if v}
            if 'B' in r:
                rec['shear_diaphragm_hz'] = {k: v['f_Hz'] for k, v in r['B'].items() if v}
                wall['thin_shell_theory_hz'] = r['B_shell_theory_Hz']
            for case, name in (('C', 'squeeze_mid_mm'), ('D', 'squeeze_end_mm')):
                if case in r:
                    rec[name] = dict(centre_approach=r[case]['approach_mm'],
                                     patch_average_inward=r[case]['patch_avg_inward_mm'])
            if 'E' in r:
                rec['pulse_mid_max_mm'] = dict(centre_approach=r['E']['approach_max_mm'],
                                               patch_average_inward=r['E']['patchavg_max_mm'])
            wall[lev] = rec
        out['walls'][key] = wall
    if quick is not None:  # the coarse mesh of --quick, re-run by the slow test
        out['quick'] = {key: record_level(levels['quick'])
                        for key, levels in quick.items() if key != 'total_time_s'}
    return out


def record_level(r):
    """Frequencies [Hz] and static squeeze [mm] of one quick run (cases A and C)."""
    return dict(free_free_hz={k: v['f_Hz'] for k, v in r['A'].items() if v},
                squeeze_mid_mm=dict(centre_approach=r['C']['approach_mm'],
                                    patch_average_inward=r['C']['patch_avg_inward_mm']))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--quick', action='store_true', help='cases A and C, coarse mesh, one wall')
    ap.add_argument('--wall', type=float, default=3.0, help='wall [mm] for --quick')
    ap.add_argument('--walls', type=float, nargs='*', default=[2.0, 3.0, 4.0, 2.5, 3.5])
    ap.add_argument('--levels', nargs='*', default=['M1', 'M2'])
    ap.add_argument('--cases', default='ABCDE')
    ap.add_argument('--verify', action='store_true')
    ap.add_argument('--selftest', action='store_true')
    ap.add_argument('--stress', action='store_true', help='peak von Mises of case C per 1000 N')
    ap.add_argument('--out', default=None)
    ap.add_argument('--record', metavar='RAW', default=None,
                    help='write the compact reference of a full run (RAW: its --out file)')
    ap.add_argument('--quick-run', metavar='QUICK', default=None,
                    help='with --record: a --quick run to record too')
    ap.add_argument('--to', default='tests/validation/data/fe_tube_reference.json',
                    help='with --record: where to write it')
    args = ap.parse_args()
    T0 = time.time()
    if args.record:
        raw = json.load(open(args.record))
        quick = json.load(open(args.quick_run)) if args.quick_run else None
        import skfem
        source = ('scripts/fe_tube_reference.py, full run (meshes M1 and M2) of %s with '
                  'scikit-fem %s and %s' % (time.strftime('%Y-%m-%d'), skfem.__version__,
                                            SOLVER_NAME))
        jdump(record(raw, source, quick), args.to)
        log('wrote %s' % args.to)
        return
    if args.selftest:
        selftest()
        return
    if args.stress:
        r = {lev: stress_run(args.walls, lev) for lev in args.levels}
        jdump(r, args.out or 'stress.json')
        return
    if args.verify:
        v = verify()
        jdump(v, args.out or 'verify.json')
        for r in v['rows']:
            log('%10.2f  n=%d ch=%d %-40s | sym %10.2f %s n=%d ch=%d  d=%.1e' % (
                r['full']['f_Hz'], r['full']['n'], r['full']['axial_sign_changes'], r['full']['type'],
                r['sym_f_Hz'], r['sym_class'], r['sym_n'], r['sym_axial_sign_changes'], r['rel_diff']))
        return
    if args.quick:
        log('QUICK mode: wall %.1f mm, mesh level "quick", cases A and C' % args.wall)
        res = {'%.1f' % args.wall: {'quick': run_wall(args.wall * 1e-3, 'quick', 'AC')}}
        res['total_time_s'] = time.time() - T0
        jdump(res, args.out or 'results_quick.json')
        log('total %.1f s' % res['total_time_s'])
        return
    out = dict(inputs=dict(E_Pa=E_MOD, nu=NU, rho=RHO, D_out_m=D_OUT, L_m=LEN, patch_len_m=PATCH_LEN,
                           patch_arc_m=PATCH_ARC, patch_half_angle_deg=np.degrees(TH_P),
                           F_patch_N=F_PATCH, F0_pulse_N=F0_PULSE, T_pulse_s=T_PULSE,
                           pressure_per_N_Pa=P_PER_N, levels=LEVELS))
    for w in args.walls:
        key = '%.1f' % w
        out[key] = {}
        for lev in args.levels:
            log('wall %s mm, mesh %s' % (key, lev))
            out[key][lev] = run_wall(w * 1e-3, lev, args.cases)
            jdump(out, args.out or 'results_raw.json')
    out['total_time_s'] = time.time() - T0
    jdump(out, args.out or 'results_raw.json')
    log('total %.1f s' % out['total_time_s'])


if __name__ == '__main__':
    main()
