/* The half-space below a plane (docs/model.md, eq. C1): d = m . (x - p),
 * n = m, G = 0.  Keys: point (m, default 0), normal (required, nonzero;
 * normalised here), extent (m, > 0, default 10: the side of the square
 * drawn in frames). */
#include <math.h>
#include <stdlib.h>

#include "contact/shape.h"

typedef struct {
    double p[3], m[3], extent;
} plane;

static cl_status plane_create(cl_config *cfg, const char *sec,
                              double pivot[3], void **shape, cl_error *err)
{
    plane s = {{0.0, 0.0, 0.0}, {NAN, NAN, NAN}, 10.0};
    char where[256];
    cl_status rc;
    if ((rc = cl_config_vector(cfg, sec, "point", 3, s.p, err)) ||
        (rc = cl_config_vector(cfg, sec, "normal", 3, s.m, err)) ||
        (rc = cl_config_double(cfg, sec, "extent", 10.0, 1e-300, INFINITY,
                               &s.extent, err)))
        return rc;
    if (isnan(s.m[0]))
        return cl_error_set(err, CL_EINVAL, "[%s] shape = plane needs its "
                            "outward normal (a nonzero vector)", sec);
    double len = sqrt(s.m[0] * s.m[0] + s.m[1] * s.m[1] + s.m[2] * s.m[2]);
    if (!(len > 0.0) || !isfinite(len))
        return cl_error_set(err, CL_EINVAL, "%s: [%s] normal = \"%s\": "
                            "expected a nonzero vector of finite length",
                            cl_config_origin(cfg, sec, "normal", where,
                                             sizeof where),
                            sec, cl_config_string(cfg, sec, "normal", ""));
    for (int i = 0; i < 3; i++)
        s.m[i] /= len;
    plane *p = malloc(sizeof *p);
    if (!p)
        return cl_error_set(err, CL_ENOMEM, "out of memory (plane)");
    *p = s;
    for (int i = 0; i < 3; i++)
        pivot[i] = s.p[i];
    *shape = p;
    return CL_OK;
}

static void plane_query(const void *shape, const double x[3],
                        cl_shape_query *q)
{
    const plane *s = shape;
    q->d = s->m[0] * (x[0] - s->p[0]) + s->m[1] * (x[1] - s->p[1]) +
           s->m[2] * (x[2] - s->p[2]);
    for (int i = 0; i < 3; i++) {
        q->n[i] = s->m[i];
        q->c[i] = x[i] - q->d * s->m[i];
    }
    for (int k = 0; k < 9; k++)
        q->G[k] = 0.0;
}

/* A square of side `extent` centred on the point, normal m. */
static cl_status plane_surface(const void *shape, cl_shape_surface *out,
                               cl_error *err)
{
    const plane *s = shape;
    const double *m = s->m;
    double a[3] = {fabs(m[0]) < 0.9 ? 1.0 : 0.0, fabs(m[0]) < 0.9 ? 0.0 : 1.0,
                   0.0};
    double e1[3] = {a[1] * m[2] - a[2] * m[1], a[2] * m[0] - a[0] * m[2],
                    a[0] * m[1] - a[1] * m[0]};
    double l = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int i = 0; i < 3; i++)
        e1[i] /= l;
    double e2[3] = {m[1] * e1[2] - m[2] * e1[1], m[2] * e1[0] - m[0] * e1[2],
                    m[0] * e1[1] - m[1] * e1[0]};
    out->vert = malloc(12 * sizeof *out->vert);
    out->tri = malloc(2 * sizeof *out->tri);
    if (!out->vert || !out->tri)
        return cl_error_set(err, CL_ENOMEM, "out of memory (plane)");
    static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 3; i++)
            out->vert[3 * k + i] = s->p[i] + 0.5 * s->extent *
                                                 (corner[k][0] * e1[i] +
                                                  corner[k][1] * e2[i]);
    static const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 3; i++)
            out->tri[k][i] = tri[k][i];
    out->nvert = 4;
    out->ntri = 2;
    return CL_OK;
}

const cl_shape_type cl_shape_plane = {
    .name = "plane",
    .doc = "half-space below a plane: point, normal",
    .create = plane_create,
    .query = plane_query,
    .surface = plane_surface,
    .free = free,
};
