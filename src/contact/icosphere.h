/* The icosphere: a regular icosahedron (12 vertices, 20 triangles) whose
 * triangles are each split into four, `level` times over, the new
 * vertices (edge midpoints) pushed out onto the sphere.  Level L has
 * 20 * 4^L triangles and 10 * 4^L + 2 vertices, counter-clockwise seen
 * from outside; its triangles are nearly equal (unlike a UV sphere's,
 * which crowd at the poles).  The drawing of the sphere shape and the
 * mesh of the benchmark; scripts/make-meshes.py writes the same mesh
 * (level 3) as problems/meshes/sphere.obj. */
#ifndef CL_ICOSPHERE_H
#define CL_ICOSPHERE_H

#include "contact/shape.h"
#include "core/decls.h"

CL_BEGIN_DECLS

/* Level 0..8 (CL_EINVAL otherwise), centre and radius > 0; free with
 * cl_shape_surface_free. */
cl_status cl_icosphere(int level, const double centre[3], double radius,
                       cl_shape_surface *s, cl_error *err);

CL_END_DECLS

#endif
