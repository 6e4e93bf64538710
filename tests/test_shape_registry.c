/* Tests for contact/registry: every shape found by its name, complete,
 * listed once; unknown names; freeing an empty surface. */
#include <criterion/criterion.h>

#include <string.h>

#include "contact/shape.h"

TestSuite(shape_registry);

/* Every row complete and found by its name; the four known shapes among
 * them in this order (a shape added to the registry passes too). */
Test(shape_registry, names_and_entries)
{
    static const char *const names[] = {"sphere", "plane", "box", "mesh"};
    size_t next = 0;
    for (size_t n = 0; cl_shape_registry[n]; n++) {
        const cl_shape_type *t = cl_shape_registry[n];
        cr_assert(t->name && t->doc && *t->doc && t->create && t->query &&
                  t->surface && t->free, "shape %zu incomplete", n);
        cr_assert_eq(cl_shape_find(t->name), t, "%s", t->name);
        if (next < 4 && !strcmp(t->name, names[next]))
            next++;
    }
    cr_assert_eq(next, 4, "the known four not all there, in order");
    cr_assert_null(cl_shape_find("cylinder"));
    cr_assert_null(cl_shape_find(""));
    cr_assert_null(cl_shape_find("Sphere"));
}

Test(shape_registry, free_empty_surface)
{
    cl_shape_surface s = {0};
    cl_shape_surface_free(&s);
    cl_shape_surface_free(&s);
    cr_assert(s.vert == NULL && s.tri == NULL && s.nvert == 0);
}
