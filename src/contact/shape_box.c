/* An axis-aligned box in its own frame (docs/model.md, eq. C1): outside,
 * the distance to the nearest face, edge or corner, with G = 0 on a face,
 * (I - n n^T - e e^T)/d at an edge of direction e, (I - n n^T)/d at a
 * corner; inside, minus the distance to the nearest face, G = 0.  Keys:
 * center (m, default 0), size (m, three full side lengths > 0,
 * required). */
#include <math.h>
#include <stdlib.h>

#include "contact/shape.h"

typedef struct {
    double c[3], h[3]; /* centre, half sides */
} box;

static cl_status box_create(cl_config *cfg, const char *sec, double pivot[3],
                            void **shape, cl_error *err)
{
    box s = {{0.0, 0.0, 0.0}, {NAN, NAN, NAN}};
    char where[256];
    cl_status rc;
    if ((rc = cl_config_vector(cfg, sec, "center", 3, s.c, err)) ||
        (rc = cl_config_vector(cfg, sec, "size", 3, s.h, err)))
        return rc;
    if (isnan(s.h[0]))
        return cl_error_set(err, CL_EINVAL, "[%s] shape = box needs its "
                            "size (m, three side lengths > 0)", sec);
    for (int i = 0; i < 3; i++) {
        if (!(s.h[i] > 0.0))
            return cl_error_set(err, CL_EINVAL, "%s: [%s] size = \"%s\": "
                                "expected three side lengths > 0 (m)",
                                cl_config_origin(cfg, sec, "size", where,
                                                 sizeof where),
                                sec, cl_config_string(cfg, sec, "size", ""));
        s.h[i] *= 0.5;
        pivot[i] = s.c[i];
    }
    box *p = malloc(sizeof *p);
    if (!p)
        return cl_error_set(err, CL_ENOMEM, "out of memory (box)");
    *p = s;
    *shape = p;
    return CL_OK;
}

/* Inside: the nearest face. */
static void box_inside(const box *s, const double r[3], cl_shape_query *q)
{
    int a = 0;
    for (int i = 1; i < 3; i++)
        if (s->h[i] - fabs(r[i]) < s->h[a] - fabs(r[a]))
            a = i;
    double sg = r[a] < 0.0 ? -1.0 : 1.0;
    q->d = -(s->h[a] - fabs(r[a]));
    for (int i = 0; i < 3; i++) {
        q->n[i] = i == a ? sg : 0.0;
        q->c[i] = s->c[i] + (i == a ? sg * s->h[a] : r[i]);
    }
    for (int k = 0; k < 9; k++)
        q->G[k] = 0.0;
}

static void box_query(const void *shape, const double x[3],
                      cl_shape_query *q)
{
    const box *s = shape;
    double r[3], diff[3], len2 = 0.0;
    int clamped = 0;
    for (int i = 0; i < 3; i++) {
        r[i] = x[i] - s->c[i];
        double cl = fmin(fmax(r[i], -s->h[i]), s->h[i]);
        diff[i] = r[i] - cl;
        clamped += diff[i] != 0.0;
        len2 += diff[i] * diff[i];
        q->c[i] = s->c[i] + cl;
    }
    if (clamped == 0) {
        box_inside(s, r, q);
        return;
    }
    q->d = sqrt(len2);
    for (int i = 0; i < 3; i++)
        q->n[i] = diff[i] / q->d;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            /* the free axes (not clamped) are the edge's direction; on a
             * face the normal's curvature vanishes */
            double e = i == j && diff[i] == 0.0 ? 1.0 : 0.0;
            q->G[3 * i + j] = clamped == 1
                                  ? 0.0
                                  : ((i == j) - q->n[i] * q->n[j] - e) / q->d;
        }
}

static cl_status box_surface(const void *shape, cl_shape_surface *out,
                             cl_error *err)
{
    const box *s = shape;
    out->vert = malloc(24 * sizeof *out->vert);
    out->tri = malloc(12 * sizeof *out->tri);
    if (!out->vert || !out->tri)
        return cl_error_set(err, CL_ENOMEM, "out of memory (box)");
    for (int k = 0; k < 8; k++) /* corner k: bit i set = + side of axis i */
        for (int i = 0; i < 3; i++)
            out->vert[3 * k + i] = s->c[i] + ((k >> i) & 1 ? s->h[i]
                                                             : -s->h[i]);
    static const int quad[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (int f = 0; f < 6; f++) {
        const int *v = quad[f];
        int t[2][3] = {{v[0], v[1], v[2]}, {v[0], v[2], v[3]}};
        for (int k = 0; k < 2; k++)
            for (int i = 0; i < 3; i++)
                out->tri[2 * f + k][i] = t[k][i];
    }
    out->nvert = 8;
    out->ntri = 12;
    return CL_OK;
}

const cl_shape_type cl_shape_box = {
    .name = "box",
    .doc = "axis-aligned box: center, size",
    .create = box_create,
    .query = box_query,
    .surface = box_surface,
    .free = free,
};
