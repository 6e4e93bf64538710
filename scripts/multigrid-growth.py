#!/usr/bin/python3
"""How the CG iterations of semi-bdf2's Newton matrix grow with the cloth's
size, under multigrid preconditioners that clothode does not build:
geometric multigrid on the cloth's grid, with and without overlapping
Schwarz smoothing, beside PETSc's smoothed aggregation and block Jacobi.

For each n the hanging cloth (problems/hang.ini) is run with semi-bdf2 to
t = steps * dt; `clothode eval` exports df/dx and df/dv at that state, and
the matrix A = M - (2 dt/3) df/dv - (4 dt^2/9) df/dx of the next step
(docs/integrators.md, 3.2) is solved, pinned particles removed, by CG from
zero to ||b - A x||_2 <= 1e-10 ||b||_2 with

  bj       point-block (3x3) Jacobi, one level;
  gamg     PETSc's GAMG, block size 3, one Chebyshev step with
           point-block Jacobi on every level (clothode's amg smooths its
           finest level by block Gauss-Seidel instead);
  gmg      geometric multigrid: bilinear interpolation between the grid
           and one with every other row and column (the last kept),
           per coordinate; Galerkin coarse operators; the smoothers of
           gamg; down to 9 x 9 particles, solved by LU;
  gmg-asm  gmg whose finest level is smoothed by one Chebyshev step on
           additive Schwarz over overlapping patches of 8 x 8 particles
           (a 4 x 4 tiling, each tile widened by two particles a side),
           each patch solved exactly.

Two right-hand sides: the forces at the state, and a reproducible random
vector.  With --courant, dt is scaled as n0/n (n0 the first size: the
same Courant number at every size) and each size runs to the same time.

Needs Debian's python3-petsc4py, python3-scipy
(`scripts/install-deps.sh multigrid`).  paper/findings.md, "Algebraic
multigrid", has its output.
"""
import argparse
import configparser
import math
import os
import subprocess
import sys

import numpy as np
import scipy.io
import scipy.sparse as sp

import petsc4py

petsc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402  (after petsc4py.init)

HANG = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                    "problems", "hang.ini")
COARSEST = 9    # particles a side of the grid solved directly
RTOL = 1e-10


def run(cmd):
    try:
        r = subprocess.run(cmd, stdout=subprocess.DEVNULL,
                           stderr=subprocess.PIPE, text=True)
    except OSError as e:
        sys.exit(f"multigrid-growth: cannot run {cmd[0]}: {e.strerror}")
    if r.returncode != 0:
        sys.exit(f"multigrid-growth: {' '.join(cmd)} failed "
                 f"(exit {r.returncode}): {r.stderr.strip()}")


def export(clothode, n, dt, t_end, work):
    """Run to t_end, export the Jacobians there; return df/dx, df/dv, the
    run's configuration and the forces at the state."""
    out = os.path.join(work, f"run{n}")
    run([clothode, "run", HANG, "--integrator", "semi-bdf2", "--linsol",
         "amg", "--dt", repr(dt), "--set", f"cloth.n={n}", "--frames", "0",
         "--samples", "1", "--t-end", repr(t_end), "--out", out])
    K, D = os.path.join(work, f"K{n}.mtx"), os.path.join(work, f"D{n}.mtx")
    run([clothode, "eval", HANG, "--state", os.path.join(out, "final.csv"),
         "--t", repr(t_end), "--set", f"cloth.n={n}", "--jacobian", K,
         "--jacobian-v", D, "--out", os.path.join(work, f"eval{n}")])
    cfg = configparser.ConfigParser(inline_comment_prefixes=(";",))
    cfg.read(os.path.join(out, "config.ini"))
    forces = np.loadtxt(os.path.join(work, f"eval{n}", "forces.csv"),
                        delimiter=",", skiprows=1)[:, 1:4]
    return scipy.io.mmread(K).tocsr(), scipy.io.mmread(D).tocsr(), cfg, forces


def pinned(cfg, n):
    """The free particles (row-major index i n + j) of the grid: pins
    given as `[pins] at` only (hang's form); any other is refused."""
    other = [s for s in cfg.sections() if s.startswith("pins") and
             (s != "pins" or set(cfg[s]) - {"at"})]
    if other or not cfg.has_option("pins", "at"):
        sys.exit("multigrid-growth: hang's pins must be given as "
                 "[pins] at = i,j ... alone")
    free = np.ones(n * n, bool)
    for pin in cfg.get("pins", "at").split():
        i, j = (int(v) % n for v in pin.split(","))
        free[i * n + j] = False
    return free


def coarse_line(x):
    """1-D linear interpolation to the points at x from every other one
    (the last kept); returns it and the kept points' coordinates."""
    nf = len(x)
    keep = list(range(0, nf - 1, 2)) + [nf - 1]
    at = {c: k for k, c in enumerate(keep)}
    rows, cols, vals = [], [], []
    for k in range(nf):
        if k in at:
            near = [(at[k], 1.0)]
        else:   # between two kept points, weighted by distance
            w = (x[k + 1] - x[k]) / (x[k + 1] - x[k - 1])
            near = [(at[k - 1], w), (at[k + 1], 1.0 - w)]
        for c, w in near:
            rows.append(k)
            cols.append(c)
            vals.append(w)
    P = sp.csr_matrix((vals, (rows, cols)), shape=(nf, len(keep)))
    return P, [x[k] for k in keep]


def grids(n, free):
    """Each level's (side, free particles) and the interpolations between
    them, finest first.  Only the finest level has pins: a coarse point's
    interpolation reaches the free fine particles around it."""
    levels, interps = [(n, free)], []
    x = list(range(n))      # a level's points along a side, in fine rows
    while levels[-1][0] > COARSEST:
        nf, ff = levels[-1]
        line, x = coarse_line(x)
        nc = line.shape[1]
        P = sp.kron(sp.kron(line, line), sp.identity(3)).tocsr()
        interps.append(P[np.repeat(ff, 3)].tocsr())
        levels.append((nc, np.ones(nc * nc, bool)))
    return levels, interps


def petsc_mat(S):
    S = S.tocsr()
    S.sort_indices()
    M = PETSc.Mat().createAIJ(size=S.shape, csr=(
        S.indptr.astype(PETSc.IntType), S.indices.astype(PETSc.IntType),
        S.data))
    M.assemble()
    return M


def patches(side, free, tile=4, widen=2):
    """Index sets of the overlapping patches on a grid's free particles."""
    row = -np.ones(side * side, int)
    row[free] = np.arange(free.sum())
    out = []
    for i0 in range(0, side, tile):
        for j0 in range(0, side, tile):
            span = [range(max(0, a - widen), min(side, a + tile + widen))
                    for a in (i0, j0)]
            ps = [row[i * side + j] for i in span[0] for j in span[1]
                  if row[i * side + j] >= 0]
            dofs = np.sort(np.concatenate([[3 * p, 3 * p + 1, 3 * p + 2]
                                           for p in ps]))
            out.append(PETSc.IS().createGeneral(dofs.astype(PETSc.IntType)))
    return out


def solve(A, b, kind, levels, interps):
    opts = PETSc.Options()
    for key in list(opts.getAll()):
        opts.delValue(key)
    smooth = {"mg_levels_ksp_type": "chebyshev", "mg_levels_ksp_max_it": 1,
              "mg_levels_pc_type": "pbjacobi",
              "mg_levels_esteig_ksp_type": "cg"}
    Am = petsc_mat(A)
    Am.setBlockSize(3)
    Am.setOption(PETSc.Mat.Option.SPD, True)
    ksp = PETSc.KSP().create()
    ksp.setType("cg")
    ksp.setOperators(Am)
    ksp.setTolerances(rtol=RTOL, atol=0.0, max_it=20000)
    ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
    pc = ksp.getPC()
    if kind == "bj":
        pc.setType("pbjacobi")
    elif kind == "gamg":
        pc.setType("gamg")
        for key, val in smooth.items():
            opts[key] = val
    else:
        nl = len(interps) + 1
        pc.setType("mg")
        pc.setMGLevels(nl)
        for k, P in enumerate(interps):
            pc.setMGInterpolation(nl - 1 - k, petsc_mat(P))
        for key, val in smooth.items():
            opts[key] = val
        opts["pc_mg_galerkin"] = "both"
        opts["mg_coarse_ksp_type"] = "preonly"
        opts["mg_coarse_pc_type"] = "lu"
        if kind == "gmg-asm":
            # the patches through the API; the level's own options keep
            # setFromOptions from making it pbjacobi like the others
            fine = pc.getMGSmoother(nl - 1).getPC()
            fine.setType("asm")
            fine.setASMType(PETSc.PC.ASMType.BASIC)
            fine.setASMLocalSubdomains(len(p := patches(*levels[0])), p)
            opts[f"mg_levels_{nl - 1}_pc_type"] = "asm"
            opts[f"mg_levels_{nl - 1}_pc_asm_type"] = "basic"
            opts["mg_levels_sub_ksp_type"] = "preonly"
            opts["mg_levels_sub_pc_type"] = "cholesky"
    ksp.setFromOptions()
    x, rhs = Am.createVecs()
    rhs.setArray(b)
    ksp.solve(rhs, x)
    res = np.linalg.norm(b - A @ x.getArray()) / np.linalg.norm(b)
    if ksp.getConvergedReason() <= 0 or res > 2 * RTOL:
        sys.exit(f"multigrid-growth: {kind} did not converge "
                 f"(reason {ksp.getConvergedReason()}, residual {res:.1e})")
    return ksp.getIterationNumber()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--clothode", default="build/clothode")
    ap.add_argument("--sizes", default="64,128,256")
    ap.add_argument("--dt", type=float, default=1e-2)
    ap.add_argument("--steps", type=int, default=7,
                    help="steps before the state, at the first size")
    ap.add_argument("--courant", action="store_true",
                    help="dt scaled as n0/n (n0 the first size), the same "
                    "simulated time")
    ap.add_argument("--solvers", default="bj,gamg,gmg,gmg-asm")
    ap.add_argument("--work", default="out/multigrid-growth")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    try:
        sizes = [int(v) for v in a.sizes.split(",")]
    except ValueError:
        sys.exit(f"multigrid-growth: --sizes {a.sizes}: not whole numbers "
                 "separated by commas")
    if min(sizes) <= COARSEST or sizes != sorted(sizes):
        sys.exit(f"multigrid-growth: --sizes {a.sizes}: increasing, each "
                 f"above {COARSEST}")
    kinds = a.solvers.split(",")
    t_end = a.steps * a.dt
    iters = {}
    print(f"{'n':>4} {'dt':>9} {'rhs':>6} " +
          " ".join(f"{k:>8}" for k in kinds))
    for n in sizes:
        dt = a.dt * sizes[0] / n if a.courant else a.dt
        K, D, cfg, forces = export(a.clothode, n, dt, t_end, a.work)
        free = pinned(cfg, n)
        m = cfg.getfloat("cloth", "mass") / (n * n)
        A = (m * sp.identity(3 * n * n) - (2 * dt / 3) * D
             - (4 * dt * dt / 9) * K)
        fd = np.repeat(free, 3)
        A = A.tocsr()[fd][:, fd].tocsr()
        levels, interps = grids(n, free)
        rng = np.random.default_rng(1)
        for name, b in (("forces", forces[free].ravel()),
                        ("random", rng.standard_normal(A.shape[0]))):
            row = [solve(A, b, k, levels, interps) for k in kinds]
            iters[(n, name)] = row
            print(f"{n:>4} {dt:>9.3g} {name:>6} " +
                  " ".join(f"{v:>8}" for v in row), flush=True)
    lo, hi = sizes[0], sizes[-1]
    if hi > lo:
        print(f"iterations ~ unknowns^e from n = {lo} to {hi}:")
        for name in ("forces", "random"):
            e = [math.log(iters[(hi, name)][k] / iters[(lo, name)][k])
                 / math.log((hi / lo) ** 2) for k in range(len(kinds))]
            print(f"{'':>14} {name:>6} " + " ".join(f"{v:>8.3f}" for v in e))


if __name__ == "__main__":
    main()
