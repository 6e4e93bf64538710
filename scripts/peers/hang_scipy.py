#!/usr/bin/env python3
"""hang_scipy.py: the `hang` cloth (problems/hang.ini) in numpy/scipy, as an
independent peer of clothode for `clothode-bench` and tests/test_peer.c.

The model (docs/model.md 1, 2, 3.1, 3.2), written from the formulas, not from
the C code:

  grid     n x n particles, particle (i, j) at (i h, 0, j h), h = size/(n-1),
           index p = i n + j; mass = total mass / n^2 per particle; pinned
           particles ([pins] at = "i,j ...", negative counts from the end)
           stay at rest and are not part of the state.
  pairs    Type1 (sequential): offsets (0,1) (1,-1) (1,0) (1,1);
           Type2 (interlaced): offsets (0,2) (2,-2) (2,0) (2,2);
           rest length L = |X_b - X_a| on the rest grid.
  pair     (docs/model.md 3.1) x_ab = x_b - x_a, d = |x_ab|, u = x_ab / d,
           f_a = s(d) u, f_b = -f_a,
           df_a/dx_b = K = s'(d) u u^T + (s/d)(I - u u^T), df_a/dx_a = -K
           (jacobian.transverse = clamp drops (s/d)(I - u u^T) where s < 0).
  Type1    s = ks (d - L) for d >= L, 0 below (tension only).
  Type2    d >= L: s = ks (d - L) (tension = spring) or 0 (none);
           d < L:  s = max(f_b, cb (d - L)),
           f_b = kb kappa^2 / (cos(kappa L/2) - sinc(kappa L/2)),
           kappa = (2/L) asinc(d/L), asinc the inverse of sin(t)/t on
           [0, pi].  With t = kappa L/2 and e = (L - d)/L, t solves
           g(t) = 1 - sin(t)/t = e (vectorised Newton below), and
           f_b = (4 kb/L^2) t^2 / D(t), D = cos t - sinc t = g(t) - 2 sin^2(t/2).
           f_b <= -12 kb/L^2, so where cb (d - L) >= -12 kb/L^2 the linear
           branch wins without solving for t.
           s'(d) on the f_b branch: (4 kb/L^2) (2 t D - t^2 D')/D^2 dt/dd,
           D' = g'(t) - sin t, dt/dd = -1/(L g'(t)).
  damping  f_a = -kd (v_a - v_b) on every Type1 and Type2 pair (Jiao, eq. 14).
  gravity  f_p = m_p g.

ODE: y = (x, v) of the free particles, x' = v, v' = M^-1 f(x, v), with the
analytic sparse Jacobian [[0, I], [M^-1 df/dx, M^-1 df/dv]] (scipy.sparse CSC,
pattern built once), integrated by solve_ivp's BDF method with its stock
settings.  scipy's BDF factorises I - c J with splu's defaults (COLAMD,
partial pivoting); on this matrix the pivoting fills the factors heavily
(measured: 0.1 s per LU at n = 16, 2.2 s at n = 32), which is most of the
peer's time.

usage:
  hang_scipy.py [PROBLEM.ini] [--set SEC.KEY=VAL]... --out FINAL.csv
                [--max-cpu S]
      integrate to [run] t_end with [run] rtol, atol; write the final state
      (p,x,y,z,vx,vy,vz, all particles) and print name,value statistics on
      stdout: cpu (process CPU seconds of the integration alone), wall, t
      (time reached), steps, nfev, njev, nlu, status (finished, or budget
      when stopped after S CPU seconds).
  hang_scipy.py [PROBLEM.ini] [--set ...] --forces STATE.csv [--out F.csv]
      forces on every particle at a state (clothode's forces.csv format,
      p,fx,fy,fz) into F.csv or stdout.
"""

import argparse
import configparser
import os
import sys
import time

import numpy as np
import scipy.sparse as sp
from scipy.integrate import BDF

TYPE1_OFFSETS = ((0, 1), (1, -1), (1, 0), (1, 1))
TYPE2_OFFSETS = ((0, 2), (2, -2), (2, 0), (2, 2))

# Keys of hang.ini this peer implements; anything else is refused so that a
# changed problem file cannot silently give a different model.
KNOWN = {
    "cloth": {"n", "size", "mass"},
    "pins": {"at"},
    "type1": {"ks"},
    "type2": {"kb", "cb", "tension", "asinc"},
    "damping": {"kd"},
    "gravity": {"g"},
    "jacobian": {"transverse"},
    "run": {"integrator", "t_end", "rtol", "atol"},
}


def fail(msg):
    sys.exit("hang_scipy: " + msg)


# ---- problem file -------------------------------------------------------


def read_problem(path, sets):
    """configparser view of the INI file with SEC.KEY=VAL overrides."""
    cfg = configparser.ConfigParser(inline_comment_prefixes=(";", "#"))
    if not cfg.read(path):
        fail(f"cannot read {path}")
    for s in sets:
        key, eq, val = s.partition("=")
        sec, dot, name = key.strip().partition(".")
        if not eq or not dot or not name:
            fail(f"--set {s}: expected SECTION.KEY=VALUE")
        if not cfg.has_section(sec):
            cfg.add_section(sec)
        cfg.set(sec, name, val.strip())
    for sec in cfg.sections():
        for key in cfg[sec]:
            if key not in KNOWN.get(sec, ()):
                fail(f"[{sec}] {key}: not supported by this peer")
    if cfg.get("type2", "asinc", fallback="exact") != "exact":
        fail("only type2.asinc = exact is implemented")
    return cfg


def vector(text):
    return np.array([float(c) for c in text.split(",")])


class Hang:
    """The model: rest grid, pairs, parameters, free-particle numbering."""

    def __init__(self, cfg):
        n = cfg.getint("cloth", "n", fallback=16)
        size = cfg.getfloat("cloth", "size", fallback=1.0)
        if n < 3:
            fail(f"cloth.n = {n}: need n >= 3")
        self.n, self.np = n, n * n
        h = size / (n - 1)
        i, j = np.divmod(np.arange(self.np), n)
        self.X0 = np.stack([i * h, np.zeros(self.np), j * h], axis=1)
        self.m = cfg.getfloat("cloth", "mass", fallback=0.1) / self.np
        self.ks = cfg.getfloat("type1", "ks", fallback=200.0)
        self.kb = cfg.getfloat("type2", "kb", fallback=5e-6)
        self.cb = cfg.getfloat("type2", "cb", fallback=self.ks)
        tension = cfg.get("type2", "tension", fallback="spring")
        if tension not in ("spring", "none"):
            fail(f"type2.tension = {tension}: expected spring or none")
        self.ks2 = self.ks if tension == "spring" else 0.0
        self.kd = cfg.getfloat("damping", "kd", fallback=0.0)
        self.g = vector(cfg.get("gravity", "g", fallback="0,-9.81,0"))
        self.clamp = cfg.get("jacobian", "transverse", fallback="full") == "clamp"
        self.pairs(n)
        self.pins(cfg.get("pins", "at", fallback="0,0 0,-1"), n)

    def pairs(self, n):
        """a, b, L and the Type2 flag of every pair (each unordered pair once)."""
        a, b, t2 = [], [], []
        for offsets, is2 in ((TYPE1_OFFSETS, False), (TYPE2_OFFSETS, True)):
            for di, dj in offsets:
                i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
                i2, j2 = i + di, j + dj
                ok = (i2 >= 0) & (i2 < n) & (j2 >= 0) & (j2 < n)
                a.append((i * n + j)[ok])
                b.append((i2 * n + j2)[ok])
                t2.append(np.full(ok.sum(), is2))
        self.a, self.b = np.concatenate(a), np.concatenate(b)
        self.type2 = np.concatenate(t2)
        dx = self.X0[self.b] - self.X0[self.a]
        self.L = np.sqrt(dx[:, 0] * dx[:, 0] + dx[:, 1] * dx[:, 1]
                         + dx[:, 2] * dx[:, 2])

    def pins(self, at, n):
        """dof[p] = free index of particle p, or -1 if pinned."""
        pinned = np.zeros(self.np, dtype=bool)
        for tok in at.split():
            i, j = (int(c) for c in tok.split(","))
            i, j = i + n if i < 0 else i, j + n if j < 0 else j
            if not (0 <= i < n and 0 <= j < n):
                fail(f"pin {tok} lies outside the {n} x {n} grid")
            pinned[i * n + j] = True
        self.free = np.flatnonzero(~pinned)
        self.dof = np.full(self.np, -1)
        self.dof[self.free] = np.arange(self.free.size)


# ---- inverse sinc and the pair law --------------------------------------

# 1 - sin(t)/t = sum_{k>=1} (-1)^(k+1) t^(2k)/(2k+1)!  (|t| < 1: no cancellation)
_G_COEF = np.array([(-1.0) ** (k + 1) / np.prod(np.arange(1.0, 2 * k + 2))
                    for k in range(1, 11)])


def one_minus_sinc(t):
    """g(t) = 1 - sin(t)/t, by its series for |t| < 1."""
    t2 = t * t
    series = np.zeros_like(t)
    for c in _G_COEF[::-1]:
        series = (series + c) * t2
    direct = 1.0 - np.sin(t) / np.where(t == 0, 1.0, t)
    return np.where(np.abs(t) < 1.0, series, direct)


def one_minus_sinc_deriv(t):
    """g'(t) = (sin t - t cos t)/t^2, by the series for |t| < 1."""
    t2 = t * t
    series = np.zeros_like(t)
    for k in range(len(_G_COEF), 0, -1):
        series = series * t2 + 2 * k * _G_COEF[k - 1]
    series = series * t
    safe = np.where(t == 0, 1.0, t)
    direct = (np.sin(t) - t * np.cos(t)) / (safe * safe)
    return np.where(np.abs(t) < 1.0, series, direct)


def asinc_1m(e):
    """t in [0, pi] with 1 - sinc(t) = e (e in (0, 1]): Newton on g(t) - e
    from the reverted series t ~ sqrt(6e)(1 + 3e/20 + 321 e^2/5600)."""
    t = np.minimum(np.sqrt(6.0 * e) * (1.0 + e * (0.15 + e * 321.0 / 5600.0)),
                   np.pi)
    for _ in range(60):
        step = (one_minus_sinc(t) - e) / one_minus_sinc_deriv(t)
        t_new = np.clip(t - step, 0.5 * t, np.pi)
        done = np.all(np.abs(t_new - t) <= 4e-16 * t)
        t = t_new
        if done:
            break
    return t


def pair_law(model, d):
    """s(d) and s'(d) of every pair (docs/model.md 3.2)."""
    L, stretch = model.L, d - model.L
    s = np.where(stretch >= 0, model.ks * stretch, 0.0)
    ds = np.where(stretch >= 0, model.ks, 0.0)
    t2 = model.type2
    s[t2] = np.where(stretch[t2] >= 0, model.ks2 * stretch[t2], 0.0)
    ds[t2] = np.where(stretch[t2] >= 0, model.ks2, 0.0)
    # Compressed Type2: s = max(f_b, cb (d - L)); f_b <= -12 kb/L^2.
    comp = t2 & (stretch < 0)
    lin = model.cb * stretch
    s[comp], ds[comp] = lin[comp], model.cb
    buck = comp & (lin < -12.0 * model.kb / (L * L))
    if buck.any():
        Lb = L[buck]
        t = asinc_1m((Lb - d[buck]) / Lb)
        g, dg = one_minus_sinc(t), one_minus_sinc_deriv(t)
        h = np.sin(0.5 * t)
        D = g - 2.0 * h * h                      # cos t - sinc t
        dD = dg - np.sin(t)
        c = 4.0 * model.kb / (Lb * Lb)
        fb = c * t * t / D
        dfb = c * (2.0 * t * D - t * t * dD) / (D * D) * (-1.0 / (Lb * dg))
        use = fb > lin[buck]
        idx = np.flatnonzero(buck)[use]
        s[idx], ds[idx] = fb[use], dfb[use]
    return s, ds


# ---- forces and Jacobian on all particles -------------------------------


def geometry(model, X):
    xab = X[model.b] - X[model.a]
    d = np.sqrt(xab[:, 0] * xab[:, 0] + xab[:, 1] * xab[:, 1]
                + xab[:, 2] * xab[:, 2])
    return d, xab / d[:, None]


def forces(model, X, V):
    """Total force on every particle (np x 3): pairs, damping, gravity."""
    d, u = geometry(model, X)
    s, _ = pair_law(model, d)
    fa = s[:, None] * u - model.kd * (V[model.a] - V[model.b])
    F = np.empty_like(X)
    for k in range(3):
        F[:, k] = (np.bincount(model.a, fa[:, k], model.np)
                   - np.bincount(model.b, fa[:, k], model.np))
    return F + model.m * model.g


class FirstOrderJacobian:
    """CSC pattern of [[0, I], [M^-1 df/dx, M^-1 df/dv]] over the free
    particles, built once; values summed into it with one bincount."""

    def __init__(self, model):
        self.model = model
        nf = model.free.size
        self.n3 = n3 = 3 * nf
        da, db = model.dof[model.a], model.dof[model.b]
        # Blocks (row particle, column particle, sign): aa -K, ab +K, ba +K, bb -K.
        self.blocks = ((da, da, -1.0), (da, db, 1.0), (db, da, 1.0), (db, db, -1.0))
        rows, cols, self.keep = [], [], []
        ii, jj = np.divmod(np.arange(9), 3)
        for r, c, _ in self.blocks:
            ok = (r >= 0) & (c >= 0)
            self.keep.append(ok)
            rr = n3 + 3 * r[ok][:, None] + ii
            cc = 3 * c[ok][:, None] + jj
            rows += [rr.ravel(), rr[:, [0, 4, 8]].ravel()]       # df/dx, df/dv
            cols += [cc.ravel(), (cc[:, [0, 4, 8]] + n3).ravel()]
        rows.append(np.arange(n3))                               # dx'/dv = I
        cols.append(np.arange(n3) + n3)
        rows, cols = np.concatenate(rows), np.concatenate(cols)
        key = cols.astype(np.int64) * (2 * n3) + rows
        uniq, self.slot = np.unique(key, return_inverse=True)
        self.indices = (uniq % (2 * n3)).astype(np.int32)
        self.indptr = np.searchsorted(uniq // (2 * n3),
                                      np.arange(2 * n3 + 1)).astype(np.int32)
        self.ident = np.full(n3, 1.0)

    def __call__(self, X):
        model = self.model
        d, u = geometry(model, X)
        s, ds = pair_law(model, d)
        uu = u[:, :, None] * u[:, None, :]
        sd = s / d
        if model.clamp:
            sd = np.where(s < 0, 0.0, sd)
        K = ds[:, None, None] * uu + sd[:, None, None] * (np.eye(3) - uu)
        K = K.reshape(-1, 9) / model.m
        kd = np.full((K.shape[0], 3), model.kd / model.m)
        vals = []
        for (_, _, sign), ok in zip(self.blocks, self.keep):
            vals += [(sign * K[ok]).ravel(), (sign * kd[ok]).ravel()]
        vals.append(self.ident)
        data = np.bincount(self.slot, np.concatenate(vals), self.indptr[-1])
        return sp.csc_matrix((data, self.indices, self.indptr),
                             shape=(2 * self.n3, 2 * self.n3))


# ---- the two modes ------------------------------------------------------


def read_state(path, model):
    rows = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if rows.shape != (model.np, 7):
        fail(f"{path}: expected {model.np} rows of p,x,y,z,vx,vy,vz")
    order = np.argsort(rows[:, 0])
    return rows[order, 1:4].copy(), rows[order, 4:7].copy()


def write_csv(path, header, index, cols):
    lines = [header] + [",".join([str(p)] + [f"{c:.17g}" for c in row])
                        for p, row in zip(index, cols)]
    text = "\n".join(lines) + "\n"
    if path is None:
        sys.stdout.write(text)
        return
    tmp = f"{path}.tmp.{os.getpid()}"
    with open(tmp, "w") as fp:
        fp.write(text)
    os.replace(tmp, path)


def integrate(model, cfg, out, max_cpu):
    """solve_ivp(method="BDF") to [run] t_end, stepped here by the loop
    solve_ivp runs (scipy.integrate.BDF.step until it reaches t_end), so
    that a CPU budget can stop it: with max_cpu > 0 the run ends at the
    first step boundary after max_cpu seconds, status "budget", and the
    state there is written (t is printed)."""
    t_end = cfg.getfloat("run", "t_end", fallback=2.0)
    rtol = cfg.getfloat("run", "rtol", fallback=1e-6)
    atol = cfg.getfloat("run", "atol", fallback=1e-8)
    free, n3 = model.free, 3 * model.free.size
    X, V = model.X0.copy(), np.zeros_like(model.X0)

    def rhs(t, y):
        X[free], V[free] = y[:n3].reshape(-1, 3), y[n3:].reshape(-1, 3)
        a = forces(model, X, V)[free] / model.m
        return np.concatenate([y[n3:], a.ravel()])

    jac = FirstOrderJacobian(model)

    def jacobian(t, y):
        X[free] = y[:n3].reshape(-1, 3)
        return jac(X)

    y0 = np.concatenate([model.X0[free].ravel(), np.zeros(n3)])
    c0, w0 = time.process_time(), time.perf_counter()
    solver = BDF(rhs, 0.0, y0, t_end, rtol=rtol, atol=atol, jac=jacobian)
    steps, status = 0, "finished"
    while solver.status == "running":
        if max_cpu > 0 and time.process_time() - c0 > max_cpu:
            status = "budget"
            break
        message = solver.step()
        steps += 1
        if solver.status == "failed":
            fail(f"BDF failed at t = {solver.t}: {message}")
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    X[free] = solver.y[:n3].reshape(-1, 3)
    V[free] = solver.y[n3:].reshape(-1, 3)
    write_csv(out, "p,x,y,z,vx,vy,vz", range(model.np), np.hstack([X, V]))
    for name, value in (("cpu", cpu), ("wall", wall), ("t", solver.t),
                        ("steps", steps), ("nfev", solver.nfev),
                        ("njev", solver.njev), ("nlu", solver.nlu),
                        ("status", status)):
        print(f"{name},{value}")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "..", "problems", "hang.ini")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("problem", nargs="?", default=default)
    ap.add_argument("--set", action="append", default=[], metavar="SEC.KEY=VAL")
    ap.add_argument("--forces", metavar="STATE.csv")
    ap.add_argument("--out", metavar="FILE")
    ap.add_argument("--max-cpu", type=float, default=0.0, metavar="S")
    args = ap.parse_args()
    cfg = read_problem(args.problem, args.set)
    model = Hang(cfg)
    if args.forces:
        X, V = read_state(args.forces, model)
        write_csv(args.out, "p,fx,fy,fz", range(model.np), forces(model, X, V))
    elif args.out:
        integrate(model, cfg, args.out, args.max_cpu)
    else:
        fail("give --out FINAL.csv (integrate) or --forces STATE.csv")


if __name__ == "__main__":
    main()
