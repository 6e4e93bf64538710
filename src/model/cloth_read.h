/* The cloth of a problem, from INI section [cloth]: a grid (the default)
 * or a triangle mesh read from a Wavefront OBJ file; and the refusal of
 * grid-only features on a mesh cloth.
 *
 * Grid keys:  n (particles per side, default 16) or nu, nv; size (m,
 *             default 1) or su, sv; diagonal (the Baraff-Witkin
 *             triangulation, model/mesh.h).
 * Mesh keys:  mesh = FILE.obj (relative to the directory of the file that
 *             sets it, io/config.h cl_config_path_of): particles are the
 *             file's vertices, triangles its triangles (io/obj.h); scale
 *             (> 0, default 1) and translate (vector, m, default 0,0,0):
 *             rest position = scale * vertex + translate.
 * Both:       mass (total kg, default 0.1); particle_mass (kg, overrides
 *             mass: every particle gets it).  A grid spreads mass evenly; a
 *             mesh by vertex areas (model/cloth.h cl_cloth_mesh).
 * Grid keys together with `mesh`, and mesh keys without it, are refused
 * with a message naming the key. */
#ifndef CL_CLOTH_READ_H
#define CL_CLOTH_READ_H

#include "core/decls.h"
#include "io/config.h"
#include "model/cloth.h"

CL_BEGIN_DECLS

cl_status cl_cloth_read(cl_config *cfg, cl_cloth *c, cl_error *err);

/* CL_OK on a grid cloth.  On a mesh cloth CL_EINVAL with the message
 *     origin: [sec] key = "value": why
 * naming [sec] key when the problem sets it (the key that asks for the
 * grid-only feature), otherwise [cloth] mesh. */
cl_status cl_cloth_grid_only(cl_config *cfg, const cl_cloth *c,
                             const char *sec, const char *key,
                             const char *why, cl_error *err);

CL_END_DECLS

#endif
