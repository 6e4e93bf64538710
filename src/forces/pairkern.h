/* Pair kernels: the per-pair work of the pair terms (forces/pairterm.h,
 * forces/pairdamp.h) as loops over structure-of-arrays buffers that GCC
 * vectorises, and the scatter of their results into forces and Jacobian
 * blocks, optionally by several OpenMP threads.
 *
 * An evaluation runs in two phases.  Phase 1 fills, for every pair k, its
 * geometry (d, u = x_ab/d), its law and its results: the force on a
 * (f0, f1, f2; the force on b is its negative) and up to two 3x3 blocks
 * (pairterm: K of docs/model.md (3.1); pairdamp: df/dv and df/dx).  Pairs
 * are independent, so threads split them in any way.  Phase 2 adds the
 * results in the order of the serial loop: force f_a += f, f_b -= f and
 * blocks aa, bb -= B, ab, ba += B, pair after pair.  With one thread it is
 * that loop; with several, each thread owns whole particles (slots) and
 * adds, for each, the contributions of its pairs in increasing k, from the
 * incidence lists built once.  Every entry is then the same sum in the
 * same order as the serial loop's, so forces and Jacobians are bitwise
 * independent of the thread count (and equal to the scalar loop's).
 *
 * The kernels carry target_clones("avx2", "default"): the loader picks the
 * AVX2 clone on CPUs that have it, the default (SSE2) clone elsewhere, so
 * the default build stays portable.  No FMA contraction happens (ISO C
 * mode, -ffp-contract=off), division and sqrt are correctly rounded in
 * either clone: the vector lanes compute bit for bit what the scalar code
 * computes.  Their files are compiled with -fno-math-errno and
 * -fno-trapping-math (the Makefile's KERNEL_CFLAGS), which GCC needs to
 * vectorise sqrt and selects; neither changes a result. */
#ifndef CL_PAIRKERN_H
#define CL_PAIRKERN_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "model/pairs.h"

CL_BEGIN_DECLS

/* Run-time dispatch by CPU features for the vectorised loops. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CL_PAIR_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define CL_PAIR_KERNEL
#endif

/* A loop body inlined into every kernel that calls it (compiled for that
 * kernel's target, with its constant arguments folded). */
#if defined(__GNUC__)
#define CL_PAIR_INLINE static inline __attribute__((always_inline))
#else
#define CL_PAIR_INLINE static inline
#endif

/* d = |x_b - x_a| and u = x_ab/d (with recip x_ab (1/d): one division
 * instead of three, u then differs from x_ab/d in the last bit), u = 0
 * for d = 0; a and b are 3 times the particle indices (cl_dist's
 * arithmetic; a loop body, inlined). */
CL_PAIR_INLINE void cl_pairkern_dir(const double *x, int a, int b,
                                    bool recip, double *d, double *u0,
                                    double *u1, double *u2)
{
    double dx = x[b] - x[a], dy = x[b + 1] - x[a + 1];
    double dz = x[b + 2] - x[a + 2];
    double dk = sqrt(dx * dx + dy * dy + dz * dz), rk = 1.0 / dk;
    double r0 = recip ? dx * rk : dx / dk;
    double r1 = recip ? dy * rk : dy / dk;
    double r2 = recip ? dz * rk : dz / dk;
    *d = dk;
    *u0 = dk > 0 ? r0 : 0.0;
    *u1 = dk > 0 ? r1 : 0.0;
    *u2 = dk > 0 ? r2 : 0.0;
}

/* Counting sort of the m codes c whose key key[c] >= 0 (keys < nkey)
 * into start (nkey + 1: key q's codes in [start[q], start[q + 1])) and
 * list: stable, so each key's codes increase. */
void cl_pairkern_incidence(const long *key, size_t m, size_t nkey,
                           size_t *start, long *list);

/* f_a += (f0, f1, f2), f_b -= (f0, f1, f2) for particles a, b (3 entries
 * each in f): a pair's force into a force array. */
static inline void cl_pairkern_scatter(double *CL_RESTRICT f, size_t a, size_t b,
                                       double f0, double f1, double f2)
{
    double *fa = f + 3 * a, *fb = f + 3 * b;
    fa[0] += f0;
    fa[1] += f1;
    fa[2] += f2;
    fb[0] -= f0;
    fb[1] -= f1;
    fb[2] -= f2;
}

/* The clone of the kernels this CPU runs: "avx2" or "default" (the
 * choice target_clones' resolver makes, by the same CPU test). */
const char *cl_pairkern_isa(void);

/* Pairs per chunk of phase 1: serially, phase 2 follows each chunk, so
 * the buffers hold one chunk; with threads they hold every pair. */
#define CL_PAIRKERN_CHUNK 256

typedef struct {
    size_t n;              /* pairs */
    int nblk;              /* blocks per pair: 1 or 2 */
    unsigned diag;         /* bit b: block b is diagonal (entries 0, 4, 8;
                            * the others are neither read nor added) */
    int *ia, *ib;          /* particle indices a, b */
    double *L;             /* rest lengths */
    /* Per-pair buffers, index k - base (base = k0 of the chunk serially, 0
     * with threads): */
    double *d, *u0, *u1, *u2; /* distance, direction (0 for d = 0) */
    double *s, *ds;        /* the law's s(d), s'(d) */
    double *f0, *f1, *f2;  /* force on a */
    double *blk;           /* nblk * 9 per pair, row-major, pair-major */
    int threads;           /* cl_pairkern_threads */
    const long *slot;      /* 4 per pair (cl_pair_slots), or NULL */
    size_t nslot;          /* blocks of the bound pattern */
    /* Incidence for the threaded phase 2 (allocated for threads > 1): */
    size_t np;             /* particles: 1 + the largest index */
    size_t *pstart;        /* np + 1: entries of particle p */
    long *pinc;            /* 2k (p is a) or 2k + 1 (p is b), increasing */
    size_t *sstart;        /* nslot + 1 */
    long *sinc;            /* 4k + j (block j of pair k), increasing */
} cl_pairkern;

/* Phase 1 of pairs [k0, k1): fill the buffers from index k0 - base. */
typedef void (*cl_pairkern_fn)(void *ctx, cl_pairkern *pk, size_t k0,
                               size_t k1, size_t base);

/* Buffers for the pairs of `set` (not owned) with nblk blocks each. */
cl_status cl_pairkern_init(cl_pairkern *pk, const cl_pairset *set, int nblk,
                           cl_error *err);
void cl_pairkern_free(cl_pairkern *pk);

/* Use `threads` threads from now on (whole buffers and incidence lists
 * for threads > 1, allocated here). */
cl_status cl_pairkern_threads(cl_pairkern *pk, int threads, cl_error *err);

/* The 4 slots per pair (aa, bb, ab, ba; -1: none) of cl_pair_slots, in a
 * pattern of nslot blocks (kept, not copied). */
cl_status cl_pairkern_bind(cl_pairkern *pk, const long *slot, size_t nslot,
                           cl_error *err);

/* d, u of pairs [k0, k1) at positions x (cl_dist's arithmetic); u =
 * x_ab/d, or with recip x_ab (1/d) (one division instead of three; u
 * then differs from x_ab/d in the last bit). */
void cl_pairkern_geometry(cl_pairkern *pk, size_t k0, size_t k1,
                          size_t base, const double *x, bool recip);

/* Central forces f = s u of pairs [k0, k1) and, with blocks, K of
 * docs/model.md (3.1) (isotropic s' I for d = 0; clamp_transverse drops
 * the transverse part where s < 0) into block 0. */
void cl_pairkern_central(cl_pairkern *pk, size_t k0, size_t k1, size_t base,
                         bool blocks, bool clamp_transverse);

/* One evaluation: phase 1 by fn over every pair, phase 2 into f (if not
 * NULL) and block b into vals[b] (b < nblk, if not NULL).  Pairs with
 * torn[k] set (torn may be NULL) add nothing. */
void cl_pairkern_eval(cl_pairkern *pk, cl_pairkern_fn fn, void *ctx,
                      const unsigned char *torn, double *f,
                      double *const vals[2]);

CL_END_DECLS

#endif
