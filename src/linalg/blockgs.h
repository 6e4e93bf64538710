/* Block Gauss-Seidel sweeps with 3x3 diagonal blocks, on the symmetric
 * halves of linalg/bsym.h or on all blocks of a cl_bpattern: the finest
 * level's smoother of the multigrid solver amg (linalg/linsol_amg.c).
 *
 * With A = L + D + U (D the 3x3 diagonal blocks, L and U the strictly
 * lower and upper blocks), a backward sweep from a zero guess solves
 * (D + U) x = b and a forward sweep from a guess x sets
 *
 *     x <- x + (D + L)^-1 (b - A x),
 *
 * i.e. x_i <- D_ii^-1 (b_i - sum_{j<i} A_ij x_j(new) - sum_{j>i} A_ij x_j).
 * For symmetric A, D + L = (D + U)^T: the backward sweep as pre-smoother
 * and the forward sweep as post-smoother make a symmetric multigrid cycle
 * (the post-smoother the adjoint of the pre-smoother: Tatebe, "The
 * multigrid preconditioned conjugate gradient method"), and for
 * symmetric positive definite A both converge in the energy norm, so the
 * cycle is positive definite and CG may use it.
 *
 * On the halves each sweep reads the stored blocks once.  The backward
 * sweep gathers row i's upper blocks with the new values of the rows below
 * it, and scatters U_ij^T x_i into the residual of row j: after the sweep
 * (D + U) x = b, so b - A x = -L x, formed in the same pass.  The forward
 * sweep gathers row i's upper blocks with the old values and scatters
 * U_ij^T x_i(new) into an accumulator that rows j > i read: sum_{j<i}
 * A_ij x_j(new). */
#ifndef CL_BLOCKGS_H
#define CL_BLOCKGS_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "linalg/bpattern.h"
#include "linalg/bsym.h"

CL_BEGIN_DECLS

/* dinv (9 nb) = the inverses of the diagonal blocks blk + 9 at[i] (at
 * NULL: blk + 9 i), row-major; false, with *row the first such row, if a
 * block's determinant is not positive and finite (then A is not
 * symmetric positive definite). */
bool cl_bgs_invert(size_t nb, const double *blk, const size_t *at,
                   double *dinv, size_t *row);

/* One sweep on the halves d, u packed as `kind` (> CL_BSYM_NONE;
 * linalg/bsym.h): backward (forward false) x = (D + U)^-1 b, and w =
 * b - A x unless w is NULL; forward x <- x + (D + L)^-1 (b - A x), w 3 nb
 * of work. */
void cl_bsym_gs(const cl_bsym *s, cl_bsym_kind kind, bool forward,
                const double *CL_RESTRICT dinv, const double *CL_RESTRICT u,
                const double *CL_RESTRICT b, double *CL_RESTRICT x,
                double *CL_RESTRICT w);

/* The same two sweeps on all blocks blk (9 nnzb) of pat, for A that is not
 * symmetric: backward x = (D + U)^-1 b (x is overwritten), forward in
 * place from the guess x. */
void cl_bgs_backward(const cl_bpattern *pat, const double *CL_RESTRICT blk,
                     const double *CL_RESTRICT dinv, const double *CL_RESTRICT b,
                     double *CL_RESTRICT x);
void cl_bgs_forward(const cl_bpattern *pat, const double *CL_RESTRICT blk,
                    const double *CL_RESTRICT dinv, const double *CL_RESTRICT b,
                    double *CL_RESTRICT x);

CL_END_DECLS

#endif
