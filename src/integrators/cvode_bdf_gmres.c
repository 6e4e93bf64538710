/* cvode-bdf-gmres: SUNDIALS CVODE BDF with matrix-free Newton-Krylov
 * (docs/integrators.md, 6)
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * variable-order variable-step BDF (orders 1..5), Newton iteration, the
 * linear systems (I - gamma J) dy = r solved by SUNLinSol_SPGMR (modified
 * Gram-Schmidt, no restarts, Krylov dimension opts->lin_maxit, default
 * CL_GM_MAXL; CVODE's linear tolerance factor opts->lin_tol, default 0.05)
 * with left preconditioning.
 *
 * Jacobian-vector product, analytic (CVodeSetJacTimes):
 *     J u = [ u_v ; M^-1 (df/dx u_x + df/dv u_v) ],
 * from the system's block Jacobians, evaluated in the jtsetup function at
 * the current Newton iterate (CVODE calls it once before every Krylov
 * solve) and reused by every jtimes call of that solve.  No difference
 * quotients.
 *
 * Preconditioner: block Jacobi on the particles.  Each free particle i
 * couples its own x and v, so the natural diagonal block of I - gamma J is
 * the 6 x 6 matrix
 *     P_i = [ I                  -gamma I                  ]
 *           [ -gamma A_i         I - gamma B_i             ],
 *     A_i = M_i^-1 (df/dx)_ii,   B_i = M_i^-1 (df/dv)_ii,
 * which P = diag(P_i) keeps exactly (all coupling between particles is
 * dropped).  P_i z = r is solved exactly by eliminating z_x = r_x +
 * gamma z_v:
 *     S_i z_v = r_v + gamma A_i r_x,   S_i = I - gamma B_i - gamma^2 A_i,
 * so psetup inverts the 3 x 3 Schur complements S_i (cofactors; a
 * singular or non-finite S_i is a recoverable setup failure) and psolve
 * costs two 3 x 3 products per particle.  A_i and B_i are refreshed from a
 * new Jacobian evaluation when CVODE asks (jok false); otherwise only
 * gamma changes.
 *
 * Options, error capture, blow-up policy as in sun_adapter.h.  Statistics:
 * lin_iters = Krylov iterations (CVodeGetNumLinIters), lin_setups =
 * preconditioner setups (CVODE's linear solver setups), lin_solves =
 * Krylov solves performed (jtsetup calls; a Newton iteration whose residual
 * is already below the linear tolerance skips both), jac_evals = system
 * Jacobian evaluations (jtsetup plus preconditioner refreshes),
 * rhs_evals = CVODE's RHS evaluations (none in the products),
 * symbolic_facts = 0. */
#include "integrators/integrator.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include "integrators/sun_adapter.h"

/* Krylov dimension when opts->lin_maxit is 0: SUNDIALS' default.  On hang
 * (n = 16, rtol 1e-4) the preconditioned solves take 1.1 to 1.4 Krylov
 * iterations each, and a dimension of 10 or 30 changes the step count by
 * under 1%. */
#define CL_GM_MAXL 5

typedef struct {
    cl_sun base; /* first: CVODE's user data is the whole state */
    double *a;   /* per particle: A_i = M_i^-1 (df/dx)_ii, 9 nb */
    double *b;   /* per particle: B_i = M_i^-1 (df/dv)_ii, 9 nb */
    double *sinv; /* per particle: S_i^-1, 9 nb */
} cl_gmres;

/* ---- Jacobian-vector product ------------------------------------------- */

static int gm_jtsetup(sunrealtype t, N_Vector y, N_Vector fy, void *data)
{
    cl_sun *s = data;
    const double *x = N_VGetArrayPointer(y);
    (void)fy;
    return cl_sun_jacobian(s, t, x, x + s->sys->n);
}

/* out_v = M^-1 (df/dx u_x + df/dv u_v) over the block pattern. */
static void gm_blockmul(const cl_sun *s, const double *ux, const double *uv,
                        double *out)
{
    const cl_bpattern *p = s->sys->pattern;
    for (size_t bi = 0; bi < p->nb; bi++) {
        for (size_t r = 0; r < 3; r++) {
            double acc = 0.0;
            for (size_t k = p->rowptr[bi]; k < p->rowptr[bi + 1]; k++) {
                const double *dx = s->dfdx + 9 * k + 3 * r;
                const double *dv = s->dfdv + 9 * k + 3 * r;
                const double *px = ux + 3 * p->col[k];
                const double *pv = uv + 3 * p->col[k];
                acc += dx[0] * px[0] + dx[1] * px[1] + dx[2] * px[2] +
                       dv[0] * pv[0] + dv[1] * pv[1] + dv[2] * pv[2];
            }
            out[3 * bi + r] = acc * s->inv_mass[3 * bi + r];
        }
    }
}

static int gm_jtimes(N_Vector u, N_Vector Ju, sunrealtype t, N_Vector y,
                     N_Vector fy, void *data, N_Vector tmp)
{
    const cl_sun *s = data;
    size_t n = s->sys->n;
    const double *pu = N_VGetArrayPointer(u);
    double *pj = N_VGetArrayPointer(Ju);
    (void)t, (void)y, (void)fy, (void)tmp;
    memcpy(pj, pu + n, n * sizeof *pj);
    gm_blockmul(s, pu, pu + n, pj + n);
    return 0;
}

/* ---- block-Jacobi preconditioner --------------------------------------- */

/* Keep M^-1 times the diagonal blocks of the Jacobian just evaluated. */
static void gm_save_diag(cl_gmres *g)
{
    const cl_sun *s = &g->base;
    const cl_bpattern *p = s->sys->pattern;
    for (size_t i = 0; i < p->nb; i++) {
        size_t k = p->diag[i];
        for (size_t e = 0; e < 9; e++) {
            double im = s->inv_mass[3 * i + e / 3];
            g->a[9 * i + e] = s->dfdx[9 * k + e] * im;
            g->b[9 * i + e] = s->dfdv[9 * k + e] * im;
        }
    }
}

/* inv = S^-1 by cofactors (row-major); false if S is singular or not
 * finite. */
static bool gm_inv3(const double *S, double *inv)
{
    inv[0] = S[4] * S[8] - S[5] * S[7];
    inv[1] = S[2] * S[7] - S[1] * S[8];
    inv[2] = S[1] * S[5] - S[2] * S[4];
    inv[3] = S[5] * S[6] - S[3] * S[8];
    inv[4] = S[0] * S[8] - S[2] * S[6];
    inv[5] = S[2] * S[3] - S[0] * S[5];
    inv[6] = S[3] * S[7] - S[4] * S[6];
    inv[7] = S[1] * S[6] - S[0] * S[7];
    inv[8] = S[0] * S[4] - S[1] * S[3];
    double det = S[0] * inv[0] + S[1] * inv[3] + S[2] * inv[6];
    if (!isfinite(det) || det == 0.0)
        return false;
    for (int e = 0; e < 9; e++)
        inv[e] /= det;
    return true;
}

static int gm_factor(cl_gmres *g, double gamma)
{
    size_t nb = g->base.sys->pattern->nb;
    for (size_t i = 0; i < nb; i++) {
        double S[9];
        for (int e = 0; e < 9; e++)
            S[e] = (e % 4 == 0 ? 1.0 : 0.0) - gamma * g->b[9 * i + e] -
                   gamma * gamma * g->a[9 * i + e];
        if (!gm_inv3(S, g->sinv + 9 * i))
            return 1;
    }
    return 0;
}

static int gm_psetup(sunrealtype t, N_Vector y, N_Vector fy, sunbooleantype jok,
                     sunbooleantype *jcur, sunrealtype gamma, void *data)
{
    cl_gmres *g = data;
    (void)fy;
    *jcur = SUNFALSE;
    if (!jok) {
        const double *x = N_VGetArrayPointer(y);
        int ret = cl_sun_jacobian(&g->base, t, x, x + g->base.sys->n);
        if (ret != 0)
            return ret;
        gm_save_diag(g);
        *jcur = SUNTRUE;
    }
    return gm_factor(g, gamma);
}

/* out = M in (3 x 3, row-major) */
static void gm_mul3(const double *M, const double *in, double *out)
{
    for (int r = 0; r < 3; r++)
        out[r] = M[3 * r] * in[0] + M[3 * r + 1] * in[1] + M[3 * r + 2] * in[2];
}

static int gm_psolve(sunrealtype t, N_Vector y, N_Vector fy, N_Vector r,
                     N_Vector z, sunrealtype gamma, sunrealtype delta, int lr,
                     void *data)
{
    const cl_gmres *g = data;
    size_t n = g->base.sys->n;
    const double *rx = N_VGetArrayPointer(r), *rv = rx + n;
    double *zx = N_VGetArrayPointer(z), *zv = zx + n;
    (void)t, (void)y, (void)fy, (void)delta, (void)lr;
    for (size_t i = 0; i < n / 3; i++) {
        double ar[3], w[3];
        gm_mul3(g->a + 9 * i, rx + 3 * i, ar);
        for (int c = 0; c < 3; c++)
            w[c] = rv[3 * i + c] + gamma * ar[c];
        gm_mul3(g->sinv + 9 * i, w, zv + 3 * i);
        for (int c = 0; c < 3; c++)
            zx[3 * i + c] = rx[3 * i + c] + gamma * zv[3 * i + c];
    }
    return 0;
}

/* ---- create / free / statistics --------------------------------------- */

static void gm_free(void *state)
{
    cl_gmres *g = state;
    if (g) {
        free(g->a);
        free(g->b);
        free(g->sinv);
    }
    cl_sun_free(state);
}

static cl_status gm_check(const cl_integrator_opts *o, cl_error *err)
{
    if (o->lin_maxit < 0 || o->lin_maxit > INT_MAX || !(o->lin_tol >= 0.0) ||
        !isfinite(o->lin_tol))
        return cl_error_set(err, CL_EINVAL, "cvode-bdf-gmres: bad options "
                            "lin_maxit = %ld, lin_tol = %g (need finite, >= 0)",
                            o->lin_maxit, o->lin_tol);
    return CL_OK;
}

static cl_status gm_linsol(cl_gmres *g, const cl_integrator_opts *o,
                           cl_error *err)
{
    cl_sun *s = &g->base;
    size_t nb = s->sys->pattern->nb;
    g->a = malloc(9 * nb * sizeof *g->a);
    g->b = malloc(9 * nb * sizeof *g->b);
    g->sinv = malloc(9 * nb * sizeof *g->sinv);
    if (!g->a || !g->b || !g->sinv)
        return cl_error_set(err, CL_ENOMEM, "cvode-bdf-gmres: out of memory");
    int maxl = o->lin_maxit > 0 ? (int)o->lin_maxit : CL_GM_MAXL, flag;
    s->ls = SUNLinSol_SPGMR(s->y, SUN_PREC_LEFT, maxl, s->ctx);
    if (!s->ls)
        return cl_sun_sunfail(s, "SUNLinSol_SPGMR", 0, err);
    if ((flag = CVodeSetLinearSolver(s->mem, s->ls, NULL)) < 0)
        return cl_sun_fail(s, "CVodeSetLinearSolver", flag, err);
    if ((flag = CVodeSetJacTimes(s->mem, gm_jtsetup, gm_jtimes)) < 0)
        return cl_sun_fail(s, "CVodeSetJacTimes", flag, err);
    if ((flag = CVodeSetPreconditioner(s->mem, gm_psetup, gm_psolve)) < 0)
        return cl_sun_fail(s, "CVodeSetPreconditioner", flag, err);
    if (o->lin_tol > 0 && (flag = CVodeSetEpsLin(s->mem, o->lin_tol)) < 0)
        return cl_sun_fail(s, "CVodeSetEpsLin", flag, err);
    return CL_OK;
}

static cl_status gm_create(const cl_system *sys, const cl_integrator_opts *o,
                           double t0, const double *x0, const double *v0,
                           void **state, cl_error *err)
{
    cl_sun *s = NULL;
    *state = NULL;
    cl_status st = gm_check(o, err);
    if (st == CL_OK)
        st = cl_sun_cvode_create(sizeof(cl_gmres), "cvode-bdf-gmres", CV_BDF,
                                 true, sys, o, t0, x0, v0, &s, err);
    if (st == CL_OK)
        st = gm_linsol((cl_gmres *)s, o, err);
    return cl_sun_finish(s, st, gm_free, state);
}

static void gm_stats(const void *state, cl_stats *out)
{
    const cl_sun *s = state;
    long njt = 0;
    cl_sun_stats(state, out);
    if (CVodeGetNumJTSetupEvals(s->mem, &njt) >= 0)
        out->lin_solves = njt;
    out->jac_evals = s->njac;
    snprintf(out->linsol, sizeof out->linsol, "spgmr+bjacobi");
}

const cl_integrator_type cl_integrator_cvode_bdf_gmres = {
    .name = "cvode-bdf-gmres",
    .region = &cl_region_bdf5,
    .doc = "CVODE BDF, Newton-Krylov: SPGMR, analytic J*v, block-Jacobi "
           "(6x6 per particle) left preconditioner",
    .fixed_step = false,
    .takes_max_order = true,
    .takes_linsol = false,
    .takes_lin_tol = true,
    .create = gm_create,
    .advance = cl_sun_advance,
    .stats = gm_stats,
    .free = gm_free,
};
