/* Closest point on a triangle (contact/triangle.h), after Ericson,
 * "Real-Time Collision Detection", section 5.1.5. */
#include "contact/triangle.h"

#include "core/vec3.h"

#include <math.h>
#include <string.h>

/* p->c = o + s u, on `feature` k. */
static void found(const double o[3], double s, const double u[3],
                  cl_tri_feature feature, int k, cl_tri_point *p)
{
    cl_v3_axpy(o, s, u, p->c);
    p->feature = feature;
    p->k = k;
}

/* The closest point with d1..d6 the dot products of Ericson's code. */
static void classify(const double x[3], const cl_tri_geom *g,
                     cl_tri_point *p)
{
    const double *a = g->a, *b = g->b, *c = g->c, *ab = g->ab, *ac = g->ac;
    double ap[3], bp[3], cp[3];
    cl_v3_sub(x, a, ap);
    double d1 = cl_v3_dot(ab, ap), d2 = cl_v3_dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
        found(a, 0, ab, CL_TRI_VERTEX, 0, p);
        return;
    }
    cl_v3_sub(x, b, bp);
    double d3 = cl_v3_dot(ab, bp), d4 = cl_v3_dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
        found(b, 0, ab, CL_TRI_VERTEX, 1, p);
        return;
    }
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        found(a, d1 / (d1 - d3), ab, CL_TRI_EDGE, 0, p);
        return;
    }
    cl_v3_sub(x, c, cp);
    double d5 = cl_v3_dot(ab, cp), d6 = cl_v3_dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
        found(c, 0, ab, CL_TRI_VERTEX, 2, p);
        return;
    }
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        found(a, d2 / (d2 - d6), ac, CL_TRI_EDGE, 2, p);
        return;
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        found(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), g->bc, CL_TRI_EDGE, 1,
              p);
        return;
    }
    double v = vb / (va + vb + vc), w = vc / (va + vb + vc);
    found(a, v, ab, CL_TRI_FACE, 0, p);
    cl_v3_axpy(p->c, w, ac, p->c);
}

void cl_tri_geom_set(const double a[3], const double b[3], const double c[3],
                     cl_tri_geom *g)
{
    memcpy(g->a, a, sizeof g->a);
    memcpy(g->b, b, sizeof g->b);
    memcpy(g->c, c, sizeof g->c);
    cl_v3_sub(b, a, g->ab);
    cl_v3_sub(c, a, g->ac);
    cl_v3_sub(c, b, g->bc);
}

void cl_tri_closest_geom(const double x[3], const cl_tri_geom *g,
                         cl_tri_point *p)
{
    classify(x, g, p);
    double r[3];
    cl_v3_sub(x, p->c, r);
    p->dist2 = cl_v3_dot(r, r);
}

void cl_tri_closest(const double x[3], const double a[3], const double b[3],
                    const double c[3], cl_tri_point *p)
{
    cl_tri_geom g;
    cl_tri_geom_set(a, b, c, &g);
    cl_tri_closest_geom(x, &g, p);
}

double cl_tri_segment(const double x0[3], const double D[3],
                      const double a[3], const double b[3],
                      const double c[3])
{
    const double tol = 1e-9;
    double e1[3], e2[3], p[3], s[3], q[3];
    cl_v3_sub(b, a, e1);
    cl_v3_sub(c, a, e2);
    cl_v3_cross(D, e2, p);
    double det = cl_v3_dot(e1, p);
    if (det == 0.0)
        return INFINITY;
    cl_v3_sub(x0, a, s);
    double u = cl_v3_dot(s, p) / det;
    cl_v3_cross(s, e1, q);
    double v = cl_v3_dot(D, q) / det, t = cl_v3_dot(e2, q) / det;
    if (u < -tol || v < -tol || u + v > 1.0 + tol || t < 0.0 || t > 1.0)
        return INFINITY;
    return t;
}

double cl_tri_solid_angle(const double x[3], const double a[3],
                          const double b[3], const double c[3])
{
    double xa[3], xb[3], xc[3], bc[3];
    cl_v3_sub(a, x, xa);
    cl_v3_sub(b, x, xb);
    cl_v3_sub(c, x, xc);
    cl_v3_cross(xb, xc, bc);
    double la = cl_v3_norm(xa), lb = cl_v3_norm(xb), lc = cl_v3_norm(xc);
    return 2 * atan2(cl_v3_dot(xa, bc), la * lb * lc +
                     cl_v3_dot(xa, xb) * lc + cl_v3_dot(xb, xc) * la +
                     cl_v3_dot(xc, xa) * lb);
}
