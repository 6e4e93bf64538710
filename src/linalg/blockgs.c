/* Block Gauss-Seidel sweeps (linalg/blockgs.h). */
#include "linalg/blockgs.h"

#include <math.h>
#include <string.h>

/* Inverse of the row-major 3x3 block a by its adjugate; false if the
 * determinant is not positive and finite. */
static bool bgs_inverse3(const double *a, double *inv)
{
    double c0 = a[4] * a[8] - a[5] * a[7];
    double c1 = a[5] * a[6] - a[3] * a[8];
    double c2 = a[3] * a[7] - a[4] * a[6];
    double det = a[0] * c0 + a[1] * c1 + a[2] * c2;
    if (!(det > 0.0) || !isfinite(det))
        return false;
    double f = 1.0 / det;
    inv[0] = f * c0;
    inv[1] = f * (a[2] * a[7] - a[1] * a[8]);
    inv[2] = f * (a[1] * a[5] - a[2] * a[4]);
    inv[3] = f * c1;
    inv[4] = f * (a[0] * a[8] - a[2] * a[6]);
    inv[5] = f * (a[2] * a[3] - a[0] * a[5]);
    inv[6] = f * c2;
    inv[7] = f * (a[1] * a[6] - a[0] * a[7]);
    inv[8] = f * (a[0] * a[4] - a[1] * a[3]);
    return true;
}

bool cl_bgs_invert(size_t nb, const double *blk, const size_t *at,
                   double *dinv, size_t *row)
{
    for (size_t i = 0; i < nb; i++)
        if (!bgs_inverse3(blk + 9 * (at ? at[i] : i), dinv + 9 * i)) {
            *row = i;
            return false;
        }
    return true;
}

/* x_i = Dinv_i t (row-major 3x3 times 3). */
static inline void bgs_apply(const double *restrict m, const double t[3],
                             double *restrict xi)
{
    xi[0] = m[0] * t[0] + m[1] * t[1] + m[2] * t[2];
    xi[1] = m[3] * t[0] + m[4] * t[1] + m[5] * t[2];
    xi[2] = m[6] * t[0] + m[7] * t[1] + m[8] * t[2];
}

/* Position of entry (r, c) of an upper block (linalg/bsym.h). */
static const int bgs_at9[9] = CL_BSYM_AT9;
static const int bgs_at6[9] = CL_BSYM_AT6;

/* t -= B q for the upper block B (layout at). */
static inline void bgs_gather(const double *restrict B, const int *at,
                              const double *restrict q, double t[3])
{
    t[0] -= B[at[0]] * q[0] + B[at[1]] * q[1] + B[at[2]] * q[2];
    t[1] -= B[at[3]] * q[0] + B[at[4]] * q[1] + B[at[5]] * q[2];
    t[2] -= B[at[6]] * q[0] + B[at[7]] * q[1] + B[at[8]] * q[2];
}

/* y += sign B^T p for the upper block B (layout at). */
static inline void bgs_scatter(const double *restrict B, const int *at,
                               double sign, const double *restrict p,
                               double *restrict y)
{
    y[0] += sign * (B[at[0]] * p[0] + B[at[3]] * p[1] + B[at[6]] * p[2]);
    y[1] += sign * (B[at[1]] * p[0] + B[at[4]] * p[1] + B[at[7]] * p[2]);
    y[2] += sign * (B[at[2]] * p[0] + B[at[5]] * p[1] + B[at[8]] * p[2]);
}

/* One sweep, `six` and `forward` constants at each call, inlined there
 * (one straight-line loop per case, as linalg/bsym.c's product; left to
 * itself GCC made one call with the tests inside, 7 % more
 * instructions).  Forward
 * (rows ascending): w accumulates sum_{j<i} U_ji^T x_j(new), scattered by
 * the rows above, which row i subtracts.  Backward (descending): w = b -
 * A x = -L x, each row scattering -U_ij^T x_i into the rows j > i, which
 * are done; w_i is still 0 when row i subtracts it. */
static inline __attribute__((always_inline)) void
bgs_sweep(const cl_bsym *s, bool six, bool forward,
          const double *restrict dinv, const double *restrict u,
          const double *restrict b, double *restrict x, double *restrict w)
{
    const int *at = six ? bgs_at6 : bgs_at9;
    size_t width = six ? 6 : 9;
    double sign = forward ? 1.0 : -1.0;
    if (w)
        memset(w, 0, 3 * s->nb * sizeof *w);
    for (size_t k = 0; k < s->nb; k++) {
        size_t i = forward ? k : s->nb - 1 - k;
        double t[3] = {b[3 * i], b[3 * i + 1], b[3 * i + 2]};
        if (w)
            for (int c = 0; c < 3; c++)
                t[c] -= w[3 * i + c];
        for (size_t e = s->rowptr[i]; e < s->rowptr[i + 1]; e++)
            bgs_gather(u + width * e, at, x + 3 * s->col[e], t);
        double *xi = x + 3 * i;
        bgs_apply(dinv + 9 * i, t, xi);
        if (!w)
            continue;
        for (size_t e = s->rowptr[i]; e < s->rowptr[i + 1]; e++)
            bgs_scatter(u + width * e, at, sign, xi, w + 3 * s->col[e]);
    }
}

void cl_bsym_gs(const cl_bsym *s, cl_bsym_kind kind, bool forward,
                const double *restrict dinv, const double *restrict u,
                const double *restrict b, double *restrict x,
                double *restrict w)
{
    bool six = kind == CL_BSYM_BLOCKS;
    if (forward && six)
        bgs_sweep(s, true, true, dinv, u, b, x, w);
    else if (forward)
        bgs_sweep(s, false, true, dinv, u, b, x, w);
    else if (six)
        bgs_sweep(s, true, false, dinv, u, b, x, w);
    else
        bgs_sweep(s, false, false, dinv, u, b, x, w);
}

/* Row i of a sweep on all blocks: x_i = Dinv_i (b_i - sum A_ij x_j) over
 * the blocks j != i with j > i only (`upper`) or all of them. */
static inline void bgs_row(const cl_bpattern *pat, const double *restrict blk,
                           const double *restrict dinv,
                           const double *restrict b, double *restrict x,
                           size_t i, bool upper)
{
    double t[3] = {b[3 * i], b[3 * i + 1], b[3 * i + 2]};
    for (size_t k = pat->rowptr[i]; k < pat->rowptr[i + 1]; k++) {
        size_t j = pat->col[k];
        if (j != i && (!upper || j > i))
            bgs_gather(blk + 9 * k, bgs_at9, x + 3 * j, t);
    }
    bgs_apply(dinv + 9 * i, t, x + 3 * i);
}

void cl_bgs_backward(const cl_bpattern *pat, const double *restrict blk,
                     const double *restrict dinv, const double *restrict b,
                     double *restrict x)
{
    for (size_t i = pat->nb; i-- > 0;)
        bgs_row(pat, blk, dinv, b, x, i, true);
}

void cl_bgs_forward(const cl_bpattern *pat, const double *restrict blk,
                    const double *restrict dinv, const double *restrict b,
                    double *restrict x)
{
    for (size_t i = 0; i < pat->nb; i++)
        bgs_row(pat, blk, dinv, b, x, i, false);
}
