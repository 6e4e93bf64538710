/* cholmod: supernodal sparse Cholesky of the reduced matrix
 * (docs/model.md, 1; docs/integrators.md, 5)
 *
 *     A = M - a df/dv - b df/dx = P^T L L^T P
 *
 * by SuiteSparse CHOLMOD through its 64-bit cholmod_l_* interface
 * (SuiteSparse_long indices, like klu_l_*), for the symmetric positive
 * definite case:
 *
 *  create  keeps the upper triangle of A's CSC pattern (linalg/reduced.h:
 *          the entries with row <= column, stype = 1), a value map and,
 *          for every stored entry (i, j), the block value feeding its
 *          mirror (j, i); then the symbolic analysis cholmod_l_analyze
 *          once: supernodal (Common.supernodal = CHOLMOD_SUPERNODAL),
 *          fill-reducing ordering the better of AMD and METIS
 *          (Common.nmethods = 2).  Measured on hang's matrix (h = 1e-3):
 *          n = 16, 32 AMD and METIS alike (factor 8-10 ms, 50-54 ms);
 *          n = 64 METIS 16 % less fill and 24 % faster (593 vs 778 ms);
 *          CHOLMOD's default (AMD alone unless its fill is poor) kept AMD
 *          there;
 *  setup   fills the upper values and checks symmetry on the way,
 *              max |A_ij - A_ji| <= 1e-10 max |A_ij|,
 *          then factorises numerically, cholmod_l_factorize (same
 *          symbolic factor, no allocation);
 *  solve   cholmod_l_solve2 (CHOLMOD_A) with its solution and workspace
 *          kept from one solve to the next.
 *
 * Fallback.  A setup whose A is not symmetric (the test above: CHOLMOD
 * would read the upper triangle only) or not positive definite (CHOLMOD
 * reports Common.status == CHOLMOD_NOT_POSDEF, e.g. jacobian.transverse =
 * full under compression, where the transverse term is negative) is handed
 * to klu (linsol_klu.c) for that setup and its solves: klu factorises A as
 * it is.  The klu solver is created at the first fallback (one allocation
 * and one symbolic analysis in the life of the solver) and kept.  Every
 * fallback is counted (cl_stats.lin_fallbacks) and noted once in the
 * statistics: linsol reads "cholmod+klu" instead of "cholmod".  Nothing is
 * hidden: the solve is exact either way.
 *
 * Statistics: lin_setups = setups that produced a factorisation (either
 * solver), lin_solves = solves, symbolic_facts = CHOLMOD's analysis plus
 * klu's, lin_fallbacks.  CHOLMOD failures other than indefiniteness (out
 * of memory, ...) are CL_ESOLVER naming the routine and CHOLMOD's status;
 * CHOLMOD prints nothing (Common.print = 0). */
#include "linalg/linsol.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>

#include "core/check.h"
#include "linalg/reduced.h"

#define CL_CHOL_SYMTOL 1e-10
#define CL_CHOL_NOMIRROR SIZE_MAX

extern const cl_linsol_type cl_linsol_klu;

typedef struct {
    const cl_bpattern *pat;     /* borrowed (for the klu fallback) */
    cl_linsol_opts opts;    /* copy (for the klu fallback) */
    size_t n;
    double *mass;               /* n */
    cholmod_common c;
    bool started;               /* cholmod_l_start succeeded */
    cholmod_sparse *A;          /* upper triangle, stype 1 */
    size_t *src, *mirror;       /* per stored entry: block-value indices */
    SuiteSparse_long *diagpos;  /* n: position of (i, i) */
    cholmod_factor *L;
    cholmod_dense *B, *X, *Y, *E;
    void *klu;                  /* fallback solver, NULL until needed */
    bool use_klu;               /* the last setup went to klu */
    bool ready;                 /* the last setup succeeded */
    long setups, solves, fallbacks;
} cl_chol;

static cl_status chol_fail(const cl_chol *s, const char *fn, cl_error *err)
{
    return cl_error_set(err, CL_ESOLVER, "cholmod: %s failed (CHOLMOD status "
                        "%d%s)", fn, s->c.status,
                        s->c.status == CHOLMOD_OUT_OF_MEMORY
                            ? ": out of memory" : "");
}

static void chol_free(void *state)
{
    cl_chol *s = state;
    if (!s)
        return;
    if (s->started) {
        cholmod_l_free_factor(&s->L, &s->c);
        cholmod_l_free_sparse(&s->A, &s->c);
        cholmod_l_free_dense(&s->B, &s->c);
        cholmod_l_free_dense(&s->X, &s->c);
        cholmod_l_free_dense(&s->Y, &s->c);
        cholmod_l_free_dense(&s->E, &s->c);
        cholmod_l_finish(&s->c);
    }
    if (s->klu)
        cl_linsol_klu.free(s->klu);
    free(s->mass);
    free(s->src);
    free(s->mirror);
    free(s->diagpos);
    free(s);
}

/* ---- the upper triangle of A ------------------------------------------- */

/* Position of row `row` in column `col` of r, or -1. */
static SuiteSparse_long chol_find(const cl_reduced *r, size_t row, size_t col)
{
    for (SuiteSparse_long e = r->colptr[col]; e < r->colptr[col + 1]; e++) {
        if ((size_t)r->rowind[e] == row)
            return e;
    }
    return -1;
}

static size_t chol_count_upper(const cl_reduced *r)
{
    size_t cnt = 0;
    for (size_t j = 0; j < r->n; j++) {
        for (SuiteSparse_long e = r->colptr[j]; e < r->colptr[j + 1]; e++)
            cnt += (size_t)r->rowind[e] <= j;
    }
    return cnt;
}

/* Copy the upper triangle of r into s->A with its value map. */
static void chol_copy_upper(cl_chol *s, const cl_reduced *r)
{
    SuiteSparse_long *Ap = s->A->p, *Ai = s->A->i, k = 0;
    for (size_t j = 0; j < r->n; j++) {
        Ap[j] = k;
        for (SuiteSparse_long e = r->colptr[j]; e < r->colptr[j + 1]; e++) {
            size_t i = (size_t)r->rowind[e];
            if (i > j)
                continue;
            SuiteSparse_long m = chol_find(r, j, i);
            Ai[k] = (SuiteSparse_long)i;
            s->src[k] = r->src[e];
            s->mirror[k] = m < 0 ? CL_CHOL_NOMIRROR : r->src[m];
            if (i == j)
                s->diagpos[j] = k;
            k++;
        }
    }
    Ap[r->n] = k;
    memset(s->A->x, 0, (size_t)k * sizeof(double));
}

static cl_status chol_alloc(cl_chol *s, size_t nnz, cl_error *err)
{
    s->src = malloc((nnz ? nnz : 1) * sizeof *s->src);
    s->mirror = malloc((nnz ? nnz : 1) * sizeof *s->mirror);
    s->diagpos = malloc(s->n * sizeof *s->diagpos);
    if (!s->src || !s->mirror || !s->diagpos)
        return cl_error_set(err, CL_ENOMEM, "cholmod: out of memory");
    s->A = cholmod_l_allocate_sparse(s->n, s->n, nnz, 1, 1, 1, CHOLMOD_REAL,
                                     &s->c);
    s->B = cholmod_l_allocate_dense(s->n, 1, s->n, CHOLMOD_REAL, &s->c);
    if (!s->A || !s->B)
        return chol_fail(s, "cholmod_l_allocate_sparse/dense", err);
    return CL_OK;
}

/* Pattern from the reduced matrix, then the symbolic analysis. */
static cl_status chol_build(cl_chol *s, cl_error *err)
{
    cl_reduced r;
    cl_error inner = {0};
    cl_status st = cl_reduced_create(s->pat, s->mass, &r, &inner);
    if (st != CL_OK)
        return cl_error_set(err, st, "cholmod: %s", inner.msg);
    st = chol_alloc(s, chol_count_upper(&r), err);
    if (st == CL_OK)
        chol_copy_upper(s, &r);
    cl_reduced_free(&r);
    if (st != CL_OK)
        return st;
    s->L = cholmod_l_analyze(s->A, &s->c);
    return s->L ? CL_OK : chol_fail(s, "cholmod_l_analyze", err);
}

static cl_status chol_start(cl_chol *s, cl_error *err)
{
    if (!cholmod_l_start(&s->c))
        return chol_fail(s, "cholmod_l_start", err);
    s->started = true;
    s->c.print = 0;
    s->c.supernodal = CHOLMOD_SUPERNODAL;
    s->c.nmethods = 2;
    s->c.method[0].ordering = CHOLMOD_AMD;
    s->c.method[1].ordering = CHOLMOD_METIS;
    s->c.quick_return_if_not_posdef = 1;
    return CL_OK;
}

static cl_status chol_create(const cl_bpattern *pat, const double *mass,
                             const cl_linsol_opts *opts, void **state,
                             cl_error *err)
{
    *state = NULL;
    if (!pat || pat->nb == 0)
        return cl_error_set(err, CL_EINVAL, "cholmod: empty system (no free "
                            "particles)");
    cl_chol *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "cholmod: out of memory");
    s->pat = pat;
    s->opts = *opts;
    s->n = 3 * pat->nb;
    s->mass = malloc(s->n * sizeof *s->mass);
    cl_status st = s->mass ? chol_start(s, err)
                           : cl_error_set(err, CL_ENOMEM, "cholmod: out of "
                                          "memory");
    if (st == CL_OK) {
        memcpy(s->mass, mass, s->n * sizeof *s->mass);
        st = chol_build(s, err);
    }
    if (st != CL_OK) {
        chol_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

/* ---- setup / solve ----------------------------------------------------- */

/* Upper values of A; true if A is symmetric (see the header). */
static bool chol_fill(cl_chol *s, double a, double b, const double *dfdx,
                      const double *dfdv)
{
    double *Ax = s->A->x, amax = 0.0, dmax = 0.0;
    size_t nnz = (size_t)((SuiteSparse_long *)s->A->p)[s->n];
    for (size_t k = 0; k < nnz; k++) {
        size_t q = s->src[k], m = s->mirror[k];
        Ax[k] = -a * dfdv[q] - b * dfdx[q];
        double mv = m == CL_CHOL_NOMIRROR ? 0.0 : -a * dfdv[m] - b * dfdx[m];
        dmax = fmax(dmax, fabs(Ax[k] - mv));
    }
    for (size_t i = 0; i < s->n; i++)
        Ax[s->diagpos[i]] += s->mass[i];
    for (size_t k = 0; k < nnz; k++)
        amax = fmax(amax, fabs(Ax[k]));
    return dmax <= CL_CHOL_SYMTOL * amax;
}

/* This setup goes to klu (created at the first need). */
static cl_status chol_fallback(cl_chol *s, double a, double b,
                               const double *dfdx, const double *dfdv,
                               cl_error *err)
{
    s->fallbacks++;
    s->use_klu = true;
    if (!s->klu) {
        cl_status st = cl_linsol_klu.create(s->pat, s->mass, &s->opts,
                                            &s->klu, err);
        if (st != CL_OK)
            return st;
    }
    return cl_linsol_klu.setup(s->klu, a, b, dfdx, dfdv, err);
}

static cl_status chol_setup(void *state, double a, double b,
                            const double *dfdx, const double *dfdv,
                            cl_error *err)
{
    cl_chol *s = state;
    cl_status st = CL_OK;
    s->ready = false;
    s->use_klu = false;
    bool symmetric = chol_fill(s, a, b, dfdx, dfdv);
    size_t nnz = (size_t)((SuiteSparse_long *)s->A->p)[s->n];
    if (!cl_all_finite(s->A->x, nnz))
        return cl_error_set(err, CL_ESOLVER, "cholmod: the matrix M - a "
                            "df/dv - b df/dx has entries that are not "
                            "finite");
    if (!symmetric) {
        st = chol_fallback(s, a, b, dfdx, dfdv, err);
    } else if (!cholmod_l_factorize(s->A, s->L, &s->c)) {
        return chol_fail(s, "cholmod_l_factorize", err);
    } else if (s->c.status == CHOLMOD_NOT_POSDEF) {
        st = chol_fallback(s, a, b, dfdx, dfdv, err);
    } else if (s->c.status != CHOLMOD_OK) {
        return chol_fail(s, "cholmod_l_factorize", err);
    }
    if (st == CL_OK) {
        s->ready = true;
        s->setups++;
    }
    return st;
}

static cl_status chol_solve(void *state, const double *rhs, double *x,
                            cl_error *err)
{
    cl_chol *s = state;
    if (!s->ready)
        return cl_error_set(err, CL_EINVAL, "cholmod: solve without a "
                            "successful setup");
    s->solves++;
    if (s->use_klu)
        return cl_linsol_klu.solve(s->klu, rhs, x, err);
    memcpy(s->B->x, rhs, s->n * sizeof *rhs);
    if (!cholmod_l_solve2(CHOLMOD_A, s->L, s->B, NULL, &s->X, NULL, &s->Y,
                          &s->E, &s->c))
        return chol_fail(s, "cholmod_l_solve2", err);
    memcpy(x, s->X->x, s->n * sizeof *x);
    return CL_OK;
}

/* CHOLMOD's flop count of the factorisation (Common.fl) and 4 nnz(L) for
 * the two triangular solves, from the analysis of the chosen ordering. */
static void chol_cost(const void *state, double *setup_flops,
                      double *solve_flops)
{
    const cl_chol *s = state;
    *setup_flops = s->c.fl;
    *solve_flops = 4.0 * s->c.lnz;
}

static void chol_stats(const void *state, cl_stats *out)
{
    const cl_chol *s = state;
    cl_stats k = {0};
    if (s->klu)
        cl_linsol_klu.stats(s->klu, &k);
    out->lin_setups += s->setups;
    out->lin_solves += s->solves;
    out->symbolic_facts += 1 + k.symbolic_facts;
    out->lin_fallbacks += s->fallbacks;
    snprintf(out->linsol, sizeof out->linsol, "%s",
             s->fallbacks ? "cholmod+klu" : "cholmod");
}

const cl_linsol_type cl_linsol_cholmod = {
    .name = "cholmod",
    .factors = 1,
    .doc = "supernodal sparse Cholesky (CHOLMOD): analyse once, factorise "
           "per setup; klu when A is not SPD",
    .create = chol_create,
    .setup = chol_setup,
    .solve = chol_solve,
    .cost = chol_cost,
    .stats = chol_stats,
    .free = chol_free,
};
