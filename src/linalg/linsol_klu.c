/* klu: sparse LU of the reduced matrix A = M - a df/dv - b df/dx
 * (docs/model.md, 1; docs/integrators.md, 5) with KLU, called directly
 * through its 64-bit klu_l_* interface (SuiteSparse_long indices, as wide
 * as SUNDIALS' sunindextype on Debian).
 *
 *  create  builds A's CSC pattern and value map once (linalg/reduced.h) and
 *          runs the symbolic analysis klu_l_analyze once, with AMD ordering
 *          (Common.ordering = 0; KLU's BTF pre-ordering left on);
 *  setup   fills the values (no search, no allocation) and factorises
 *          numerically: klu_l_factor at the first setup, klu_l_refactor
 *          (same pivot order, no allocation) afterwards.  A refactorisation
 *          that fails (a zero pivot in the old order) or whose reciprocal
 *          pivot ratio klu_l_rcond (min |U_ii| / max |U_ii|) falls below
 *          eps^(2/3) ~ 3.7e-11 (SUNDIALS' own threshold in sunlinsol_klu.c)
 *          is replaced by a fresh klu_l_factor, which pivots anew; these
 *          fall-backs are counted (`fallbacks`, not part of cl_stats) and
 *          reuse the same symbolic analysis;
 *  solve   klu_l_solve in place on a copy of the right-hand side.
 *
 * Statistics: lin_setups = setup calls that produced a factorisation,
 * lin_solves = solves, symbolic_facts = successful klu_l_analyze calls (1
 * for the life of the solver: the pattern never changes).  A singular A
 * (KLU_SINGULAR from klu_l_factor) or any other KLU failure is CL_ESOLVER
 * naming the KLU routine and its status. */
#include "linalg/linsol.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include <klu.h>

#include "core/check.h"
#include "linalg/reduced.h"

typedef struct {
    cl_reduced red;
    double *val;            /* nnz values of A, CSC order */
    klu_l_common common;
    klu_l_symbolic *sym;
    klu_l_numeric *num;
    bool ready;             /* the last setup succeeded */
    long setups, solves, analyses, fallbacks;
} cl_klu;

static cl_status klu_fail(const cl_klu *s, const char *fn, cl_error *err)
{
    long st = (long)s->common.status;
    if (st == KLU_SINGULAR)
        return cl_error_set(err, CL_ESOLVER,
                            "klu: %s: the matrix M - a df/dv - b df/dx is "
                            "singular (zero pivot, column %ld)", fn,
                            (long)s->common.singular_col);
    return cl_error_set(err, CL_ESOLVER, "klu: %s failed (KLU status %ld%s)",
                        fn, st,
                        st == KLU_OUT_OF_MEMORY ? ": out of memory" : "");
}

static void lklu_free(void *state)
{
    cl_klu *s = state;
    if (!s)
        return;
    if (s->num)
        klu_l_free_numeric(&s->num, &s->common);
    if (s->sym)
        klu_l_free_symbolic(&s->sym, &s->common);
    cl_reduced_free(&s->red);
    free(s->val);
    free(s);
}

static cl_status lklu_analyse(cl_klu *s, cl_error *err)
{
    if (!klu_l_defaults(&s->common))
        return klu_fail(s, "klu_l_defaults", err);
    s->common.ordering = 0; /* AMD */
    s->sym = klu_l_analyze((SuiteSparse_long)s->red.n, s->red.colptr,
                           s->red.rowind, &s->common);
    if (!s->sym)
        return klu_fail(s, "klu_l_analyze", err);
    s->analyses++;
    return CL_OK;
}

static cl_status lklu_create(const cl_bpattern *pat, const double *mass,
                             const cl_linsol_opts *opts, void **state,
                             cl_error *err)
{
    (void)opts;
    *state = NULL;
    if (!pat || pat->nb == 0)
        return cl_error_set(err, CL_EINVAL, "klu: empty system (no free "
                            "particles)");
    cl_klu *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "klu: out of memory");
    cl_error inner = {0};
    cl_status st = cl_reduced_create(pat, mass, &s->red, &inner);
    if (st != CL_OK)
        cl_error_set(err, st, "klu: %s", inner.msg);
    if (st == CL_OK) {
        s->val = malloc((size_t)s->red.nnz * sizeof *s->val);
        if (!s->val)
            st = cl_error_set(err, CL_ENOMEM, "klu: out of memory");
    }
    if (st == CL_OK)
        st = lklu_analyse(s, err);
    if (st != CL_OK) {
        lklu_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

static cl_status lklu_factor(cl_klu *s, cl_error *err)
{
    if (s->num)
        klu_l_free_numeric(&s->num, &s->common);
    s->num = klu_l_factor(s->red.colptr, s->red.rowind, s->val, s->sym,
                          &s->common);
    return s->num ? CL_OK : klu_fail(s, "klu_l_factor", err);
}

/* Numeric refactorisation in the old pivot order; true if usable. */
static bool lklu_refactor(cl_klu *s)
{
    const double rcond_min = pow(DBL_EPSILON, 2.0 / 3.0);
    if (!klu_l_refactor(s->red.colptr, s->red.rowind, s->val, s->sym,
                        s->num, &s->common))
        return false;
    if (!klu_l_rcond(s->sym, s->num, &s->common))
        return false;
    return s->common.rcond >= rcond_min;
}

static cl_status lklu_setup(void *state, double a, double b,
                            const double *dfdx, const double *dfdv,
                            cl_error *err)
{
    cl_klu *s = state;
    s->ready = false;
    cl_reduced_fill(&s->red, a, b, dfdx, dfdv, s->val);
    if (!cl_all_finite(s->val, (size_t)s->red.nnz)) /* no factors of it */
        return cl_error_set(err, CL_ESOLVER, "klu: the matrix M - a df/dv "
                            "- b df/dx has entries that are not finite");
    cl_status st = CL_OK;
    if (!s->num) {
        st = lklu_factor(s, err);
    } else if (!lklu_refactor(s)) {
        s->fallbacks++;
        st = lklu_factor(s, err);
    }
    if (st == CL_OK)
        s->setups++;
    s->ready = st == CL_OK;
    return st;
}

static cl_status lklu_solve(void *state, const double *rhs, double *x,
                            cl_error *err)
{
    cl_klu *s = state;
    if (!s->ready)
        return cl_error_set(err, CL_EINVAL, "klu: solve without a "
                            "successful setup");
    if (x != rhs)
        memcpy(x, rhs, s->red.n * sizeof *x);
    if (!klu_l_solve(s->sym, s->num, (SuiteSparse_long)s->red.n, 1, x,
                     &s->common))
        return klu_fail(s, "klu_l_solve", err);
    s->solves++;
    return CL_OK;
}

static void lklu_stats(const void *state, cl_stats *out)
{
    const cl_klu *s = state;
    out->lin_setups += s->setups;
    out->lin_solves += s->solves;
    out->symbolic_facts += s->analyses;
}

const cl_linsol_type cl_linsol_klu = {
    .name = "klu",
    .factors = 2,
    .doc = "sparse LU (KLU, AMD ordering): analyse once, refactor per setup",
    .create = lklu_create,
    .setup = lklu_setup,
    .solve = lklu_solve,
    .stats = lklu_stats,
    .free = lklu_free,
};
