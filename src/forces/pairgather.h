/* Per-particle sums of per-pair forces (the fused force passes of
 * forces/term.h, fuse).  A pass writes, for every pair k = (a, b), the
 * force on a into f4[4k], f4[4k + 1], f4[4k + 2] and 0 into f4[4k + 3]
 * (one vector load each; the force on b is its negative);
 * cl_pairgather_add then adds to each particle p
 *
 *     sum of f[k] over the pairs with a = p, in increasing k,
 *   - sum of f[k] over the pairs with b = p, in increasing k,
 *
 * each sum on its own, from lists built once.  A particle's sum is read,
 * not scattered into, so particles are independent: threads split them
 * in any way and the result is bitwise independent of their count.  The
 * order differs from a pair-by-pair scatter (f_a += f, f_b -= f), so the
 * sums round differently from it (a few ulp of the largest term). */
#ifndef CL_PAIRGATHER_H
#define CL_PAIRGATHER_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct {
    size_t n, np;        /* pairs; particles (above the largest index) */
    size_t *start;       /* 2 np + 1: pairs with a = p in [start[2p],
                          * start[2p + 1]), with b = p up to start[2p + 2] */
    long *list;          /* 2 n: 4k for pair k (its place in f4),
                          * increasing in each list */
    double *f4;          /* per pair: the force on a, and 0 (4 n) */
} cl_pairgather;

/* Lists for the n pairs (ia[k], ib[k]), ia[k] != ib[k], of np particles
 * (every index below np; the caller's pairkern has it, cl_pairkern.np). */
cl_status cl_pairgather_init(cl_pairgather *g, const int *ia, const int *ib,
                             size_t n, size_t np, cl_error *err);
void cl_pairgather_free(cl_pairgather *g);

/* f[3p + i] += the sums above, for every particle p, on `threads`
 * threads (bitwise the same for every count). */
void cl_pairgather_add(const cl_pairgather *g, int threads, double *f);

CL_END_DECLS

#endif
