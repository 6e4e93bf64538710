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

/* |X0 + a D - c|^2 = r^2, D = X1 - X0: A a^2 + 2 B a + C = 0 with
 * A = D.D, B = D.(X0 - c), C = |X0 - c|^2 - r^2; its least root, written
 * a = C / (-B + sqrt(B^2 - A C)) so that no difference cancels. */
static double sphere_toi(const void *shape, const double X0[3],
                         const double X1[3])
{
    const sphere *s = shape;
    double D[3], e[3];
    cl_v3_sub(X1, X0, D);
    cl_v3_sub(X0, s->c, e);
    double A = cl_v3_dot(D, D), B = cl_v3_dot(D, e);
    double C = cl_v3_dot(e, e) - s->r * s->r, disc = B * B - A * C;
    if (C <= 0.0)
        return 0.0;
    if (B >= 0.0 || disc < 0.0)
        return INFINITY;
    double a = C / (-B + sqrt(disc));
    return a <= 1.0 ? a : INFINITY;
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
