/* The obstacle shapes selectable by `shape = NAME` (contact/shape.h): one
 * row per shape file.
 *
 *   sphere  centre and radius
 *   plane   a half-space: a point and the outward normal
 *   box     axis-aligned, centre and side lengths
 *   mesh    a closed triangle mesh read from an OBJ file */
#include <stdlib.h>
#include <string.h>

#include "contact/shape.h"

extern const cl_shape_type cl_shape_sphere;
extern const cl_shape_type cl_shape_plane;
extern const cl_shape_type cl_shape_box;
extern const cl_shape_type cl_shape_mesh;

const cl_shape_type *const cl_shape_registry[] = {
    &cl_shape_sphere,
    &cl_shape_plane,
    &cl_shape_box,
    &cl_shape_mesh,
    NULL,
};

const cl_shape_type *cl_shape_find(const char *name)
{
    for (size_t k = 0; cl_shape_registry[k]; k++)
        if (!strcmp(cl_shape_registry[k]->name, name))
            return cl_shape_registry[k];
    return NULL;
}

void cl_shape_surface_free(cl_shape_surface *s)
{
    free(s->vert);
    free(s->tri);
    *s = (cl_shape_surface){0};
}
