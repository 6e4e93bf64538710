/* Closed, consistently oriented triangle surfaces: every edge shared by
 * exactly two triangles that run it in opposite directions, so that the
 * surface bounds a solid and its triangles all face the same side of it.
 * The edges come from model/mesh (cl_mesh_from_triangles); here each side
 * of each triangle learns its edge and so the triangle across it. */
#ifndef CL_CLOSED_H
#define CL_CLOSED_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "model/mesh.h"

CL_BEGIN_DECLS

typedef struct {
    cl_mesh mesh;       /* its edges: all interior, mesh.nboundary == 0 */
    int (*side)[3];     /* side[t][k]: the edge of side k of triangle t,
                           from tri[t][k] to tri[t][(k + 1) % 3] */
} cl_closed;

/* CL_EINVAL, naming an edge by its vertices (numbered from 0), for an edge
 * of more than two triangles, an edge of one triangle only (the surface
 * is not closed) or an edge its two triangles run the same way (they face
 * opposite sides); CL_ENOMEM. */
cl_status cl_closed_build(size_t ntri, const int (*tri)[3], cl_closed *s,
                          cl_error *err);

void cl_closed_free(cl_closed *s);

/* The triangle across side k of triangle t. */
int cl_closed_across(const cl_closed *s, int t, int k);

CL_END_DECLS

#endif
