/* Tests for the plane shape (contact/shape_plane.c): a half-space with a
 * normalised normal, G = 0, bad keys, the drawn square. */
#include <criterion/criterion.h>

#include "shapecheck.h"

TestSuite(shape_plane);

Test(shape_plane, known_points)
{
    sc_shape s;
    sc_create(&s, "plane", SC_SETS("point = 0, 0, 1", "normal = 0 0 2"));
    cr_assert(s.pivot[0] == 0 && s.pivot[1] == 0 && s.pivot[2] == 1);
    cl_shape_query q = sc_expect(&s, (double[]){3, 4, 5}, 4,
                                 (double[]){0, 0, 1}, 0);
    cr_assert(q.c[0] == 3 && q.c[1] == 4 && q.c[2] == 1);
    cr_assert_eq(fd_maxabs(q.G, 9), 0);
    sc_expect(&s, (double[]){-3, 4, -1}, -2, (double[]){0, 0, 1}, 0);
    sc_free(&s);

    double r = sqrt(0.5);
    sc_create(&s, "plane", SC_SETS("point = 1, 0, 0", "normal = 1, 1, 0"));
    sc_expect(&s, (double[]){1, 1, 7}, r, (double[]){r, r, 0}, 1e-15);
    sc_expect(&s, (double[]){0, 0, 0}, -r, (double[]){r, r, 0}, 1e-15);
    sc_free(&s);

    /* no square overflows or underflows */
    sc_create(&s, "plane", SC_SETS("normal = 1e200, 0, 1e200"));
    sc_expect(&s, (double[]){1, 0, 0}, r, (double[]){r, 0, r}, 1e-15);
    sc_free(&s);
    sc_create(&s, "plane", SC_SETS("normal = 0, -1e-200, 0"));
    sc_expect(&s, (double[]){0, 2, 0}, -2, (double[]){0, -1, 0}, 0);
    sc_free(&s);
}

Test(shape_plane, hessian_is_zero)
{
    sc_shape s;
    sc_create(&s, "plane", SC_SETS("point = 0.3, 0.1, 0", "normal = 1 2 3"));
    fd_rng r = {11};
    for (int k = 0; k < 50; k++) {
        double x[3] = {3 * fd_rand(&r), 3 * fd_rand(&r), 3 * fd_rand(&r)};
        cr_assert_eq(sc_check_fd(&s, x, 1e-6, 1e-9), 0);
    }
    sc_free(&s);
}

Test(shape_plane, bad_keys_refused)
{
    sc_refused("plane", SC_SETS("point = 0 0 0"), "[ob] normal: required",
               NULL);
    sc_refused("plane", SC_SETS("normal = 0, 0, 0"),
               "--set: [ob] normal = \"0, 0, 0\": expected a nonzero vector",
               NULL);
    sc_refused("plane", SC_SETS("normal = 0, 1"), "normal", "3 finite");
    sc_refused("plane", SC_SETS("normal = 0, 1, 0", "extent = 0"),
               "[ob] extent = \"0\": expected a number > 0", NULL);
    sc_refused("plane", SC_SETS("normal = 0, 1, 0", "point = x"), "point",
               "3 finite");
}

/* A square of side `extent` around the point, counter-clockwise seen from
 * the side the normal points to. */
Test(shape_plane, drawn_as_a_square)
{
    sc_shape s;
    sc_create(&s, "plane", SC_SETS("point = 1, 2, 3", "normal = 0, 1, 1",
                                   "extent = 4"));
    sc_check_surface(&s, 2, 1e-15);
    cl_shape_surface sf;
    cl_error err = {0};
    cr_assert_eq(s.type->surface(s.shape, &sf, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(sf.nvert, 4);
    for (int k = 0; k < 4; k++) {
        double side[3], diag[3];
        cl_v3_sub(sf.vert + 3 * ((k + 1) % 4), sf.vert + 3 * k, side);
        cl_v3_sub(sf.vert + 3 * k, (double[]){1, 2, 3}, diag);
        cr_assert(fabs(cl_v3_norm(side) - 4) < 1e-14);
        cr_assert(fabs(cl_v3_norm(diag) - 2 * sqrt(2)) < 1e-14);
    }
    cl_shape_surface_free(&sf);
    sc_free(&s);
}

/* Continuous detection: where n . (x - p) reaches the offset. */
Test(shape_plane, time_of_impact)
{
    sc_shape s;
    sc_create(&s, "plane", SC_SETS("point = 0, 1, 0", "normal = 0, 2, 0"));
    cr_assert_float_eq(s.type->toi(s.shape, (double[]){3, 3, 0},
                                   (double[]){5, -1, 1}, 0.5), 0.375, 1e-15);
    cr_assert(isinf(s.type->toi(s.shape, (double[]){3, 3, 0},
                                (double[]){3, 2, 0}, 0.5)));
    cr_assert_eq(s.type->toi(s.shape, (double[]){3, 1.2, 0},
                             (double[]){3, 2, 0}, 0.5), 0.0);
    sc_free(&s);
}
