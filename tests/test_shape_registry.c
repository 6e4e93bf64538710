/* Tests for contact/registry: every shape found by its name, complete,
 * listed once; unknown names; freeing an empty surface. */
#include <criterion/criterion.h>

#include <string.h>

#include "contact/shape.h"

TestSuite(shape_registry);

Test(shape_registry, names_and_entries)
{
    static const char *const names[] = {"sphere", "plane", "box", "mesh"};
    size_t n = 0;
    for (; cl_shape_registry[n]; n++) {
        const cl_shape_type *t = cl_shape_registry[n];
        cr_assert(t->name && t->doc && *t->doc && t->create && t->query &&
                  t->surface && t->free, "shape %zu incomplete", n);
        cr_assert_eq(cl_shape_find(t->name), t, "%s", t->name);
    }
    cr_assert_eq(n, 4);
    for (size_t k = 0; k < 4; k++)
        cr_assert_str_eq(cl_shape_registry[k]->name, names[k]);
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
