/* A bounding-volume hierarchy over a triangle mesh: a binary tree of
 * axis-aligned boxes built once by median splits, stored in flat arrays,
 * and the nearest triangle to a point by branch and bound.
 *
 * Build: a node holds the triangles order[first .. first + count); a node
 * of more than CL_BVH_LEAF triangles is split at the median of their
 * centroids along the longest side of the centroids' bounding box, so the
 * tree is balanced and its depth at most ceil(log2(ntri)) <= 30.  Nodes
 * are stored depth first: an inner node's left child follows it, its
 * right child is node[first].
 *
 * Query: a depth-first walk with a fixed stack on the C stack (no
 * allocation), the nearer child first, skipping every box farther than
 * the best triangle found so far; a triangle of a visited leaf is skipped
 * too when its plane is that far (a lower bound of its distance), and
 * otherwise gets the exact closest point (contact/triangle.h).  Brute
 * force tries every triangle the same way.  The answer is the triangle at
 * the least (computed) distance, the one of least index among triangles
 * at exactly that distance, whatever order they are tried in.  A
 * non-finite point gets some triangle with a non-finite distance. */
#ifndef CL_BVH_H
#define CL_BVH_H

#include <stdbool.h>
#include <stddef.h>

#include "contact/triangle.h"
#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

#define CL_BVH_LEAF 4

typedef struct {
    double lo[3], hi[3];    /* bounds of the node's triangles */
    int first;              /* leaf: first index into order; inner: right
                               child */
    int count;              /* leaf: number of triangles; inner: 0 */
} cl_bvh_node;

typedef struct {
    const double *vert;     /* 3 per vertex (borrowed) */
    const int (*tri)[3];    /* (borrowed) */
    size_t ntri;
    int *order;             /* triangle indices, leaf after leaf */
    cl_bvh_node *node;
    size_t nnode;
    double (*normal)[3];    /* unit normal of each triangle */
    cl_tri_geom *geom;      /* vertices and edges of each triangle */
} cl_bvh;

typedef struct {
    int tri;                /* the nearest triangle */
    cl_tri_point p;         /* its closest point and feature */
    double dist;            /* |x - p.c|, sqrt(p.dist2) */
} cl_bvh_hit;

/* The tree of ntri >= 1 triangles (at most INT_MAX / 2, none degenerate);
 * vert and tri are borrowed and must outlive it.  CL_EINVAL for no
 * triangles or too many, CL_ENOMEM. */
cl_status cl_bvh_build(cl_bvh *b, const double *vert, size_t ntri,
                       const int (*tri)[3], cl_error *err);

void cl_bvh_free(cl_bvh *b);

void cl_bvh_nearest(const cl_bvh *b, const double x[3], cl_bvh_hit *hit);

/* The nearest triangle of a point that moves little between queries
 * (temporal coherence with a certificate).  A full query keeps, besides
 * the answer, the CL_BVH_KEEP triangles nearest to the point x0 it was
 * made at, lower bounds of their distances there (their distances, after
 * a full query), and r0: every other triangle is at least r0 from x0.  At
 * x, d = |x - x0|, a triangle is at least its bound less d away (the
 * distance to a set is 1-Lipschitz), one not kept at least r0 - d; so
 * when the nearest kept one is within r0 - d it is the nearest of all,
 * and the kept triangles are all that is tried (in the order of their
 * bounds, stopping at the first whose bound less d is farther than the
 * best at x).  Otherwise a full query at x refills the cache (the kept
 * triangles measured at x first, so that the walk starts with a tight
 * bound).  When more than CL_BVH_TRIED kept triangles had to be tried (d
 * has grown), the anchor moves to x without measuring any more: the
 * bounds become the distances measured at x and, for the others, their
 * bounds less d, and r0 becomes r0 - d, so that d stays small and the
 * next queries try fewer.  The answer is cl_bvh_nearest's; true when the
 * kept triangles gave it, false when the tree was searched.  A zeroed
 * cache is empty. */
#define CL_BVH_KEEP 8
#define CL_BVH_TRIED 1

typedef struct {
    double x0[3];
    double r0;                  /* other triangles' distance from x0 */
    double dist[CL_BVH_KEEP];   /* the kept ones' distance bounds at x0,
                                   ascending */
    int tri[CL_BVH_KEEP];
    int n;                      /* kept; 0: empty */
} cl_bvh_cache;

bool cl_bvh_nearest_cached(const cl_bvh *b, const double x[3],
                           cl_bvh_cache *cache, cl_bvh_hit *hit);

/* The distance from x to the box of all triangles (0 inside): a lower
 * bound of the distance to any of them. */
double cl_bvh_box_distance(const cl_bvh *b, const double x[3]);

/* The least fraction a in [0, 1] at which the segment from x0 to x1
 * crosses a triangle (cl_tri_segment), INFINITY if none: a walk of the
 * boxes the segment meets (the slab test, boxes widened by 1e-9 of the
 * segment's length), the nearer child first, skipping boxes entered after
 * the best crossing found so far. */
double cl_bvh_segment(const cl_bvh *b, const double x0[3],
                      const double x1[3]);

/* The distance from x to [lo, hi] along one axis (0 inside). */
static inline double cl_axis_gap(double x, double lo, double hi)
{
    return x < lo ? lo - x : x > hi ? x - hi : 0.0;
}

/* The squared distance from x to the box [lo, hi] (0 inside), written
 * out per axis (GCC -O2 keeps a three-trip loop as a loop). */
static inline double cl_box_dist2(const double lo[3], const double hi[3],
                                  const double x[3])
{
    double d0 = cl_axis_gap(x[0], lo[0], hi[0]);
    double d1 = cl_axis_gap(x[1], lo[1], hi[1]);
    double d2 = cl_axis_gap(x[2], lo[2], hi[2]);
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/* Every triangle of the subtrees whose boxes `enter` accepts: a walk from
 * the root that skips a node and all below it when enter(lo, hi, ctx) is
 * false, and hands each triangle of an entered leaf to visit(t, ctx).  For
 * the build of structures that look at a mesh's neighbourhoods. */
void cl_bvh_walk(const cl_bvh *b,
                 bool (*enter)(const double lo[3], const double hi[3],
                               void *ctx),
                 void (*visit)(int t, void *ctx), void *ctx);

/* The same answer by trying every triangle: the reference of the tests and
 * of the benchmark. */
void cl_bvh_nearest_brute(const cl_bvh *b, const double x[3],
                          cl_bvh_hit *hit);

CL_END_DECLS

#endif
