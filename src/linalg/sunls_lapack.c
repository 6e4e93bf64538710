/* Dense LU through LAPACK as a SUNLinearSolver (see sunls_lapack.h). */
#include "linalg/sunls_lapack.h"

#include <lapacke.h>
#include <stdlib.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "linalg/sunls.h"

typedef struct {
    lapack_int n;
    lapack_int *pivots;
    sunindextype last_flag;
} lapack_content;

static int lapack_initialize(SUNLinearSolver S)
{
    ((lapack_content *)S->content)->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
}

/* A = P L U in place. */
static int lapack_setup(SUNLinearSolver S, SUNMatrix A)
{
    lapack_content *c = S->content;
    lapack_int info = LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, c->n, c->n,
                                          SUNDenseMatrix_Data(A), c->n,
                                          c->pivots);
    c->last_flag = info;
    return info < 0 ? SUNLS_PACKAGE_FAIL_UNREC : (int)info;
}

/* x = A^-1 b from the factors of the last setup. */
static int lapack_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x,
                        N_Vector b, sunrealtype tol)
{
    (void)tol;
    lapack_content *c = S->content;
    N_VScale(1.0, b, x);
    lapack_int info = LAPACKE_dgetrs_work(
        LAPACK_COL_MAJOR, 'N', c->n, 1, SUNDenseMatrix_Data(A), c->n,
        c->pivots, N_VGetArrayPointer(x), c->n);
    c->last_flag = info;
    return info ? SUNLS_PACKAGE_FAIL_UNREC : SUNLS_SUCCESS;
}

static sunindextype lapack_lastflag(SUNLinearSolver S)
{
    return ((lapack_content *)S->content)->last_flag;
}

static int lapack_space(SUNLinearSolver S, long *lrw, long *liw)
{
    *lrw = 0;
    *liw = 2 + ((lapack_content *)S->content)->n;
    return SUNLS_SUCCESS;
}

static int lapack_free(SUNLinearSolver S)
{
    if (S) {
        lapack_content *c = S->content;
        if (c)
            free(c->pivots);
        free(c);
        S->content = NULL;
        SUNLinSolFreeEmpty(S);
    }
    return SUNLS_SUCCESS;
}

SUNLinearSolver cl_sunls_lapack_dense(N_Vector y, SUNContext ctx)
{
    SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
    if (!S)
        return NULL;
    S->ops->gettype = cl_sunls_type_direct;
    S->ops->getid = cl_sunls_id_custom;
    S->ops->initialize = lapack_initialize;
    S->ops->setup = lapack_setup;
    S->ops->solve = lapack_solve;
    S->ops->lastflag = lapack_lastflag;
    S->ops->space = lapack_space;
    S->ops->free = lapack_free;
    lapack_content *c = calloc(1, sizeof *c);
    S->content = c;
    if (c) {
        c->n = (lapack_int)N_VGetLength(y);
        c->pivots = malloc((size_t)(c->n > 0 ? c->n : 1) * sizeof *c->pivots);
    }
    if (!c || !c->pivots) {
        lapack_free(S);
        return NULL;
    }
    return S;
}
