/* First-order Jacobian J = [[0, I], [M^-1 df/dx, M^-1 df/dv]] in CSC:
 * compared entry by entry with a dense matrix built independently from the
 * block pattern, on random non-symmetric blocks over a pattern with a pinned
 * particle; structure (sorted rows, full diagonal), refill after SUNMatZero,
 * in-place I - gamma J, argument checks. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <sundials/sundials_context.h>

#include "linalg/firstorder.h"

#include "blockcase.h" /* last: defines NP, NB, N */

#define NN (2 * N)

typedef struct {
    cl_bpattern pat;
    double mass[N];
    double *dfdx, *dfdv;
    cl_firstorder fo;
} fo_case;

static void case_init(fo_case *c)
{
    memset(c, 0, sizeof *c);
    bc_init(&c->pat, c->mass, &c->dfdx, &c->dfdv);
    unsigned long seed = 12345;
    size_t nval = 9 * c->pat.nnzb;
    for (size_t k = 0; k < nval; k++) {
        c->dfdx[k] = bc_rand(&seed) + (bc_rand(&seed) > 0 ? 2.0 : -2.0);
        c->dfdv[k] = bc_rand(&seed) + (bc_rand(&seed) > 0 ? 2.0 : -2.0);
    }
    cl_error err;
    cr_assert_eq(cl_firstorder_create(&c->pat, c->mass, &c->fo, &err), CL_OK,
                 "%s", err.msg);
}

static void case_free(fo_case *c)
{
    cl_firstorder_free(&c->fo);
    bc_free(&c->pat, c->dfdx, c->dfdv);
}

/* Dense reference, row-major NN x NN, from the block CSR directly. */
static void dense_reference(const fo_case *c, double *D)
{
    memset(D, 0, NN * NN * sizeof *D);
    for (size_t i = 0; i < N; i++)
        D[i * NN + N + i] = 1.0;
    for (size_t bi = 0; bi < NB; bi++) {
        for (size_t k = c->pat.rowptr[bi]; k < c->pat.rowptr[bi + 1]; k++) {
            size_t bj = c->pat.col[k];
            for (size_t r = 0; r < 3; r++) {
                size_t row = N + 3 * bi + r;
                double m = c->mass[3 * bi + r];
                for (size_t q = 0; q < 3; q++) {
                    D[row * NN + 3 * bj + q] = c->dfdx[9 * k + 3 * r + q] / m;
                    D[row * NN + N + 3 * bj + q] =
                        c->dfdv[9 * k + 3 * r + q] / m;
                }
            }
        }
    }
}

/* Expand CSC arrays to dense; hits[] counts how often each entry is stored. */
static void expand(const sunindextype *cp, const sunindextype *rv,
                   const double *val, double *D, int *hits)
{
    memset(D, 0, NN * NN * sizeof *D);
    memset(hits, 0, NN * NN * sizeof *hits);
    for (size_t j = 0; j < NN; j++) {
        for (sunindextype k = cp[j]; k < cp[j + 1]; k++) {
            cr_assert(rv[k] >= 0 && rv[k] < NN, "row %ld", (long)rv[k]);
            D[(size_t)rv[k] * NN + j] += val[k];
            hits[(size_t)rv[k] * NN + j]++;
        }
    }
}

Test(firstorder, matches_dense_reference)
{
    fo_case c;
    case_init(&c);
    static double ref[NN * NN], got[NN * NN];
    static int hits[NN * NN];
    sunindextype *cp = malloc((NN + 1) * sizeof *cp);
    sunindextype *rv = malloc((size_t)c.fo.nnz * sizeof *rv);
    double *val = malloc((size_t)c.fo.nnz * sizeof *val);
    cl_firstorder_fill_arrays(&c.fo, c.dfdx, c.dfdv, cp, rv, val);
    dense_reference(&c, ref);
    expand(cp, rv, val, got, hits);
    for (size_t r = 0; r < NN; r++) {
        for (size_t q = 0; q < NN; q++) {
            double a = ref[r * NN + q], b = got[r * NN + q];
            cr_assert(fabs(a - b) <= 1e-15 * fabs(a), "J(%zu,%zu) = %.17g, "
                      "reference %.17g", r, q, b, a);
            int stored = a != 0.0 || r == q;
            cr_assert_eq(hits[r * NN + q], stored, "J(%zu,%zu) stored %d "
                         "times", r, q, hits[r * NN + q]);
        }
    }
    free(cp);
    free(rv);
    free(val);
    case_free(&c);
}

/* The dense form (GSL's msbdf, spectra) equals the CSC matrix expanded. */
Test(firstorder, dense_equals_csc)
{
    fo_case c;
    case_init(&c);
    static double csc[NN * NN], dense[NN * NN];
    static int hits[NN * NN];
    double inv_mass[N];
    for (size_t i = 0; i < N; i++)
        inv_mass[i] = 1.0 / c.mass[i];
    sunindextype *cp = malloc((NN + 1) * sizeof *cp);
    sunindextype *rv = malloc((size_t)c.fo.nnz * sizeof *rv);
    double *val = malloc((size_t)c.fo.nnz * sizeof *val);
    cr_assert(cp && rv && val);
    cl_firstorder_fill_arrays(&c.fo, c.dfdx, c.dfdv, cp, rv, val);
    expand(cp, rv, val, csc, hits);
    cl_firstorder_dense(&c.pat, inv_mass, c.dfdx, c.dfdv, dense);
    for (size_t k = 0; k < NN * NN; k++)
        cr_assert(fabs(dense[k] - csc[k]) <= 1e-15 * fabs(csc[k]),
                  "J(%zu,%zu) = %.17g, CSC %.17g", k / NN, k % NN, dense[k],
                  csc[k]);
    free(cp);
    free(rv);
    free(val);
    case_free(&c);
}

Test(firstorder, structure_sorted_with_full_diagonal)
{
    fo_case c;
    case_init(&c);
    const cl_firstorder *fo = &c.fo;
    cr_assert_eq(fo->size, NN);
    cr_assert_eq(fo->nnz, (sunindextype)(2 * N + 18 * c.pat.nnzb));
    cr_assert_eq(fo->colptr[0], 0);
    cr_assert_eq(fo->colptr[NN], fo->nnz);
    for (sunindextype j = 0; j < NN; j++) {
        int diag = 0;
        cr_assert(fo->colptr[j + 1] > fo->colptr[j]);
        for (sunindextype k = fo->colptr[j]; k < fo->colptr[j + 1]; k++) {
            if (k > fo->colptr[j])
                cr_assert_gt(fo->rowval[k], fo->rowval[k - 1],
                             "column %ld not strictly ascending", (long)j);
            if (fo->rowval[k] == j) {
                diag = 1;
                cr_assert(j >= N ? fo->src[k] >= 0 : fo->src[k] == CL_FO_ZERO,
                          "diagonal (%ld) source %ld", (long)j, fo->src[k]);
            }
        }
        cr_assert(diag, "diagonal entry %ld not stored", (long)j);
    }
    case_free(&c);
}

Test(firstorder, refill_after_zero_and_scale_add_identity_in_place)
{
    fo_case c;
    case_init(&c);
    SUNContext ctx;
    cr_assert_eq(SUNContext_Create(NULL, &ctx), 0);
    SUNMatrix J = SUNSparseMatrix(NN, NN, c.fo.nnz, CSC_MAT, ctx);
    cr_assert_not_null(J);
    cl_error err;
    cr_assert_eq(cl_firstorder_fill(&c.fo, c.dfdx, c.dfdv, J, &err), CL_OK);
    size_t nnz = (size_t)c.fo.nnz;
    double *v1 = malloc(nnz * sizeof *v1);
    memcpy(v1, SUNSparseMatrix_Data(J), nnz * sizeof *v1);
    cr_assert_eq(SUNMatZero(J), 0);
    cr_assert_eq(SUNSparseMatrix_IndexPointers(J)[NN], 0,
                 "SUNMatZero should wipe the index arrays");
    cr_assert_eq(cl_firstorder_fill(&c.fo, c.dfdx, c.dfdv, J, &err), CL_OK);
    cr_assert_eq(memcmp(SUNSparseMatrix_IndexPointers(J), c.fo.colptr,
                        (NN + 1) * sizeof(sunindextype)), 0);
    cr_assert_eq(memcmp(SUNSparseMatrix_IndexValues(J), c.fo.rowval,
                        nnz * sizeof(sunindextype)), 0);
    cr_assert_eq(memcmp(SUNSparseMatrix_Data(J), v1, nnz * sizeof *v1), 0);
    /* I - gamma J (CVODE's form) keeps the storage: no missing diagonal. */
    double *data = SUNSparseMatrix_Data(J), gamma = 0.125;
    cr_assert_eq(SUNMatScaleAddI(-gamma, J), 0);
    cr_assert_eq(SUNSparseMatrix_Data(J), data, "storage was reallocated");
    cr_assert_eq(SUNSparseMatrix_IndexPointers(J)[NN], c.fo.nnz);
    for (sunindextype j = 0; j < NN; j++) {
        for (sunindextype k = c.fo.colptr[j]; k < c.fo.colptr[j + 1]; k++) {
            double want = -gamma * v1[k] + (c.fo.rowval[k] == j ? 1.0 : 0.0);
            cr_assert_float_eq(data[k], want, 1e-15);
        }
    }
    free(v1);
    SUNMatDestroy(J);
    SUNContext_Free(&ctx);
    case_free(&c);
}

Test(firstorder, rejects_wrong_matrix_and_bad_mass)
{
    fo_case c;
    case_init(&c);
    SUNContext ctx;
    cr_assert_eq(SUNContext_Create(NULL, &ctx), 0);
    SUNMatrix csr = SUNSparseMatrix(NN, NN, c.fo.nnz, CSR_MAT, ctx);
    SUNMatrix small = SUNSparseMatrix(NN, NN, c.fo.nnz - 1, CSC_MAT, ctx);
    SUNMatrix wrong = SUNSparseMatrix(NN - 1, NN - 1, c.fo.nnz, CSC_MAT, ctx);
    cl_error err;
    cr_assert_eq(cl_firstorder_fill(&c.fo, c.dfdx, c.dfdv, csr, &err),
                 CL_EINVAL);
    cr_assert_eq(cl_firstorder_fill(&c.fo, c.dfdx, c.dfdv, small, &err),
                 CL_EINVAL);
    cr_assert_eq(cl_firstorder_fill(&c.fo, c.dfdx, c.dfdv, wrong, &err),
                 CL_EINVAL);
    SUNMatDestroy(csr);
    SUNMatDestroy(small);
    SUNMatDestroy(wrong);
    SUNContext_Free(&ctx);

    cl_firstorder fo2;
    c.mass[4] = 0.0;
    cr_assert_eq(cl_firstorder_create(&c.pat, c.mass, &fo2, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "mass[4]"), "%s", err.msg);
    c.mass[4] = NAN;
    cr_assert_eq(cl_firstorder_create(&c.pat, c.mass, &fo2, &err), CL_EINVAL);
    case_free(&c);
}
