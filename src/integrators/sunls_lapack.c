/* Dense LU through LAPACK as a SUNLinearSolver (see sunls_lapack.h), a
 * shell of the SUNDIALS adapter (sun_adapter.h) that owns its content. */
#include "integrators/sunls_lapack.h"

#include <lapacke.h>
#include <stdlib.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "integrators/sun_adapter.h"

typedef struct {
    lapack_int n;
    lapack_int *pivots;
    sunindextype last_flag;
} lapack_content;

static int lapack_initialize(void *data)
{
    ((lapack_content *)data)->last_flag = SUNLS_SUCCESS;
    return SUNLS_SUCCESS;
}

/* A = P L U in place. */
static int lapack_setup(void *data, SUNMatrix A)
{
    lapack_content *c = data;
    lapack_int info = LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, c->n, c->n,
                                          SUNDenseMatrix_Data(A), c->n,
                                          c->pivots);
    c->last_flag = info;
    return info < 0 ? SUNLS_PACKAGE_FAIL_UNREC : (int)info;
}

/* x = A^-1 b from the factors of the last setup. */
static int lapack_solve(void *data, SUNMatrix A, N_Vector x, N_Vector b,
                        sunrealtype tol)
{
    (void)tol;
    lapack_content *c = data;
    N_VScale(1.0, b, x);
    lapack_int info = LAPACKE_dgetrs_work(
        LAPACK_COL_MAJOR, 'N', c->n, 1, SUNDenseMatrix_Data(A), c->n,
        c->pivots, N_VGetArrayPointer(x), c->n);
    c->last_flag = info;
    return info ? SUNLS_PACKAGE_FAIL_UNREC : SUNLS_SUCCESS;
}

static sunindextype lapack_lastflag(void *data)
{
    return ((lapack_content *)data)->last_flag;
}

static int lapack_space(void *data, long *lrw, long *liw)
{
    *lrw = 0;
    *liw = 2 + ((lapack_content *)data)->n;
    return SUNLS_SUCCESS;
}

static void lapack_free(void *data)
{
    lapack_content *c = data;
    if (c)
        free(c->pivots);
    free(c);
}

static const cl_sun_lsdef lapack_def = {
    .type = SUNLINEARSOLVER_DIRECT,
    .initialize = lapack_initialize,
    .setup = lapack_setup,
    .solve = lapack_solve,
    .lastflag = lapack_lastflag,
    .space = lapack_space,
    .free = lapack_free,
};

SUNLinearSolver cl_sunls_lapack_dense(N_Vector y, SUNContext ctx)
{
    lapack_content *c = calloc(1, sizeof *c);
    if (c) {
        c->n = (lapack_int)N_VGetLength(y);
        c->pivots = malloc((size_t)(c->n > 0 ? c->n : 1) * sizeof *c->pivots);
    }
    SUNLinearSolver S = c && c->pivots ? cl_sun_shell_linsol(&lapack_def, c,
                                                             ctx)
                                       : NULL;
    if (!S)
        lapack_free(c);
    return S;
}
