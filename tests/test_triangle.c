/* Tests for contact/triangle: the closest point of a triangle and its
 * feature, in each of the seven Voronoi regions and at random points
 * against the optimality conditions and a dense sampling (and from a
 * triangle's kept record, the same bits); the solid angle against an
 * octant and a closed tetrahedron. */
#include <criterion/criterion.h>

#include <math.h>

#include "contact/triangle.h"
#include "core/vec3.h"
#include "fdcheck.h"

TestSuite(triangle);

static const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0};

static void expect(const double x[3], cl_tri_feature f, int k,
                   const double c[3])
{
    cl_tri_point p;
    cl_tri_closest(x, A, B, C, &p);
    cr_assert(p.feature == f && p.k == k, "(%g, %g, %g): feature %d %d, "
              "expected %d %d", x[0], x[1], x[2], p.feature, p.k, f, k);
    double r[3];
    cl_v3_sub(p.c, c, r);
    cr_assert(cl_v3_norm(r) <= 1e-15, "closest (%g, %g, %g)", p.c[0],
              p.c[1], p.c[2]);
    cl_v3_sub(x, c, r);
    cr_assert(fabs(p.dist2 - cl_v3_dot(r, r)) <= 1e-15);
}

Test(triangle, seven_regions)
{
    expect((double[]){-1, -1, 1}, CL_TRI_VERTEX, 0, A);
    expect((double[]){2, -0.5, 0}, CL_TRI_VERTEX, 1, B);
    expect((double[]){-0.5, 2, -3}, CL_TRI_VERTEX, 2, C);
    expect((double[]){0.5, -1, 0.3}, CL_TRI_EDGE, 0, (double[]){0.5, 0, 0});
    expect((double[]){1, 1, 0.5}, CL_TRI_EDGE, 1, (double[]){0.5, 0.5, 0});
    expect((double[]){-1, 0.25, 0}, CL_TRI_EDGE, 2, (double[]){0, 0.25, 0});
    expect((double[]){0.2, 0.3, 0.7}, CL_TRI_FACE, 0,
           (double[]){0.2, 0.3, 0});
    expect((double[]){0.2, 0.3, 0}, CL_TRI_FACE, 0, (double[]){0.2, 0.3, 0});
}

/* The closest point lies in the triangle, x - c is perpendicular to the
 * feature, and no point of a fine grid of the triangle is nearer. */
Test(triangle, random_points)
{
    fd_rng r = {5};
    for (int k = 0; k < 300; k++) {
        double v[3][3], x[3], n[3], u[3], w[3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                v[i][j] = fd_rand(&r);
        for (int j = 0; j < 3; j++)
            x[j] = 2 * fd_rand(&r);
        cl_tri_point p, pg;
        cl_tri_geom g;
        cl_tri_closest(x, v[0], v[1], v[2], &p);
        cl_tri_geom_set(v[0], v[1], v[2], &g);
        cl_tri_closest_geom(x, &g, &pg);   /* the kept record: the same */
        cr_assert(pg.c[0] == p.c[0] && pg.c[1] == p.c[1] &&
                  pg.c[2] == p.c[2] && pg.dist2 == p.dist2 &&
                  pg.feature == p.feature && pg.k == p.k);
        cl_v3_tri_cross(v[0], v[1], v[2], n);
        cl_v3_sub(x, p.c, u);
        if (p.feature == CL_TRI_FACE) {
            cl_v3_cross(u, n, w);
            cr_assert(cl_v3_norm(w) <= 1e-12 * cl_v3_norm(n));
        } else if (p.feature == CL_TRI_EDGE) {
            cl_v3_sub(v[(p.k + 1) % 3], v[p.k], w);
            cr_assert(fabs(cl_v3_dot(u, w)) <= 1e-12);
        } else {
            cr_assert(p.c[0] == v[p.k][0] && p.c[1] == v[p.k][1] &&
                      p.c[2] == v[p.k][2]);
        }
        for (int a = 0; a <= 40; a++)
            for (int b = 0; a + b <= 40; b++) {
                double q[3], s = a / 40.0, t = b / 40.0;
                for (int j = 0; j < 3; j++)
                    q[j] = v[0][j] + s * (v[1][j] - v[0][j]) +
                           t * (v[2][j] - v[0][j]);
                cl_v3_sub(x, q, w);
                cr_assert(cl_v3_dot(w, w) >= p.dist2 - 1e-14);
            }
    }
}

/* cl_tri_segment at known answers: a crossing, through an edge, beyond
 * the segment's end, outside the triangle, in its plane. */
Test(triangle, segment_crossings)
{
    cr_assert_float_eq(cl_tri_segment((double[]){0.25, 0.25, 2},
                                      (double[]){0, 0, -5}, A, B, C),
                       0.4, 1e-15);
    /* from below, slanted, through the edge B-C at the segment's end */
    cr_assert_float_eq(cl_tri_segment((double[]){0, 0, -1},
                                      (double[]){0.5, 0.5, 1}, A, B, C),
                       1.0, 1e-15);
    cr_assert_eq(cl_tri_segment((double[]){0.25, 0.25, 2},
                                (double[]){0, 0, -1.95}, A, B, C), INFINITY);
    cr_assert_eq(cl_tri_segment((double[]){0.75, 0.75, 2},
                                (double[]){0, 0, -10}, A, B, C), INFINITY);
    cr_assert_eq(cl_tri_segment((double[]){-1, 0.2, 0},
                                (double[]){10, 0, 0}, A, B, C), INFINITY);
}

/* The triangle of the unit points on the axes spans an octant seen from
 * the origin, 4 pi / 8, with the sign of its orientation; a tetrahedron's
 * outward faces add up to 4 pi from inside and to 0 from outside. */
Test(triangle, solid_angle)
{
    const double o[3] = {0, 0, 0}, e[3][3] = {{1, 0, 0}, {0, 1, 0},
                                              {0, 0, 1}};
    cr_expect_float_eq(cl_tri_solid_angle(o, e[0], e[1], e[2]), M_PI / 2,
                       1e-15);
    cr_expect_float_eq(cl_tri_solid_angle(o, e[0], e[2], e[1]), -M_PI / 2,
                       1e-15);
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    const double in[3] = {0.2, 0.2, 0.2}, out[3] = {1, 1, 1};
    double wi = 0, wo = 0;
    for (int k = 0; k < 4; k++) {
        wi += cl_tri_solid_angle(in, v[f[k][0]], v[f[k][1]], v[f[k][2]]);
        wo += cl_tri_solid_angle(out, v[f[k][0]], v[f[k][1]], v[f[k][2]]);
    }
    cr_expect_float_eq(wi, 4 * M_PI, 1e-13, "inside %.17g", wi);
    cr_expect_float_eq(wo, 0.0, 1e-13, "outside %.17g", wo);
}
