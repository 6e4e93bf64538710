/* Pair connection sets on a cloth (docs/model.md, 2), each unordered pair
 * once.
 *
 * On a grid:
 *
 *  Choi-Ko Type1 (sequential): (i,j)-(i+-1,j), (i,j+-1), (i+-1,j+-1);
 *    count 2(n-1)(2n-1) on an n x n grid.
 *  Choi-Ko Type2 (interlaced): (i,j)-(i+-2,j), (i,j+-2), (i+-2,j+-2);
 *    count 4(n-1)(n-2).
 *  Constraint levels 1..k (the Verlet-and-PBD report's "Level of
 *  Constraint"): level l
 *    connects (i,j) to (i+-l,j), (i,j+-l), (i+-l,j+-l); count
 *    2(n-l)(2n-l) per level l < n (level 1 = Type1's pairs).
 * On the triangles of any cloth (cl_cloth tri; the springs of Zischg, Chea
 * and Aigner's mesh cloth, "Cloth Simulation"):
 *  edges: every triangle edge (3n^2 - 4n + 1 on an n x n grid);
 *  bend: the two far vertices of the two triangles of every interior edge
 *    ((n-1)(3n-5) on an n x n grid), each pair once, pairs that are
 *    triangle edges themselves (small closed meshes) left out.
 * The grid sets need a grid cloth (cl_cloth kind); the triangle sets work
 * on both kinds.
 * Rest lengths come from cl_dist on the rest positions: the same expression
 * that forces use for current lengths, so that d == L bit for bit at rest. */
#ifndef CL_PAIRS_H
#define CL_PAIRS_H

#include <math.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "model/cloth.h"

CL_BEGIN_DECLS

typedef struct {
    int a, b;       /* particle indices, a < b */
    double rest;    /* rest length L */
} cl_pair;

typedef struct {
    size_t n;
    cl_pair *pair;
} cl_pairset;

/* Offsets (di, dj) with di > 0 or (di == 0 and dj > 0) generate each
 * unordered pair once. */
cl_status cl_pairs_from_offsets(const cl_cloth *c, size_t noff,
                                const int (*off)[2], cl_pairset *s,
                                cl_error *err);
cl_status cl_pairs_type1(const cl_cloth *c, cl_pairset *s, cl_error *err);
cl_status cl_pairs_type2(const cl_cloth *c, cl_pairset *s, cl_error *err);

/* Generating offsets of levels 1..levels, 4 per level in the order (0,l),
 * (l,0), (l,l), (l,-l), into off (room for 4 levels rows); returns their
 * number. */
size_t cl_level_offsets(long levels, int (*off)[2]);
/* The pairs of levels 1..levels (levels beyond the grid add none). */
cl_status cl_pairs_levels(const cl_cloth *c, long levels, cl_pairset *s,
                          cl_error *err);
cl_status cl_pairs_mesh_edges(const cl_cloth *c, cl_pairset *s,
                              cl_error *err);
/* CL_EINVAL for a pair whose vertices coincide at rest (a folded mesh). */
cl_status cl_pairs_mesh_bend(const cl_cloth *c, cl_pairset *s, cl_error *err);

/* The nearest neighbours, for stretch diagnostics: Type1's pairs on a grid,
 * the triangle edges on a mesh. */
cl_status cl_pairs_neighbours(const cl_cloth *c, cl_pairset *s,
                              cl_error *err);

/* Append the pairs of *more to *s and free *more (also on failure). */
cl_status cl_pairs_append(cl_pairset *s, cl_pairset *more, cl_error *err);
void cl_pairs_free(cl_pairset *s);

/* |x_b - x_a|: the one distance expression used for rest and current
 * lengths. */
static inline double cl_dist(const double *xa, const double *xb)
{
    double dx = xb[0] - xa[0], dy = xb[1] - xa[1], dz = xb[2] - xa[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

CL_END_DECLS

#endif
