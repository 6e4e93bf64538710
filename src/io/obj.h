/* Wavefront OBJ triangle meshes: the obstacle meshes of the contact layer
 * and the cloth meshes of model/cloth (seed 003 builds its skirt and its
 * sphere in Blender and exports them as OBJ).
 *
 * Read: `v x y z [w]` vertices (w ignored), `f` faces of three or more
 * vertices, each vertex `i`, `i/t`, `i//n` or `i/t/n` with i 1-based or
 * negative (relative to the vertices read so far); polygons are split into
 * a fan (0, k, k+1).  `vt`, `vn`, `o`, `g`, `s`, `usemtl`, `mtllib` and
 * comments are accepted and ignored; any other statement, a non-numeric or
 * non-finite coordinate, an index 0 or out of range, a degenerate triangle
 * (a repeated vertex or zero area), a line longer than CL_OBJ_MAX_LINE, a
 * file without vertices or without faces are refused with CL_EPARSE naming
 * the file, the line and the reason. */
#ifndef CL_OBJ_H
#define CL_OBJ_H

#include <stddef.h>

#include "core/error.h"

#define CL_OBJ_MAX_LINE 65536

typedef struct {
    size_t nvert;
    double *vert;   /* 3 * nvert coordinates */
    size_t ntri;
    int (*tri)[3];  /* 0-based vertex indices, in the file's orientation */
} cl_obj;

cl_status cl_obj_read(const char *path, cl_obj *m, cl_error *err);
void cl_obj_free(cl_obj *m);

#endif
