/* Compiled vector operations for serial N_Vectors (see nvec.h).  Each
 * function performs the arithmetic of its N_Vector_Serial counterpart in
 * the same order:
 *
 *   linearsum  z = a x + b y, with the serial special cases: y += a x
 *              (b = 1, z = y), x += b y (a = 1, z = x; axpy: +x for a
 *              factor 1, -x for -1), x + y, x - y, a x + y, a x - y,
 *              a (x + y), a (x - y);
 *   scale      z = c x (x *= c in place; copy for c = 1; -x for c = -1);
 *   wrmsnorm   sqrt(sum (x_i w_i)^2 / N), mask: only id_i > 0;
 *   wl2norm    sqrt(sum (x_i w_i)^2);
 *   the others elementwise; dot products and unmasked weighted sums of
 *   squares in four interleaved partial sums (nv_sum4), the other
 *   reductions in index order; the dot product of the threaded vectors
 *   by nv_sum4 per chunk (nv_chunk: about equal parts of at most
 *   CL_NVEC_CHUNK entries), the chunks' sums added in chunk order
 *   (nv_reduce).
 * Threads (cl_nvec_threads): linearsum, scale, prod, const and the
 * threaded vectors' dot product split into those chunks, so their
 * results do not depend on the thread count.
 * Every loop reads entry i of each input before it writes entry i of the
 * output, so any of the vectors may be the same. */
#include "linalg/nvec.h"

#include <math.h>
#include <stdbool.h>

/* The elementwise loops carry no dependence from one entry to the next
 * (entry i is read before it is written, whatever aliases), so they may be
 * vectorised: the same operations on every entry, hence the same results.
 * Reductions are not marked: vectorising them would reorder their sums. */
#define CL_SIMD _Pragma("omp simd")

#define NV_N(v) NV_LENGTH_S(v)
#define NV_D(v) NV_DATA_S(v)

/* ---- linear sums ------------------------------------------------------- */

/* The kernels take entries [0, n) of raw arrays, so that a threaded call
 * (nv_run) hands each of them one chunk. */

/* y <- a x + y */
static void nv_axpy(sunrealtype a, sunindextype n, const sunrealtype *xd,
                    sunrealtype *yd)
{
    if (a == 1.0) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            yd[i] += xd[i];
    } else if (a == -1.0) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            yd[i] -= xd[i];
    } else {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            yd[i] += a * xd[i];
    }
}

/* z = sx x + sy y for the sign patterns (+1, +1), (+1, -1) */
static void nv_sum(sunindextype n, const sunrealtype *xd,
                   const sunrealtype *yd, sunrealtype *zd, bool diff)
{
    if (diff) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = xd[i] - yd[i];
    } else {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = xd[i] + yd[i];
    }
}

/* z = a x + y (plus) or a x - y */
static void nv_lin(sunrealtype a, sunindextype n, const sunrealtype *xd,
                   const sunrealtype *yd, sunrealtype *zd, bool plus)
{
    if (plus) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = (a * xd[i]) + yd[i];
    } else {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = (a * xd[i]) - yd[i];
    }
}

/* z = c (x + y) (plus) or c (x - y) */
static void nv_scalesum(sunrealtype c, sunindextype n, const sunrealtype *xd,
                        const sunrealtype *yd, sunrealtype *zd, bool plus)
{
    if (plus) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = c * (xd[i] + yd[i]);
    } else {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = c * (xd[i] - yd[i]);
    }
}

/* z = a x + b y over n entries; z == y and z == x (the same vector) select
 * the in-place cases as N_VLinearSum_Serial does. */
static void nv_linearsum_n(sunrealtype a, const sunrealtype *xd,
                           sunrealtype b, const sunrealtype *yd,
                           sunrealtype *zd, sunindextype n)
{
    if (b == 1.0 && zd == yd) {
        nv_axpy(a, n, xd, zd);
    } else if (a == 1.0 && zd == xd) {
        nv_axpy(b, n, yd, zd);
    } else if (a == 1.0 && b == 1.0) {
        nv_sum(n, xd, yd, zd, false);
    } else if (a == 1.0 && b == -1.0) {
        nv_sum(n, xd, yd, zd, true);
    } else if (a == -1.0 && b == 1.0) {
        nv_sum(n, yd, xd, zd, true);
    } else if (a == 1.0 || b == 1.0) {
        nv_lin(a == 1.0 ? b : a, n, a == 1.0 ? yd : xd, a == 1.0 ? xd : yd,
               zd, true);
    } else if (a == -1.0 || b == -1.0) {
        nv_lin(a == -1.0 ? b : a, n, a == -1.0 ? yd : xd,
               a == -1.0 ? xd : yd, zd, false);
    } else if (a == b) {
        nv_scalesum(a, n, xd, yd, zd, true);
    } else if (a == -b) {
        nv_scalesum(a, n, xd, yd, zd, false);
    } else {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = (a * xd[i]) + (b * yd[i]);
    }
}

/* z = c x over n entries (x *= c in place; copy for c = 1; -x for -1) */
static void nv_scale_n(sunrealtype c, const sunrealtype *xd, sunrealtype *zd,
                       sunindextype n)
{
    if (zd == xd) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] *= c;
    } else if (c == 1.0) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = xd[i];
    } else if (c == -1.0) {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = -xd[i];
    } else {
        CL_SIMD
        for (sunindextype i = 0; i < n; i++)
            zd[i] = c * xd[i];
    }
}

/* ---- threads ------------------------------------------------------------ */

/* Threads of the operations called from this thread (cl_nvec_threads). */
static _Thread_local int nv_threads = 1;

int cl_nvec_threads(int threads)
{
    int old = nv_threads;
    nv_threads = threads > 1 ? threads : 1;
    return old;
}

/* The chunks of an n-entry vector, independent of the thread count:
 * P = ceil(n / CL_NVEC_CHUNK) (at most NV_MAXCHUNKS) about equal parts,
 * each of c entries (c a multiple of 4) but the last, which has the
 * rest; *nc of them (P, or fewer after the rounding).  A vector of at
 * most CL_NVEC_CHUNK entries is one chunk. */
#define NV_MAXCHUNKS 1024

static sunindextype nv_chunk(sunindextype n, sunindextype *nc)
{
    sunindextype p = (n + CL_NVEC_CHUNK - 1) / CL_NVEC_CHUNK;
    p = p < 1 ? 1 : p > NV_MAXCHUNKS ? NV_MAXCHUNKS : p;
    sunindextype c = ((n + p - 1) / p + 3) / 4 * 4;
    c = c < 4 ? 4 : c;
    *nc = (n + c - 1) / c;
    return c;
}

/* One elementwise operation of the threaded set, on raw arrays. */
typedef enum { NV_LINEARSUM, NV_SCALE, NV_PROD, NV_CONST } nv_op;

typedef struct {
    nv_op op;
    sunrealtype a, b;
    const sunrealtype *x, *y;
    sunrealtype *z;
} nv_job;

static void nv_prod_n(const sunrealtype *xd, const sunrealtype *yd,
                      sunrealtype *zd, sunindextype n)
{
    CL_SIMD
    for (sunindextype i = 0; i < n; i++)
        zd[i] = xd[i] * yd[i];
}

static void nv_const_n(sunrealtype c, sunrealtype *zd, sunindextype n)
{
    CL_SIMD
    for (sunindextype i = 0; i < n; i++)
        zd[i] = c;
}

/* Entries [lo, hi) of job j. */
static void nv_apply(const nv_job *j, sunindextype lo, sunindextype hi)
{
    const sunrealtype *x = j->x + lo, *y = j->y ? j->y + lo : NULL;
    sunrealtype *z = j->z + lo;
    switch (j->op) {
    case NV_LINEARSUM:
        nv_linearsum_n(j->a, x, j->b, y, z, hi - lo);
        break;
    case NV_SCALE:
        nv_scale_n(j->a, x, z, hi - lo);
        break;
    case NV_PROD:
        nv_prod_n(x, y, z, hi - lo);
        break;
    case NV_CONST:
        nv_const_n(j->a, z, hi - lo);
        break;
    }
}

/* Job j over n entries: whole when one thread (or one chunk), else chunk
 * by chunk on nv_threads threads.  Elementwise: the same values for any
 * split. */
static void nv_run(const nv_job *j, sunindextype n)
{
    sunindextype nc, c = nv_chunk(n, &nc);
    int nt = nv_threads;
    if (nt <= 1 || nc <= 1) {
        nv_apply(j, 0, n);
        return;
    }
#pragma omp parallel for num_threads(nt) schedule(static)
    for (sunindextype k = 0; k < nc; k++)
        nv_apply(j, k * c, k + 1 < nc ? (k + 1) * c : n);
}

static void nv_linearsum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y,
                         N_Vector z)
{
    nv_job j = {NV_LINEARSUM, a, b, NV_D(x), NV_D(y), NV_D(z)};
    nv_run(&j, NV_N(x));
}

static void nv_scale(sunrealtype c, N_Vector x, N_Vector z)
{
    nv_job j = {NV_SCALE, c, 0.0, NV_D(x), NULL, NV_D(z)};
    nv_run(&j, NV_N(x));
}

/* ---- elementwise ------------------------------------------------------- */

static void nv_const(sunrealtype c, N_Vector z)
{
    nv_job j = {NV_CONST, c, 0.0, NV_D(z), NULL, NV_D(z)};
    nv_run(&j, NV_N(z));
}

static void nv_prod(N_Vector x, N_Vector y, N_Vector z)
{
    nv_job j = {NV_PROD, 0.0, 0.0, NV_D(x), NV_D(y), NV_D(z)};
    nv_run(&j, NV_N(x));
}

static void nv_div(N_Vector x, N_Vector y, N_Vector z)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x), *yd = NV_D(y);
    sunrealtype *zd = NV_D(z);
    CL_SIMD
    for (sunindextype i = 0; i < n; i++)
        zd[i] = xd[i] / yd[i];
}

static void nv_abs(N_Vector x, N_Vector z)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype *zd = NV_D(z);
    CL_SIMD
    for (sunindextype i = 0; i < n; i++)
        zd[i] = fabs(xd[i]);
}

static void nv_inv(N_Vector x, N_Vector z)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype *zd = NV_D(z);
    CL_SIMD
    for (sunindextype i = 0; i < n; i++)
        zd[i] = 1.0 / xd[i];
}

static void nv_addconst(N_Vector x, sunrealtype b, N_Vector z)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype *zd = NV_D(z);
    CL_SIMD
    for (sunindextype i = 0; i < n; i++)
        zd[i] = xd[i] + b;
}

static void nv_compare(sunrealtype c, N_Vector x, N_Vector z)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype *zd = NV_D(z);
    for (sunindextype i = 0; i < n; i++)
        zd[i] = fabs(xd[i]) >= c ? 1.0 : 0.0;
}

static sunbooleantype nv_invtest(N_Vector x, N_Vector z)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype *zd = NV_D(z);
    sunbooleantype no_zero = SUNTRUE;
    for (sunindextype i = 0; i < n; i++) {
        if (xd[i] == 0.0)
            no_zero = SUNFALSE;
        else
            zd[i] = 1.0 / xd[i];
    }
    return no_zero;
}

/* ---- reductions -------------------------------------------------------- */

/* The two reductions CVODE and PCG call at every iteration (dot products,
 * weighted norms) sum in four interleaved partial sums (entry i into sum
 * i mod 4, in index order), added as (s0 + s1) + (s2 + s3), then the tail:
 * a fixed order, so results are reproducible, but not N_Vector_Serial's
 * single running sum (they agree to round-off).  One running sum waits
 * for the previous addition at every entry; four keep the adder busy. */
static sunrealtype nv_sum4(const sunrealtype *x, const sunrealtype *y,
                           sunindextype n, bool square)
{
    sunrealtype s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    sunindextype i = 0;
    if (square) { /* (x_i y_i)^2 */
        for (; i + 4 <= n; i += 4) {
            sunrealtype p0 = x[i] * y[i], p1 = x[i + 1] * y[i + 1];
            sunrealtype p2 = x[i + 2] * y[i + 2], p3 = x[i + 3] * y[i + 3];
            s0 += p0 * p0;
            s1 += p1 * p1;
            s2 += p2 * p2;
            s3 += p3 * p3;
        }
    } else { /* x_i y_i */
        for (; i + 4 <= n; i += 4) {
            s0 += x[i] * y[i];
            s1 += x[i + 1] * y[i + 1];
            s2 += x[i + 2] * y[i + 2];
            s3 += x[i + 3] * y[i + 3];
        }
    }
    sunrealtype sum = (s0 + s1) + (s2 + s3);
    for (; i < n; i++) {
        sunrealtype p = x[i] * y[i];
        sum += square ? p * p : p;
    }
    return sum;
}

/* sum x_i y_i (or (x_i y_i)^2) chunk by chunk (nv_chunk), each chunk by
 * nv_sum4, the chunks' sums added in chunk order: the same value for any
 * thread count.  A vector of one chunk is summed as by nv_sum4 alone. */
static sunrealtype nv_reduce(const sunrealtype *x, const sunrealtype *y,
                             sunindextype n, bool square, int threads)
{
    sunindextype nc, c = nv_chunk(n, &nc);
    if (nc <= 1)
        return nv_sum4(x, y, n, square);
    sunrealtype part[NV_MAXCHUNKS];
    if (threads <= 1) {
        for (sunindextype k = 0; k < nc; k++)
            part[k] = nv_sum4(x + k * c, y + k * c,
                              k + 1 < nc ? c : n - k * c, square);
    } else {
#pragma omp parallel for num_threads(threads) schedule(static)
        for (sunindextype k = 0; k < nc; k++)
            part[k] = nv_sum4(x + k * c, y + k * c,
                              k + 1 < nc ? c : n - k * c, square);
    }
    sunrealtype sum = part[0];
    for (sunindextype k = 1; k < nc; k++)
        sum += part[k];
    return sum;
}

double cl_nvec_dot(const double *x, const double *y, size_t n, int threads)
{
    return nv_reduce(x, y, (sunindextype)n, false, threads);
}

static sunrealtype nv_dotprod(N_Vector x, N_Vector y)
{
    return nv_sum4(NV_D(x), NV_D(y), NV_N(x), false);
}

/* The dot product of the threaded vectors (cl_nvec_new_threaded). */
static sunrealtype nv_dotprod_chunks(N_Vector x, N_Vector y)
{
    return nv_reduce(NV_D(x), NV_D(y), NV_N(x), false, nv_threads);
}

static sunrealtype nv_maxnorm(N_Vector x)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype max = 0.0;
    for (sunindextype i = 0; i < n; i++) {
        if (fabs(xd[i]) > max)
            max = fabs(xd[i]);
    }
    return max;
}

/* sum (x_i w_i)^2 over the entries with id_i > 0 (all if id is NULL) */
static sunrealtype nv_wsqrsum(N_Vector x, N_Vector w, N_Vector id)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x), *wd = NV_D(w);
    const sunrealtype *idd = id ? NV_D(id) : NULL;
    if (!idd)
        return nv_sum4(xd, wd, n, true);
    sunrealtype sum = 0.0;
    for (sunindextype i = 0; i < n; i++) {
        if (!(idd[i] > 0.0))
            continue;
        sunrealtype p = xd[i] * wd[i];
        sum += p * p;
    }
    return sum;
}

static sunrealtype nv_wsqrsumlocal(N_Vector x, N_Vector w)
{
    return nv_wsqrsum(x, w, NULL);
}

static sunrealtype nv_wsqrsummasklocal(N_Vector x, N_Vector w, N_Vector id)
{
    return nv_wsqrsum(x, w, id);
}

static sunrealtype nv_wrmsnorm(N_Vector x, N_Vector w)
{
    return sqrt(nv_wsqrsum(x, w, NULL) / (sunrealtype)NV_N(x));
}

static sunrealtype nv_wrmsnormmask(N_Vector x, N_Vector w, N_Vector id)
{
    return sqrt(nv_wsqrsum(x, w, id) / (sunrealtype)NV_N(x));
}

static sunrealtype nv_wl2norm(N_Vector x, N_Vector w)
{
    return sqrt(nv_wsqrsum(x, w, NULL));
}

static sunrealtype nv_min(N_Vector x)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype min = n > 0 ? xd[0] : 0.0;
    for (sunindextype i = 1; i < n; i++) {
        if (xd[i] < min)
            min = xd[i];
    }
    return min;
}

static sunrealtype nv_l1norm(N_Vector x)
{
    sunindextype n = NV_N(x);
    const sunrealtype *xd = NV_D(x);
    sunrealtype sum = 0.0;
    for (sunindextype i = 0; i < n; i++)
        sum += fabs(xd[i]);
    return sum;
}

/* ---- installation ------------------------------------------------------ */

void cl_nvec_fast(N_Vector v)
{
    N_Vector_Ops o = v->ops;
    o->nvlinearsum = nv_linearsum;
    o->nvconst = nv_const;
    o->nvprod = nv_prod;
    o->nvdiv = nv_div;
    o->nvscale = nv_scale;
    o->nvabs = nv_abs;
    o->nvinv = nv_inv;
    o->nvaddconst = nv_addconst;
    o->nvdotprod = nv_dotprod;
    o->nvmaxnorm = nv_maxnorm;
    o->nvwrmsnorm = nv_wrmsnorm;
    o->nvwrmsnormmask = nv_wrmsnormmask;
    o->nvmin = nv_min;
    o->nvwl2norm = nv_wl2norm;
    o->nvl1norm = nv_l1norm;
    o->nvcompare = nv_compare;
    o->nvinvtest = nv_invtest;
    o->nvdotprodlocal = nv_dotprod;
    o->nvmaxnormlocal = nv_maxnorm;
    o->nvminlocal = nv_min;
    o->nvl1normlocal = nv_l1norm;
    o->nvinvtestlocal = nv_invtest;
    o->nvwsqrsumlocal = nv_wsqrsumlocal;
    o->nvwsqrsummasklocal = nv_wsqrsummasklocal;
}

N_Vector cl_nvec_new(sunindextype n, SUNContext ctx)
{
    N_Vector v = N_VNew_Serial(n, ctx);
    if (v)
        cl_nvec_fast(v);
    return v;
}

N_Vector cl_nvec_new_threaded(sunindextype n, SUNContext ctx)
{
    N_Vector v = cl_nvec_new(n, ctx);
    if (v) {
        v->ops->nvdotprod = nv_dotprod_chunks;
        v->ops->nvdotprodlocal = nv_dotprod_chunks;
    }
    return v;
}
