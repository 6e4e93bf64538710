/* Pair kernels: vectorised per-pair loops and the ordered scatter of their
 * results (forces/pairkern.h). */
#include "forces/pairkern.h"

#include <stdlib.h>
#include <string.h>

/* (Re)allocate the per-pair buffers for m pairs. */
static bool alloc_buffers(cl_pairkern *pk, size_t m)
{
    double **arr[] = {&pk->d, &pk->u0, &pk->u1, &pk->u2, &pk->s, &pk->ds,
                      &pk->f0, &pk->f1, &pk->f2};
    bool ok = true;
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++) {
        free(*arr[i]);
        ok &= (*arr[i] = malloc((m + 1) * sizeof **arr[i])) != NULL;
    }
    free(pk->blk);
    pk->blk = malloc(9 * (size_t)pk->nblk * (m + 1) * sizeof *pk->blk);
    return ok && pk->blk;
}

cl_status cl_pairkern_init(cl_pairkern *pk, const cl_pairset *set, int nblk,
                           cl_error *err)
{
    size_t n = set->n;
    memset(pk, 0, sizeof *pk);
    pk->n = n;
    pk->nblk = nblk;
    pk->threads = 1;
    pk->ia = malloc((n + 1) * sizeof *pk->ia);
    pk->ib = malloc((n + 1) * sizeof *pk->ib);
    pk->L = malloc((n + 1) * sizeof *pk->L);
    if (!pk->ia || !pk->ib || !pk->L ||
        !alloc_buffers(pk, n < CL_PAIRKERN_CHUNK ? n : CL_PAIRKERN_CHUNK))
        return cl_error_set(err, CL_ENOMEM, "out of memory (pair kernels, "
                            "%zu pairs)", n);
    for (size_t k = 0; k < n; k++) {
        pk->ia[k] = set->pair[k].a;
        pk->ib[k] = set->pair[k].b;
        pk->L[k] = set->pair[k].rest;
        size_t top = (size_t)(pk->ia[k] > pk->ib[k] ? pk->ia[k] : pk->ib[k]);
        pk->np = top + 1 > pk->np ? top + 1 : pk->np;
    }
    return CL_OK;
}

void cl_pairkern_free(cl_pairkern *pk)
{
    void *arr[] = {pk->ia, pk->ib, pk->L, pk->d, pk->u0, pk->u1, pk->u2,
                   pk->s, pk->ds, pk->f0, pk->f1, pk->f2, pk->blk,
                   pk->pstart, pk->pinc, pk->sstart, pk->sinc};
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++)
        free(arr[i]);
    memset(pk, 0, sizeof *pk);
}

void cl_pairkern_incidence(const long *key, size_t m, size_t nkey,
                           size_t *start, long *list)
{
    memset(start, 0, (nkey + 1) * sizeof *start);
    for (size_t c = 0; c < m; c++)
        if (key[c] >= 0)
            start[key[c] + 1]++;
    for (size_t q = 0; q < nkey; q++)
        start[q + 1] += start[q];
    for (size_t c = 0; c < m; c++)
        if (key[c] >= 0)
            list[start[key[c]]++] = (long)c; /* start[q]: end of q after */
    memmove(start + 1, start, nkey * sizeof *start);
    start[0] = 0;
}

/* The slot incidence (threads > 1 and a bound pattern). */
static cl_status slot_incidence(cl_pairkern *pk, cl_error *err)
{
    if (pk->threads <= 1 || !pk->slot)
        return CL_OK;
    free(pk->sstart);
    free(pk->sinc);
    pk->sstart = malloc((pk->nslot + 1) * sizeof *pk->sstart);
    pk->sinc = malloc((4 * pk->n + 1) * sizeof *pk->sinc);
    if (!pk->sstart || !pk->sinc)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pair kernels, "
                            "slot incidence)");
    cl_pairkern_incidence(pk->slot, 4 * pk->n, pk->nslot, pk->sstart,
                          pk->sinc);
    return CL_OK;
}

/* The particle incidence: code 2k + (p is b) of pair k under particle p. */
static cl_status particle_incidence(cl_pairkern *pk, cl_error *err)
{
    long *key = malloc((2 * pk->n + 1) * sizeof *key);
    free(pk->pstart);
    free(pk->pinc);
    pk->pstart = malloc((pk->np + 1) * sizeof *pk->pstart);
    pk->pinc = malloc((2 * pk->n + 1) * sizeof *pk->pinc);
    if (!key || !pk->pstart || !pk->pinc) {
        free(key);
        return cl_error_set(err, CL_ENOMEM, "out of memory (pair kernels, "
                            "incidence)");
    }
    for (size_t k = 0; k < pk->n; k++) {
        key[2 * k] = pk->ia[k];
        key[2 * k + 1] = pk->ib[k];
    }
    cl_pairkern_incidence(key, 2 * pk->n, pk->np, pk->pstart, pk->pinc);
    free(key);
    return CL_OK;
}

cl_status cl_pairkern_threads(cl_pairkern *pk, int threads, cl_error *err)
{
    cl_status rc;
    if (threads > 1 && pk->threads <= 1) {
        if (!alloc_buffers(pk, pk->n))
            return cl_error_set(err, CL_ENOMEM, "out of memory (pair "
                                "kernels, %zu pairs)", pk->n);
        if ((rc = particle_incidence(pk, err)))
            return rc;
    }
    /* Whole buffers stay once allocated: they serve one thread as well. */
    pk->threads = threads;
    return slot_incidence(pk, err);
}

cl_status cl_pairkern_bind(cl_pairkern *pk, const long *slot, size_t nslot,
                           cl_error *err)
{
    pk->slot = slot;
    pk->nslot = nslot;
    return slot_incidence(pk, err);
}

/* The geometry loop; recip (a constant where it is inlined): u = x_ab
 * (1/d), one division instead of three. */
CL_PAIR_INLINE void geometry(cl_pairkern *pk, size_t k0, size_t k1,
                             size_t base, const double *x, bool recip)
{
    const int *ia = pk->ia, *ib = pk->ib;
    double *restrict d = pk->d - base, *restrict u0 = pk->u0 - base;
    double *restrict u1 = pk->u1 - base, *restrict u2 = pk->u2 - base;
#pragma omp simd
    for (size_t k = k0; k < k1; k++)
        cl_pairkern_dir(x, 3 * ia[k], 3 * ib[k], recip, &d[k], &u0[k],
                        &u1[k], &u2[k]);
}

const char *cl_pairkern_isa(void)
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") ? "avx2" : "default";
#else
    return "default";
#endif
}

CL_PAIR_KERNEL
void cl_pairkern_geometry(cl_pairkern *pk, size_t k0, size_t k1,
                          size_t base, const double *x, bool recip)
{
    if (recip)
        geometry(pk, k0, k1, base, x, true);
    else
        geometry(pk, k0, k1, base, x, false);
}

/* Entry (r, c) of K = (s' - t) u u^T + t I, rounded as cl_pair_block
 * rounds it; s' alone on the diagonal for coincident particles. */
static inline double central_entry(bool some, double dst, double ur,
                                   double uc, double diag, double iso)
{
    double e = dst * ur * uc + diag;
    return some ? e : iso;
}

CL_PAIR_KERNEL
void cl_pairkern_central(cl_pairkern *pk, size_t k0, size_t k1, size_t base,
                         bool blocks, bool clamp_transverse)
{
    const double *restrict s = pk->s - base, *restrict ds = pk->ds - base;
    const double *restrict d = pk->d - base;
    const double *restrict u0 = pk->u0 - base, *restrict u1 = pk->u1 - base;
    const double *restrict u2 = pk->u2 - base;
    double *restrict f0 = pk->f0 - base, *restrict f1 = pk->f1 - base;
    double *restrict f2 = pk->f2 - base;
    size_t w = 9 * (size_t)pk->nblk;
    double *restrict K = pk->blk - w * base;
#pragma omp simd
    for (size_t k = k0; k < k1; k++) {
        f0[k] = s[k] * u0[k];
        f1[k] = s[k] * u1[k];
        f2[k] = s[k] * u2[k];
    }
    if (!blocks)
        return;
#pragma omp simd
    for (size_t k = k0; k < k1; k++) {
        double q = s[k] / d[k];
        double t = clamp_transverse & (s[k] < 0) ? 0.0 : q;
        double a = u0[k], b = u1[k], c = u2[k], dst = ds[k] - t;
        double v = ds[k];
        bool y = d[k] > 0;
        double *B = K + w * k;
        B[0] = central_entry(y, dst, a, a, t, v);
        B[1] = central_entry(y, dst, a, b, 0.0, 0.0);
        B[2] = central_entry(y, dst, a, c, 0.0, 0.0);
        B[3] = central_entry(y, dst, b, a, 0.0, 0.0);
        B[4] = central_entry(y, dst, b, b, t, v);
        B[5] = central_entry(y, dst, b, c, 0.0, 0.0);
        B[6] = central_entry(y, dst, c, a, 0.0, 0.0);
        B[7] = central_entry(y, dst, c, b, 0.0, 0.0);
        B[8] = central_entry(y, dst, c, c, t, v);
    }
}

static inline bool is_torn(const unsigned char *torn, size_t k)
{
    return torn && torn[k];
}

/* Phase 2 serially, pairs [k0, k1): f_a += f, f_b -= f. */
static void forces_serial(const cl_pairkern *pk, size_t k0, size_t k1,
                          size_t base, const unsigned char *torn,
                          double *restrict f)
{
    const int *restrict ia = pk->ia, *restrict ib = pk->ib;
    const double *restrict f0 = pk->f0 - base, *restrict f1 = pk->f1 - base;
    const double *restrict f2 = pk->f2 - base;
    for (size_t k = k0; k < k1; k++)
        if (!torn || !torn[k])
            cl_pairkern_scatter(f, (size_t)ia[k], (size_t)ib[k], f0[k], f1[k],
                                f2[k]);
}

/* Phase 2 by threads: each particle's contributions in increasing k. */
static void forces_threaded(const cl_pairkern *pk, const unsigned char *torn,
                            double *f)
{
    const double *f0 = pk->f0, *f1 = pk->f1, *f2 = pk->f2;
#pragma omp parallel for num_threads(pk->threads) schedule(static)
    for (size_t p = 0; p < pk->np; p++) {
        double *fp = f + 3 * p;
        for (size_t e = pk->pstart[p]; e < pk->pstart[p + 1]; e++) {
            size_t k = (size_t)pk->pinc[e] >> 1;
            if (is_torn(torn, k))
                continue;
            if (pk->pinc[e] & 1) {
                fp[0] -= f0[k];
                fp[1] -= f1[k];
                fp[2] -= f2[k];
            } else {
                fp[0] += f0[k];
                fp[1] += f1[k];
                fp[2] += f2[k];
            }
        }
    }
}

/* vals[slot] -= B for the aa, bb blocks (j < 2), += B for ab, ba (the
 * same roundings as adding -1 B).  A diagonal block adds its diagonal
 * alone: adding its zeros would change nothing, as entries start at +0
 * and sums and differences of them are never -0. */
static inline void add_block(double *restrict vals, long slot, int j,
                             const double *restrict B, bool diag)
{
    double *restrict dst = vals + 9 * slot;
    if (diag && j < 2) {
        dst[0] -= B[0];
        dst[4] -= B[4];
        dst[8] -= B[8];
    } else if (diag) {
        dst[0] += B[0];
        dst[4] += B[4];
        dst[8] += B[8];
    } else if (j < 2) {
#pragma omp simd
        for (int i = 0; i < 9; i++)
            dst[i] -= B[i];
    } else {
#pragma omp simd
        for (int i = 0; i < 9; i++)
            dst[i] += B[i];
    }
}

CL_PAIR_KERNEL
static void blocks_serial(const cl_pairkern *pk, size_t k0, size_t k1,
                          size_t base, const unsigned char *torn, int b,
                          double *vals)
{
    size_t w = 9 * (size_t)pk->nblk;
    bool diag = pk->diag >> b & 1;
    for (size_t k = k0; k < k1; k++) {
        if (is_torn(torn, k))
            continue;
        const double *B = pk->blk + w * (k - base) + 9 * (size_t)b;
        const long *s = pk->slot + 4 * k;
        for (int j = 0; j < 4; j++)
            if (s[j] >= 0)
                add_block(vals, s[j], j, B, diag);
    }
}

static void blocks_threaded(const cl_pairkern *pk, const unsigned char *torn,
                            int b, double *vals)
{
    size_t w = 9 * (size_t)pk->nblk;
    bool diag = pk->diag >> b & 1;
#pragma omp parallel for num_threads(pk->threads) schedule(static)
    for (size_t q = 0; q < pk->nslot; q++)
        for (size_t e = pk->sstart[q]; e < pk->sstart[q + 1]; e++) {
            size_t k = (size_t)pk->sinc[e] >> 2;
            if (!is_torn(torn, k))
                add_block(vals, (long)q, (int)(pk->sinc[e] & 3),
                          pk->blk + w * k + 9 * (size_t)b, diag);
        }
}

static size_t chunk_end(const cl_pairkern *pk, size_t c)
{
    size_t e = (c + 1) * CL_PAIRKERN_CHUNK;
    return e < pk->n ? e : pk->n;
}

void cl_pairkern_eval(cl_pairkern *pk, cl_pairkern_fn fn, void *ctx,
                      const unsigned char *torn, double *f,
                      double *const vals[2])
{
    size_t nch = (pk->n + CL_PAIRKERN_CHUNK - 1) / CL_PAIRKERN_CHUNK;
    if (pk->threads <= 1) {
        for (size_t c = 0; c < nch; c++) {
            size_t k0 = c * CL_PAIRKERN_CHUNK, k1 = chunk_end(pk, c);
            size_t base = pk->pinc ? 0 : k0;
            fn(ctx, pk, k0, k1, base);
            if (f)
                forces_serial(pk, k0, k1, base, torn, f);
            for (int b = 0; vals && b < pk->nblk; b++)
                if (vals[b])
                    blocks_serial(pk, k0, k1, base, torn, b, vals[b]);
        }
        return;
    }
#pragma omp parallel for num_threads(pk->threads) schedule(static)
    for (size_t c = 0; c < nch; c++)
        fn(ctx, pk, c * CL_PAIRKERN_CHUNK, chunk_end(pk, c), 0);
    if (f)
        forces_threaded(pk, torn, f);
    for (int b = 0; vals && b < pk->nblk; b++)
        if (vals[b])
            blocks_threaded(pk, torn, b, vals[b]);
}
