/* Spatial hash (forces/sphash.h). */
#include "forces/sphash.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cell indices are clamped to +-2^40 so that any finite or infinite
 * coordinate converts to long without overflow; NaN goes to cell 0 (such
 * a point is farther than `cell` from every point anyway: the distance
 * test fails). */
#define SPHASH_LIMIT 1099511627776.0

cl_status cl_sphash_init(cl_sphash *h, size_t np, double cell,
                         cl_error *err)
{
    memset(h, 0, sizeof *h);
    if (!(cell > 0) || !isfinite(cell))
        return cl_error_set(err, CL_EINVAL,
                            "spatial hash: cell = %g: need a finite number "
                            "> 0", cell);
    h->cell = cell;
    h->np = np;
    h->nbucket = 1;
    while (h->nbucket < 2 * np)
        h->nbucket *= 2;
    h->start = calloc(h->nbucket + 1, sizeof *h->start);
    h->pt = malloc((np + 1) * sizeof *h->pt);
    h->ijk = malloc((np + 1) * sizeof *h->ijk);
    if (!h->start || !h->pt || !h->ijk) {
        cl_sphash_free(h);
        return cl_error_set(err, CL_ENOMEM, "out of memory (spatial hash "
                            "of %zu points)", np);
    }
    return CL_OK;
}

void cl_sphash_free(cl_sphash *h)
{
    free(h->start);
    free(h->pt);
    free(h->ijk);
    memset(h, 0, sizeof *h);
}

static long cell_index(double x, double cell)
{
    double q = floor(x / cell);
    if (!(q == q))
        return 0;
    return (long)fmax(-SPHASH_LIMIT, fmin(SPHASH_LIMIT, q));
}

/* Teschner et al.'s hash of cell (i, j, k). */
static size_t bucket(const cl_sphash *h, long i, long j, long k)
{
    unsigned long u = ((unsigned long)i * 73856093ul) ^
                      ((unsigned long)j * 19349663ul) ^
                      ((unsigned long)k * 83492791ul);
    return (size_t)(u & (h->nbucket - 1));
}

void cl_sphash_build(cl_sphash *h, const double *x)
{
    memset(h->start, 0, (h->nbucket + 1) * sizeof *h->start);
    for (size_t p = 0; p < h->np; p++) {
        long *c = h->ijk[p];
        for (int i = 0; i < 3; i++)
            c[i] = cell_index(x[3 * p + i], h->cell);
        h->start[bucket(h, c[0], c[1], c[2]) + 1]++;
    }
    for (size_t b = 0; b < h->nbucket; b++)
        h->start[b + 1] += h->start[b];
    /* start[b + 1] is now the end of bucket b; filled from the back it
     * ends at the bucket's first point, and each bucket lists its points
     * in increasing order */
    for (size_t p = h->np; p-- > 0;) {
        const long *c = h->ijk[p];
        h->pt[--h->start[bucket(h, c[0], c[1], c[2]) + 1]] = (int)p;
    }
    for (size_t b = 0; b < h->nbucket; b++)
        h->start[b] = h->start[b + 1];
    h->start[h->nbucket] = h->np;
}

/* The distinct buckets of the 27 cells around cell c, into out; returns
 * their number. */
static int around(const cl_sphash *h, const long c[3], size_t out[27])
{
    int n = 0;
    for (long di = -1; di <= 1; di++)
        for (long dj = -1; dj <= 1; dj++)
            for (long dk = -1; dk <= 1; dk++) {
                size_t b = bucket(h, c[0] + di, c[1] + dj, c[2] + dk);
                int k = 0;
                while (k < n && out[k] != b)
                    k++;
                if (k == n)
                    out[n++] = b;
            }
    return n;
}

void cl_sphash_pairs(const cl_sphash *h, const double *x,
                     cl_sphash_visit visit, void *ctx)
{
    double r2 = h->cell * h->cell;
    for (size_t a = 0; a < h->np; a++) {
        size_t nb[27];
        int n = around(h, h->ijk[a], nb);
        const double *xa = x + 3 * a;
        for (int k = 0; k < n; k++)
            for (size_t e = h->start[nb[k]]; e < h->start[nb[k] + 1]; e++) {
                int b = h->pt[e];
                if ((size_t)b <= a)
                    continue;
                const double *xb = x + 3 * (size_t)b;
                double dx = xb[0] - xa[0], dy = xb[1] - xa[1],
                       dz = xb[2] - xa[2];
                double d2 = dx * dx + dy * dy + dz * dz;
                if (d2 < r2)
                    visit(ctx, (int)a, b, d2);
            }
    }
}
