/* Symmetric block matrices stored by halves (linalg/bsym.h). */
#include "linalg/bsym.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>


void cl_bsym_free(cl_bsym *s)
{
    free(s->rowptr);
    free(s->col);
    free(s->up);
    free(s->low);
    memset(s, 0, sizeof *s);
}

static cl_status bsym_alloc(cl_bsym *s, const cl_bpattern *pat, cl_error *err)
{
    s->nb = pat->nb;
    s->ne = (pat->nnzb - pat->nb) / 2;
    size_t ne = s->ne ? s->ne : 1;
    s->rowptr = malloc((s->nb + 1) * sizeof *s->rowptr);
    s->col = malloc(ne * sizeof *s->col);
    s->up = malloc(ne * sizeof *s->up);
    s->low = malloc(ne * sizeof *s->low);
    if (!s->rowptr || !s->col || !s->up || !s->low)
        return cl_error_set(err, CL_ENOMEM, "out of memory (symmetric "
                            "blocks, %zu)", s->ne);
    return CL_OK;
}

cl_status cl_bsym_create(const cl_bpattern *pat, cl_bsym *s, cl_error *err)
{
    memset(s, 0, sizeof *s);
    cl_status st = bsym_alloc(s, pat, err);
    size_t e = 0;
    for (size_t i = 0; st == CL_OK && i < pat->nb; i++) {
        s->rowptr[i] = e;
        for (size_t k = pat->rowptr[i]; k < pat->rowptr[i + 1]; k++) {
            size_t j = pat->col[k];
            if (j <= i)
                continue;
            long low = cl_bpattern_find(pat, (long)j, (long)i);
            if (low < 0 || e == s->ne) {
                st = cl_error_set(err, CL_EINVAL, "symmetric blocks: block "
                                  "(%zu, %zu) has no transpose in the "
                                  "pattern", i, j);
                break;
            }
            s->col[e] = j;
            s->up[e] = k;
            s->low[e++] = (size_t)low;
        }
    }
    if (st == CL_OK && e != s->ne)
        st = cl_error_set(err, CL_EINVAL, "symmetric blocks: %zu upper "
                          "blocks for %zu off-diagonal ones", e,
                          pat->nnzb - pat->nb);
    if (st != CL_OK) {
        cl_bsym_free(s);
        return st;
    }
    s->rowptr[s->nb] = e;
    s->diag = pat->diag;
    return CL_OK;
}

/* Whether block kt is the transpose of block kb to within tol, relative
 * to kb's largest entry (false for NaN).  Unrolled: it runs over every
 * block of every Jacobian. */
static inline bool bsym_transposed(const double *blk, size_t kb, size_t kt,
                                   double tol)
{
    const double *b = blk + 9 * kb, *bt = blk + 9 * kt;
    double big = 0.0;
#pragma GCC unroll 9
    for (int q = 0; q < 9; q++)
        big = fabs(b[q]) > big ? fabs(b[q]) : big;
    double lim = tol * big;
    bool ok = true;
#pragma GCC unroll 9
    for (int q = 0; q < 9; q++)
        ok &= fabs(b[q] - bt[3 * (q % 3) + q / 3]) <= lim; /* (r,c), (c,r) */
    return ok;
}

bool cl_bsym_check(const cl_bsym *s, const double *blk, double tol)
{
    bool ok = true;
    for (size_t i = 0; ok && i < s->nb; i++)
        ok = bsym_transposed(blk, s->diag[i], s->diag[i], tol);
    for (size_t e = 0; ok && e < s->ne; e++)
        ok = bsym_transposed(blk, s->up[e], s->low[e], tol);
    return ok;
}

/* out = ca x + cb y over 9 values. */
static inline void bsym_combine(double ca, const double *restrict x,
                                double cb, const double *restrict y,
                                double *restrict out)
{
#pragma GCC unroll 9
    for (int q = 0; q < 9; q++)
        out[q] = ca * x[q] + cb * y[q];
}

void cl_bsym_pack(const cl_bsym *s, double ca, const double *x, double cb,
                  const double *y, const double *mass, double *d, double *u)
{
    /* Without Y: ca X + 0 X, the same values for finite X. */
    if (!y) {
        y = x;
        cb = 0.0;
    }
    for (size_t i = 0; i < s->nb; i++) {
        double *b = d + 9 * i;
        bsym_combine(ca, x + 9 * s->diag[i], cb, y + 9 * s->diag[i], b);
        if (mass)
            for (int r = 0; r < 3; r++)
                b[4 * r] += mass[3 * i + r];
    }
    for (size_t e = 0; e < s->ne; e++)
        bsym_combine(ca, x + 9 * s->up[e], cb, y + 9 * s->up[e], u + 9 * e);
}

/* Row i's sum is kept in registers; the transposed contributions to the
 * rows below go straight into y, which is read when their turn comes. */
void cl_bsym_matvec(const cl_bsym *s, const double *restrict d,
                    const double *restrict u, const double *restrict p,
                    double *restrict y)
{
    memset(y, 0, 3 * s->nb * sizeof *y);
    for (size_t i = 0; i < s->nb; i++) {
        const double *D = d + 9 * i, *pi = p + 3 * i;
        double p0 = pi[0], p1 = pi[1], p2 = pi[2];
        double y0 = y[3 * i] + D[0] * p0 + D[1] * p1 + D[2] * p2;
        double y1 = y[3 * i + 1] + D[3] * p0 + D[4] * p1 + D[5] * p2;
        double y2 = y[3 * i + 2] + D[6] * p0 + D[7] * p1 + D[8] * p2;
        for (size_t e = s->rowptr[i]; e < s->rowptr[i + 1]; e++) {
            const double *B = u + 9 * e, *q = p + 3 * s->col[e];
            double *yj = y + 3 * s->col[e];
            y0 += B[0] * q[0] + B[1] * q[1] + B[2] * q[2];
            y1 += B[3] * q[0] + B[4] * q[1] + B[5] * q[2];
            y2 += B[6] * q[0] + B[7] * q[1] + B[8] * q[2];
            yj[0] += B[0] * p0 + B[3] * p1 + B[6] * p2;
            yj[1] += B[1] * p0 + B[4] * p1 + B[7] * p2;
            yj[2] += B[2] * p0 + B[5] * p1 + B[8] * p2;
        }
        y[3 * i] = y0;
        y[3 * i + 1] = y1;
        y[3 * i + 2] = y2;
    }
}
