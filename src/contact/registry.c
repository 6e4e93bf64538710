/* The obstacle shapes.  A new shape is one file defining a cl_shape_type
 * plus one row here. */
#include "contact/shape.h"

#include <stdlib.h>
#include <string.h>

extern const cl_shape_type cl_shape_sphere, cl_shape_plane, cl_shape_box,
    cl_shape_mesh;

const cl_shape_type *const cl_shape_registry[] = {
    &cl_shape_sphere,
    &cl_shape_plane,
    &cl_shape_box,
    &cl_shape_mesh,
    NULL,
};

const cl_shape_type *cl_shape_find(const char *name)
{
    for (size_t k = 0; name && cl_shape_registry[k]; k++)
        if (!strcmp(cl_shape_registry[k]->name, name))
            return cl_shape_registry[k];
    return NULL;
}

void cl_shape_surface_free(cl_shape_surface *s)
{
    free(s->vert);
    free(s->tri);
    memset(s, 0, sizeof *s);
}
