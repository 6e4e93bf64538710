/* The reduced Newton matrix A = M - a df/dv - b df/dx (docs/model.md, 1;
 * docs/integrators.md, 5) as the Krylov solvers (pcg, amg) hold it: the
 * values of its diagonal and upper blocks packed by halves when A is
 * symmetric (linalg/bsym.h: the usual case, conservative forces with
 * linear damping), else all its blocks (linalg/reduced.h), and the product
 * y = A x on whichever form the last fill made.
 *
 * Usage: cl_amat_init once; per Jacobian cl_amat_jacobian (which tests its
 * symmetry, once); per setup cl_amat_fill; then any number of products.
 * Nothing is allocated after cl_amat_init. */
#ifndef CL_AMAT_H
#define CL_AMAT_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"
#include "linalg/bsym.h"

CL_BEGIN_DECLS

typedef struct {
    const cl_bpattern *pat;  /* borrowed: the system's pattern */
    size_t n;                /* 3 nb */
    int threads;             /* of the products, checks and packing */
    double *mass;            /* n: a copy of the diagonal masses */
    double *ablk;            /* 9 nnzb: A's block values (kind NONE) */
    cl_bsym sym;             /* A's halves, if it is symmetric: */
    double *sdiag, *supper;  /* 9 nb, 9 ne: their values */
    cl_bsym_kind jac_kind;   /* df/dx and df/dv as last told */
    cl_bsym_kind kind;       /* the last fill packed the halves (sdiag,
                              * supper) unless CL_BSYM_NONE (then ablk) */
} cl_amat;

/* Storage for A on `pat` (which must outlive m) with the masses `mass`
 * (3 nb, finite and > 0; CL_EINVAL naming `who` otherwise), the products
 * by `threads` OpenMP threads.  On failure m is left for cl_amat_free. */
cl_status cl_amat_init(cl_amat *m, const char *who, const cl_bpattern *pat,
                       const double *mass, int threads, cl_error *err);
void cl_amat_free(cl_amat *m);

/* Told of new Jacobian values: which form the next fills can take. */
void cl_amat_jacobian(cl_amat *m, const double *dfdx, const double *dfdv);

/* A's values from df/dx and df/dv (9 nnzb each): its halves if the last
 * Jacobian told was symmetric, else all its blocks; the halves' values are
 * those of cl_reduced_blocks bit for bit. */
void cl_amat_fill(cl_amat *m, double a, double b, const double *dfdx,
                  const double *dfdv);

/* Whether every value the last fill wrote is finite. */
bool cl_amat_finite(const cl_amat *m);

/* A's diagonal block i (9 values, row-major) in the last fill's form. */
const double *cl_amat_diag_block(const cl_amat *m, size_t i);

/* y = A x (n each, not overlapping), bitwise the same for every thread
 * count. */
void cl_amat_mult(const cl_amat *m, const double *x, double *y);

CL_END_DECLS

#endif
