/* First-order Jacobian J = [[0, I], [M^-1 df/dx, M^-1 df/dv]] in CSC.
 *
 * Column j < n (a position unknown) holds the explicit zero J(j, j) and, for
 * every stored block (bi, bj = j / 3), the three entries M^-1 df/dx at rows
 * n + 3 bi + r.  Column n + j (a velocity unknown) holds the identity entry
 * at row j and the entries M^-1 df/dv at rows n + 3 bi + r.  Rows ascend in
 * every column because j < n and the block entries come in the ascending
 * order of the block pattern's scalar CSC (linalg/csc.h).
 * The position of every diagonal entry is recorded once for the implicit
 * (IDA) matrix, which shares pattern and value map (see the header). */
#include "linalg/firstorder.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "linalg/csc.h"

/* Append the leading entry (row j, source `first`) and the block entries of
 * column j of the block CSC at rows n + row, offsetting sources by base. */
static sunindextype fill_column(cl_firstorder *fo, const cl_csc_blocks *b,
                                size_t j, sunindextype pos, long first,
                                size_t base)
{
    fo->rowval[pos] = (sunindextype)j;
    fo->src[pos++] = first;
    for (size_t e = b->colptr[j]; e < b->colptr[j + 1]; e++) {
        fo->rowval[pos] = (sunindextype)(fo->n + b->row[e]);
        fo->src[pos++] = (long)(base + b->src[e]);
    }
    return pos;
}

static void build_columns(cl_firstorder *fo, const cl_csc_blocks *b)
{
    size_t n = fo->n;
    sunindextype pos = 0;
    for (size_t j = 0; j < n; j++) {
        fo->colptr[j] = pos;
        pos = fill_column(fo, b, j, pos, CL_FO_ZERO, 0);
    }
    for (size_t j = 0; j < n; j++) {
        fo->colptr[n + j] = pos;
        pos = fill_column(fo, b, j, pos, CL_FO_ONE, fo->nval);
    }
    fo->colptr[2 * n] = pos;
}

/* Position of (i, i) in every column (each column holds it exactly once). */
static void find_diagonal(cl_firstorder *fo)
{
    for (sunindextype j = 0; j < fo->size; j++) {
        for (sunindextype k = fo->colptr[j]; k < fo->colptr[j + 1]; k++) {
            if (fo->rowval[k] == j)
                fo->diag[j] = k;
        }
    }
}

static cl_status alloc_arrays(cl_firstorder *fo, cl_error *err)
{
    size_t nnz = (size_t)fo->nnz;
    fo->colptr = malloc(((size_t)fo->size + 1) * sizeof *fo->colptr);
    fo->rowval = malloc((nnz ? nnz : 1) * sizeof *fo->rowval);
    fo->src = malloc((nnz ? nnz : 1) * sizeof *fo->src);
    fo->inv_mass = malloc((fo->n ? fo->n : 1) * sizeof *fo->inv_mass);
    fo->mass = malloc((fo->n ? fo->n : 1) * sizeof *fo->mass);
    fo->diag = malloc(((size_t)fo->size + 1) * sizeof *fo->diag);
    if (!fo->colptr || !fo->rowval || !fo->src || !fo->inv_mass ||
        !fo->mass || !fo->diag)
        return cl_error_set(err, CL_ENOMEM,
                            "out of memory (first-order Jacobian, %zu entries)",
                            nnz);
    return CL_OK;
}

cl_status cl_firstorder_create(const cl_bpattern *pat, const double *mass,
                               cl_firstorder *fo, cl_error *err)
{
    memset(fo, 0, sizeof *fo);
    fo->n = 3 * pat->nb;
    fo->nval = 9 * pat->nnzb;
    fo->size = (sunindextype)(2 * fo->n);
    fo->nnz = (sunindextype)(2 * fo->n + 2 * fo->nval);
    cl_status st = cl_check_masses(mass, fo->n, "first-order Jacobian", err);
    if (st == CL_OK)
        st = alloc_arrays(fo, err);
    cl_csc_blocks b = {0};
    if (st == CL_OK)
        st = cl_csc_from_blocks(pat, "first-order Jacobian", &b, err);
    if (st != CL_OK) {
        cl_firstorder_free(fo);
        return st;
    }
    build_columns(fo, &b);
    cl_csc_blocks_free(&b);
    find_diagonal(fo);
    for (size_t i = 0; i < fo->n; i++) {
        fo->mass[i] = mass[i];
        fo->inv_mass[i] = 1.0 / mass[i];
    }
    return CL_OK;
}

void cl_firstorder_free(cl_firstorder *fo)
{
    free(fo->colptr);
    free(fo->rowval);
    free(fo->src);
    free(fo->inv_mass);
    free(fo->mass);
    free(fo->diag);
    memset(fo, 0, sizeof *fo);
}

/* Copy the pattern and write every value: block values times vscale[row]
 * (v rows) when vscale is given, else times sign; identity entries sign. */
static void fill_values(const cl_firstorder *fo, const double *dfdx,
                        const double *dfdv, const double *vscale, double sign,
                        sunindextype *colptr, sunindextype *rowval,
                        sunrealtype *val)
{
    size_t nnz = (size_t)fo->nnz;
    long nval = (long)fo->nval;
    sunindextype n = (sunindextype)fo->n;
    memcpy(colptr, fo->colptr, ((size_t)fo->size + 1) * sizeof *colptr);
    memcpy(rowval, fo->rowval, nnz * sizeof *rowval);
    for (size_t k = 0; k < nnz; k++) {
        long s = fo->src[k];
        if (s >= 0) {
            double b = s < nval ? dfdx[s] : dfdv[s - nval];
            val[k] = vscale ? b * vscale[fo->rowval[k] - n] : sign * b;
        } else {
            val[k] = s == CL_FO_ONE ? sign : 0.0;
        }
    }
}

void cl_firstorder_fill_arrays(const cl_firstorder *fo, const double *dfdx,
                               const double *dfdv, sunindextype *colptr,
                               sunindextype *rowval, sunrealtype *val)
{
    fill_values(fo, dfdx, dfdv, fo->inv_mass, 1.0, colptr, rowval, val);
}

void cl_firstorder_fill_implicit_arrays(const cl_firstorder *fo,
                                        const double *dfdx, const double *dfdv,
                                        double cj, sunindextype *colptr,
                                        sunindextype *rowval, sunrealtype *val)
{
    fill_values(fo, dfdx, dfdv, NULL, -1.0, colptr, rowval, val);
    for (size_t i = 0; i < fo->n; i++) {
        val[fo->diag[i]] += cj;
        val[fo->diag[fo->n + i]] += cj * fo->mass[i];
    }
}

static cl_status check_matrix(const cl_firstorder *fo, SUNMatrix J,
                              cl_error *err)
{
    if (SUNMatGetID(J) != SUNMATRIX_SPARSE ||
        SUNSparseMatrix_SparseType(J) != CSC_MAT ||
        SUNSparseMatrix_Rows(J) != fo->size ||
        SUNSparseMatrix_Columns(J) != fo->size ||
        SUNSparseMatrix_NNZ(J) < fo->nnz)
        return cl_error_set(err, CL_EINVAL,
                            "first-order Jacobian: matrix is not a %ld x %ld "
                            "CSC sparse matrix with room for %ld entries",
                            (long)fo->size, (long)fo->size, (long)fo->nnz);
    return CL_OK;
}

cl_status cl_firstorder_fill(const cl_firstorder *fo, const double *dfdx,
                             const double *dfdv, SUNMatrix J, cl_error *err)
{
    cl_status st = check_matrix(fo, J, err);
    if (st == CL_OK)
        cl_firstorder_fill_arrays(fo, dfdx, dfdv,
                                  SUNSparseMatrix_IndexPointers(J),
                                  SUNSparseMatrix_IndexValues(J),
                                  SUNSparseMatrix_Data(J));
    return st;
}

cl_status cl_firstorder_fill_implicit(const cl_firstorder *fo,
                                      const double *dfdx, const double *dfdv,
                                      double cj, SUNMatrix G, cl_error *err)
{
    cl_status st = check_matrix(fo, G, err);
    if (st == CL_OK)
        cl_firstorder_fill_implicit_arrays(fo, dfdx, dfdv, cj,
                                           SUNSparseMatrix_IndexPointers(G),
                                           SUNSparseMatrix_IndexValues(G),
                                           SUNSparseMatrix_Data(G));
    return st;
}

void cl_firstorder_dense(const cl_bpattern *pat, const double *inv_mass,
                         const double *dfdx, const double *dfdv, double *J)
{
    size_t n = 3 * pat->nb, dim = 2 * n;
    memset(J, 0, dim * dim * sizeof *J);
    for (size_t i = 0; i < n; i++)
        J[i * dim + n + i] = 1.0;
    for (size_t bi = 0; bi < pat->nb; bi++)
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
            size_t bj = pat->col[k];
            for (size_t r = 0; r < 3; r++) {
                double w = inv_mass[3 * bi + r];
                double *row = J + (n + 3 * bi + r) * dim;
                for (size_t c = 0; c < 3; c++) {
                    row[3 * bj + c] = w * dfdx[9 * k + 3 * r + c];
                    row[n + 3 * bj + c] = w * dfdv[9 * k + 3 * r + c];
                }
            }
        }
}
