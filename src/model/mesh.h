/* Triangle mesh of a cloth and its interior edges (docs/model.md, 2), the
 * elements of the Baraff-Witkin model (docs/model.md, 3.3).
 *
 * Triangles: two per quad, from cl_grid_triangles (io/frames.h): quad
 * a = (i,j), b = (i+1,j), c = (i+1,j+1), d = (i,j+1) is split along a-c into
 * (a,b,c), (a,c,d).  With `[cloth] diagonal = alternate` the quads with
 * i + j odd are split along b-d instead, into (a,b,d), (b,c,d), so the
 * diagonals form a herringbone and the mesh has no preferred shear
 * direction.  Both splits keep every triangle counter-clockwise in the rest
 * (u, v) = (x, z) coordinates, so a shared edge runs in opposite directions
 * in its two triangles.  An n x n grid has 2(n-1)^2 triangles,
 * 3n^2 - 4n + 1 edges of which 4(n-1) lie on the boundary and
 * (n-1)(3n-5) are interior (the bending hinges).
 *
 * Interior edge k: v[0] -> v[1] is the edge as it runs in triangle tri[0],
 * v[2] the third vertex of tri[0], v[3] the third vertex of tri[1]. */
#ifndef CL_MESH_H
#define CL_MESH_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "io/config.h"

CL_BEGIN_DECLS

typedef enum { CL_DIAGONAL_FIXED = 0, CL_DIAGONAL_ALTERNATE = 1 } cl_diagonal;

typedef struct {
    int v[4];   /* edge v[0] -> v[1] (as in tri[0]), opposite v[2], v[3] */
    int tri[2]; /* the two triangles sharing the edge */
} cl_mesh_edge;

typedef struct {
    size_t ntri;
    int (*tri)[3];       /* particle indices, counter-clockwise at rest */
    size_t nedge;        /* interior edges */
    cl_mesh_edge *edge;
    size_t nboundary;    /* edges with one triangle */
} cl_mesh;

/* [cloth] diagonal = fixed (default) | alternate. */
cl_status cl_mesh_read_diagonal(cl_config *cfg, cl_diagonal *diag,
                                cl_error *err);

/* The mesh of an nu x nv grid (no triangles if nu < 2 or nv < 2). */
cl_status cl_mesh_grid(int nu, int nv, cl_diagonal diag, cl_mesh *m,
                       cl_error *err);

/* A mesh from a triangle list (copied): finds the interior edges.  An edge
 * shared by more than two triangles is an error. */
cl_status cl_mesh_from_triangles(size_t ntri, const int (*tri)[3], cl_mesh *m,
                                 cl_error *err);

void cl_mesh_free(cl_mesh *m);

CL_END_DECLS

#endif
