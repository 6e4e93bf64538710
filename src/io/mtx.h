/* Matrix Market output of 3x3 block matrices (Jacobians df/dx, df/dv) and a
 * small reader of "coordinate real general" files into triplets, used to
 * check what was written.
 *
 * A block matrix with nb block rows is written as a 3nb x 3nb matrix with
 * all 9 entries of every stored block (zeros included, so the file shows
 * the pattern), 1-based indices, values "%.17g", entries sorted by row and
 * then column. */
#ifndef CL_MTX_H
#define CL_MTX_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

/* val holds 9 * pat->nnzb values, block k row-major at val[9k..9k+8].
 * Written atomically. */
cl_status cl_mtx_write_blocks(const char *path, const cl_bpattern *pat,
                              const double *val, cl_error *err);

typedef struct {
    size_t nrows, ncols;
    size_t nnz;
    size_t *row, *col;  /* 0-based */
    double *val;
} cl_triplets;

/* Read "%%MatrixMarket matrix coordinate real general" (keywords
 * case-insensitive).  Comment lines ('%') and blank lines are skipped.
 * CL_EIO if the file cannot be read; CL_EPARSE "file:line: ..." for a bad
 * banner, size line or entry, an index out of range, a non-finite value, or
 * a number of entries different from the size line.  Entries are returned
 * in file order; duplicates are kept.  Free with cl_triplets_free. */
cl_status cl_mtx_read(const char *path, cl_triplets *t, cl_error *err);

void cl_triplets_free(cl_triplets *t);

CL_END_DECLS

#endif
