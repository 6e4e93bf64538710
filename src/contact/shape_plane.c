/* The plane shape, a half-space: [obstacle.NAME] shape = plane,
 *   point   a point of the plane (m, vector, default 0), the pivot
 *   normal  the outward normal (vector, nonzero, required; normalised)
 *   extent  the side of the square drawn around point (m, > 0, default 10)
 * d = n . (x - p), the normal is n everywhere and G = 0.  The drawing is
 * a square of two triangles, counter-clockwise seen from the outside. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/shape_impl.h"
#include "core/vec3.h"

typedef struct {
    double p[3], n[3], extent;
} plane;

/* n / |n| (scaled first, so that no square overflows or underflows);
 * false for the zero vector. */
static bool normalise(double n[3])
{
    double m = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
    if (!(m > 0))
        return false;
    for (int i = 0; i < 3; i++)
        n[i] /= m;
    cl_v3_normalize(n);
    return true;
}

static cl_status plane_create(cl_config *cfg, const char *sec,
                              double pivot[3], void **shape, cl_error *err)
{
    plane s = {{0, 0, 0}, {0, 0, 0}, 0};
    cl_status rc;
    if ((rc = cl_shape_vector(cfg, sec, "point", false, s.p, err)) ||
        (rc = cl_shape_vector(cfg, sec, "normal", true, s.n, err)) ||
        (rc = cl_shape_positive(cfg, sec, "extent", 10.0, &s.extent, err)))
        return rc;
    if (!normalise(s.n))
        return cl_shape_bad_value(cfg, sec, "normal", "a nonzero vector",
                                  err);
    return cl_shape_copy(&s, sizeof s, s.p, pivot, shape, err);
}

static void plane_query(const void *shape, const double x[3],
                        void *cache, cl_shape_query *q)
{
    (void)cache;
    const plane *s = shape;
    double r[3];
    cl_v3_sub(x, s->p, r);
    q->d = cl_v3_dot(s->n, r);
    memcpy(q->n, s->n, sizeof q->n);
    cl_v3_axpy(x, -q->d, s->n, q->c);
    memset(q->G, 0, sizeof q->G);
}

static void plane_halfspace(const void *shape, double n[3], double p[3])
{
    const plane *s = shape;
    memcpy(n, s->n, sizeof s->n);
    memcpy(p, s->p, sizeof s->p);
}

/* Where n . (x - p) - offset, linear along the segment, reaches 0. */
static double plane_toi(const void *shape, const double a[3],
                        const double b[3], double offset)
{
    const plane *s = shape;
    double ra[3], rb[3];
    cl_v3_sub(a, s->p, ra);
    cl_v3_sub(b, s->p, rb);
    double da = cl_v3_dot(s->n, ra) - offset, db = cl_v3_dot(s->n, rb) - offset;
    if (da <= 0.0)
        return 0.0;
    return db > 0.0 ? INFINITY : da / (da - db);
}

/* Unit u, v in the plane with u x v = n. */
static void tangents(const double n[3], double u[3], double v[3])
{
    int a = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(n[i]) < fabs(n[a]))
            a = i;
    double e[3] = {0, 0, 0};
    e[a] = 1;
    cl_v3_axpy(e, -n[a], n, u);
    cl_v3_normalize(u);
    cl_v3_cross(n, u, v);
}

static cl_status plane_surface(const void *shape, cl_shape_surface *s,
                               cl_error *err)
{
    static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    const plane *pl = shape;
    double u[3], v[3];
    cl_status rc = cl_shape_surface_alloc(s, 4, 2, tri, err);
    if (rc)
        return rc;
    tangents(pl->n, u, v);
    for (int k = 0; k < 4; k++) {
        double *w = s->vert + 3 * k;
        cl_v3_axpy(pl->p, 0.5 * pl->extent * corner[k][0], u, w);
        cl_v3_axpy(w, 0.5 * pl->extent * corner[k][1], v, w);
    }
    return CL_OK;
}

const cl_shape_type cl_shape_plane = {
    .name = "plane",
    .doc = "half-space: point (vector), normal (outward, nonzero), extent "
           "(drawn square's side, > 0)",
    .create = plane_create,
    .query = plane_query,
    .halfspace = plane_halfspace,
    .toi = plane_toi,
    .surface = plane_surface,
    .free = free,
};
