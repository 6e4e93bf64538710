/* A 3x3-block pattern (cl_bpattern) spelled out as a compressed sparse
 * column pattern, shared by the first-order Jacobian (linalg/firstorder)
 * and the reduced Newton matrix (linalg/reduced), which both lay their
 * block values out column by column in this order.
 *
 * Column j = 3 bj + c of the n x n scalar matrix (n = 3 nb) holds, for every
 * stored block (bi, bj) in ascending bi, the three entries at rows
 * 3 bi + r (r = 0, 1, 2), whose value is entry (r, c) of block k: source
 * index 9 k + 3 r + c into a block-value array.  Rows ascend within every
 * column.  Each user copies this into its own index types and adds what is
 * particular to it (leading entries, row offsets, diagonal positions). */
#ifndef CL_CSC_H
#define CL_CSC_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

typedef struct {
    size_t n;        /* 3 nb: rows and columns */
    size_t nnz;      /* 9 nnzb: stored entries */
    size_t *colptr;  /* n + 1 */
    size_t *row;     /* nnz, ascending within each column */
    size_t *src;     /* nnz: block-value index 9 k + 3 r + c */
} cl_csc_blocks;

/* Build the scalar CSC pattern of `pat`.  `what` names the matrix being
 * built in the out-of-memory message ("out of memory (<what> pattern)"). */
cl_status cl_csc_from_blocks(const cl_bpattern *pat, const char *what,
                             cl_csc_blocks *csc, cl_error *err);
void cl_csc_blocks_free(cl_csc_blocks *csc);

CL_END_DECLS

#endif
