#!/usr/bin/env python
"""
fe_ball_contact_finite.py -- the ball's contact footprint at LARGE compression: the independent
3-D finite-element reference of scripts/fe_ball_contact.py (whose mesh, geometry and Hertz
formulas it reuses; nothing of batcert) with finite deformation, up to u/R_b = 0.4, the
compressions the engine reaches (docs/validation.md, "The ball's footprint").

What differs from the linear model (fe_ball_contact.py):
  * kinematics : geometrically nonlinear, total Lagrangian (the reference configuration is the
                 undeformed ball; F = I + Grad u at every Gauss point)
  * material   : compressible neo-Hookean, W = mu/2 (I1 - 3 - 2 ln J) + lam/2 (ln J)^2, with the
                 Lame constants of E and the small-strain Poisson's ratio nu (so that it is the
                 linear model in the small-strain limit); P = mu F + (lam ln J - mu) F^-T;
                 consistent tangent dP/dF
  * loading    : the same dead uniform body force along -y (per reference volume: the ball's
                 deceleration), balanced by the contact; the compression u, the mean
                 displacement along y (the centre of mass's approach, exact at finite strain as
                 the mass is conserved), is prescribed and stepped from 0.005 R_b to 0.4 R_b;
                 the body force is the load factor, an unknown (a bordered Newton system)
  * contact    : frictionless, node-to-rigid-surface on the ball's lower-hemisphere surface
                 nodes, the gap measured on the DEFORMED positions to the true surface (the
                 cylinder's radial distance minus R_c; y + R_b on the flat), the reaction along
                 the surface's normal at the deformed node; enforced by a stiff penalty (nodal
                 stiffness PENALTY x E x the node's tributary surface area / R_b: penetrations
                 about 1e-4 of u or less, reported); a primal-dual active set with Newton inside:
                 the set is held while Newton converges (residual below NEWTON_TOL of the load),
                 then every node on the wrong side (held with g > 0, or penetrating outside) is
                 moved, one at a time if a set comes back (Murty's rule, as the linear model);
                 the first set of a step: the nodes within half the increment of the surface.
                 The pole keeps u_y = 0 (it is on both symmetry planes and touches at any load)
  * solver     : Newton per load step; the linear solves by GMRES preconditioned with a sparse
                 LU (SuperLU) of the tangent, refactored when the contact set changes or GMRES
                 needs more than GMRES_MAX iterations
  * footprint  : a_eq = sqrt(5 <x^2>), b_eq = sqrt(5 <s^2>) as in the linear model, with the
                 reactions' weights, at the nodes' DEFORMED positions on the counterface (x
                 along the axis, s the arc length around it); the same at the undeformed
                 positions is reported too (it is the linear model's measure)

Cases: 'cyl_2.625in', 'cyl_2.25in', 'flat'; nu = 0.3 and 0.45; mesh levels Q3 (n = 3, below)
and those of fe_ball_contact.LEVELS ('quick': n = 4; M1 and M2 are too slow for a Newton
iteration here).  Results at every load step (STEPS).  Recorded: Q3 for all six cases (6-13 min
each on a shared 2-core machine), quick for the 2 5/8 in barrel at nu = 0.3 (33 min).

Usage
  python scripts/fe_ball_contact_finite.py --level quick --nu 0.3 --counterface cyl_2.625in \
         --out case.json                 # one case (several may run in parallel)
  python scripts/fe_ball_contact_finite.py --record a.json b.json ...   # add the compact
         records to tests/validation/data/fe_ball_contact.json (key "finite_strain")
  python scripts/fe_ball_contact_finite.py --smoke --out s.json          # the slow test's
         run: the first two steps (u/R_b = 0.01, 0.02) of the recorded Q3 run on the 2 5/8 in
         barrel at nu = 0.3 (about a minute)
Units inside: SI.  Reported: mm, N.
"""
import os

os.environ.setdefault('OPENBLAS_NUM_THREADS', '1')
import argparse  # noqa: E402
import json  # noqa: E402
import logging  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402
import scipy.sparse.linalg as spl  # noqa: E402
from skfem import CellBasis, ElementHex2  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fe_ball_contact as lin  # noqa: E402  (mesh, geometry, Hertz; independent of batcert)

R_B, E_MOD = lin.R_B, lin.E_MOD
STEPS = (0.01, 0.02, 0.04, 0.07, 0.10, 0.15, 0.20, 0.25, 0.30, 0.35, 0.40)
SMOKE_STEPS = (0.01, 0.02)
# a level below fe_ball_contact's 'quick' (n = 4), the production level here: a Newton
# iteration factorises the tangent, 6 s at n = 3 (14.6k DOF), 7-35 s at n = 4 (32k), 100 s
# at M1 (n = 6, 107k) on the machine used; the mesh convergence is measured between Q3 and
# quick on the 2 5/8 in barrel at nu = 0.3
LEVELS = dict(lin.LEVELS, Q3=dict(n=3, rho0=3.0e-3))
lin.LEVELS = LEVELS
PENALTY = 1e5
GMRES_MAX = 15
NEWTON_TOL = 1e-7
VERBOSE = True
log = lin.log


class FiniteBall:
    """The quarter ball at finite strain: reference gradients, assembly pattern, constraints."""

    def __init__(self, lev, nu, chunk=600):
        L = lin.LEVELS[lev]
        self.mesh, self.info = lin.build_mesh(L['n'], L['rho0'])
        basis = CellBasis(self.mesh, ElementHex2(), intorder=5)
        self.X = basis.doflocs
        self.nn = basis.N
        self.N = 3 * self.nn
        self.G = np.stack([basis.basis[a][0].grad for a in range(27)]).transpose(2, 3, 0, 1).copy()
        # G[e, q, a, J] = dN_a / dX_J; dx[e, q] = quadrature weight x det J
        self.dx = basis.dx
        self.ed = basis.element_dofs                                  # (27, nel)
        phi = np.stack([basis.basis[a][0].value for a in range(27)])
        w = np.zeros(self.nn)
        np.add.at(w, self.ed.ravel(), np.einsum('aeq,eq->ae', phi, self.dx).ravel())
        self.w, self.volume = w, float(w.sum())
        self.lam, self.mu = lin.lame(nu)
        self.nu, self.chunk = nu, chunk
        x, y, z = self.X
        tol = 1e-12
        self.pole = int(np.argmin(np.linalg.norm(self.X - lin.P_POLE[:, None], axis=0)))
        fixed = np.concatenate([3 * np.nonzero(np.abs(x) < tol)[0], 3 * np.nonzero(np.abs(z) < tol)[0] + 2,
                                [3 * self.pole + 1]])
        free = np.ones(self.N, bool)
        free[fixed] = False
        self.free = np.nonzero(free)[0]
        pos = -np.ones(self.N, int)
        pos[self.free] = np.arange(self.free.size)
        self.pos = pos
        on_sphere = np.abs(np.linalg.norm(self.X, axis=0) - R_B) < 1e-9 * R_B
        cand = np.nonzero(on_sphere & (y < 0))[0]
        self.cand = cand[cand != self.pole]
        self.area = self._areas(on_sphere)
        # the pattern of K restricted to the free DOFs, and each element entry's place in it
        vd = (3 * self.ed.T[:, :, None] + np.arange(3)).reshape(-1, 81)     # (nel, 81)
        self.vd = vd
        r = np.repeat(vd, 81, axis=1).ravel()
        c = np.tile(vd, (1, 81)).ravel()
        pr, pc = pos[r], pos[c]
        keep = (pr >= 0) & (pc >= 0)
        nf = self.free.size
        key = np.where(keep, pr.astype(np.int64) * nf + pc, -1)
        uniq, inv = np.unique(key[keep], return_inverse=True)
        self.slot = np.full(key.size, uniq.size, dtype=np.int64)
        self.slot[keep] = inv
        rows = uniq // nf
        self.indices = (uniq % nf).astype(np.int32)
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(rows, minlength=nf))]).astype(np.int32)
        self.nnz = uniq.size
        fb = np.zeros(self.N)
        fb[1::3] = -self.w / self.volume       # 1 N downward on the quarter, uniform per volume
        self.fb = fb

    def _areas(self, on_sphere):
        """A_i = integral of the surface trace of N_i (the nodes' tributary areas, for the penalty)."""
        cand = self.cand
        surf = lin.Surface(_Shim(self), cand)
        return surf.area

    def mean_uy(self, u):
        return float(self.w @ u[1::3]) / self.volume

    def internal(self, u, tangent=True):
        """Internal force (N) and, if asked, the tangent restricted to the free DOFs (CSR)."""
        f = np.zeros(self.N)
        data = np.zeros(self.nnz + 1) if tangent else None
        ue = u.reshape(-1, 3)[self.ed.T]                                    # (nel, 27, 3)
        mu, lam = self.mu, self.lam
        nel = ue.shape[0]
        I3 = np.eye(3)
        for c0 in range(0, nel, self.chunk):
            sl = slice(c0, min(nel, c0 + self.chunk))
            G, dx = self.G[sl], self.dx[sl]
            F = I3 + np.einsum('eai,eqaJ->eqiJ', ue[sl], G)
            J = np.linalg.det(F)
            if np.any(J <= 0):
                raise FloatingPointError('J <= 0')
            Fi = np.linalg.inv(F)                                            # Fi[J, i]
            lnJ = np.log(J)
            FiT = Fi.swapaxes(-1, -2)
            P = mu * F + ((lam * lnJ - mu)[..., None, None]) * FiT
            fe = np.einsum('eqiJ,eqaJ,eq->eai', P, G, dx, optimize=True)
            np.add.at(f, self.vd[sl].ravel(), fe.reshape(-1))
            if not tangent:
                continue
            # A[iJkL] = mu d_ik d_JL + lam Fi_Lk Fi_Ji - (lam lnJ - mu) Fi_Jk Fi_Li
            A = (mu * np.einsum('ik,JL->iJkL', I3, I3)[None, None]
                 + lam * np.einsum('eqLk,eqJi->eqiJkL', Fi, Fi)
                 - (lam * lnJ - mu)[..., None, None, None, None] * np.einsum('eqJk,eqLi->eqiJkL', Fi, Fi))
            ne = A.shape[0]
            A2 = A.transpose(0, 1, 3, 2, 4, 5).reshape(ne, 27, 3, 27)       # [e, q, J, (i,k,L)]
            T = np.matmul(G, A2)                                             # [e, q, a, (i,k,L)]
            T = T.reshape(ne, 27, 27, 3, 3, 3).transpose(0, 2, 3, 4, 1, 5).reshape(ne, 243, 81)
            Gd = (G * dx[:, :, None, None]).transpose(0, 1, 3, 2).reshape(ne, 81, 27)   # [(q,L), b]
            Ke = np.matmul(T, Gd).reshape(ne, 27, 3, 3, 27).transpose(0, 1, 2, 4, 3)    # [a,i,b,k]
            data += np.bincount(self.slot[c0 * 6561:(c0 + ne) * 6561], weights=Ke.ravel(),
                                minlength=self.nnz + 1)
        if not tangent:
            return f, None
        nf = self.free.size
        K = sp.csr_matrix((data[:-1], self.indices, self.indptr), shape=(nf, nf))
        return f, K


class _Shim:
    """What lin.Surface reads of a ball."""

    def __init__(self, b):
        self.ed, self.X, self.nn = b.ed, b.X, b.nn
        self.on_sphere = np.abs(np.linalg.norm(b.X, axis=0) - R_B) < 1e-9 * R_B


def contact(ball, u, rc, stiff, force=None):
    """Penalty contact on the candidates at the deformed positions: force (N), tangent (free
    DOFs, CSR), and per candidate the gap, the reaction and the normal."""
    c = ball.cand
    xd = ball.X[:, c] + u.reshape(-1, 3)[c].T
    if np.isinf(rc):
        g = xd[1] + R_B
        n = np.zeros((3, c.size))
        n[1] = 1.0
        curv = np.zeros(c.size)
    else:
        dy, dz = xd[1] + R_B + rc, xd[2]
        r = np.hypot(dy, dz)
        g = r - rc
        n = np.array([np.zeros(c.size), dy / r, dz / r])
        curv = 1.0 / r
    act = g < 0 if force is None else force
    lam = np.where(act, -stiff * g, 0.0)                 # reaction along n (>= 0 if g < 0)
    f = np.zeros(ball.N)
    for i in range(3):
        f[3 * c + i] = lam * n[i]
    # tangent of -f (the contact force is subtracted from the residual): stiff n n^T
    # - lam curv (I - n n^T) on the y, z block (the normal turns with the node on a cylinder)
    rows, cols, vals = [], [], []
    ia = np.nonzero(act)[0]
    for i in range(1, 3):
        for k in range(1, 3):
            v = stiff[ia] * n[i, ia] * n[k, ia] - lam[ia] * curv[ia] * ((i == k) - n[i, ia] * n[k, ia])
            rows.append(ball.pos[3 * c[ia] + i])
            cols.append(ball.pos[3 * c[ia] + k])
            vals.append(v)
    rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
    ok = (rows >= 0) & (cols >= 0)
    nf = ball.free.size
    Kc = sp.csr_matrix((vals[ok], (rows[ok], cols[ok])), shape=(nf, nf))
    return f, Kc, dict(gap=g, lam=lam, normal=n, xd=xd, active=act)


class Linear:
    """Solves with the current tangent: GMRES preconditioned by a (possibly older) LU."""

    def __init__(self):
        self.lu, self.of, self.factors, self.gmres_its, self.active = None, None, 0, 0, None
        self.time_factor = 0.0

    def factor(self, M):
        t0 = time.time()
        self.lu = spl.splu(M.tocsc(), permc_spec='MMD_AT_PLUS_A')
        self.of = M
        self.factors += 1
        self.time_factor += time.time() - t0

    def solve(self, M, B, active):
        """M^-1 b for each b of B: by the LU if it is M's, else, when the LU's contact set is
        the same, by GMRES (a fresh LU if that fails or the set differs)."""
        if self.lu is None or not np.array_equal(active, self.active):
            self.factor(M)
            self.active = active.copy()
        if self.of is not M:
            out = [self._gmres(M, b) for b in B]
            if all(x is not None for x in out):
                return out
            self.factor(M)
        return [self.lu.solve(b) for b in B]

    def _gmres(self, M, b):
        if not np.any(b):
            return np.zeros_like(b)
        pre = spl.LinearOperator(M.shape, matvec=self.lu.solve)
        its = [0]

        def count(_):
            its[0] += 1
        x, info = spl.gmres(M, b, M=pre, rtol=1e-10, atol=0.0, restart=GMRES_MAX, maxiter=1,
                            callback=count, callback_type='pr_norm')
        self.gmres_its += its[0]
        return x if info == 0 else None


def solve_step(ball, rc, stiff, u, Fq, u0, linear, force, max_it=60):
    """Newton on (u, Fq) at the prescribed mean displacement -u0; returns u, Fq, contact state,
    iterations and active-set updates. A primal-dual active set with Newton inside: the
    contact's set is held fixed (``force``: the predicted one) while Newton converges (a smooth
    problem), then the nodes on the wrong side (held with a tensile reaction, g > 0, or
    penetrating outside the set) are moved and Newton resumes, until none is left; if a set
    comes back, one node at a time (Murty's least-index rule), as fe_ball_contact.signorini.
    """
    fr = ball.free
    held, seen, murty = force.copy(), set(), False
    wv = np.zeros(ball.N)
    wv[1::3] = ball.w / ball.volume
    wf = wv[fr]
    for it in range(1, max_it + 1):
        t0 = time.time()
        fi, K = ball.internal(u)
        t1 = time.time()
        fc, Kc, st = contact(ball, u, rc, stiff, held)
        R = (fi - Fq * ball.fb - fc)[fr]
        cm = ball.mean_uy(u) + u0
        res = np.linalg.norm(R, np.inf) / max(abs(Fq), 1e-300)
        if it > 1 and res < NEWTON_TOL and abs(cm) < 1e-10 * u0:
            g = st['gap']
            wrong = (held & (g > 0)) | (~held & (g < -1e-9 * u0))
            if not wrong.any():
                return u, Fq, st, it - 1, len(seen)
            if np.packbits(held ^ wrong).tobytes() in seen:
                murty = True
            if murty:   # a set came back: move the first wrong node only (Murty's rule)
                wrong[np.nonzero(wrong)[0][1:]] = False
            held = held ^ wrong
            seen.add(np.packbits(held).tobytes())
            continue
        M = K + Kc
        x1, x2 = linear.solve(M, [-R, ball.fb[fr]], st['active'])
        if VERBOSE:
            log('    it %d res %.2e cm %.1e active %d min gap/u %.2e %s[asm %.1f s, solve %.1f s, %d LU, %d GMRES]'
                % (it, res, cm / u0, st['active'].sum(), st['gap'].min() / u0, '',
                   t1 - t0, time.time() - t1, linear.factors, linear.gmres_its))
        dF = (-cm - wf @ x1) / (wf @ x2)
        du = np.zeros(ball.N)
        du[fr] = x1 + dF * x2
        t = 1.0
        while True:   # the longest step of 1, 1/2, ... that keeps J > 0 everywhere
            try:
                ball.internal(u + t * du, tangent=False)
                break
            except FloatingPointError:
                t *= 0.5
                assert t > 1e-3, 'no admissible step'
        u, Fq = u + t * du, Fq + t * dF
        if VERBOSE and t < 1:
            log('      step cut to %g (J > 0)' % t)
    raise RuntimeError('Newton did not converge in %d iterations (residual %.2e)' % (max_it, res))


def footprint(ball, u, Fq, st, rc):
    """Footprint measures at the converged state (full-ball values)."""
    c = ball.cand
    fi, _ = ball.internal(u, tangent=False)
    pole_r = (fi - Fq * ball.fb)[3 * ball.pole + 1]       # the pole's reaction along +y
    lam = np.concatenate([[pole_r], st['lam']])
    act = lam > 0
    xd = np.concatenate([lin.P_POLE[:, None], st['xd']], axis=1)
    X0 = np.concatenate([lin.P_POLE[:, None], ball.X[:, c]], axis=1)
    tot = lam.sum()
    out = {}
    for tag, P in (('', xd), ('_undeformed', X0)):
        x, s = P[0], lin.arc(P[2], rc)
        mx2, ms2 = (lam * x ** 2).sum() / tot, (lam * s ** 2).sum() / tot
        out['a_eq%s_mm' % tag] = np.sqrt(5 * mx2) * 1e3
        out['b_eq%s_mm' % tag] = np.sqrt(5 * ms2) * 1e3
        if not tag:
            out['x4_over_x2sq'] = (lam * x ** 4).sum() / tot / mx2 ** 2
            out['s4_over_s2sq'] = (lam * s ** 4).sum() / tot / ms2 ** 2
            out['x_max_mm'] = x[act].max() * 1e3
            out['s_max_mm'] = s[act].max() * 1e3
    # the contact must stay inside the candidates with a ring of inactive ones around it
    F = 4 * Fq
    tot_y = pole_r + (st['lam'] * st['normal'][1]).sum()
    out.update(F_N=F, F_contact_check=tot_y / Fq - 1, pole_reaction_N=4 * pole_r,
               n_contact_nodes_quarter=int(act.sum()),
               min_reaction_over_max=float(lam.min() / lam.max()),
               max_penetration_over_u=float(max(0.0, -st['gap'].min())))
    return out


def run_case(lev, nu, name, steps=STEPS, dump=None):
    T0 = time.time()
    rc = lin.COUNTERFACES[name]
    ball = FiniteBall(lev, nu)
    t_setup = time.time() - T0
    log('%s nu=%.2f %s: %d el, %d dof, setup %.1f s' % (lev, nu, name, ball.ed.shape[1], ball.N, t_setup))
    stiff = PENALTY * E_MOD * ball.area[ball.cand] / R_B
    linear = Linear()
    u = np.zeros(ball.N)
    Fq = 0.0
    hist = []
    rows = []
    for ur in steps:
        u0 = ur * R_B
        # start from the last converged state (the first Newton step is then the tangent
        # predictor at its active set); from the linear problem's guess at the first step
        ug, Fg = (hist[-1][0], hist[-1][1]) if hist else (np.zeros(ball.N), 0.0)
        t0 = time.time()
        # the first iteration's active set: the nodes within half the increment of the surface
        du0 = u0 - (hist[-1][2] if hist else 0.0)
        first = contact(ball, ug, rc, stiff)[2]['gap'] < 0.5 * du0
        u, Fq, st, its, sets = solve_step(ball, rc, stiff, ug, Fg, u0, linear, first)
        hist.append((u.copy(), Fq, u0))
        r = dict(u_over_R=ur, u_mm=u0 * 1e3, newton_iterations=its, active_set_updates=sets)
        r.update(footprint(ball, u, Fq, st, rc))
        r['max_penetration_over_u'] /= u0
        h = lin.hertz(u0, rc, nu)
        r['hertz'] = dict(a_mm=h['a'] * 1e3, b_mm=h['b'] * 1e3, F_N=h['F'])
        r['ratio_to_hertz'] = dict(a_eq=r['a_eq_mm'] / r['hertz']['a_mm'], b_eq=r['b_eq_mm'] / r['hertz']['b_mm'],
                                   F=r['F_N'] / h['F'],
                                   b_over_a=(r['b_eq_mm'] / r['a_eq_mm']) / (h['b'] / h['a']))
        rows.append(r)
        if dump:
            lin.jdump(dict(partial=True, level=lev, nu=nu, counterface=name, rows=rows), dump)
        log('  u/R=%.3f F=%9.3f N a_eq=%6.3f (H %6.3f) b_eq=%6.3f (H %6.3f) mm n=%4d its %d pen %.1e'
            '  [%.0f s, %d LU, %d GMRES]' % (
                ur, r['F_N'], r['a_eq_mm'], r['hertz']['a_mm'], r['b_eq_mm'], r['hertz']['b_mm'],
                r['n_contact_nodes_quarter'], its, r['max_penetration_over_u'], time.time() - t0,
                linear.factors, linear.gmres_its))
    m = ball.info
    return dict(level=lev, nu=nu, counterface=name, model='finite-strain neo-Hookean',
                penalty=PENALTY, mesh=dict(n=m['n'], rho0_mm=m['rho0_mm'], elements=m['nel'],
                                           dof=m['ndof'], candidates=int(ball.cand.size)),
                rows=rows, lu_factorisations=linear.factors, gmres_iterations=linear.gmres_its,
                time_factor_s=linear.time_factor, time_s=time.time() - T0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--level', default='Q3', choices=list(LEVELS))
    ap.add_argument('--nu', type=float, default=0.3)
    ap.add_argument('--counterface', default='cyl_2.625in', choices=list(lin.COUNTERFACES))
    ap.add_argument('--smoke', action='store_true')
    ap.add_argument('--out', default=None)
    ap.add_argument('--record', nargs='*', default=None)
    ap.add_argument('--to', default='tests/validation/data/fe_ball_contact.json')
    args = ap.parse_args()
    logging.getLogger('skfem').setLevel(logging.ERROR)
    if args.record is not None:
        record(args.record, args.to)
        return
    steps = SMOKE_STEPS if args.smoke else STEPS
    if args.smoke:   # the first two steps of the recorded Q3 run on the 2 5/8 in barrel, nu 0.3
        args.level, args.counterface, args.nu = 'Q3', 'cyl_2.625in', 0.3
    out = args.out or 'fe_finite_%s_%s_%.2f.json' % (args.level, args.counterface, args.nu)
    res = run_case(args.level, args.nu, args.counterface, steps, dump=out)
    lin.jdump(res, out)
    log('total %.1f s' % res['time_s'])


ROW_KEYS = ('u_over_R', 'u_mm', 'F_N', 'a_eq_mm', 'b_eq_mm', 'a_eq_undeformed_mm', 'b_eq_undeformed_mm',
            'x4_over_x2sq', 's4_over_s2sq', 'x_max_mm', 's_max_mm', 'n_contact_nodes_quarter',
            'max_penetration_over_u', 'min_reaction_over_max', 'active_set_updates', 'F_contact_check',
            'newton_iterations',
            'hertz', 'ratio_to_hertz')
FIT_LEVEL, FIT_NU = 'Q3', 'nu=0.30'
CONVERGENCE_CASE = ('nu=0.30', 'cyl_2.625in')


def fit(results, nu_key=FIT_NU):
    """Least-squares f = 1 + c1 sqrt(x) + c2 x (x = u/R_b) of a_eq / a_Hertz, b_eq / b_Hertz and
    the barrel's stiffness factor over Hertz's, (F_cylinder / F_flat) / gamma_Hertz, per
    counterface (the flat's stiffness factor is 1 by definition)."""
    res = results[nu_key]
    flat = {r['u_over_R']: r for r in res['flat']}
    out = dict(form='f = 1 + c1 sqrt(x) + c2 x, x = u / R_b; least squares over the recorded x',
               counterfaces=[], rho=[], a=[], b=[], stiffness=[], max_abs_residual={})
    worst = dict(a=0.0, b=0.0, stiffness=0.0)
    for name in ('flat', 'cyl_2.625in', 'cyl_2.25in'):
        rows = res[name]
        rc = lin.COUNTERFACES[name]
        x = np.array([r['u_over_R'] for r in rows])
        A = np.stack([np.sqrt(x), x], axis=1)
        g_h = 1.0 if np.isinf(rc) else float(lin.hertz(1.0, rc, 0.3)['F'] / lin.hertz(1.0, np.inf, 0.3)['F'])
        ys = dict(a=[r['a_eq_mm'] / r['hertz']['a_mm'] for r in rows],
                  b=[r['b_eq_mm'] / r['hertz']['b_mm'] for r in rows],
                  stiffness=[r['F_N'] / flat[r['u_over_R']]['F_N'] / g_h for r in rows])
        out['counterfaces'].append(name)
        out['rho'].append(0.0 if np.isinf(rc) else R_B / rc)
        for k, y in ys.items():
            y = np.array(y) - 1.0
            c = np.zeros(2) if (k == 'stiffness' and np.isinf(rc)) else np.linalg.lstsq(A, y, rcond=None)[0]
            out[k].append([float(c[0]), float(c[1])])
            worst[k] = max(worst[k], float(np.abs(A @ c - y).max()))
    out['max_abs_residual'] = worst
    return out


def record(files, to):
    """Add the finite-strain runs (``--out`` files of run_case) to the compact reference under
    "finite_strain": results per level, nu and counterface, the mesh convergence (quick
    against Q3 on CONVERGENCE_CASE) and the fit of FIT_LEVEL at FIT_NU."""
    import scipy
    import skfem
    runs = []
    for f in files:
        r = json.load(open(f))
        if r.get('partial'):   # a run cut short: its steps so far, named as main() names them
            level, rest = os.path.basename(f)[:-5].split('_', 1)
            name, nu = rest.rsplit('_', 1)
            r.update(level=level, counterface=name, nu=float(nu), mesh=dict(partial=True), time_s=None,
                     lu_factorisations=None, gmres_iterations=None)
        runs.append(r)
    results, meshes, times = {}, {}, {}
    for r in runs:
        nu = 'nu=%.2f' % r['nu']
        results.setdefault(r['level'], {}).setdefault(nu, {})[r['counterface']] = [
            lin._sig({k: row[k] for k in ROW_KEYS}) for row in r['rows']]
        meshes[r['level']] = r['mesh']
        times['%s %s %s' % (r['level'], nu, r['counterface'])] = dict(
            time_s=r['time_s'] and round(r['time_s'], 1), partial=bool(r.get('partial')),
            lu_factorisations=r['lu_factorisations'],
            gmres_iterations=r['gmres_iterations'])
    nu, name = CONVERGENCE_CASE
    conv = {}
    if 'quick' in results and name in results['quick'].get(nu, {}):
        fine = {r['u_over_R']: r for r in results['quick'][nu][name]}
        coarse = [r for r in results[FIT_LEVEL][nu][name] if r['u_over_R'] in fine]
        conv = dict(case='%s %s' % (nu, name), note='Q3 / quick - 1 at each compression both reached',
                    u_over_R=[r['u_over_R'] for r in coarse],
                    **{q: [r[q] / fine[r['u_over_R']][q] - 1 for r in coarse]
                       for q in ('F_N', 'a_eq_mm', 'b_eq_mm')})
    data = json.load(open(to))
    data['meta'].setdefault('model', 'linear elasticity, small strain, gap at the undeformed positions '
                                     '(scripts/fe_ball_contact.py); the finite-strain model is under '
                                     '"finite_strain"')
    data['finite_strain'] = dict(
        meta=dict(
            source='scripts/fe_ball_contact_finite.py with scikit-fem %s, SciPy %s (SuperLU)' % (
                skfem.__version__, scipy.__version__),
            date=time.strftime('%Y-%m-%d'),
            model=('finite strain: total Lagrangian, compressible neo-Hookean W = mu/2 (I1 - 3 - 2 ln J) + '
                   'lam/2 (ln J)^2 with the Lame constants of E = 10 MPa and the small-strain nu; dead '
                   'uniform body force; compression = centre-of-mass approach, prescribed and stepped'),
            contact=('frictionless node-to-rigid-surface on the lower hemisphere\'s surface nodes, gap and '
                     'normal at the deformed positions, penalty %.0e x E x tributary area / R_b, active set '
                     'updated every Newton iteration' % PENALTY),
            footprint=('a_eq = sqrt(5 <x^2>), b_eq = sqrt(5 <s^2>) weighted by the nodal reactions at the '
                       'deformed positions (x along the axis, s arc length around it); *_undeformed_mm: the '
                       'same at the undeformed positions (the linear model\'s measure)'),
            meshes={lev: dict(m, **lin.LEVELS[lev]) for lev, m in meshes.items()},
            steps=list(STEPS), newton_tolerance=NEWTON_TOL, runs=times),
        results=results, mesh_convergence=lin._sig(conv),
        fit=dict(level=FIT_LEVEL, nu=FIT_NU, **lin._sig(fit(results[FIT_LEVEL]), 6)))
    lin.jdump(data, to)
    log('wrote %s' % to)


if __name__ == '__main__':
    main()
