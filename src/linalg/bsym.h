/* Symmetric 3x3-block matrices on a cl_bpattern, stored by halves.
 *
 * The matrices the Krylov solvers multiply by (A = M - a df/dv - b df/dx,
 * and df/dx itself) are symmetric for every conservative force with linear
 * damping: block (j, i) is the transpose of block (i, j).  The full block
 * product (linalg/reduced.h: cl_bmatvec) then reads every off-diagonal
 * value twice, and at n >= 64 that product is bound by memory traffic.
 * Here the diagonal blocks and the upper blocks (i < j) are kept, and
 *
 *     y_i = B_ii p_i + sum_{j > i} B_ij p_j + sum_{j < i} B_ji^T p_j
 *
 * is formed in one pass over the upper blocks: each contributes B_ij p_j to
 * row i and B_ij^T p_i to row j.  About half the values and indices of the
 * full product are read.
 *
 * Whether a matrix qualifies is decided from its values (cl_bsym_check,
 * once per Jacobian): |B_ji - B_ij^T| <= tol max|B_ij| entrywise, so
 * round-off in the assembly of a symmetric matrix (the
 * pair block s' uu^T + (s/d)(I - uu^T) is rounded differently in its two
 * triangles) passes, and a non-symmetric one (axial damping, Baraff-
 * Witkin's damping derivative) is refused: the caller then keeps the full
 * product.  The packed matrix uses the upper block and its transpose, so
 * it is exactly symmetric off the diagonal. */
#ifndef CL_BSYM_H
#define CL_BSYM_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

/* Relative tolerance of the symmetry test: well above assembly round-off
 * (a few units of 1e-16), far below any real asymmetry. */
#define CL_BSYM_TOL 1e-10

typedef struct {
    size_t nb;          /* block rows */
    size_t ne;          /* upper off-diagonal blocks (i < j) */
    size_t *rowptr;     /* nb + 1: upper blocks of row i */
    size_t *col;        /* ne: block column j (> i), ascending in a row */
    size_t *up;         /* ne: pattern index of block (i, j) */
    size_t *low;        /* ne: pattern index of block (j, i) */
    size_t *diag;       /* nb: pattern index of block (i, i) (borrowed) */
    /* For the threaded product (cl_bsym_transpose; NULL until then): the
     * upper blocks (j, i), j < i, of each block row i: */
    size_t *tstart;     /* nb + 1 */
    size_t *tlist;      /* ne: upper block e, increasing */
    size_t *trow;       /* ne: the row j of upper block tlist[.] */
} cl_bsym;

/* The halves of `pat` (which must outlive s: its diagonal index is shared);
 * CL_EINVAL if the pattern is not structurally symmetric. */
cl_status cl_bsym_create(const cl_bpattern *pat, cl_bsym *s, cl_error *err);
void cl_bsym_free(cl_bsym *s);

/* What a block matrix allows (each kind also has the ones before it). */
typedef enum {
    CL_BSYM_NONE = 0,   /* not symmetric: the full product */
    CL_BSYM_HALVES,     /* symmetric: diagonal and upper blocks, 9 values */
    CL_BSYM_BLOCKS,     /* and every block symmetric itself (pair forces,
                         * linear damping): upper blocks by their 6 upper
                         * entries, a third less to read */
} cl_bsym_kind;

/* Position of entry (r, c) (at 3 r + c) of an upper block in its stored
 * values: 9 row-major (CL_BSYM_HALVES), or the 6 of a symmetric block
 * (b0 b1 b2; b1 b3 b4; b2 b4 b5; CL_BSYM_BLOCKS).  Initialisers, so that
 * each file's loops see the indices as constants. */
#define CL_BSYM_AT9 {0, 1, 2, 3, 4, 5, 6, 7, 8}
#define CL_BSYM_AT6 {0, 1, 2, 1, 3, 4, 2, 4, 5}

/* The kind of the block matrix with values blk (9 nnzb on the pattern),
 * to within tol (see above; for CL_BSYM_BLOCKS the same test within each
 * block). */
cl_bsym_kind cl_bsym_check(const cl_bsym *s, const double *blk, double tol);

/* cl_bsym_check on `threads` OpenMP threads (the same kind for every
 * count: the least kind over the blocks). */
cl_bsym_kind cl_bsym_check_threads(const cl_bsym *s, const double *blk,
                                   double tol, int threads);

/* The kind both x and y have (the lesser of theirs): that of any
 * combination ca x + cb y + diag(mass), as cl_bsym_pack makes it; checked
 * on `threads` threads. */
cl_bsym_kind cl_bsym_check_pair(const cl_bsym *s, const double *x,
                                const double *y, double tol, int threads);

/* Pack B = ca X + cb Y + diag(mass) (block values X, Y: 9 nnzb on the
 * pattern; Y and mass may be NULL, mass has 3 nb entries) into d (9 nb:
 * the diagonal blocks, all 9 entries) and u (the upper blocks, 9 ne values
 * for CL_BSYM_HALVES, 6 ne for CL_BSYM_BLOCKS).  For X and Y whose kinds
 * are at least `kind` (> CL_BSYM_NONE): the lower blocks are not read.
 * The values are those of linalg/reduced.h's cl_reduced_blocks for
 * ca = -a, X = dfdv, cb = -b, Y = dfdx, bit for bit. */
void cl_bsym_pack(const cl_bsym *s, cl_bsym_kind kind, double ca,
                  const double *x, double cb, const double *y,
                  const double *mass, double *d, double *u);

/* cl_bsym_pack block by block on `threads` OpenMP threads (the same
 * values). */
void cl_bsym_pack_threads(const cl_bsym *s, cl_bsym_kind kind, double ca,
                          const double *x, double cb, const double *y,
                          const double *mass, double *d, double *u,
                          int threads);

/* The full block values (9 nnzb on the pattern) of the packed matrix d, u
 * of `kind` (> CL_BSYM_NONE): the diagonal blocks as packed, each upper
 * block and, for block (j, i), its transpose, so the result is the
 * exactly symmetric matrix cl_bsym_matvec multiplies by. */
void cl_bsym_unpack(const cl_bsym *s, cl_bsym_kind kind, const double *d,
                    const double *u, double *blk);

/* The column lists of the upper blocks, for cl_bsym_matvec_threads. */
cl_status cl_bsym_transpose(cl_bsym *s, cl_error *err);

/* y = B p as cl_bsym_matvec, by `threads` OpenMP threads (which needs
 * cl_bsym_transpose first; without it, serially), bitwise equal to it for
 * every count: row i sums the transposed upper blocks of the rows above,
 * its diagonal block and its upper blocks, in cl_bsym_matvec's order. */
void cl_bsym_matvec_threads(const cl_bsym *s, cl_bsym_kind kind,
                            const double *CL_RESTRICT d,
                            const double *CL_RESTRICT u,
                            const double *CL_RESTRICT p, double *CL_RESTRICT y,
                            int threads);

/* y = B p for B packed as `kind`; p and y have 3 nb entries and must not
 * overlap. */
void cl_bsym_matvec(const cl_bsym *s, cl_bsym_kind kind,
                    const double *CL_RESTRICT d, const double *CL_RESTRICT u,
                    const double *CL_RESTRICT p, double *CL_RESTRICT y);

CL_END_DECLS

#endif
