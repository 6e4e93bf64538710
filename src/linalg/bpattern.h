/* Block-sparse pattern of df/dx and df/dv: 3x3 blocks, block CSR over the
 * "dof particles" (free particles in a simulation; every particle when the
 * full Jacobian is written by `clothode eval`).
 *
 * Built once from the coupled particle pairs of all force terms.  Every
 * diagonal block is present.  Terms look up the slots of their blocks once
 * (cl_bpattern_find) and then write values straight into them: block k
 * occupies val[9k .. 9k+8], row-major. */
#ifndef CL_BPATTERN_H
#define CL_BPATTERN_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct {
    size_t nb;        /* block rows (= block columns) */
    size_t nnzb;      /* stored blocks */
    size_t *rowptr;   /* nb + 1 */
    size_t *col;      /* nnzb, sorted within each row */
    size_t *diag;     /* nb: index of the diagonal block of each row */
} cl_bpattern;

/* dof[p] maps particle p (0..np-1) to its block row, or -1 if it carries no
 * unknowns; pairs[k] = {a, b} are particle pairs that couple (in any order,
 * duplicates allowed, pairs touching a -1 particle contribute only the
 * blocks between dof particles). */
cl_status cl_bpattern_build(size_t np, const int *dof, size_t nb,
                            size_t npairs, const int (*pairs)[2],
                            cl_bpattern *pat, cl_error *err);
void cl_bpattern_free(cl_bpattern *pat);

/* Index of block (bi, bj), or -1 if either is negative or not stored. */
long cl_bpattern_find(const cl_bpattern *pat, long bi, long bj);

CL_END_DECLS

#endif
