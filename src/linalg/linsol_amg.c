/* amg, amg-hypre: conjugate gradients preconditioned by algebraic
 * multigrid on the reduced matrix A = M - a df/dv - b df/dx (docs/model.md,
 * 1; docs/integrators.md, 5), by PETSc in the plug-in clothode-petsc.so
 * (linalg/plugin.h; its side: linsol_amg_petsc.c):
 *
 *   amg        PCGAMG, smoothed aggregation (Vanek, Mandel and Brezina,
 *              "Algebraic multigrid by smoothed aggregation for second and
 *              fourth order elliptic problems") with block size 3 (the
 *              three translations per particle as near-null space),
 *              the finest level smoothed by this side's symmetric block
 *              Gauss-Seidel (linalg/blockgs.h: a backward sweep before
 *              the coarse correction, a forward one after it), the
 *              coarser levels by Chebyshev with 3x3 point-block Jacobi;
 *   amg-hypre  hypre's BoomerAMG (classical Ruge-Stueben coarsening) with
 *              nodal coarsening and vector interpolation for the 3 unknowns
 *              per particle.
 *
 * The pattern is built once (create).  CG multiplies by A, and the finest
 * level of the multigrid cycle sweeps, through this side's callbacks the
 * plug-in calls (amg_mult, amg_sweep): for a symmetric A (the usual case) on
 * the diagonal and upper blocks only, each upper block by its 6 distinct
 * entries when it is symmetric itself, else on every block: pcg's storage
 * (linalg/amat.h).  That storage is under a third of the bytes of
 * PETSc's SeqAIJ copy, and the fine matrix is read three times per CG
 * iteration (CG's product, the backward sweep that also forms the cycle's
 * residual, the forward sweep), so it sets the cost of an iteration.  A setup
 * packs A's values straight from df/dx and df/dv (a symmetric A's halves,
 * as pcg does), inverts its 3x3 diagonal blocks for the sweeps and, when
 * the preconditioner is built or its coarse operators recomputed, writes
 * A's full blocks (a symmetric A's unpacked from its halves: the exactly
 * symmetric matrix CG multiplies by) into the slots of PETSc's SeqAIJ copy
 * (the preconditioner's) and
 * sets the preconditioner up, either afresh (a rebuild: coarsening,
 * interpolation, coarse operators, smoothers) or reusing the hierarchy
 * (linalg/linsol_amg_abi.h).  For amg a reuse keeps the coarse operators and
 * their smoothers, and the finest level's sweeps read the new A (a V-cycle
 * whose smoothers converge is symmetric positive definite whatever SPD
 * coarse operators it uses, so stale ones cost iterations, not definiteness;
 * block Gauss-Seidel converges for every SPD A and has no eigenvalue bound
 * to go stale, unlike the Chebyshev smoother the finest level had before,
 * whose stale bound made the cycle indefinite); when the last solve took
 * more than CL_AMG_COARSE_REGROW times the iterations of the first after the
 * coarse operators were last computed, they are recomputed, P^T A P on the
 * kept interpolation P.  amg-hypre builds BoomerAMG afresh at every
 * setup: PETSc can keep hypre's preconditioner only whole, its finest
 * relaxation then sweeping the old A, and on hang that cost more CG
 * iterations than the builds it saved (paper/findings.md).  amg's
 * hierarchy is rebuilt at the first setup, and when the
 * last solve took more than CL_AMG_REGROW times the iterations of the first
 * solve after the last rebuild although the coarse operators are
 * fresh.  Iterations also grow when the problem itself gets harder (a
 * cloth leaving its rest state), and then no recompute helps: each
 * recompute a growth triggered is judged by the next solve.  One that
 * took no fewer iterations than the solve that triggered it doubles the
 * coarse operators' factor's excess over 1 (1.1, 1.2, 1.4), up to
 * CL_AMG_REGROW, where a growth builds a new hierarchy instead; if it was
 * the first P^T A P on a new interpolation, which cannot be stale yet, the
 * growth was the problem's, and the rebuild's reference moves to that
 * solve's count.  One that helped puts the factor back to
 * CL_AMG_COARSE_REGROW.  Recovery: a solve that fails (CG finds the
 * preconditioner indefinite, breaks down or reaches lin_maxit) is redone
 * once on a hierarchy rebuilt from scratch whose smoothers' eigenvalue
 * bounds (the coarser levels') are estimated with CLP_AMG_RECOVER_STEPS
 * Lanczos steps instead of 10 (linsol_amg_petsc.c, kept until the next
 * build), whether the failed hierarchy was reused or fresh; only if that
 * fails too is the solve an error (amg-hypre, freshly built and without
 * such bounds, fails at once).  A diagonal
 * block whose determinant is not positive (A not SPD) fails amg's setup.
 * Nothing is allocated by setup or solve on this side (PETSc allocates
 * within its setups: the eigenvalue estimates' work arrays, and everything
 * of a rebuild).
 *
 * Tolerance: solve stops at ||b - A x||_2 <= lin_tol ||b||_2 (default
 * 1e-10, as pcg); solve_tol at ||w .* (b - A x)||_2 <= delta, ensured by
 * ||b - A x||_2 <= delta / max(w) (since ||w .* r||_2 <= max(w) ||r||_2).
 * CG needs A symmetric positive definite: an indefinite A (or
 * preconditioner), a breakdown or no convergence within lin_maxit
 * (default max(1000, 2n)) is CL_ESOLVER with PETSc's reason.
 *
 * Statistics: lin_setups (setups), lin_solves, lin_iters (CG iterations,
 * both attempts of a recovered solve), symbolic_facts (hierarchy
 * rebuilds, recoveries' included; the other setups reused it),
 * lin_recoveries (solves redone on a rebuilt hierarchy). */
#include "linalg/linsol.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "core/stop.h"
#include "linalg/amat.h"
#include "linalg/blockgs.h"
#include "linalg/linsol_amg_abi.h"
#include "linalg/petscenv.h"
#include "linalg/plugin.h"

#define CL_AMG_TOL 1e-10
#define CL_AMG_REGROW 1.5
#define CL_AMG_COARSE_REGROW 1.1

typedef struct {
    const char *name;
    size_t n;                /* 3 nb */
    cl_amat A;               /* A's values, its product */
    bool ablk_current;       /* A.ablk holds the last setup's A */
    double *dinv;            /* 9 nb: A's diagonal blocks inverted (amg) */
    double *acc;             /* n: the forward sweep's work (amg) */
    double *rhs;             /* n: a copy of the right-hand side of a
                              * solve in place (x == rhs), which PETSc's
                              * zero first guess would overwrite */
    double tol;
    clp_amg_setup_fn setup;
    clp_amg_solve_fn solve;
    clp_amg_free_fn free;
    void *h;                 /* the plug-in's solver */
    bool ready;              /* a setup succeeded */
    int hypre;
    bool coarse_fresh;       /* the coarse operators were computed at the
                              * last setup (a build, or P^T A P on the
                              * kept P) */
    long base_iters;         /* first solve after the last rebuild; -1 */
    long cbase_iters;        /* ... after the coarse operators' last; -1 */
    long last_iters;         /* the last solve's */
    long trigger_iters;      /* the solve whose growth made the last setup
                              * recompute; 0: none to judge */
    bool first_galerkin;     /* ... which was the first P^T A P on the
                              * interpolation of the last build */
    bool galerkin_done;      /* P^T A P computed since the last build */
    double coarse_regrow;    /* the coarse operators' growth factor */
    long setups, rebuilds, solves, iters, recoveries;
} cl_amg;

static void amg_free(void *state)
{
    cl_amg *s = state;
    if (!s)
        return;
    if (s->h)
        s->free(s->h);
    free(s->dinv);
    free(s->acc);
    free(s->rhs);
    cl_amat_free(&s->A);
    free(s);
}

/* The plug-in's entry points clp_amg_*. */
static cl_status amg_symbols(cl_amg *s, clp_amg_create_fn *create,
                             cl_error *err)
{
    void *sym[4];
    const char *const names[4] = {"clp_amg_create", "clp_amg_setup",
                                  "clp_amg_solve", "clp_amg_free"};
    cl_status st = cl_petsc_start(err);
    for (int k = 0; k < 4 && st == CL_OK; k++)
        st = cl_plugin_symbol("petsc", names[k], &sym[k], err);
    if (st != CL_OK)
        return st;
    *create = (clp_amg_create_fn)sym[0];
    s->setup = (clp_amg_setup_fn)sym[1];
    s->solve = (clp_amg_solve_fn)sym[2];
    s->free = (clp_amg_free_fn)sym[3];
    return CL_OK;
}

static cl_status amg_alloc(cl_amg *s, const cl_bpattern *pat,
                           const double *mass, int threads, cl_error *err)
{
    cl_status st = cl_amat_init(&s->A, s->name, pat, mass, threads, err);
    if (st == CL_OK && !(s->rhs = malloc(s->n * sizeof *s->rhs)))
        st = cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    if (st != CL_OK || s->hypre)    /* BoomerAMG relaxes on its own */
        return st;
    s->dinv = malloc(9 * pat->nb * sizeof *s->dinv);
    s->acc = malloc(s->n * sizeof *s->acc);
    if (!s->dinv || !s->acc)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    return CL_OK;
}

/* y = A x, the plug-in's operator: A's packed halves, or all its blocks.
 * Once a stop is requested (core/stop.h), y = NaN instead: CG ends at
 * once (KSP_DIVERGED_NANORINF), and amg_run reports the stop. */
static void amg_mult(void *ctx, const double *x, double *y)
{
    const cl_amg *s = ctx;
    if (!cl_stop_requested()) {
        cl_amat_mult(&s->A, x, y);
        return;
    }
    for (size_t i = 0; i < s->n; i++)
        y[i] = NAN;
}

/* The finest level's smoother (linsol_amg_abi.h: clp_amg_sweep): block
 * Gauss-Seidel on A's packed halves, or on all its blocks (then the
 * residual by a product). */
static void amg_sweep(void *ctx, int forward, const double *b, double *x,
                      double *r)
{
    cl_amg *s = ctx;
    const cl_amat *A = &s->A;
    if (A->kind != CL_BSYM_NONE) {
        cl_bsym_gs(&A->sym, A->kind, forward, s->dinv, A->supper, b, x,
                   forward ? s->acc : r);
        return;
    }
    if (forward) {
        cl_bgs_forward(A->pat, A->ablk, s->dinv, b, x);
        return;
    }
    cl_bgs_backward(A->pat, A->ablk, s->dinv, b, x);
    amg_mult(s, x, r);
    for (size_t i = 0; i < s->n; i++)
        r[i] = b[i] - r[i];
}

static cl_status amg_create_named(const char *name, int hypre,
                                  const cl_bpattern *pat, const double *mass,
                                  const cl_linsol_opts *o, void **state,
                                  cl_error *err)
{
    void *p;
    *state = NULL;
    cl_status st = cl_linsol_new_state(name, pat, o, sizeof(cl_amg), &p,
                                       err);
    if (st != CL_OK)
        return st;
    cl_amg *s = p;
    *s = (cl_amg){.name = name, .n = 3 * pat->nb,
                  .tol = o->tol > 0.0 ? o->tol : CL_AMG_TOL,
                  .hypre = hypre, .base_iters = -1, .cbase_iters = -1,
                  .coarse_regrow = CL_AMG_COARSE_REGROW};
    long maxit = cl_linsol_maxit(o->maxit, s->n);
    clp_amg_create_fn create = NULL;
    cl_plugin_msg msg = {.text = ""};
    st = amg_alloc(s, pat, mass, o->threads, err);
    if (st == CL_OK)
        st = amg_symbols(s, &create, err);
    if (st == CL_OK && create(pat->nb, pat->rowptr, pat->col, hypre, maxit,
                              amg_mult, amg_sweep, s, &s->h, &msg) != 0)
        st = cl_error_set(err, CL_ESOLVER, "%s: %s", name, msg.text);
    if (st != CL_OK) {
        amg_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

static cl_status amg_create(const cl_bpattern *pat, const double *mass,
                            const cl_linsol_opts *o, void **state,
                            cl_error *err)
{
    return amg_create_named("amg", 0, pat, mass, o, state, err);
}

static cl_status amg_create_hypre(const cl_bpattern *pat, const double *mass,
                                  const cl_linsol_opts *o, void **state,
                                  cl_error *err)
{
    return amg_create_named("amg-hypre", 1, pat, mass, o, state, err);
}

/* Set the preconditioner up on A's full blocks as `mode` says
 * (linsol_amg_abi.h). */
static cl_status amg_prepare(cl_amg *s, int mode, cl_error *err)
{
    cl_plugin_msg msg = {.text = ""};
    cl_amat *A = &s->A;
    s->ready = false;
    /* all but a smoother refresh read A's full blocks */
    if (mode != CLP_AMG_SMOOTHER && !s->ablk_current) {
        cl_bsym_unpack(&A->sym, A->kind, A->sdiag, A->supper, A->ablk);
        s->ablk_current = true;
    }
    if (s->setup(s->h, A->ablk, mode, &msg) != 0)
        return cl_error_set(err, CL_ESOLVER, "%s: %s", s->name, msg.text);
    s->ready = true;
    bool fresh = mode == CLP_AMG_BUILD || mode == CLP_AMG_RECOVER;
    s->coarse_fresh = mode != CLP_AMG_SMOOTHER;
    if (s->coarse_fresh)
        s->cbase_iters = -1;
    s->galerkin_done = !fresh && (s->galerkin_done || s->coarse_fresh);
    if (fresh) {
        s->rebuilds++;
        s->base_iters = -1;
        s->last_iters = 0;
    }
    return CL_OK;
}

/* Whether the last solve took more than `factor` times `base`. */
static bool amg_grew(const cl_amg *s, long base, double factor)
{
    return base > 0 && (double)s->last_iters > factor * (double)base;
}

/* What this setup recomputes: everything at the first, and at every one
 * of amg-hypre's; a new hierarchy
 * when the last solve took more than CL_AMG_REGROW times the iterations of
 * the first after the last build although the coarse operators were
 * recomputed at the last setup; the coarse operators on the kept
 * interpolation when it took more than s->coarse_regrow times those of the
 * first after they were last recomputed (a new hierarchy once that factor
 * is CL_AMG_REGROW), or CL_AMG_REGROW times the build's; else the finest
 * smoother only. */
static int amg_mode(const cl_amg *s)
{
    if (s->rebuilds == 0 || s->hypre)
        return CLP_AMG_BUILD;
    bool grew = amg_grew(s, s->base_iters, CL_AMG_REGROW);
    if (grew && s->coarse_fresh)
        return CLP_AMG_BUILD;
    if (amg_grew(s, s->cbase_iters, s->coarse_regrow))
        return s->coarse_regrow < CL_AMG_REGROW ? CLP_AMG_GALERKIN
                                                : CLP_AMG_BUILD;
    return grew ? CLP_AMG_GALERKIN : CLP_AMG_SMOOTHER;
}

/* Judge the recompute the last setup made for a growth by this first solve
 * after it (`its`): it paid if the solve took fewer iterations than the
 * one that triggered it, and then the coarse operators' factor is back to
 * CL_AMG_COARSE_REGROW.  If not, the factor's excess over 1 doubles, up
 * to CL_AMG_REGROW; and if it was the first P^T A P on a new
 * interpolation, whose staleness cannot be the cause, the growth was the
 * problem's, and the rebuild's reference moves to `its` (a later one
 * that did not help may have a stale interpolation to blame, which only a
 * rebuild tests). */
static void amg_judge(cl_amg *s, long its)
{
    if (its < s->trigger_iters) {
        s->coarse_regrow = CL_AMG_COARSE_REGROW;
        return;
    }
    if (s->first_galerkin)
        s->base_iters = its;
    double f = 2.0 * s->coarse_regrow - 1.0;
    s->coarse_regrow = f < CL_AMG_REGROW ? f : CL_AMG_REGROW;
}

static cl_status amg_setup(void *state, double a, double b,
                           const double *dfdx, const double *dfdv,
                           cl_error *err)
{
    cl_amg *s = state;
    cl_amat *A = &s->A;
    s->ready = false;
    /* A's packed halves when it is symmetric (the full blocks the plug-in
     * reads are unpacked from them only when a setup recomputes), else
     * all its blocks */
    cl_amat_fill(A, a, b, dfdx, dfdv);
    s->ablk_current = A->kind == CL_BSYM_NONE;
    if (!cl_amat_finite(A))
        return cl_error_set(err, CL_ESOLVER, "%s: the matrix M - a df/dv - "
                            "b df/dx has entries that are not finite",
                            s->name);
    /* amg's finest smoother's diagonal blocks, inverted once per setup */
    size_t row = 0;
    bool sym = A->kind != CL_BSYM_NONE;
    if (!s->hypre && !cl_bgs_invert(A->pat->nb, sym ? A->sdiag : A->ablk,
                       sym ? NULL : A->pat->diag, s->dinv, &row))
        return cl_error_set(err, CL_ESOLVER, "%s: the diagonal block of "
                            "particle row %zu of M - a df/dv - b df/dx is "
                            "not positive definite (determinant not "
                            "positive)", s->name, row);
    /* what the next solve judges (amg_judge): a recompute for a growth
     * (amg-hypre's builds are not for one) */
    int mode = amg_mode(s);
    long trigger = mode != CLP_AMG_SMOOTHER && s->rebuilds > 0 && !s->hypre
                       ? s->last_iters : 0;
    bool first = mode == CLP_AMG_GALERKIN && !s->galerkin_done;
    cl_status st = amg_prepare(s, mode, err);
    if (st != CL_OK)
        return st;
    s->trigger_iters = trigger;
    s->first_galerkin = first;
    s->setups++;
    return CL_OK;
}

static void amg_jacobian(void *state, const double *dfdx, const double *dfdv)
{
    cl_amg *s = state;
    cl_amat_jacobian(&s->A, dfdx, dfdv);
}

/* CG to ||r||_2 <= max(rtol ||b||_2, atol); if that fails, once more on
 * a hierarchy rebuilt with careful eigenvalue bounds (CLP_AMG_RECOVER;
 * not for hypre, whose preconditioner was just built and has no such
 * bounds). */
static cl_status amg_run(cl_amg *s, const double *rhs, double *x,
                         double rtol, double atol, cl_error *err)
{
    cl_status st = cl_linsol_check_solve(s->name, s->ready, rhs, s->n, err);
    if (st != CL_OK)
        return st;
    if (x == rhs) { /* in place: CG starts from x = 0 */
        memcpy(s->rhs, rhs, s->n * sizeof *rhs);
        rhs = s->rhs;
    }
    cl_plugin_msg msg = {.text = ""};
    long its = 0;
    int bad = s->solve(s->h, rhs, x, rtol, atol, &its, &msg);
    s->solves++;
    s->iters += its;
    bool retry = bad && !s->hypre && !cl_stop_requested();
    if (retry) {
        st = amg_prepare(s, CLP_AMG_RECOVER, err);
        if (st != CL_OK && !cl_stop_requested())
            return st;
        if (st == CL_OK) {
            s->recoveries++;
            msg.text[0] = '\0';
            bad = s->solve(s->h, rhs, x, rtol, atol, &its, &msg);
            s->solves++;
            s->iters += its;
        }
    }
    if (bad && cl_stop_requested()) /* amg_mult's NaN, or a failure the
                                     * stop came after: the stop's */
        return cl_error_set(err, CL_EINTR, "%s: stopped by %s in iteration "
                            "%ld", s->name,
                            cl_stop_signal_name(cl_stop_requested()), its);
    if (bad)
        return cl_error_set(err, CL_ESOLVER, "%s: %s%s", s->name, msg.text,
                            retry ? " (also on a hierarchy rebuilt with "
                                    "careful eigenvalue bounds)"
                                  : "");
    s->last_iters = its;
    if (s->trigger_iters > 0 && !retry)
        amg_judge(s, its);
    s->trigger_iters = 0;
    if (s->base_iters < 0 && its > 0)
        s->base_iters = its;
    if (s->cbase_iters < 0 && its > 0)
        s->cbase_iters = its;
    return CL_OK;
}

static cl_status amg_solve(void *state, const double *rhs, double *x,
                           cl_error *err)
{
    cl_amg *s = state;
    return amg_run(s, rhs, x, s->tol, 0.0, err);
}

static cl_status amg_solve_tol(void *state, const double *rhs, double *x,
                               const double *w, double delta, cl_error *err)
{
    cl_amg *s = state;
    cl_status st = cl_linsol_check_weights(s->name, w, s->n, delta, err);
    if (st != CL_OK)
        return st;
    double wmax = 0.0;
    for (size_t i = 0; i < s->n; i++)
        wmax = fmax(wmax, w[i]);
    return amg_run(s, rhs, x, 0.0, delta / wmax, err);
}

static void amg_stats(const void *state, cl_stats *out)
{
    const cl_amg *s = state;
    out->lin_setups += s->setups;
    out->lin_solves += s->solves;
    out->lin_iters += s->iters;
    out->symbolic_facts += s->rebuilds;
    out->lin_recoveries += s->recoveries;
}

const cl_linsol_type cl_linsol_amg = {
    .name = "amg",
    .doc = "PETSc CG + GAMG smoothed aggregation (block size 3, block "
           "Gauss-Seidel on the finest level, Chebyshev/point-block Jacobi "
           "below), hierarchy reused across setups (A SPD)",
    .create = amg_create,
    .jacobian = amg_jacobian,
    .setup = amg_setup,
    .solve = amg_solve,
    .solve_tol = amg_solve_tol,
    .stats = amg_stats,
    .free = amg_free,
};

const cl_linsol_type cl_linsol_amg_hypre = {
    .name = "amg-hypre",
    .doc = "PETSc CG + hypre BoomerAMG, nodal coarsening (A SPD)",
    .create = amg_create_hypre,
    .jacobian = amg_jacobian,
    .setup = amg_setup,
    .solve = amg_solve,
    .solve_tol = amg_solve_tol,
    .stats = amg_stats,
    .free = amg_free,
};
