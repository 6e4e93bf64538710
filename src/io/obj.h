/* Wavefront OBJ triangle meshes: the obstacle meshes of the contact layer
 * and the cloth meshes of model/cloth (meshes made in a modeller such as
 * Blender and exported as OBJ).
 *
 * Read: `v x y z [w]` vertices (w ignored), `f` faces of three or more
 * vertices, each vertex `i`, `i/t`, `i//n` or `i/t/n` with i 1-based or
 * negative (relative to the vertices read so far: -1 is the last one);
 * a face may only use vertices defined above it.  Polygons are split into
 * a fan (0, k, k+1).  `vt`, `vn`, `o`, `g`, `s`, `usemtl`, `mtllib` and
 * comments ('#' to the end of the line) are accepted and ignored; any
 * other statement, a non-numeric or non-finite coordinate, an index 0 or
 * out of range, a degenerate triangle (a repeated vertex, or zero area:
 * |(b - a) x (c - a)| <= 1e-14 (|b - a|^2 + |c - b|^2 + |a - c|^2)), a
 * line longer than CL_OBJ_MAX_LINE characters (found without reading the
 * rest of it), a NUL byte, a file without vertices or without faces are
 * refused with CL_EPARSE and the message "PATH:LINE: reason"; a file that
 * cannot be opened or read gives CL_EIO. */
#ifndef CL_OBJ_H
#define CL_OBJ_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

#define CL_OBJ_MAX_LINE 65536

typedef struct {
    size_t nvert;
    double *vert;   /* 3 * nvert coordinates */
    size_t ntri;
    int (*tri)[3];  /* 0-based vertex indices, in the file's orientation */
} cl_obj;

/* On failure m is left empty (nothing to free). */
cl_status cl_obj_read(const char *path, cl_obj *m, cl_error *err);
/* Free and empty m (harmless on an empty or already freed mesh). */
void cl_obj_free(cl_obj *m);

/* Place the vertices: x <- scale x + shift (the `scale` and `translate`
 * keys of mesh cloths and mesh obstacles). */
void cl_obj_place(cl_obj *m, double scale, const double shift[3]);

CL_END_DECLS

#endif
