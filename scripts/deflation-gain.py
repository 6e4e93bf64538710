#!/usr/bin/python3
"""What deflating CG by the previous solve's Ritz vectors would save on
semi-bdf2's Newton matrix under GAMG (a Krylov recycling that clothode does
not build).

The hanging cloth (problems/hang.ini) is run with semi-bdf2 to t = steps *
dt and to one step later; at both states `clothode eval` exports df/dx and
df/dv, and the next step's matrix A = M - (2 dt/3) df/dv - (4 dt^2/9) df/dx
(docs/integrators.md, 3.2), pinned particles removed, is formed as in
scripts/multigrid-growth.py, whose helpers this script uses.  Each matrix
gets its own GAMG preconditioner B (one Chebyshev step with point-block
Jacobi on every level, block size 3).

The first matrix is solved by preconditioned CG from zero to ||b - A x||_2
<= 1e-10 ||b||_2 (b the forces at the state), keeping the preconditioned
residuals: CG's coefficients give the Lanczos matrix of B A, whose smallest
Ritz pairs approximate the modes the multigrid cycle reduces least.  The
k Ritz vectors W of the smallest Ritz values then deflate CG on the second
matrix (Saad, Yeung, Erhel and Guyomarc'h, "A deflated version of the
conjugate gradient algorithm"): x0 = W (W^T A W)^-1 W^T b, and each search
direction is made A-orthogonal to W.  Printed: the smallest Ritz values,
CG's iterations on the second matrix without deflation and with k = 4, 8,
16, 32, for the forces and for a reproducible random right-hand side, and
with the same vectors on the first matrix (the vectors' own matrix: what
deflation could save if they did not go stale).  A deflated iteration
reads 2k more vectors than a plain one.

Needs Debian's python3-petsc4py, python3-scipy
(`scripts/install-deps.sh multigrid`).  paper/findings.md, "Algebraic
multigrid", has its output.
"""
import argparse
import importlib.util
import os
import sys

import numpy as np
import scipy.linalg as sl
import scipy.sparse as sp

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location(
    "multigrid_growth", os.path.join(HERE, "multigrid-growth.py"))
mg = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mg)
PETSc = mg.PETSc


def newton_matrix(clothode, n, dt, steps, work):
    """The step's matrix after `steps` steps, and the forces there."""
    d = os.path.join(work, f"n{n}-s{steps}")
    os.makedirs(d, exist_ok=True)
    K, D, cfg, forces = mg.export(clothode, n, dt, steps * dt, d)
    free = mg.pinned(cfg, n)
    m = cfg.getfloat("cloth", "mass") / (n * n)
    A = m * sp.identity(3 * n * n) - (2 * dt / 3) * D - (4 * dt * dt / 9) * K
    fd = np.repeat(free, 3)
    return A.tocsr()[fd][:, fd].tocsr(), forces[free].ravel()


def gamg(A):
    """x -> B x for GAMG on A (the smoothers of multigrid-growth's gamg)."""
    opts = PETSc.Options()
    for key in list(opts.getAll()):
        opts.delValue(key)
    for key, val in {"mg_levels_ksp_type": "chebyshev",
                     "mg_levels_ksp_max_it": 1,
                     "mg_levels_pc_type": "pbjacobi",
                     "mg_levels_esteig_ksp_type": "cg"}.items():
        opts[key] = val
    Am = mg.petsc_mat(A)
    Am.setBlockSize(3)
    Am.setOption(PETSc.Mat.Option.SPD, True)
    pc = PETSc.PC().create()
    pc.setOperators(Am)
    pc.setType("gamg")
    pc.setFromOptions()
    pc.setUp()
    x, y = Am.createVecs()

    def apply(r):
        x.setArray(r)
        pc.apply(x, y)
        return y.getArray().copy()
    return apply


def lanczos_ritz(alpha, beta, V):
    """Ritz values and vectors of B A from CG's coefficients: the Lanczos
    matrix has diagonal 1/alpha_j + beta_(j-1)/alpha_(j-1) and
    off-diagonal sqrt(beta_j)/alpha_j; V holds the Lanczos vectors
    (-1)^j z_j / sqrt(r_j . z_j) as columns."""
    m = len(alpha)
    T = np.zeros((m, m))
    for j in range(m):
        T[j, j] = 1 / alpha[j] + (beta[j - 1] / alpha[j - 1] if j else 0)
        if j + 1 < m:
            T[j, j + 1] = T[j + 1, j] = np.sqrt(beta[j]) / alpha[j]
    theta, S = np.linalg.eigh(T)
    return theta, V @ S


def pcg(A, b, B, W=None, keep=False):
    """CG preconditioned by B from zero (deflated by the columns of W if
    given) to the relative residual mg.RTOL; its iterations, and with keep
    the Ritz pairs of B A."""
    nb = np.linalg.norm(b)
    if W is not None:
        AW = A @ W
        E = sl.cho_factor(W.T @ AW)
        x = W @ sl.cho_solve(E, W.T @ b)
    else:
        x = np.zeros_like(b)
    r = b - A @ x
    z = B(r)
    p = z if W is None else z - W @ sl.cho_solve(E, AW.T @ z)
    rz = r @ z
    alpha, beta, V = [], [], []
    for it in range(1, 20001):
        if keep:
            V.append((-1) ** (it - 1) * z / np.sqrt(rz))
        Ap = A @ p
        a = rz / (p @ Ap)
        x += a * p
        r -= a * Ap
        alpha.append(a)
        if np.linalg.norm(r) <= mg.RTOL * nb:
            break
        z = B(r)
        rz, rz_old = r @ z, rz
        beta.append(rz / rz_old)
        p = beta[-1] * p + z
        if W is not None:
            p -= W @ sl.cho_solve(E, AW.T @ z)
    else:
        sys.exit("deflation-gain: CG did not converge in 20000 iterations")
    return it, (lanczos_ritz(alpha, beta, np.array(V).T) if keep else None)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--clothode", default="build/clothode")
    ap.add_argument("--n", type=int, default=128)
    ap.add_argument("--dt", type=float, default=1e-2)
    ap.add_argument("--steps", type=int, default=7,
                    help="steps before the first matrix")
    ap.add_argument("--work", default="out/deflation-gain")
    a = ap.parse_args()
    if a.n <= mg.COARSEST or a.steps < 1 or not a.dt > 0:
        sys.exit(f"deflation-gain: --n above {mg.COARSEST}, --steps >= 1 "
                 "and --dt > 0")
    A0, b0 = newton_matrix(a.clothode, a.n, a.dt, a.steps, a.work)
    A1, b1 = newton_matrix(a.clothode, a.n, a.dt, a.steps + 1, a.work)
    B0, B1 = gamg(A0), gamg(A1)
    it0, (theta, Y) = pcg(A0, b0, B0, keep=True)
    print(f"n = {a.n}, dt = {a.dt:g}, after step {a.steps}: {it0} CG "
          f"iterations; smallest Ritz values of B A "
          + " ".join(f"{t:.4f}" for t in theta[:8])
          + f"; largest {theta[-1]:.3f}")
    rnd = np.random.default_rng(2).standard_normal(A1.shape[0])
    rnd0 = np.random.default_rng(3).standard_normal(A0.shape[0])
    print(f"{'k':>3} {'next, forces':>13} {'next, random':>13} "
          f"{'own, random':>12}")
    print(f"{0:>3} {pcg(A1, b1, B1)[0]:>13} {pcg(A1, rnd, B1)[0]:>13} "
          f"{pcg(A0, rnd0, B0)[0]:>12}", flush=True)
    for k in (4, 8, 16, 32):
        W = Y[:, :k]
        print(f"{k:>3} {pcg(A1, b1, B1, W)[0]:>13} "
              f"{pcg(A1, rnd, B1, W)[0]:>13} "
              f"{pcg(A0, rnd0, B0, W)[0]:>12}", flush=True)


if __name__ == "__main__":
    main()
