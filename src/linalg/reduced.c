/* A = M - a df/dv - b df/dx (SPEC 1, 5) in CSC and as 3x3 blocks.
 *
 * CSC: column j = 3 bj + c holds, for every stored block (bi, bj) in
 * ascending bi, the three entries at rows 3 bi + r (r = 0, 1, 2), whose
 * value is entry (r, c) of the block: source index 9 k + 3 r + c for block
 * k.  Block columns come from a counting transpose of the block-CSR
 * pattern, visiting block rows in ascending order, so rows ascend within
 * every column.  The diagonal blocks are always stored (cl_bpattern), hence
 * every diagonal entry is; its position is remembered so that the fill adds
 * the mass without a search:
 *
 *     val[e] = -a dfdv[src[e]] - b dfdx[src[e]],   val[diagpos[i]] += m_i. */
#include "linalg/reduced.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Counting transpose of the block pattern: for block column bj, the block
 * rows bi (ascending) and block indices k of its stored blocks. */
typedef struct {
    size_t *ptr; /* nb + 1 */
    size_t *row; /* nnzb */
    size_t *blk; /* nnzb */
} red_bcols;

static void red_bcols_free(red_bcols *bc)
{
    free(bc->ptr);
    free(bc->row);
    free(bc->blk);
}

static cl_status red_bcols_build(const cl_bpattern *pat, red_bcols *bc,
                                 cl_error *err)
{
    size_t nb = pat->nb, nnzb = pat->nnzb;
    bc->ptr = calloc(nb + 1, sizeof *bc->ptr);
    bc->row = malloc((nnzb ? nnzb : 1) * sizeof *bc->row);
    bc->blk = malloc((nnzb ? nnzb : 1) * sizeof *bc->blk);
    size_t *next = malloc((nb ? nb : 1) * sizeof *next);
    if (!bc->ptr || !bc->row || !bc->blk || !next) {
        free(next);
        red_bcols_free(bc);
        return cl_error_set(err, CL_ENOMEM,
                            "out of memory (reduced matrix pattern)");
    }
    for (size_t k = 0; k < nnzb; k++)
        bc->ptr[pat->col[k] + 1]++;
    for (size_t j = 0; j < nb; j++) {
        bc->ptr[j + 1] += bc->ptr[j];
        next[j] = bc->ptr[j];
    }
    for (size_t bi = 0; bi < nb; bi++) {
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
            size_t slot = next[pat->col[k]]++;
            bc->row[slot] = bi;
            bc->blk[slot] = k;
        }
    }
    free(next);
    return CL_OK;
}

/* Column j = 3 bj + c from position pos on; returns the next position. */
static SuiteSparse_long red_column(cl_reduced *r, const red_bcols *bc,
                                   size_t bj, size_t c, SuiteSparse_long pos)
{
    size_t j = 3 * bj + c;
    for (size_t q = bc->ptr[bj]; q < bc->ptr[bj + 1]; q++) {
        for (size_t row = 0; row < 3; row++) {
            size_t i = 3 * bc->row[q] + row;
            if (i == j)
                r->diagpos[i] = pos;
            r->rowind[pos] = (SuiteSparse_long)i;
            r->src[pos++] = 9 * bc->blk[q] + 3 * row + c;
        }
    }
    return pos;
}

static cl_status red_check_masses(const double *mass, size_t n, cl_error *err)
{
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(mass[i]) || !(mass[i] > 0.0))
            return cl_error_set(err, CL_EINVAL,
                                "reduced matrix: mass[%zu] = %g, must be "
                                "finite and > 0", i, mass[i]);
    }
    return CL_OK;
}

static cl_status red_alloc(cl_reduced *r, cl_error *err)
{
    size_t nnz = (size_t)r->nnz, n = r->n ? r->n : 1;
    r->colptr = malloc((r->n + 1) * sizeof *r->colptr);
    r->rowind = malloc((nnz ? nnz : 1) * sizeof *r->rowind);
    r->src = malloc((nnz ? nnz : 1) * sizeof *r->src);
    r->diagpos = malloc(n * sizeof *r->diagpos);
    r->mass = malloc(n * sizeof *r->mass);
    if (!r->colptr || !r->rowind || !r->src || !r->diagpos || !r->mass)
        return cl_error_set(err, CL_ENOMEM,
                            "out of memory (reduced matrix, %zu entries)",
                            nnz);
    return CL_OK;
}

cl_status cl_reduced_create(const cl_bpattern *pat, const double *mass,
                            cl_reduced *r, cl_error *err)
{
    memset(r, 0, sizeof *r);
    r->nb = pat->nb;
    r->n = 3 * pat->nb;
    r->nval = 9 * pat->nnzb;
    r->nnz = (SuiteSparse_long)r->nval;
    cl_status st = red_check_masses(mass, r->n, err);
    if (st == CL_OK)
        st = red_alloc(r, err);
    red_bcols bc = {0};
    if (st == CL_OK)
        st = red_bcols_build(pat, &bc, err);
    if (st != CL_OK) {
        cl_reduced_free(r);
        return st;
    }
    SuiteSparse_long pos = 0;
    for (size_t j = 0; j < r->n; j++) {
        r->colptr[j] = pos;
        pos = red_column(r, &bc, j / 3, j % 3, pos);
    }
    r->colptr[r->n] = pos;
    red_bcols_free(&bc);
    memcpy(r->mass, mass, r->n * sizeof *r->mass);
    return CL_OK;
}

void cl_reduced_free(cl_reduced *r)
{
    free(r->colptr);
    free(r->rowind);
    free(r->src);
    free(r->diagpos);
    free(r->mass);
    memset(r, 0, sizeof *r);
}

void cl_reduced_fill(const cl_reduced *r, double a, double b,
                     const double *dfdx, const double *dfdv, double *val)
{
    size_t nnz = (size_t)r->nnz;
    for (size_t e = 0; e < nnz; e++)
        val[e] = -a * dfdv[r->src[e]] - b * dfdx[r->src[e]];
    for (size_t i = 0; i < r->n; i++)
        val[r->diagpos[i]] += r->mass[i];
}

/* ---- block views ------------------------------------------------------- */

void cl_reduced_blocks(const cl_bpattern *pat, const double *mass, double a,
                       double b, const double *dfdx, const double *dfdv,
                       double *ablk)
{
    size_t nval = 9 * pat->nnzb;
    for (size_t q = 0; q < nval; q++)
        ablk[q] = -a * dfdv[q] - b * dfdx[q];
    for (size_t i = 0; i < pat->nb; i++) {
        double *d = ablk + 9 * pat->diag[i];
        for (size_t r = 0; r < 3; r++)
            d[4 * r] += mass[3 * i + r];
    }
}

/* y3 += s B p3 for one row-major 3x3 block B. */
static void red_block_axpy(double s, const double *B, const double *p3,
                           double *y3)
{
    for (size_t r = 0; r < 3; r++)
        y3[r] += s * (B[3 * r] * p3[0] + B[3 * r + 1] * p3[1] +
                      B[3 * r + 2] * p3[2]);
}

void cl_bmatvec(const cl_bpattern *pat, const double *blk, const double *p,
                double *y)
{
    for (size_t bi = 0; bi < pat->nb; bi++) {
        double *y3 = y + 3 * bi;
        y3[0] = y3[1] = y3[2] = 0.0;
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++)
            red_block_axpy(1.0, blk + 9 * k, p + 3 * pat->col[k], y3);
    }
}

void cl_reduced_matvec(const cl_bpattern *pat, const double *mass, double a,
                       double b, const double *dfdx, const double *dfdv,
                       const double *p, double *y)
{
    for (size_t bi = 0; bi < pat->nb; bi++) {
        double *y3 = y + 3 * bi;
        for (size_t r = 0; r < 3; r++)
            y3[r] = mass[3 * bi + r] * p[3 * bi + r];
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
            const double *p3 = p + 3 * pat->col[k];
            red_block_axpy(-a, dfdv + 9 * k, p3, y3);
            red_block_axpy(-b, dfdx + 9 * k, p3, y3);
        }
    }
}

void cl_reduced_diag_blocks(const cl_bpattern *pat, const double *mass,
                            double a, double b, const double *dfdx,
                            const double *dfdv, double *d)
{
    for (size_t i = 0; i < pat->nb; i++) {
        size_t k = pat->diag[i];
        for (size_t q = 0; q < 9; q++)
            d[9 * i + q] = -a * dfdv[9 * k + q] - b * dfdx[9 * k + q];
        for (size_t r = 0; r < 3; r++)
            d[9 * i + 4 * r] += mass[3 * i + r];
    }
}
