/* Tests for the sphere shape (contact/shape_sphere.c): answers at known
 * points, G against central differences, bad keys, the drawing. */
#include <criterion/criterion.h>

#include "shapecheck.h"

TestSuite(shape_sphere);

Test(shape_sphere, known_points)
{
    sc_shape s;
    sc_create(&s, "sphere", SC_SETS("center = 1, 2, 3", "radius = 0.5"));
    cr_assert(s.pivot[0] == 1 && s.pivot[1] == 2 && s.pivot[2] == 3);
    cl_shape_query q = sc_expect(&s, (double[]){1, 2, 5}, 1.5,
                                 (double[]){0, 0, 1}, 1e-15);
    cr_assert(q.c[0] == 1 && q.c[1] == 2 && q.c[2] == 3.5);
    double G[9] = {0.5, 0, 0, 0, 0.5, 0, 0, 0, 0};   /* (I - n n^T) / 2 */
    cr_assert_leq(fd_relerr(q.G, G, 9), 1e-15);
    sc_expect(&s, (double[]){1 - 0.3, 2 + 0.4, 3}, -0.0,
              (double[]){-0.6, 0.8, 0}, 1e-15);
    sc_expect(&s, (double[]){1, 1.9, 3}, -0.4, (double[]){0, -1, 0}, 1e-15);
    /* the centre: +z, G = 0 */
    q = sc_expect(&s, (double[]){1, 2, 3}, -0.5, (double[]){0, 0, 1}, 0);
    cr_assert_eq(fd_maxabs(q.G, 9), 0);
    sc_free(&s);
}

Test(shape_sphere, hessian_against_differences)
{
    sc_shape s;
    sc_create(&s, "sphere", SC_SETS("center = 0.1 -0.2 0.3", "radius = 2"));
    fd_rng r = {7};
    for (int k = 0; k < 200; k++) {
        double x[3], c[3] = {0.1, -0.2, 0.3}, rel[3];
        for (int i = 0; i < 3; i++)
            x[i] = 4 * fd_rand(&r);
        cl_v3_sub(x, c, rel);
        if (cl_v3_norm(rel) < 0.1)
            continue;   /* too near the centre for a step of 1e-6 */
        cr_assert_eq(sc_check_fd(&s, x, 1e-6, 1e-6), 2);
    }
    sc_free(&s);
}

Test(shape_sphere, bad_keys_refused)
{
    sc_refused("sphere", SC_SETS("center = 0 0 0"), "[ob] radius: required",
               "> 0");
    sc_refused("sphere", SC_SETS("radius = 0"),
               "--set: [ob] radius = \"0\": expected a number > 0", NULL);
    sc_refused("sphere", SC_SETS("radius = -1"), "\"-1\"", "> 0");
    sc_refused("sphere", SC_SETS("radius = inf"), "\"inf\"", "> 0");
    sc_refused("sphere", SC_SETS("radius = one"), "\"one\"", "> 0");
    sc_refused("sphere", SC_SETS("radius = 1", "center = 1, 2"),
               "[ob] center = \"1, 2\"", "3 finite numbers");
    sc_refused("sphere", SC_SETS("radius = 1", "center = 1, nan, 2"),
               "center", "3 finite numbers");
}

Test(shape_sphere, drawn_as_an_icosphere)
{
    sc_shape s;
    sc_create(&s, "sphere", SC_SETS("center = 1, 2, 3", "radius = 0.5"));
    sc_check_surface(&s, 1280, 1e-15);
    sc_free(&s);
}

Test(shape_sphere, non_finite_point_does_not_crash)
{
    sc_shape s;
    sc_create(&s, "sphere", SC_SETS("radius = 1"));
    cl_shape_query q;
    s.type->query(s.shape, (double[]){NAN, 0, 0}, NULL, &q);
    cr_assert(isnan(q.d));
    sc_free(&s);
}

/* Continuous detection: the entry into the sphere grown by the offset. */
Test(shape_sphere, time_of_impact)
{
    sc_shape s;
    sc_create(&s, "sphere", SC_SETS("center = 1, 2, 3", "radius = 0.5"));
    double (*toi)(const void *, const double *, const double *, double) =
        s.type->toi;
    /* straight at the centre: z = 3.6 reached at s = 2.4 / 4 */
    cr_assert_float_eq(toi(s.shape, (double[]){1, 2, 6}, (double[]){1, 2, 2},
                           0.1), 0.6, 1e-15);
    /* 0.55 from the centre: missed with offset 0, grazed with 0.1 at
     * z = 3 + sqrt(0.6^2 - 0.55^2) */
    cr_assert(isinf(toi(s.shape, (double[]){1.55, 2, 6},
                        (double[]){1.55, 2, 0}, 0.0)));
    cr_assert_float_eq(toi(s.shape, (double[]){1.55, 2, 6},
                           (double[]){1.55, 2, 0}, 0.1),
                       (3 - sqrt(0.0575)) / 6, 1e-15);
    /* moving away, or stopping short */
    cr_assert(isinf(toi(s.shape, (double[]){1, 2, 6}, (double[]){1, 2, 9},
                        0.0)));
    cr_assert(isinf(toi(s.shape, (double[]){1, 2, 6}, (double[]){1, 2, 4},
                        0.0)));
    sc_free(&s);
}
