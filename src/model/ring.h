/* Topological neighbourhoods of a cloth's particles (docs/model.md 3.5):
 * the particles within `ring` steps of each particle in the graph of
 * nearest neighbours (cl_pairs_neighbours: structural and both diagonal
 * pairs of a grid, the triangle edges of a mesh), the particle itself
 * excluded.  On a grid, ring r is the (2r+1) x (2r+1) block around a
 * particle; ring 1 is every particle that shares a triangle edge (and on a
 * grid the other diagonal of its cells).
 *
 * Built once; cl_ring_has answers by a binary search in the particle's
 * sorted list, with no allocation. */
#ifndef CL_RING_H
#define CL_RING_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "model/cloth.h"

CL_BEGIN_DECLS

typedef struct {
    size_t np;
    int ring;        /* steps */
    size_t *start;   /* np + 1: the neighbours of p are nb[start[p] ..
                      * start[p+1]), sorted */
    int *nb;
} cl_ring;

/* ring >= 1. */
cl_status cl_ring_build(const cl_cloth *c, int ring, cl_ring *r,
                        cl_error *err);
void cl_ring_free(cl_ring *r);

/* Whether b is within r->ring steps of a (a != b). */
bool cl_ring_has(const cl_ring *r, int a, int b);

CL_END_DECLS

#endif
