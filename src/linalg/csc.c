/* Block pattern to scalar CSC (see the header).
 *
 * A counting transpose of the block-CSR pattern gives the block-column
 * pointers; scalar column 3 bj + c then starts at 9 ptr[bj] + 3 c cnt(bj)
 * (cnt(bj) blocks of 3 entries in each of the columns before it in the
 * block column).  Block rows are visited in ascending order, so each block
 * lands in the next free slot of its block column and rows ascend within
 * every scalar column. */
#include "linalg/csc.h"

#include <stdlib.h>
#include <string.h>

/* Block-column pointers ptr (nb + 1) of the pattern, and next[bj] =
 * ptr[bj], the first free slot of each block column. */
static void block_columns(const cl_bpattern *pat, size_t *ptr, size_t *next)
{
    for (size_t k = 0; k < pat->nnzb; k++)
        ptr[pat->col[k] + 1]++;
    for (size_t j = 0; j < pat->nb; j++) {
        ptr[j + 1] += ptr[j];
        next[j] = ptr[j];
    }
}

/* Scalar column pointers, then every block's 9 entries at their places. */
static void scatter_blocks(const cl_bpattern *pat, const size_t *ptr,
                           size_t *next, cl_csc_blocks *csc)
{
    for (size_t bj = 0; bj < pat->nb; bj++) {
        size_t cnt = ptr[bj + 1] - ptr[bj];
        for (size_t c = 0; c < 3; c++)
            csc->colptr[3 * bj + c] = 9 * ptr[bj] + 3 * c * cnt;
    }
    csc->colptr[csc->n] = csc->nnz;
    for (size_t bi = 0; bi < pat->nb; bi++) {
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
            size_t bj = pat->col[k], q = next[bj]++ - ptr[bj];
            for (size_t c = 0; c < 3; c++) {
                for (size_t r = 0; r < 3; r++) {
                    size_t e = csc->colptr[3 * bj + c] + 3 * q + r;
                    csc->row[e] = 3 * bi + r;
                    csc->src[e] = 9 * k + 3 * r + c;
                }
            }
        }
    }
}

cl_status cl_csc_from_blocks(const cl_bpattern *pat, const char *what,
                             cl_csc_blocks *csc, cl_error *err)
{
    size_t nb = pat->nb;
    memset(csc, 0, sizeof *csc);
    csc->n = 3 * nb;
    csc->nnz = 9 * pat->nnzb;
    csc->colptr = malloc((csc->n + 1) * sizeof *csc->colptr);
    csc->row = malloc((csc->nnz ? csc->nnz : 1) * sizeof *csc->row);
    csc->src = malloc((csc->nnz ? csc->nnz : 1) * sizeof *csc->src);
    size_t *ptr = calloc(nb + 1, sizeof *ptr);
    size_t *next = malloc((nb ? nb : 1) * sizeof *next);
    cl_status st = CL_OK;
    if (!csc->colptr || !csc->row || !csc->src || !ptr || !next) {
        cl_csc_blocks_free(csc);
        st = cl_error_set(err, CL_ENOMEM, "out of memory (%s pattern)", what);
    } else {
        block_columns(pat, ptr, next);
        scatter_blocks(pat, ptr, next, csc);
    }
    free(ptr);
    free(next);
    return st;
}

void cl_csc_blocks_free(cl_csc_blocks *csc)
{
    free(csc->colptr);
    free(csc->row);
    free(csc->src);
    memset(csc, 0, sizeof *csc);
}
