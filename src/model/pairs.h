/* Pair connection sets on a grid cloth (SPEC 2), each unordered pair once.
 *
 *  Choi-Ko Type1 (sequential): (i,j)-(i+-1,j), (i,j+-1), (i+-1,j+-1);
 *    count 2(n-1)(2n-1) on an n x n grid.
 *  Choi-Ko Type2 (interlaced): (i,j)-(i+-2,j), (i,j+-2), (i+-2,j+-2);
 *    count 4(n-1)(n-2).
 *  Constraint levels 1..k (seed 004 "Level of Constraint"): level l
 *    connects (i,j) to (i+-l,j), (i,j+-l), (i+-l,j+-l); count
 *    2(n-l)(2n-l) per level l < n (level 1 = Type1's pairs).
 * Rest lengths come from cl_dist on the rest positions: the same expression
 * that forces use for current lengths, so that d == L bit for bit at rest. */
#ifndef CL_PAIRS_H
#define CL_PAIRS_H

#include <math.h>
#include <stddef.h>

#include "core/error.h"
#include "model/cloth.h"

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
void cl_pairs_free(cl_pairset *s);

/* |x_b - x_a|: the one distance expression used for rest and current
 * lengths. */
static inline double cl_dist(const double *xa, const double *xb)
{
    double dx = xb[0] - xa[0], dy = xb[1] - xa[1], dz = xb[2] - xa[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

#endif
