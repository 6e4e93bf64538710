/* Tests for the box shape (contact/shape_box.c): the exact signed
 * distance outside (face, edge, corner regions) and inside, G against
 * central differences in every region, bad keys, the drawing. */
#include <criterion/criterion.h>

#include "shapecheck.h"

TestSuite(shape_box);

/* Centre (1, 2, 3), half sides 0.5, 1, 1.5. */
#define BOX SC_SETS("center = 1 2 3", "size = 1, 2, 3")

static void at(double p0, double p1, double p2, double x[3])
{
    x[0] = 1 + p0;
    x[1] = 2 + p1;
    x[2] = 3 + p2;
}

Test(shape_box, outside_regions)
{
    sc_shape s;
    sc_create(&s, "box", BOX);
    cr_assert(s.pivot[0] == 1 && s.pivot[1] == 2 && s.pivot[2] == 3);
    double x[3], r = sqrt(0.5);
    at(1, 0.1, -0.2, x);                        /* face +x */
    cl_shape_query q = sc_expect(&s, x, 0.5, (double[]){1, 0, 0}, 1e-15);
    cr_assert_eq(fd_maxabs(q.G, 9), 0);
    at(0.2, -1.25, 1, x);                       /* face -y */
    sc_expect(&s, x, 0.25, (double[]){0, -1, 0}, 1e-15);
    at(1, 1.5, 0.3, x);                         /* edge along z */
    q = sc_expect(&s, x, r, (double[]){r, r, 0}, 1e-15);
    double G[9] = {0.5, -0.5, 0, -0.5, 0.5, 0, 0, 0, 0};
    for (int k = 0; k < 9; k++)
        G[k] /= r;                              /* (I - nn^T - zz^T) / d */
    cr_assert_leq(fd_relerr(q.G, G, 9), 1e-15);
    cr_assert(fabs(q.c[0] - 1.5) < 1e-15 && fabs(q.c[1] - 3) < 1e-15 &&
              fabs(q.c[2] - 3.3) < 1e-15);
    at(-0.9, -1.3, -1.5, x);                    /* edge along z, -x -y */
    sc_expect(&s, x, 0.5, (double[]){-0.8, -0.6, 0}, 1e-15);
    at(1.5, 2, 2.5, x);                         /* corner (+, +, +) */
    q = sc_expect(&s, x, sqrt(3), (double[]){1 / sqrt(3), 1 / sqrt(3),
                                             1 / sqrt(3)}, 1e-15);
    cr_assert_eq(sc_region(&q), 2);
    sc_free(&s);
}

Test(shape_box, inside_nearest_face)
{
    sc_shape s;
    sc_create(&s, "box", BOX);
    double x[3];
    at(0.4, 0, 0, x);
    cl_shape_query q = sc_expect(&s, x, -0.1, (double[]){1, 0, 0}, 1e-15);
    cr_assert(fabs(q.c[0] - 1.5) < 1e-15 && q.c[1] == 2 && q.c[2] == 3);
    cr_assert_eq(fd_maxabs(q.G, 9), 0);
    at(0, -0.95, 0.1, x);
    sc_expect(&s, x, -0.05, (double[]){0, -1, 0}, 1e-15);
    at(0.1, 0.2, -1.3, x);
    sc_expect(&s, x, -0.2, (double[]){0, 0, -1}, 1e-15);
    at(0, 0, 0, x);                             /* the centre: face +x */
    sc_expect(&s, x, -0.5, (double[]){1, 0, 0}, 0);
    at(0.5, 0.3, 0, x);                         /* on the face */
    sc_expect(&s, x, 0, (double[]){1, 0, 0}, 0);
    at(0.5, 1, 1.5, x);                         /* on the corner */
    sc_expect(&s, x, 0, (double[]){1, 0, 0}, 0);
    sc_free(&s);
}

/* Random points in and around the box, away from the boundaries of the
 * regions: G against central differences, every region met. */
Test(shape_box, hessian_against_differences)
{
    static const double h[3] = {0.5, 1, 1.5};
    sc_shape s;
    sc_create(&s, "box", BOX);
    fd_rng r = {3};
    int seen[3] = {0, 0, 0}, inside = 0;
    for (int k = 0; k < 4000; k++) {
        double p[3], x[3], gap[3];
        int out = 0;
        for (int i = 0; i < 3; i++) {
            p[i] = 2 * h[i] * fd_rand(&r);
            gap[i] = fabs(p[i]) - h[i];
            out += gap[i] > 0;
        }
        double g0 = fmax(gap[0], fmax(gap[1], gap[2])), g1 = -INFINITY;
        for (int i = 0; i < 3; i++)
            if (gap[i] != g0)
                g1 = fmax(g1, gap[i]);
        if (fabs(gap[0]) < 1e-3 || fabs(gap[1]) < 1e-3 ||
            fabs(gap[2]) < 1e-3 || (!out && g0 - g1 < 1e-3))
            continue;
        at(p[0], p[1], p[2], x);
        int region = sc_check_fd(&s, x, 1e-6, 1e-6);
        cr_assert_eq(region, out ? out - 1 : 0);
        if (out)
            seen[out - 1]++;
        else
            inside++;
    }
    cr_assert(seen[0] > 100 && seen[1] > 100 && seen[2] > 100 &&
              inside > 100, "regions met: %d %d %d, inside %d", seen[0],
              seen[1], seen[2], inside);
    sc_free(&s);
}

Test(shape_box, bad_keys_refused)
{
    sc_refused("box", SC_SETS("center = 0 0 0"), "[ob] size: required",
               NULL);
    sc_refused("box", SC_SETS("size = 1, 0, 1"),
               "--set: [ob] size = \"1, 0, 1\": expected three side lengths "
               "> 0", NULL);
    sc_refused("box", SC_SETS("size = 1, 1, -2"), "\"1, 1, -2\"", "> 0");
    sc_refused("box", SC_SETS("size = 1 2"), "size", "3 finite");
    sc_refused("box", SC_SETS("size = 1 2 3", "center = 0 0 inf"), "center",
               "3 finite");
}

Test(shape_box, drawn_with_twelve_triangles)
{
    sc_shape s;
    sc_create(&s, "box", BOX);
    sc_check_surface(&s, 12, 0);
    sc_free(&s);
}

/* Continuous detection: the entry into the box grown by the offset. */
Test(shape_box, time_of_impact)
{
    sc_shape s;
    sc_create(&s, "box", SC_SETS("center = 1, 0, 0", "size = 1, 1, 1"));
    cr_assert_float_eq(s.type->toi(s.shape, (double[]){-1, 0, 0},
                                   (double[]){3, 0, 0}, 0.1), 0.35, 1e-15);
    cr_assert_float_eq(s.type->toi(s.shape, (double[]){-1, 0, 0},
                                   (double[]){3, 0, 0}, 0.0), 0.375, 1e-15);
    cr_assert(isinf(s.type->toi(s.shape, (double[]){-1, 0.7, 0},
                                (double[]){3, 0.7, 0}, 0.1)));
    sc_free(&s);
}
