/* The sphere shape: [obstacle.NAME] shape = sphere,
 *   center  the centre (m, vector, default 0), the pivot
 *   radius  (m, > 0, required)
 * d = |x - c| - r, n = (x - c) / |x - c|, G = (I - n n^T) / |x - c|.  At
 * the centre itself (|x - c| <= 1e-12 r), where no direction is nearer
 * than another, n = +z and G = 0.  Drawn as an icosphere of 1280
 * triangles (contact/icosphere.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/icosphere.h"
#include "contact/shape_impl.h"
#include "core/vec3.h"

#define DRAW_LEVEL 3

typedef struct {
    double c[3], r;
} sphere;

static cl_status sphere_create(cl_config *cfg, const char *sec,
                               double pivot[3], void **shape, cl_error *err)
{
    sphere s = {{0, 0, 0}, 0};
    cl_status rc;
    if ((rc = cl_shape_vector(cfg, sec, "center", false, s.c, err)) ||
        (rc = cl_shape_positive(cfg, sec, "radius", NAN, &s.r, err)))
        return rc;
    return cl_shape_copy(&s, sizeof s, s.c, pivot, shape, err);
}

static void sphere_query(const void *shape, const double x[3],
                         void *cache, cl_shape_query *q)
{
    (void)cache;
    const sphere *s = shape;
    double rel[3];
    cl_v3_sub(x, s->c, rel);
    double rho = cl_v3_norm(rel);
    bool away = rho > 1e-12 * s->r;
    for (int i = 0; i < 3; i++)
        q->n[i] = away ? rel[i] / rho : i == 2;
    q->d = rho - s->r;
    cl_v3_axpy(s->c, s->r, q->n, q->c);
    if (away)
        cl_shape_hessian(q->n, NULL, rho, q->G);
    else
        memset(q->G, 0, sizeof q->G);
}

/* The entry into the sphere of radius r + offset: the lesser root of
 * |e + s d|^2 = (r + offset)^2, e = a - c, d = b - a, written as
 * C / (-B + sqrt(B^2 - A C)) to keep its digits when the path grazes. */
static double sphere_toi(const void *shape, const double a[3],
                         const double b[3], double offset)
{
    const sphere *s = shape;
    double e[3], d[3], rho = s->r + offset;
    cl_v3_sub(a, s->c, e);
    cl_v3_sub(b, a, d);
    double A = cl_v3_dot(d, d), B = cl_v3_dot(e, d);
    double C = cl_v3_dot(e, e) - rho * rho, disc = B * B - A * C;
    if (C <= 0.0)
        return 0.0;
    if (!(B < 0.0) || !(disc >= 0.0))
        return INFINITY;
    double t = C / (-B + sqrt(disc));
    return t <= 1.0 ? t : INFINITY;
}

static cl_status sphere_surface(const void *shape, cl_shape_surface *s,
                                cl_error *err)
{
    const sphere *sp = shape;
    return cl_icosphere(DRAW_LEVEL, sp->c, sp->r, s, err);
}

const cl_shape_type cl_shape_sphere = {
    .name = "sphere",
    .doc = "sphere: center (vector), radius (> 0)",
    .create = sphere_create,
    .query = sphere_query,
    .toi = sphere_toi,
    .surface = sphere_surface,
    .free = free,
};
