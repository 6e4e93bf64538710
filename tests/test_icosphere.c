/* Tests for contact/icosphere: counts, vertices on the sphere, a closed
 * outward surface, the refusals, and problems/meshes/sphere.obj (written
 * by scripts/make-meshes.py) equal to level 3. */
#include <criterion/criterion.h>

#include "contact/closed.h"
#include "contact/icosphere.h"
#include "core/vec3.h"
#include "io/obj.h"

TestSuite(icosphere);

static void check_sphere(const double *vert, size_t nvert,
                         const int (*tri)[3], size_t ntri, int level)
{
    const double c[3] = {1, -2, 0.5}, r = 3;
    size_t n4 = (size_t)1 << (2 * level);
    cr_assert_eq(ntri, 20 * n4);
    cr_assert_eq(nvert, 10 * n4 + 2);
    for (size_t v = 0; v < nvert; v++) {
        double d[3];
        cl_v3_sub(vert + 3 * v, c, d);
        cr_assert(fabs(cl_v3_norm(d) - r) <= 1e-9, "vertex %zu", v);
    }
    for (size_t t = 0; t < ntri; t++) {
        double n[3], d[3];
        cl_v3_tri_cross(vert + 3 * tri[t][0], vert + 3 * tri[t][1],
                        vert + 3 * tri[t][2], n);
        cl_v3_sub(vert + 3 * tri[t][0], c, d);
        cr_assert_gt(cl_v3_dot(n, d), 0, "triangle %zu faces inwards", t);
    }
    cl_closed s;
    cl_error err = {0};
    cr_assert_eq(cl_closed_build(ntri, tri, &s, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(s.mesh.nedge, 30 * n4);
    cl_closed_free(&s);
}

Test(icosphere, levels_zero_to_three)
{
    for (int level = 0; level <= 3; level++) {
        cl_shape_surface s;
        cl_error err = {0};
        cr_assert_eq(cl_icosphere(level, (double[]){1, -2, 0.5}, 3, &s, &err),
                     CL_OK, "%s", err.msg);
        check_sphere(s.vert, s.nvert, (const int(*)[3])s.tri, s.ntri, level);
        cl_shape_surface_free(&s);
    }
}

Test(icosphere, bad_arguments)
{
    cl_shape_surface s;
    cl_error err = {0};
    cr_assert_eq(cl_icosphere(9, (double[]){0, 0, 0}, 1, &s, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "level 0..8"), "%s", err.msg);
    cr_assert_eq(cl_icosphere(1, (double[]){0, 0, 0}, 0, &s, &err),
                 CL_EINVAL);
    cr_assert_eq(cl_icosphere(-1, (double[]){0, 0, 0}, 1, &s, &err),
                 CL_EINVAL);
    cr_assert_null(s.vert);
}

/* The committed mesh is level 3 of radius 1 at the origin, vertex for
 * vertex and triangle for triangle (tests run from the repository root). */
Test(icosphere, committed_sphere_obj)
{
    cl_obj m;
    cl_shape_surface s;
    cl_error err = {0};
    cr_assert_eq(cl_obj_read("problems/meshes/sphere.obj", &m, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_icosphere(3, (double[]){0, 0, 0}, 1, &s, &err), CL_OK);
    cr_assert_eq(m.nvert, s.nvert);
    cr_assert_eq(m.ntri, s.ntri);
    for (size_t k = 0; k < 3 * m.nvert; k++)
        cr_assert(fabs(m.vert[k] - s.vert[k]) <= 1e-12, "coordinate %zu", k);
    for (size_t t = 0; t < m.ntri; t++)
        for (int k = 0; k < 3; k++)
            cr_assert_eq(m.tri[t][k], s.tri[t][k], "triangle %zu", t);
    cl_shape_surface_free(&s);
    cl_obj_free(&m);
}
