/* pcg, pcg-jacobi: preconditioned conjugate gradients on the reduced matrix
 * A = M - a df/dv - b df/dx (docs/model.md, 1; docs/integrators.md, 5),
 * Baraff-Witkin's choice of solver, by SUNDIALS' SUNLinSol_PCG (no
 * hand-written Krylov loop):
 *
 *  - matrix-free product (SUNLinSolSetATimes): y = A p from A's 3x3 block
 *    values, formed at every setup: when A is symmetric (it is for
 *    conservative forces with linear damping) its diagonal and upper
 *    blocks only (linalg/bsym.h: half the memory of the full product),
 *    else every block (linalg/reduced.h: cl_reduced_blocks, cl_bmatvec),
 *    held as linalg/amat.h holds them (amg's storage too);
 *  - preconditioner (SUNLinSolSetPreconditioner, applied as z = P^-1 r):
 *      pcg         3x3 block-Jacobi, P = blockdiag(S_ii), S_ii the
 *                  symmetric part of A's diagonal block i, inverted
 *                  explicitly after Sylvester's test (leading minors > 0);
 *      pcg-jacobi  point Jacobi, P = diag(A_ii), every A_ii > 0.
 *    P is set up in the PCG's Psetup callback, called by SUNLinSolSetup.
 *
 * Tolerance.  SUNDIALS' PCG (6.4.1, sunlinsol_pcg.c) stops when
 *     || s .* r_k ||_2 <= delta,     r_k = b - A x_k,
 * the residual of the *unpreconditioned* system as updated by the CG
 * recurrence, weighted componentwise by the scaling vector s; the
 * preconditioner does not enter the test.  We set s = ones (so the test is
 * on the plain 2-norm of the residual) and pass delta = lin_tol ||b||_2
 * (opts->tol, default 1e-10): a relative residual test.  solve_tol
 * instead takes the weights s = w and delta from the caller (CVODE and IDA
 * pass their own, linear tolerance, integrators/sun_reduced.h).  The
 * iteration starts from x_0 = 0 (SUNLinSolSetZeroGuess).  At most
 * opts->maxit iterations per solve (default max(1000, 2n)).
 *
 * Failures are reported as CL_ESOLVER, never hidden:
 *  - CG needs A symmetric positive definite.  SUNDIALS' PCG does not check
 *    the curvature p^T A p of its search directions; our product callback
 *    does, and stops the iteration (returning -1, SUNLS_ATIMES_FAIL_UNREC)
 *    when p^T A p <= 0 (or is not finite): A is not positive definite;
 *  - a preconditioner block that is not positive definite fails the setup;
 *  - no convergence within the iteration cap (SUNLS_RES_REDUCED or
 *    SUNLS_CONV_FAIL): the message gives the residual reached and delta.
 * A stop requested during a solve (core/stop.h) ends it at the next
 * product with CL_EINTR.
 * A is assumed symmetric (the Choi-Ko and spring Jacobians are); with a
 * nonsymmetric A, CG may fail to converge, which is then reported.
 *
 * Threads (opts->threads, docs/architecture.md "Pair kernels and
 * threads"): the products, the packing of A, the symmetry check, the
 * block-Jacobi setup and solve (equal ranges of block rows) and, through
 * cl_nvec_threads around each solve, SUNDIALS' vector operations on our
 * vectors (linalg/nvec.h; dot products over chunks fixed by n) run on
 * that many OpenMP threads, with results bitwise independent of it.
 *
 * Statistics: lin_setups (setups), lin_solves (solves), lin_iters (PCG
 * iterations, SUNLinSolNumIters summed over solves). */
#include "linalg/linsol.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_pcg.h>

#include "core/stop.h"
#include "linalg/amat.h"
#include "linalg/nvec.h"

#define CL_PCG_TOL 1e-10

typedef struct {
    const char *name;
    size_t nb, n;            /* block rows, 3 nb */
    bool block;              /* block-Jacobi (else point Jacobi) */
    cl_amat A;               /* A's values, its product */
    double *pinv;            /* 9 nb (block) or n (point): P^-1 */
    double tol;
    int maxit;
    int threads;             /* of the matrix-vector products */
    SUNContext ctx;
    N_Vector b, x, ones, w;  /* w: the caller's weights (solve_tol) */
    SUNLinearSolver ls;
    int nprod;               /* products in the current solve */
    char why[256];           /* what a callback found wrong */
    bool stopped;            /* the solve ended by a stop (core/stop.h) */
    bool ready;              /* a setup succeeded */
    long setups, solves, iters;
} cl_pcg;

/* ---- SUNDIALS callbacks ------------------------------------------------ */

/* z = A v, with the curvature check v^T A v > 0 (summed as the dot
 * products, linalg/nvec.h: the same value for every thread count); once a
 * stop is requested (SIGINT, SIGTERM, a budget's timer), the iteration
 * ends here, so that a long solve does not delay it. */
static int pcg_atimes(void *data, N_Vector v, N_Vector z)
{
    cl_pcg *s = data;
    if (cl_stop_requested()) {
        s->stopped = true;
        return -1;
    }
    const double *vp = N_VGetArrayPointer(v);
    double *zp = N_VGetArrayPointer(z);
    cl_amat_mult(&s->A, vp, zp);
    s->nprod++;
    double curv = cl_nvec_dot(vp, zp, s->n, s->threads);
    if (curv > 0.0 && isfinite(curv))
        return 0;
    double vv = cl_nvec_dot(vp, vp, s->n, s->threads);
    snprintf(s->why, sizeof s->why, "the matrix M - a df/dv - b df/dx is "
             "not positive definite: p^T A p = %.6g (|p|^2 = %.6g) for the "
             "search direction of iteration %d", curv, vv, s->nprod);
    return -1;
}

/* Inverse of the symmetric part of the 3x3 block B if it is positive
 * definite (leading minors > 0); false otherwise. */
static bool pcg_inv3(const double *B, double *inv, double minor[3])
{
    double s00 = B[0], s11 = B[4], s22 = B[8];
    double s01 = 0.5 * (B[1] + B[3]), s02 = 0.5 * (B[2] + B[6]);
    double s12 = 0.5 * (B[5] + B[7]);
    double c00 = s11 * s22 - s12 * s12, c01 = s02 * s12 - s01 * s22;
    double c02 = s01 * s12 - s02 * s11, c11 = s00 * s22 - s02 * s02;
    double c12 = s01 * s02 - s00 * s12, c22 = s00 * s11 - s01 * s01;
    minor[0] = s00;
    minor[1] = c22;
    minor[2] = s00 * c00 + s01 * c01 + s02 * c02;
    if (!(minor[0] > 0.0) || !(minor[1] > 0.0) || !(minor[2] > 0.0) ||
        !isfinite(minor[2]))
        return false;
    double d = 1.0 / minor[2];
    const double c[9] = {c00, c01, c02, c01, c11, c12, c02, c12, c22};
    for (int q = 0; q < 9; q++)
        inv[q] = c[q] * d;
    return true;
}

/* The first block of [lo, hi) whose symmetric part is not positive
 * definite, or hi; every other block of the range inverted. */
static size_t pcg_invert_blocks(cl_pcg *s, size_t lo, size_t hi)
{
    size_t bad = hi;
    for (size_t i = lo; i < hi; i++) {
        double minor[3];
        if (!pcg_inv3(cl_amat_diag_block(&s->A, i), s->pinv + 9 * i, minor) &&
            bad == hi)
            bad = i;
    }
    return bad;
}

/* Every block inverted, by s->threads threads over equal ranges of
 * blocks; the message names the first block that is not positive
 * definite. */
static int pcg_psetup_block(cl_pcg *s)
{
    size_t nb = s->nb, bad = nb;
    int nt = s->threads;
    if (nt <= 1) {
        bad = pcg_invert_blocks(s, 0, nb);
    } else {
#pragma omp parallel for num_threads(nt) schedule(static) \
    reduction(min : bad)
        for (int t = 0; t < nt; t++) {
            size_t hi = nb * (size_t)(t + 1) / (size_t)nt;
            size_t b = pcg_invert_blocks(s, nb * (size_t)t / (size_t)nt, hi);
            bad = b < hi && b < bad ? b : bad;
        }
    }
    if (bad == nb)
        return 0;
    double minor[3];
    pcg_inv3(cl_amat_diag_block(&s->A, bad), s->pinv + 9 * bad, minor);
    snprintf(s->why, sizeof s->why, "the matrix M - a df/dv - b df/dx is "
             "not positive definite: its diagonal block %zu is not (leading "
             "minors %.6g, %.6g, %.6g; no block-Jacobi preconditioner)", bad,
             minor[0], minor[1], minor[2]);
    return -1;
}

static int pcg_psetup_point(cl_pcg *s)
{
    for (size_t i = 0; i < s->n; i++) {
        double d = cl_amat_diag_block(&s->A, i / 3)[4 * (i % 3)];
        if (!(d > 0.0) || !isfinite(d)) {
            snprintf(s->why, sizeof s->why, "the matrix M - a df/dv - b "
                     "df/dx is not positive definite: its diagonal entry "
                     "%zu is %.6g (no Jacobi preconditioner)", i, d);
            return -1;
        }
        s->pinv[i] = 1.0 / d;
    }
    return 0;
}

static int pcg_psetup(void *data)
{
    cl_pcg *s = data;
    return s->block ? pcg_psetup_block(s) : pcg_psetup_point(s);
}

/* Block rows [lo, hi) of z = P^-1 r (entries, for point Jacobi). */
static void pcg_precondition(const cl_pcg *s, const double *rp, double *zp,
                             size_t lo, size_t hi)
{
    if (!s->block) {
        for (size_t i = 3 * lo; i < 3 * hi; i++)
            zp[i] = s->pinv[i] * rp[i];
        return;
    }
    for (size_t i = lo; i < hi; i++) {
        const double *P = s->pinv + 9 * i, *r3 = rp + 3 * i;
        for (size_t q = 0; q < 3; q++)
            zp[3 * i + q] = P[3 * q] * r3[0] + P[3 * q + 1] * r3[1] +
                            P[3 * q + 2] * r3[2];
    }
}

/* z = P^-1 r, on s->threads threads over equal ranges of block rows: the
 * same values for every count. */
static int pcg_psolve(void *data, N_Vector r, N_Vector z, sunrealtype tol,
                      int lr)
{
    cl_pcg *s = data;
    const double *rp = N_VGetArrayPointer(r);
    double *zp = N_VGetArrayPointer(z);
    size_t nb = s->nb;
    int nt = s->threads;
    (void)tol, (void)lr;
    if (nt <= 1) {
        pcg_precondition(s, rp, zp, 0, nb);
        return 0;
    }
#pragma omp parallel for num_threads(nt) schedule(static)
    for (int t = 0; t < nt; t++)
        pcg_precondition(s, rp, zp, nb * (size_t)t / (size_t)nt,
                         nb * (size_t)(t + 1) / (size_t)nt);
    return 0;
}

/* ---- create / free ----------------------------------------------------- */

static void pcg_free(void *state)
{
    cl_pcg *s = state;
    if (!s)
        return;
    if (s->ls)
        SUNLinSolFree(s->ls);
    if (s->b)
        N_VDestroy(s->b);
    if (s->x)
        N_VDestroy(s->x);
    if (s->ones)
        N_VDestroy(s->ones);
    if (s->w)
        N_VDestroy(s->w);
    if (s->ctx)
        SUNContext_Free(&s->ctx);
    free(s->pinv);
    cl_amat_free(&s->A);
    free(s);
}

static cl_status pcg_sunfail(const cl_pcg *s, const char *fn, int flag,
                             cl_error *err)
{
    return cl_error_set(err, CL_ESOLVER, "%s: %s failed (flag %d)", s->name,
                        fn, flag);
}

static cl_status pcg_alloc(cl_pcg *s, const cl_bpattern *pat,
                           const double *mass, cl_error *err)
{
    cl_status st = cl_amat_init(&s->A, s->name, pat, mass, s->threads, err);
    if (st != CL_OK)
        return st;
    s->pinv = calloc(s->block ? 9 * s->nb : s->n, sizeof *s->pinv);
    if (!s->pinv)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    return CL_OK;
}

static cl_status pcg_sundials(cl_pcg *s, cl_error *err)
{
    int flag = SUNContext_Create(NULL, &s->ctx);
    if (flag != 0)
        return pcg_sunfail(s, "SUNContext_Create", flag, err);
    sunindextype n = (sunindextype)s->n;
    s->b = cl_nvec_new_threaded(n, s->ctx);
    s->x = s->b ? cl_nvec_new_threaded(n, s->ctx) : NULL;
    s->ones = s->x ? cl_nvec_new_threaded(n, s->ctx) : NULL;
    s->w = s->ones ? cl_nvec_new_threaded(n, s->ctx) : NULL;
    if (!s->w)
        return pcg_sunfail(s, "cl_nvec_new_threaded", 0, err);
    N_VConst(1.0, s->ones);
    s->ls = SUNLinSol_PCG(s->x, SUN_PREC_LEFT, s->maxit, s->ctx);
    if (!s->ls)
        return pcg_sunfail(s, "SUNLinSol_PCG", 0, err);
    if ((flag = SUNLinSolSetATimes(s->ls, s, pcg_atimes)) != 0)
        return pcg_sunfail(s, "SUNLinSolSetATimes", flag, err);
    if ((flag = SUNLinSolSetPreconditioner(s->ls, s, pcg_psetup,
                                           pcg_psolve)) != 0)
        return pcg_sunfail(s, "SUNLinSolSetPreconditioner", flag, err);
    if ((flag = SUNLinSolInitialize(s->ls)) != 0)
        return pcg_sunfail(s, "SUNLinSolInitialize", flag, err);
    return CL_OK;
}

static cl_status pcg_create_named(const char *name, bool block,
                                  const cl_bpattern *pat, const double *mass,
                                  const cl_linsol_opts *o, void **state,
                                  cl_error *err)
{
    void *p;
    *state = NULL;
    cl_status st = cl_linsol_new_state(name, pat, o, sizeof(cl_pcg), &p,
                                       err);
    if (st != CL_OK)
        return st;
    cl_pcg *s = p;
    s->name = name;
    s->nb = pat->nb;
    s->n = 3 * pat->nb;
    s->block = block;
    s->tol = o->tol > 0.0 ? o->tol : CL_PCG_TOL;
    s->maxit = cl_linsol_maxit(o->maxit, s->n);
    s->threads = o->threads;
    st = pcg_alloc(s, pat, mass, err);
    if (st == CL_OK)
        st = pcg_sundials(s, err);
    if (st != CL_OK) {
        pcg_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

static cl_status pcg_create_block(const cl_bpattern *pat, const double *mass,
                                  const cl_linsol_opts *o, void **state,
                                  cl_error *err)
{
    return pcg_create_named("pcg", true, pat, mass, o, state, err);
}

static cl_status pcg_create_point(const cl_bpattern *pat, const double *mass,
                                  const cl_linsol_opts *o, void **state,
                                  cl_error *err)
{
    return pcg_create_named("pcg-jacobi", false, pat, mass, o, state, err);
}

/* ---- setup / solve ----------------------------------------------------- */

static cl_status pcg_setup(void *state, double a, double b,
                           const double *dfdx, const double *dfdv,
                           cl_error *err)
{
    cl_pcg *s = state;
    cl_amat_fill(&s->A, a, b, dfdx, dfdv);
    s->why[0] = '\0';
    s->ready = false;
    int flag = SUNLinSolSetup(s->ls, NULL);
    if (flag != 0)
        return s->why[0] ? cl_error_set(err, CL_ESOLVER, "%s: %s", s->name,
                                        s->why)
                         : pcg_sunfail(s, "SUNLinSolSetup", flag, err);
    s->ready = true;
    s->setups++;
    return CL_OK;
}

static void pcg_jacobian(void *state, const double *dfdx, const double *dfdv)
{
    cl_pcg *s = state;
    cl_amat_jacobian(&s->A, dfdx, dfdv);
}

/* `test` says what delta is, for the message. */
static cl_status pcg_solve_fail(const cl_pcg *s, int flag, double delta,
                                const char *test, cl_error *err)
{
    int nli = SUNLinSolNumIters(s->ls);
    double res = SUNLinSolResNorm(s->ls);
    if (s->stopped)
        return cl_error_set(err, CL_EINTR, "%s: stopped by %s in iteration "
                            "%d", s->name,
                            cl_stop_signal_name(cl_stop_requested()), nli);
    if (s->why[0])
        return cl_error_set(err, CL_ESOLVER, "%s: %s", s->name, s->why);
    if (flag == SUNLS_RES_REDUCED || flag == SUNLS_CONV_FAIL)
        return cl_error_set(err, CL_ESOLVER,
                            "%s: no convergence in %d iterations: residual "
                            "%.6g > %.6g (%s)", s->name, nli, res, delta,
                            test);
    return pcg_sunfail(s, "SUNLinSolSolve", flag, err);
}

/* PCG from x = 0 on s->b (already filled) until ||scale .* r||_2 <= delta;
 * the solution into x. */
static cl_status pcg_run(cl_pcg *s, N_Vector scale, double delta,
                         const char *test, double *x, cl_error *err)
{
    int flag = SUNLinSolSetScalingVectors(s->ls, scale, NULL);
    if (flag != 0)
        return pcg_sunfail(s, "SUNLinSolSetScalingVectors", flag, err);
    N_VConst(0.0, s->x);
    if ((flag = SUNLinSolSetZeroGuess(s->ls, SUNTRUE)) != 0)
        return pcg_sunfail(s, "SUNLinSolSetZeroGuess", flag, err);
    s->why[0] = '\0';
    s->stopped = false;
    s->nprod = 0;
    int outer = cl_nvec_threads(s->threads); /* PCG's vector operations */
    flag = SUNLinSolSolve(s->ls, NULL, s->x, s->b, delta);
    cl_nvec_threads(outer);
    s->solves++;
    s->iters += SUNLinSolNumIters(s->ls);
    if (flag != SUNLS_SUCCESS)
        return pcg_solve_fail(s, flag, delta, test, err);
    memcpy(x, N_VGetArrayPointer(s->x), s->n * sizeof *x);
    return CL_OK;
}

/* Copy rhs into s->b; CL_OK if a setup succeeded and rhs is finite. */
static cl_status pcg_load(cl_pcg *s, const double *rhs, cl_error *err)
{
    cl_status st = cl_linsol_check_solve(s->name, s->ready, rhs, s->n, err);
    if (st == CL_OK)
        memcpy(N_VGetArrayPointer(s->b), rhs, s->n * sizeof *rhs);
    return st;
}

static cl_status pcg_solve(void *state, const double *rhs, double *x,
                           cl_error *err)
{
    cl_pcg *s = state;
    cl_status st = pcg_load(s, rhs, err);
    if (st != CL_OK)
        return st;
    double bnorm = sqrt(N_VDotProd(s->b, s->b));
    char test[96];
    snprintf(test, sizeof test, "lin_tol %g x |b| %.6g", s->tol, bnorm);
    return pcg_run(s, s->ones, s->tol * bnorm, test, x, err);
}

static cl_status pcg_solve_tol(void *state, const double *rhs, double *x,
                               const double *w, double delta, cl_error *err)
{
    cl_pcg *s = state;
    cl_status st = cl_linsol_check_weights(s->name, w, s->n, delta, err);
    if (st == CL_OK)
        st = pcg_load(s, rhs, err);
    if (st != CL_OK)
        return st;
    memcpy(N_VGetArrayPointer(s->w), w, s->n * sizeof *w);
    return pcg_run(s, s->w, delta, "the integrator's weighted tolerance",
                   x, err);
}

static void pcg_stats(const void *state, cl_stats *out)
{
    const cl_pcg *s = state;
    out->lin_setups += s->setups;
    out->lin_solves += s->solves;
    out->lin_iters += s->iters;
}

const cl_linsol_type cl_linsol_pcg = {
    .name = "pcg",
    .doc = "SUNDIALS PCG, matrix-free, 3x3 block-Jacobi preconditioner "
           "(A must be SPD)",
    .create = pcg_create_block,
    .jacobian = pcg_jacobian,
    .setup = pcg_setup,
    .solve = pcg_solve,
    .solve_tol = pcg_solve_tol,
    .stats = pcg_stats,
    .free = pcg_free,
};

const cl_linsol_type cl_linsol_pcg_jacobi = {
    .name = "pcg-jacobi",
    .doc = "SUNDIALS PCG, matrix-free, point Jacobi preconditioner "
           "(A must be SPD)",
    .create = pcg_create_point,
    .jacobian = pcg_jacobian,
    .setup = pcg_setup,
    .solve = pcg_solve,
    .solve_tol = pcg_solve_tol,
    .stats = pcg_stats,
    .free = pcg_free,
};
