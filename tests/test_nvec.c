/* Compiled serial vector operations (linalg/nvec.h) against SUNDIALS'
 * N_Vector_Serial: every replaced operation, with the special cases of
 * N_VLinearSum and N_VScale (factors 1, -1, a = b, a = -b, results in
 * place), gives bitwise the same numbers, the dot product and weighted
 * norms (four partial sums) the same to round-off; clones inherit the operations;
 * the vector is still a serial one.  Threads: on threaded vectors of
 * several chunks, the operations give bitwise the same results for 1, 2
 * and 3 threads, and the dot product is the chunks' four partial sums
 * added in chunk order; on the other vectors it stays one chunk. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "linalg/nvec.h"

#define NV_LEN 37

typedef struct {
    SUNContext ctx;
    N_Vector ref[3], fast[3]; /* x, y, z: same data in both */
} nv_pair;

static void nv_fill(N_Vector v, unsigned seed)
{
    double *d = N_VGetArrayPointer(v);
    for (int i = 0; i < NV_LEN; i++)
        d[i] = sin(1.7 * (i + 1) * (seed + 1)) * (i % 4 == 3 ? 0.0 : 3.0);
}

static void nv_init(nv_pair *p)
{
    cr_assert_eq(SUNContext_Create(NULL, &p->ctx), 0);
    for (int k = 0; k < 3; k++) {
        p->ref[k] = N_VNew_Serial(NV_LEN, p->ctx);
        p->fast[k] = cl_nvec_new(NV_LEN, p->ctx);
        cr_assert(p->ref[k] && p->fast[k]);
        nv_fill(p->ref[k], (unsigned)k);
        nv_fill(p->fast[k], (unsigned)k);
    }
}

static void nv_free(nv_pair *p)
{
    for (int k = 0; k < 3; k++) {
        N_VDestroy(p->ref[k]);
        N_VDestroy(p->fast[k]);
    }
    SUNContext_Free(&p->ctx);
}

static void nv_same(const nv_pair *p, const char *what)
{
    for (int k = 0; k < 3; k++)
        cr_assert_eq(memcmp(N_VGetArrayPointer(p->ref[k]),
                            N_VGetArrayPointer(p->fast[k]),
                            NV_LEN * sizeof(double)), 0, "%s: vector %d",
                     what, k);
}

static void nv_same_value(double a, double b, const char *what)
{
    cr_assert(memcmp(&a, &b, sizeof a) == 0, "%s: %.17g vs %.17g", what, a,
              b);
}

/* The sums in four partial sums (nvec.h): round-off apart, not bitwise
 * (37 entries: nine rounds of four and a tail of one). */
static void nv_close_value(double a, double b, const char *what)
{
    cr_assert(fabs(a - b) <= 1e-14 * fabs(a) && a != 0.0,
              "%s: %.17g vs %.17g", what, a, b);
}

Test(nvec, linear_sum_and_scale_cases_bitwise)
{
    const double f[] = {1.0, -1.0, 0.37, -2.5, 0.0};
    const int nf = sizeof f / sizeof f[0];
    /* z index: 2 (separate), 0 (z = x), 1 (z = y) */
    for (int za = 0; za < 3; za++) {
        for (int i = 0; i < nf; i++) {
            for (int j = 0; j < nf + 2; j++) {
                nv_pair p;
                nv_init(&p);
                double b = j < nf ? f[j] : (j == nf ? f[i] : -f[i]);
                int z = (2 + za) % 3;
                N_VLinearSum(f[i], p.ref[0], b, p.ref[1], p.ref[z]);
                N_VLinearSum(f[i], p.fast[0], b, p.fast[1], p.fast[z]);
                nv_same(&p, "linearsum");
                N_VScale(f[i], p.ref[1], p.ref[z]);
                N_VScale(f[i], p.fast[1], p.fast[z]);
                nv_same(&p, "scale");
                nv_free(&p);
            }
        }
    }
}

Test(nvec, elementwise_and_reductions_bitwise)
{
    nv_pair p;
    nv_init(&p);
    N_Vector *r = p.ref, *q = p.fast;
    N_VAbs(r[0], r[2]);
    N_VAbs(q[0], q[2]);
    N_VAddConst(r[2], 0.5, r[2]);
    N_VAddConst(q[2], 0.5, q[2]);
    nv_close_value(N_VWrmsNorm(r[0], r[2]), N_VWrmsNorm(q[0], q[2]),
                   "wrms");
    nv_same_value(N_VWrmsNormMask(r[0], r[2], r[1]),
                  N_VWrmsNormMask(q[0], q[2], q[1]), "wrmsmask");
    nv_close_value(N_VWL2Norm(r[0], r[2]), N_VWL2Norm(q[0], q[2]), "wl2");
    nv_close_value(N_VDotProd(r[0], r[1]), N_VDotProd(q[0], q[1]), "dot");
    nv_same_value(N_VMaxNorm(r[1]), N_VMaxNorm(q[1]), "maxnorm");
    nv_same_value(N_VMin(r[1]), N_VMin(q[1]), "min");
    nv_same_value(N_VL1Norm(r[1]), N_VL1Norm(q[1]), "l1");
    N_VProd(r[0], r[1], r[1]);
    N_VProd(q[0], q[1], q[1]);
    N_VDiv(r[0], r[2], r[0]);
    N_VDiv(q[0], q[2], q[0]);
    nv_same(&p, "prod, div");
    N_VInv(r[2], r[2]);
    N_VInv(q[2], q[2]);
    N_VCompare(0.4, r[0], r[1]);
    N_VCompare(0.4, q[0], q[1]);
    nv_same(&p, "inv, compare");
    cr_assert_eq(N_VInvTest(r[1], r[0]), N_VInvTest(q[1], q[0]));
    nv_same(&p, "invtest");
    N_VConst(-0.25, r[2]);
    N_VConst(-0.25, q[2]);
    nv_same(&p, "const");
    nv_free(&p);
}

Test(nvec, clones_inherit_and_stay_serial)
{
    SUNContext ctx;
    cr_assert_eq(SUNContext_Create(NULL, &ctx), 0);
    N_Vector v = cl_nvec_new(5, ctx);
    cr_assert_not_null(v);
    N_Vector c = N_VClone(v);
    cr_assert_not_null(c);
    cr_assert_eq(N_VGetVectorID(c), SUNDIALS_NVEC_SERIAL);
    cr_assert_eq(c->ops->nvlinearsum, v->ops->nvlinearsum);
    cr_assert_eq(c->ops->nvwrmsnorm, v->ops->nvwrmsnorm);
    cr_assert_neq((void *)v->ops->nvdotprod, (void *)N_VDotProd_Serial);
    cr_assert_eq(NV_LENGTH_S(c), 5);
    N_VDestroy(c);
    N_VDestroy(v);
    SUNContext_Free(&ctx);
}

/* Several chunks and a tail (nvec.h: CL_NVEC_CHUNK). */
#define NV_LONG (3 * CL_NVEC_CHUNK + 7)

/* The documented order (nvec.h): P = ceil(n / most) chunks of
 * c entries (a multiple of 4), the last the rest; per chunk four
 * interleaved partial sums, added as (s0 + s1) + (s2 + s3), then the
 * chunk's tail; the chunks in order. */
static double nv_chunked_dot(const double *x, const double *y, size_t n,
                             size_t most)
{
    size_t p = (n + most - 1) / most;
    size_t c = ((n + p - 1) / p + 3) / 4 * 4;
    double sum = 0.0;
    for (size_t lo = 0; lo < n; lo += c) {
        size_t hi = lo + c < n ? lo + c : n, i = lo;
        double s[4] = {0.0, 0.0, 0.0, 0.0};
        for (; i + 4 <= hi; i += 4)
            for (int q = 0; q < 4; q++)
                s[q] += x[i + q] * y[i + q];
        double part = (s[0] + s[1]) + (s[2] + s[3]);
        for (; i < hi; i++)
            part += x[i] * y[i];
        sum = lo == 0 ? part : sum + part;
    }
    return sum;
}

/* PCG's operations on `threads` threads: the vectors and the reductions. */
static void nv_pcg_ops(int threads, N_Vector v[3], double out[4])
{
    int old = cl_nvec_threads(threads);
    for (int k = 0; k < 3; k++) {
        double *d = N_VGetArrayPointer(v[k]);
        for (int i = 0; i < NV_LONG; i++)
            d[i] = sin(0.37 * (i + 1) * (k + 1)) + 0.5 * k;
    }
    out[0] = N_VDotProd(v[0], v[1]);
    N_VLinearSum(0.37, v[0], -2.5, v[1], v[2]);
    N_VLinearSum(1.0, v[2], 0.25, v[1], v[1]); /* y += a x */
    N_VLinearSum(1.0, v[0], -0.75, v[2], v[0]); /* x += b y */
    N_VScale(-1.5, v[1], v[2]);
    N_VProd(v[0], v[2], v[2]);
    out[1] = N_VDotProd(v[2], v[1]);
    out[2] = N_VWrmsNorm(v[0], v[1]);
    out[3] = cl_nvec_dot(N_VGetArrayPointer(v[0]),
                         N_VGetArrayPointer(v[2]), NV_LONG, threads);
    cr_assert_eq(cl_nvec_threads(old), threads);
}

Test(nvec, threads_bitwise_and_chunk_order)
{
    SUNContext ctx;
    cr_assert_eq(SUNContext_Create(NULL, &ctx), 0);
    N_Vector one[3], many[3];
    for (int k = 0; k < 3; k++) {
        one[k] = cl_nvec_new_threaded(NV_LONG, ctx);
        many[k] = N_VClone(one[k]); /* clones inherit the chunks */
        cr_assert(one[k] && many[k]);
    }
    double r1[4], rt[4];
    nv_pcg_ops(1, one, r1);
    const double *x = N_VGetArrayPointer(one[0]),
                 *z = N_VGetArrayPointer(one[2]);
    nv_same_value(r1[3], nv_chunked_dot(x, z, NV_LONG, CL_NVEC_CHUNK),
                  "chunk order");
    nv_same_value(N_VDotProd(one[0], one[2]), r1[3], "threaded vectors");
    N_Vector plain = cl_nvec_new(NV_LONG, ctx), pz = N_VClone(plain);
    cr_assert(plain && pz);
    memcpy(N_VGetArrayPointer(plain), x, NV_LONG * sizeof *x);
    memcpy(N_VGetArrayPointer(pz), z, NV_LONG * sizeof *z);
    /* N_VDotProd(x, y) calls y's operation: both plain here */
    nv_same_value(N_VDotProd(plain, pz),
                  nv_chunked_dot(x, z, NV_LONG, NV_LONG),
                  "other vectors: one chunk");
    N_VDestroy(pz);
    N_VDestroy(plain);
    for (int t = 2; t <= 3; t++) {
        nv_pcg_ops(t, many, rt);
        for (int k = 0; k < 3; k++)
            cr_assert_eq(memcmp(N_VGetArrayPointer(one[k]),
                                N_VGetArrayPointer(many[k]),
                                NV_LONG * sizeof(double)), 0,
                         "%d threads: vector %d", t, k);
        for (int q = 0; q < 4; q++)
            nv_same_value(r1[q], rt[q], "threaded reduction");
    }
    for (int k = 0; k < 3; k++) {
        N_VDestroy(one[k]);
        N_VDestroy(many[k]);
    }
    SUNContext_Free(&ctx);
}
