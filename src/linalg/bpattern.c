/* Block-sparse (3x3) pattern built once from coupled particle pairs. */
#include "linalg/bpattern.h"

#include <stdlib.h>
#include <string.h>

static int cmp_size(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

/* Count blocks per row (diagonal + both directions of each pair, duplicates
 * included), fill, then sort and remove duplicates row by row. */
static cl_status fill_rows(size_t np, const int *dof, size_t nb, size_t npairs,
                           const int (*pairs)[2], cl_bpattern *pat,
                           cl_error *err)
{
    size_t *count = calloc(nb + 1, sizeof *count);
    if (!count)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pattern rows)");
    for (size_t i = 0; i < nb; i++)
        count[i] = 1;
    for (size_t k = 0; k < npairs; k++) {
        int a = pairs[k][0], b = pairs[k][1];
        if (a < 0 || b < 0 || (size_t)a >= np || (size_t)b >= np) {
            free(count);
            return cl_error_set(err, CL_EINVAL,
                                "pattern: pair %zu (%d, %d) out of range",
                                k, a, b);
        }
        if (dof[a] >= 0 && dof[b] >= 0 && a != b) {
            count[dof[a]]++;
            count[dof[b]]++;
        }
    }
    pat->rowptr[0] = 0;
    for (size_t i = 0; i < nb; i++)
        pat->rowptr[i + 1] = pat->rowptr[i] + count[i];
    pat->col = malloc((pat->rowptr[nb] ? pat->rowptr[nb] : 1) * sizeof *pat->col);
    if (!pat->col) {
        free(count);
        return cl_error_set(err, CL_ENOMEM, "out of memory (pattern)");
    }
    for (size_t i = 0; i < nb; i++) {
        count[i] = pat->rowptr[i];
        pat->col[count[i]++] = i;
    }
    for (size_t k = 0; k < npairs; k++) {
        int a = pairs[k][0], b = pairs[k][1];
        if (dof[a] >= 0 && dof[b] >= 0 && a != b) {
            pat->col[count[dof[a]]++] = (size_t)dof[b];
            pat->col[count[dof[b]]++] = (size_t)dof[a];
        }
    }
    free(count);
    return CL_OK;
}

static void compress_rows(cl_bpattern *pat)
{
    size_t out = 0;
    for (size_t i = 0; i < pat->nb; i++) {
        size_t lo = pat->rowptr[i], hi = pat->rowptr[i + 1];
        qsort(pat->col + lo, hi - lo, sizeof *pat->col, cmp_size);
        pat->rowptr[i] = out;
        for (size_t k = lo; k < hi; k++) {
            if (k > lo && pat->col[k] == pat->col[k - 1])
                continue;
            if (pat->col[k] == i)
                pat->diag[i] = out;
            pat->col[out++] = pat->col[k];
        }
    }
    pat->rowptr[pat->nb] = out;
    pat->nnzb = out;
}

cl_status cl_bpattern_build(size_t np, const int *dof, size_t nb,
                            size_t npairs, const int (*pairs)[2],
                            cl_bpattern *pat, cl_error *err)
{
    memset(pat, 0, sizeof *pat);
    pat->nb = nb;
    pat->rowptr = malloc((nb + 1) * sizeof *pat->rowptr);
    pat->diag = malloc((nb ? nb : 1) * sizeof *pat->diag);
    if (!pat->rowptr || !pat->diag) {
        cl_bpattern_free(pat);
        return cl_error_set(err, CL_ENOMEM, "out of memory (pattern)");
    }
    cl_status st = fill_rows(np, dof, nb, npairs, pairs, pat, err);
    if (st != CL_OK) {
        cl_bpattern_free(pat);
        return st;
    }
    compress_rows(pat);
    return CL_OK;
}

void cl_bpattern_free(cl_bpattern *pat)
{
    if (!pat)
        return;
    free(pat->rowptr);
    free(pat->col);
    free(pat->diag);
    memset(pat, 0, sizeof *pat);
}

long cl_bpattern_find(const cl_bpattern *pat, long bi, long bj)
{
    if (bi < 0 || bj < 0 || (size_t)bi >= pat->nb || (size_t)bj >= pat->nb)
        return -1;
    size_t lo = pat->rowptr[bi], hi = pat->rowptr[bi + 1];
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (pat->col[mid] < (size_t)bj)
            lo = mid + 1;
        else
            hi = mid;
    }
    return (lo < pat->rowptr[bi + 1] && pat->col[lo] == (size_t)bj)
               ? (long)lo : -1;
}
