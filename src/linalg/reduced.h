/* The half-size ("reduced") Newton matrix of the second-order form
 * (docs/model.md, 1; docs/integrators.md, 5):
 *
 *     A = M - a df/dv - b df/dx          (n x n, n = 3 nb)
 *
 * with M the diagonal mass matrix and method-dependent a, b (backward
 * Euler: a = h, b = h^2; BDF2 as in Jiao's eq. 15: a = 2h/3, b = 4h^2/9).
 * df/dx and df/dv come as 3x3-block values in the fixed cl_bpattern of the
 * system (block k at val[9k .. 9k+8], row-major).
 *
 * Two views of A:
 *  - compressed sparse column (CSC) with SuiteSparse_long indices, for KLU's
 *    klu_l_* routines (SuiteSparse_long and SUNDIALS' sunindextype are both
 *    64-bit on Debian).  The pattern and a value map (which block value
 *    feeds each stored entry) are built once, every diagonal entry is
 *    stored (the diagonal blocks always are), rows ascend in each column;
 *    cl_reduced_fill then writes the values without search or allocation.
 *  - 3x3 blocks over the cl_bpattern itself, for matrix-free Krylov methods:
 *    the block values of A, a block matrix-vector product, and the 3x3
 *    diagonal blocks of A (block-Jacobi preconditioning).
 * No symmetry of df/dx or df/dv is assumed by any of these. */
#ifndef CL_REDUCED_H
#define CL_REDUCED_H

#include <stddef.h>

#include <SuiteSparse_config.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

typedef struct {
    size_t nb;                  /* block rows */
    size_t n;                   /* 3 nb: matrix size */
    size_t nval;                /* 9 nnzb: length of each block-value array */
    SuiteSparse_long nnz;       /* stored entries: 9 nnzb */
    SuiteSparse_long *colptr;   /* n + 1 */
    SuiteSparse_long *rowind;   /* nnz, ascending within each column */
    size_t *src;                /* nnz: block-value index feeding the entry */
    SuiteSparse_long *diagpos;  /* n: position of entry (i, i) */
    double *mass;               /* n: copy of the diagonal masses */
} cl_reduced;

/* Build the CSC pattern and value map of A for the blocks of `pat` and the
 * n = 3 pat->nb diagonal masses (finite, > 0; CL_EINVAL otherwise). */
cl_status cl_reduced_create(const cl_bpattern *pat, const double *mass,
                            cl_reduced *r, cl_error *err);
void cl_reduced_free(cl_reduced *r);

/* val[0 .. nnz-1] = values of A = M - a dfdv - b dfdx in r's CSC order
 * (dfdx, dfdv: nval block values each). */
void cl_reduced_fill(const cl_reduced *r, double a, double b,
                     const double *dfdx, const double *dfdv, double *val);

/* ---- block (matrix-free) views, straight from the cl_bpattern ---------- */

/* Block values of A (9 nnzb): ablk = -a dfdv - b dfdx, plus diag(mass) on
 * the diagonal blocks.  mass has 3 nb entries. */
void cl_reduced_blocks(const cl_bpattern *pat, const double *mass, double a,
                       double b, const double *dfdx, const double *dfdv,
                       double *ablk);

/* y = B p for any block matrix B with values blk (9 nnzb) on pat;
 * p and y have 3 nb entries and must not overlap. */
void cl_bmatvec(const cl_bpattern *pat, const double *blk, const double *p,
                double *y);
/* The same by `threads` OpenMP threads, each computing whole block rows:
 * bitwise equal to cl_bmatvec for every count. */
void cl_bmatvec_threads(const cl_bpattern *pat, const double *blk,
                        const double *p, double *y, int threads);

/* y = A p = M p - a dfdv p - b dfdx p without forming A (p, y: 3 nb, not
 * overlapping). */
void cl_reduced_matvec(const cl_bpattern *pat, const double *mass, double a,
                       double b, const double *dfdx, const double *dfdv,
                       const double *p, double *y);

/* The 3x3 diagonal blocks of A: d[9i .. 9i+8] = block (i, i), row-major. */
void cl_reduced_diag_blocks(const cl_bpattern *pat, const double *mass,
                            double a, double b, const double *dfdx,
                            const double *dfdv, double *d);

/* ---- filters (Baraff-Witkin constraints; docs/integrators.md, 3.4) ----- */

/* out = S B S block by block: out_k = S_bi B_k S_bj for every stored block
 * k = (bi, bj) of blk (9 nnzb), S the per-row 3x3 filters (9 nb,
 * row-major). */
void cl_reduced_filter(const cl_bpattern *pat, const double *S,
                       const double *blk, double *out);

/* y_i = S_i p_i for the nb blocks (p, y: 3 nb; may be the same array). */
void cl_bdiag_apply(size_t nb, const double *S, const double *p, double *y);

CL_END_DECLS

#endif
