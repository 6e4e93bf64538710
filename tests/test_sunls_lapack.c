/* The LAPACK dense SUNLinearSolver: solves against a known solution, a
 * factorisation reused for several right-hand sides, a zero pivot
 * reported as a recoverable (positive) setup failure, and its identity. */
#include <criterion/criterion.h>

#include <math.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "integrators/sunls_lapack.h"

typedef struct {
    SUNContext ctx;
    N_Vector x, b;
    SUNMatrix A;
    SUNLinearSolver S;
} fixture;

static void fixture_open(fixture *f, sunindextype n)
{
    cr_assert_eq(SUNContext_Create(NULL, &f->ctx), 0);
    f->x = N_VNew_Serial(n, f->ctx);
    f->b = N_VNew_Serial(n, f->ctx);
    f->A = SUNDenseMatrix(n, n, f->ctx);
    f->S = cl_sunls_lapack_dense(f->x, f->ctx);
    cr_assert(f->x && f->b && f->A && f->S);
    cr_assert_eq(SUNLinSolInitialize(f->S), SUNLS_SUCCESS);
}

static void fixture_close(fixture *f)
{
    SUNLinSolFree(f->S);
    SUNMatDestroy(f->A);
    N_VDestroy(f->b);
    N_VDestroy(f->x);
    SUNContext_Free(&f->ctx);
}

/* A non-symmetric, well-conditioned matrix that needs pivoting (zero
 * leading entry): A_ij = cos(i j + i) + 4 [i == j], except A_00 = 0. */
static void fill_matrix(SUNMatrix A, sunindextype n)
{
    for (sunindextype j = 0; j < n; j++)
        for (sunindextype i = 0; i < n; i++)
            SM_ELEMENT_D(A, i, j) = cos((double)(i * j + i)) +
                                    (i == j ? 4.0 : 0.0);
    SM_ELEMENT_D(A, 0, 0) = 0.0;
}

/* b = A x for x_i = sin(i + shift). */
static void fill_rhs(const double *A, sunindextype n, double shift,
                     double *b, double *x)
{
    for (sunindextype i = 0; i < n; i++)
        x[i] = sin((double)i + shift);
    for (sunindextype i = 0; i < n; i++) {
        b[i] = 0.0;
        for (sunindextype j = 0; j < n; j++)
            b[i] += A[j * n + i] * x[j];
    }
}

Test(sunls_lapack, solves_with_pivoting_for_several_rhs)
{
    enum { N = 40 };
    fixture f;
    fixture_open(&f, N);
    fill_matrix(f.A, N);
    double A[N * N], want[N];
    for (int k = 0; k < N * N; k++)
        A[k] = SUNDenseMatrix_Data(f.A)[k];
    cr_assert_eq(SUNLinSolSetup(f.S, f.A), SUNLS_SUCCESS);
    for (int r = 0; r < 3; r++) {
        fill_rhs(A, N, 0.7 * r, N_VGetArrayPointer(f.b), want);
        cr_assert_eq(SUNLinSolSolve(f.S, f.A, f.x, f.b, 0.0), SUNLS_SUCCESS);
        const double *x = N_VGetArrayPointer(f.x);
        for (int i = 0; i < N; i++)
            cr_assert_float_eq(x[i], want[i], 1e-11, "rhs %d, x[%d]", r, i);
    }
    cr_assert_eq(SUNLinSolLastFlag(f.S), 0);
    fixture_close(&f);
}

Test(sunls_lapack, zero_pivot_is_recoverable)
{
    fixture f;
    fixture_open(&f, 3);
    fill_matrix(f.A, 3);
    for (int i = 0; i < 3; i++) /* column 2 = column 1 */
        SM_ELEMENT_D(f.A, i, 2) = SM_ELEMENT_D(f.A, i, 1);
    int flag = SUNLinSolSetup(f.S, f.A);
    cr_assert_eq(flag, 3, "setup returned %d", flag);
    cr_assert_eq(SUNLinSolLastFlag(f.S), 3);
    fixture_close(&f);
}

Test(sunls_lapack, is_a_custom_direct_solver)
{
    fixture f;
    fixture_open(&f, 2);
    cr_assert_eq(SUNLinSolGetType(f.S), SUNLINEARSOLVER_DIRECT);
    cr_assert_eq(SUNLinSolGetID(f.S), SUNLINEARSOLVER_CUSTOM);
    long lrw = -1, liw = -1;
    cr_assert_eq(SUNLinSolSpace(f.S, &lrw, &liw), SUNLS_SUCCESS);
    cr_assert_eq(liw, 4);
    fixture_close(&f);
}
