/* A = M - a df/dv - b df/dx (docs/model.md, 1; docs/integrators.md, 5) in
 * CSC and as 3x3 blocks.
 *
 * CSC: exactly the block pattern's scalar CSC (linalg/csc.h): column
 * j = 3 bj + c holds, for every stored block (bi, bj) in ascending bi, the
 * three entries at rows 3 bi + r (r = 0, 1, 2), whose value is entry (r, c)
 * of the block: source index 9 k + 3 r + c for block k; rows ascend within
 * every column.  The diagonal blocks are always stored (cl_bpattern), hence
 * every diagonal entry is; its position is remembered so that the fill adds
 * the mass without a search:
 *
 *     val[e] = -a dfdv[src[e]] - b dfdx[src[e]],   val[diagpos[i]] += m_i. */
#include "linalg/reduced.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "linalg/csc.h"

/* Copy the block pattern's scalar CSC into r's index types and remember
 * the position of every diagonal entry. */
static void red_copy_pattern(cl_reduced *r, const cl_csc_blocks *b)
{
    for (size_t j = 0; j <= r->n; j++)
        r->colptr[j] = (SuiteSparse_long)b->colptr[j];
    for (size_t j = 0; j < r->n; j++) {
        for (size_t e = b->colptr[j]; e < b->colptr[j + 1]; e++) {
            if (b->row[e] == j)
                r->diagpos[j] = (SuiteSparse_long)e;
            r->rowind[e] = (SuiteSparse_long)b->row[e];
            r->src[e] = b->src[e];
        }
    }
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
    cl_status st = cl_check_masses(mass, r->n, "reduced matrix", err);
    if (st == CL_OK)
        st = red_alloc(r, err);
    cl_csc_blocks b = {0};
    if (st == CL_OK)
        st = cl_csc_from_blocks(pat, "reduced matrix", &b, err);
    if (st != CL_OK) {
        cl_reduced_free(r);
        return st;
    }
    red_copy_pattern(r, &b);
    cl_csc_blocks_free(&b);
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

/* The row sums stay in registers (y may not alias blk or p), which makes
 * this, the inner loop of every matrix-free solve, about twice as fast as
 * accumulating into y block by block. */
/* Block row bi of y = B p. */
static inline void bmatvec_row(const cl_bpattern *pat, const double *blk,
                               const double *p, double *y, size_t bi)
{
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
        const double *B = blk + 9 * k, *q = p + 3 * pat->col[k];
        double q0 = q[0], q1 = q[1], q2 = q[2];
        y0 += B[0] * q0 + B[1] * q1 + B[2] * q2;
        y1 += B[3] * q0 + B[4] * q1 + B[5] * q2;
        y2 += B[6] * q0 + B[7] * q1 + B[8] * q2;
    }
    y[3 * bi] = y0;
    y[3 * bi + 1] = y1;
    y[3 * bi + 2] = y2;
}

void cl_bmatvec(const cl_bpattern *pat, const double *blk, const double *p,
                double *y)
{
    for (size_t bi = 0; bi < pat->nb; bi++)
        bmatvec_row(pat, blk, p, y, bi);
}

void cl_bmatvec_threads(const cl_bpattern *pat, const double *blk,
                        const double *p, double *y, int threads)
{
    if (threads <= 1) {
        cl_bmatvec(pat, blk, p, y);
        return;
    }
#pragma omp parallel for num_threads(threads) schedule(static)
    for (size_t bi = 0; bi < pat->nb; bi++)
        bmatvec_row(pat, blk, p, y, bi);
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

/* ---- filters ----------------------------------------------------------- */

/* C = A B for row-major 3x3 blocks (C distinct from A and B). */
static void red_mul3(const double *A, const double *B, double *C)
{
    for (size_t r = 0; r < 3; r++)
        for (size_t c = 0; c < 3; c++)
            C[3 * r + c] = A[3 * r] * B[c] + A[3 * r + 1] * B[3 + c] +
                           A[3 * r + 2] * B[6 + c];
}

void cl_reduced_filter(const cl_bpattern *pat, const double *S,
                       const double *blk, double *out)
{
    for (size_t bi = 0; bi < pat->nb; bi++)
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
            double T[9];
            red_mul3(S + 9 * bi, blk + 9 * k, T);
            red_mul3(T, S + 9 * pat->col[k], out + 9 * k);
        }
}

void cl_bdiag_apply(size_t nb, const double *S, const double *p, double *y)
{
    for (size_t i = 0; i < nb; i++) {
        const double *B = S + 9 * i, *q = p + 3 * i;
        double q0 = q[0], q1 = q[1], q2 = q[2];
        for (size_t r = 0; r < 3; r++)
            y[3 * i + r] = B[3 * r] * q0 + B[3 * r + 1] * q1 +
                           B[3 * r + 2] * q2;
    }
}
