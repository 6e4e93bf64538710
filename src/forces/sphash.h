/* A spatial hash of points for close-pair queries (Teschner, Heidelberger,
 * Mueller, Pomeranets and Gross, "Optimized Spatial Hashing for Collision
 * Detection of Deformable Objects", 2003): space is cut into cubic cells
 * of side `cell`; cell (i, j, k) = floor(x / cell) goes to bucket
 * (i p1 xor j p2 xor k p3) mod nbucket with their primes p1, p2, p3.
 * Every point lies in one bucket, sorted by bucket with a counting sort.
 * Two points closer than `cell` lie in neighbouring cells (each index
 * differs by at most 1), so the pairs closer than `cell` are found among
 * the points of the 27 buckets around each point (a bucket met twice,
 * when two of those cells collide, is scanned once); the distance test
 * drops the points of other cells that share a bucket.
 *
 * All arrays are sized at creation for np points (nbucket = the smallest
 * power of two >= 2 np): building and querying allocate nothing, so the
 * hash can be rebuilt at every force evaluation. */
#ifndef CL_SPHASH_H
#define CL_SPHASH_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct {
    double cell;        /* cell side (m), > 0 */
    size_t np;          /* points */
    size_t nbucket;     /* a power of two */
    size_t *start;      /* nbucket + 1: bucket b holds pt[start[b] ..
                         * start[b+1]) */
    int *pt;            /* np point numbers, by bucket */
    long (*ijk)[3];     /* np: each point's cell */
} cl_sphash;

/* For np points and cells of side `cell` (> 0). */
cl_status cl_sphash_init(cl_sphash *h, size_t np, double cell,
                         cl_error *err);
void cl_sphash_free(cl_sphash *h);

/* Sort the points x (3 np) into their buckets. */
void cl_sphash_build(cl_sphash *h, const double *x);

/* visit(ctx, a, b, d2) once for every pair a < b of the points last built
 * with |x_a - x_b|^2 < cell^2 (d2 that squared distance); x the same
 * positions. */
typedef void (*cl_sphash_visit)(void *ctx, int a, int b, double d2);
void cl_sphash_pairs(const cl_sphash *h, const double *x,
                     cl_sphash_visit visit, void *ctx);

CL_END_DECLS

#endif
