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
    free(s->tstart);
    free(s->tlist);
    free(s->trow);
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

/* The kind of blocks kb, kt (kt the transpose partner of kb; kb = kt for a
 * diagonal block) to within tol, relative to kb's largest entry:
 * CL_BSYM_NONE if kt^T differs from kb (or any entry is NaN), else
 * CL_BSYM_BLOCKS if kb is symmetric itself, else CL_BSYM_HALVES.
 * Unrolled: it runs over every block of every Jacobian. */
static inline cl_bsym_kind bsym_pair(const double *blk, size_t kb, size_t kt,
                                     double tol)
{
    const double *b = blk + 9 * kb, *bt = blk + 9 * kt;
    double big = 0.0;
#pragma GCC unroll 9
    for (int q = 0; q < 9; q++)
        big = fabs(b[q]) > big ? fabs(b[q]) : big;
    double lim = tol * big;
    bool halves = true;
#pragma GCC unroll 9
    for (int q = 0; q < 9; q++)
        halves &= fabs(b[q] - bt[3 * (q % 3) + q / 3]) <= lim; /* (r,c), (c,r) */
    bool own = fabs(b[1] - b[3]) <= lim && fabs(b[2] - b[6]) <= lim &&
               fabs(b[5] - b[7]) <= lim;
    return !halves ? CL_BSYM_NONE : own ? CL_BSYM_BLOCKS : CL_BSYM_HALVES;
}

cl_bsym_kind cl_bsym_check(const cl_bsym *s, const double *blk, double tol)
{
    cl_bsym_kind kind = CL_BSYM_BLOCKS;
    for (size_t i = 0; kind != CL_BSYM_NONE && i < s->nb; i++) {
        cl_bsym_kind k = bsym_pair(blk, s->diag[i], s->diag[i], tol);
        kind = k < kind ? k : kind;
    }
    for (size_t e = 0; kind != CL_BSYM_NONE && e < s->ne; e++) {
        cl_bsym_kind k = bsym_pair(blk, s->up[e], s->low[e], tol);
        kind = k < kind ? k : kind;
    }
    return kind;
}

cl_bsym_kind cl_bsym_check_threads(const cl_bsym *s, const double *blk,
                                   double tol, int threads)
{
    if (threads <= 1)
        return cl_bsym_check(s, blk, tol);
    int kind = CL_BSYM_BLOCKS; /* the least kind of any pair: any order */
#pragma omp parallel for num_threads(threads) schedule(static) \
    reduction(min : kind)
    for (size_t k = 0; k < s->nb + s->ne; k++) {
        int kk = k < s->nb ? (int)bsym_pair(blk, s->diag[k], s->diag[k], tol)
                           : (int)bsym_pair(blk, s->up[k - s->nb],
                                            s->low[k - s->nb], tol);
        kind = kk < kind ? kk : kind;
    }
    return (cl_bsym_kind)kind;
}

cl_bsym_kind cl_bsym_check_pair(const cl_bsym *s, const double *x,
                                const double *y, double tol, int threads)
{
    cl_bsym_kind kx = cl_bsym_check_threads(s, x, tol, threads);
    cl_bsym_kind ky = kx ? cl_bsym_check_threads(s, y, tol, threads)
                         : CL_BSYM_NONE;
    return kx < ky ? kx : ky;
}

/* Entries (r <= c) of a symmetric block kept by CL_BSYM_BLOCKS. */
static const int bsym_upper6[6] = {0, 1, 2, 4, 5, 8};

/* out = ca x + cb y over 9 values, or over the 6 of the upper triangle. */
static inline void bsym_combine(double ca, const double *restrict x,
                                double cb, const double *restrict y,
                                bool six, double *restrict out)
{
    if (six) {
#pragma GCC unroll 6
        for (int q = 0; q < 6; q++)
            out[q] = ca * x[bsym_upper6[q]] + cb * y[bsym_upper6[q]];
        return;
    }
#pragma GCC unroll 9
    for (int q = 0; q < 9; q++)
        out[q] = ca * x[q] + cb * y[q];
}

/* Diagonal blocks [dlo, dhi) and upper blocks [elo, ehi) of the packing
 * (cl_bsym_pack; y not NULL). */
static void bsym_pack_range(const cl_bsym *s, bool six, double ca,
                            const double *x, double cb, const double *y,
                            const double *mass, double *d, double *u,
                            const size_t range[4])
{
    for (size_t i = range[0]; i < range[1]; i++) {
        double *b = d + 9 * i;
        bsym_combine(ca, x + 9 * s->diag[i], cb, y + 9 * s->diag[i], false,
                     b);
        if (mass)
            for (int r = 0; r < 3; r++)
                b[4 * r] += mass[3 * i + r];
    }
    size_t w = six ? 6 : 9;
    for (size_t e = range[2]; e < range[3]; e++)
        bsym_combine(ca, x + 9 * s->up[e], cb, y + 9 * s->up[e], six,
                     u + w * e);
}

void cl_bsym_pack(const cl_bsym *s, cl_bsym_kind kind, double ca,
                  const double *x, double cb, const double *y,
                  const double *mass, double *d, double *u)
{
    cl_bsym_pack_threads(s, kind, ca, x, cb, y, mass, d, u, 1);
}

void cl_bsym_pack_threads(const cl_bsym *s, cl_bsym_kind kind, double ca,
                          const double *x, double cb, const double *y,
                          const double *mass, double *d, double *u,
                          int threads)
{
    /* Without Y: ca X + 0 X, the same values for finite X. */
    if (!y) {
        y = x;
        cb = 0.0;
    }
    bool six = kind == CL_BSYM_BLOCKS;
    if (threads <= 1) {
        const size_t all[4] = {0, s->nb, 0, s->ne};
        bsym_pack_range(s, six, ca, x, cb, y, mass, d, u, all);
        return;
    }
    size_t nb = s->nb, ne = s->ne, nt = (size_t)threads;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (size_t t = 0; t < nt; t++) {
        const size_t part[4] = {nb * t / nt, nb * (t + 1) / nt, ne * t / nt,
                                ne * (t + 1) / nt};
        bsym_pack_range(s, six, ca, x, cb, y, mass, d, u, part);
    }
}

void cl_bsym_unpack(const cl_bsym *s, cl_bsym_kind kind, const double *d,
                    const double *u, double *blk)
{
    static const int at9[9] = CL_BSYM_AT9, at6[9] = CL_BSYM_AT6;
    bool six = kind == CL_BSYM_BLOCKS;
    const int *at = six ? at6 : at9;
    size_t w = six ? 6 : 9;
    for (size_t i = 0; i < s->nb; i++)
        memcpy(blk + 9 * s->diag[i], d + 9 * i, 9 * sizeof *blk);
    for (size_t e = 0; e < s->ne; e++) {
        double *up = blk + 9 * s->up[e], *low = blk + 9 * s->low[e];
        const double *v = u + w * e;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                up[3 * r + c] = low[3 * c + r] = v[at[3 * r + c]];
    }
}

/* The products below keep row i's sum in registers; the transposed
 * contributions to the rows below go straight into y, which is read when
 * their turn comes. */

/* Row r of a 9-value block times (p0, p1, p2). */
static inline double bsym_row(const double *D, int r, double p0, double p1,
                              double p2)
{
    return D[3 * r] * p0 + D[3 * r + 1] * p1 + D[3 * r + 2] * p2;
}

/* Position of entry (r, c) of an upper block (bsym.h). */
static const int bsym_at9[9] = CL_BSYM_AT9;
static const int bsym_at6[9] = CL_BSYM_AT6;

/* One pass over the upper blocks, `six` a constant at each call so that
 * each layout gets its own straight-line loop. */
static inline void bsym_product(const cl_bsym *s, bool six,
                                const double *restrict d,
                                const double *restrict u,
                                const double *restrict p, double *restrict y)
{
    const int *at = six ? bsym_at6 : bsym_at9;
    size_t w = six ? 6 : 9;
    for (size_t i = 0; i < s->nb; i++) {
        const double *D = d + 9 * i, *pi = p + 3 * i;
        double p0 = pi[0], p1 = pi[1], p2 = pi[2];
        double y0 = y[3 * i] + bsym_row(D, 0, p0, p1, p2);
        double y1 = y[3 * i + 1] + bsym_row(D, 1, p0, p1, p2);
        double y2 = y[3 * i + 2] + bsym_row(D, 2, p0, p1, p2);
        for (size_t e = s->rowptr[i]; e < s->rowptr[i + 1]; e++) {
            const double *B = u + w * e, *q = p + 3 * s->col[e];
            double *yj = y + 3 * s->col[e];
            y0 += B[at[0]] * q[0] + B[at[1]] * q[1] + B[at[2]] * q[2];
            y1 += B[at[3]] * q[0] + B[at[4]] * q[1] + B[at[5]] * q[2];
            y2 += B[at[6]] * q[0] + B[at[7]] * q[1] + B[at[8]] * q[2];
            yj[0] += B[at[0]] * p0 + B[at[3]] * p1 + B[at[6]] * p2;
            yj[1] += B[at[1]] * p0 + B[at[4]] * p1 + B[at[7]] * p2;
            yj[2] += B[at[2]] * p0 + B[at[5]] * p1 + B[at[8]] * p2;
        }
        y[3 * i] = y0;
        y[3 * i + 1] = y1;
        y[3 * i + 2] = y2;
    }
}

void cl_bsym_matvec(const cl_bsym *s, cl_bsym_kind kind,
                    const double *restrict d, const double *restrict u,
                    const double *restrict p, double *restrict y)
{
    memset(y, 0, 3 * s->nb * sizeof *y);
    if (kind == CL_BSYM_BLOCKS)
        bsym_product(s, true, d, u, p, y);
    else
        bsym_product(s, false, d, u, p, y);
}

cl_status cl_bsym_transpose(cl_bsym *s, cl_error *err)
{
    free(s->tstart);
    free(s->tlist);
    free(s->trow);
    s->tstart = calloc(s->nb + 1, sizeof *s->tstart);
    s->tlist = malloc((s->ne + 1) * sizeof *s->tlist);
    s->trow = malloc((s->ne + 1) * sizeof *s->trow);
    if (!s->tstart || !s->tlist || !s->trow)
        return cl_error_set(err, CL_ENOMEM, "out of memory (symmetric "
                            "blocks by column, %zu)", s->ne);
    for (size_t e = 0; e < s->ne; e++)
        s->tstart[s->col[e] + 1]++;
    for (size_t i = 0; i < s->nb; i++)
        s->tstart[i + 1] += s->tstart[i];
    /* Rows in order, so each column's list increases; tstart[c] runs to
     * the end of column c and is shifted back below. */
    for (size_t j = 0; j < s->nb; j++)
        for (size_t e = s->rowptr[j]; e < s->rowptr[j + 1]; e++) {
            size_t at = s->tstart[s->col[e]]++;
            s->tlist[at] = e;
            s->trow[at] = j;
        }
    memmove(s->tstart + 1, s->tstart, s->nb * sizeof *s->tstart);
    s->tstart[0] = 0;
    return CL_OK;
}

/* Row i of the product, each contribution formed as bsym_product forms it
 * and added in its order: the transposed blocks of the rows above (in
 * increasing row), the diagonal block, the upper blocks. */
static inline void bsym_row_all(const cl_bsym *s, bool six, size_t i,
                                const double *restrict d,
                                const double *restrict u,
                                const double *restrict p, double *restrict y)
{
    const int *at = six ? bsym_at6 : bsym_at9;
    size_t w = six ? 6 : 9;
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (size_t t = s->tstart[i]; t < s->tstart[i + 1]; t++) {
        const double *B = u + w * s->tlist[t], *q = p + 3 * s->trow[t];
        y0 += B[at[0]] * q[0] + B[at[3]] * q[1] + B[at[6]] * q[2];
        y1 += B[at[1]] * q[0] + B[at[4]] * q[1] + B[at[7]] * q[2];
        y2 += B[at[2]] * q[0] + B[at[5]] * q[1] + B[at[8]] * q[2];
    }
    const double *D = d + 9 * i, *pi = p + 3 * i;
    y0 = y0 + bsym_row(D, 0, pi[0], pi[1], pi[2]);
    y1 = y1 + bsym_row(D, 1, pi[0], pi[1], pi[2]);
    y2 = y2 + bsym_row(D, 2, pi[0], pi[1], pi[2]);
    for (size_t e = s->rowptr[i]; e < s->rowptr[i + 1]; e++) {
        const double *B = u + w * e, *q = p + 3 * s->col[e];
        y0 += B[at[0]] * q[0] + B[at[1]] * q[1] + B[at[2]] * q[2];
        y1 += B[at[3]] * q[0] + B[at[4]] * q[1] + B[at[5]] * q[2];
        y2 += B[at[6]] * q[0] + B[at[7]] * q[1] + B[at[8]] * q[2];
    }
    y[3 * i] = y0;
    y[3 * i + 1] = y1;
    y[3 * i + 2] = y2;
}

void cl_bsym_matvec_threads(const cl_bsym *s, cl_bsym_kind kind,
                            const double *restrict d,
                            const double *restrict u,
                            const double *restrict p, double *restrict y,
                            int threads)
{
    if (threads <= 1 || !s->tstart) {
        cl_bsym_matvec(s, kind, d, u, p, y);
        return;
    }
    bool six = kind == CL_BSYM_BLOCKS;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (size_t i = 0; i < s->nb; i++)
        bsym_row_all(s, six, i, d, u, p, y);
}
