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
 * force tries every triangle the same way.  The answer is a triangle at
 * the least distance (which one, among triangles at exactly that
 * distance, is unspecified).  A non-finite point gets some triangle with
 * a non-finite distance. */
#ifndef CL_BVH_H
#define CL_BVH_H

#include <stddef.h>

#include "contact/triangle.h"
#include "core/error.h"

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
} cl_bvh;

typedef struct {
    int tri;                /* the nearest triangle */
    cl_tri_point p;         /* its closest point and feature */
} cl_bvh_hit;

/* The tree of ntri >= 1 triangles (at most INT_MAX / 2, none degenerate);
 * vert and tri are borrowed and must outlive it.  CL_EINVAL for no
 * triangles or too many, CL_ENOMEM. */
cl_status cl_bvh_build(cl_bvh *b, const double *vert, size_t ntri,
                       const int (*tri)[3], cl_error *err);

void cl_bvh_free(cl_bvh *b);

void cl_bvh_nearest(const cl_bvh *b, const double x[3], cl_bvh_hit *hit);

/* The distance from x to the box of all triangles (0 inside): a lower
 * bound of the distance to any of them. */
double cl_bvh_box_distance(const cl_bvh *b, const double x[3]);

/* The same answer by trying every triangle: the reference of the tests and
 * of the benchmark. */
void cl_bvh_nearest_brute(const cl_bvh *b, const double x[3],
                          cl_bvh_hit *hit);

#endif
