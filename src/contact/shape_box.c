/* The box shape, axis-aligned in its own frame: [obstacle.NAME]
 * shape = box,
 *   center  the centre (m, vector, default 0), the pivot
 *   size    the three full side lengths (m, each > 0, required)
 * Exact signed distance.  Outside, the closest point is x clamped to the
 * box; it lies on a face (one coordinate outside: G = 0), an edge (two:
 * G = (I - n n^T - e e^T) / d, e the edge's axis) or a corner (three:
 * G = (I - n n^T) / d).  Inside, d is minus the distance to the nearest
 * face, n that face's normal, G = 0 (a point as near to two faces takes
 * the first of them, x before y before z).  Drawn as 12 triangles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/segment.h"
#include "contact/shape_impl.h"
#include "core/vec3.h"

typedef struct {
    double c[3], h[3];  /* centre, half sides */
} box;

static cl_status box_create(cl_config *cfg, const char *sec, double pivot[3],
                            void **shape, cl_error *err)
{
    box s = {{0, 0, 0}, {0, 0, 0}};
    double size[3];
    cl_status rc;
    if ((rc = cl_shape_vector(cfg, sec, "center", false, s.c, err)) ||
        (rc = cl_shape_vector(cfg, sec, "size", true, size, err)))
        return rc;
    for (int i = 0; i < 3; i++) {
        if (!(size[i] > 0))
            return cl_shape_bad_value(cfg, sec, "size", "three side lengths "
                                      "> 0", err);
        s.h[i] = 0.5 * size[i];
    }
    return cl_shape_copy(&s, sizeof s, s.c, pivot, shape, err);
}

/* x outside the box: the closest point is p (x relative to the centre)
 * clamped.  With two coordinates of p outside, e is the axis of the
 * third, the direction of the nearest edge. */
static void query_outside(const box *b, const double x[3], const double p[3],
                          cl_shape_query *q)
{
    double c[3], n0[3] = {0, 0, 0}, e[3] = {0, 0, 0};
    int out = 0;
    for (int i = 0; i < 3; i++) {
        if (fabs(p[i]) > b->h[i]) {
            c[i] = b->c[i] + (p[i] > 0 ? b->h[i] : -b->h[i]);
            if (!out++)
                n0[i] = p[i] > 0 ? 1 : -1;
        } else {
            c[i] = x[i];    /* x - c exactly 0 along the box */
            e[i] = 1;
        }
    }
    double tiny = 1e-12 * fmax(b->h[0], fmax(b->h[1], b->h[2]));
    if (cl_shape_answer(x, c, 1.0, n0, tiny, q) && out > 1)
        cl_shape_hessian(q->n, out == 2 ? e : NULL, q->d, q->G);
}

/* x inside (or on) the box: the nearest face. */
static void query_inside(const box *b, const double x[3], const double p[3],
                         cl_shape_query *q)
{
    int a = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(p[i]) - b->h[i] > fabs(p[a]) - b->h[a])
            a = i;
    double s = p[a] >= 0 ? 1 : -1, c[3], n0[3] = {0, 0, 0};
    memcpy(c, x, sizeof c);
    c[a] = b->c[a] + s * b->h[a];
    n0[a] = s;
    cl_shape_answer(x, c, -1.0, n0, 0.0, q);
}

static void box_query(const void *shape, const double x[3],
                      void *cache, cl_shape_query *q)
{
    (void)cache;
    const box *b = shape;
    double p[3];
    cl_v3_sub(x, b->c, p);
    if (fabs(p[0]) > b->h[0] || fabs(p[1]) > b->h[1] || fabs(p[2]) > b->h[2])
        query_outside(b, x, p, q);
    else
        query_inside(b, x, p, q);
}

/* The entry into the box grown by offset on every side. */
static double box_toi(const void *shape, const double a[3],
                      const double b[3], double offset)
{
    const box *bx = shape;
    double lo[3], hi[3], d[3], s;
    for (int i = 0; i < 3; i++) {
        lo[i] = bx->c[i] - bx->h[i] - offset;
        hi[i] = bx->c[i] + bx->h[i] + offset;
    }
    cl_v3_sub(b, a, d);
    return cl_segment_box(lo, hi, a, d, 1.0, &s) ? s : INFINITY;
}

static cl_status box_surface(const void *shape, cl_shape_surface *s,
                             cl_error *err)
{
    /* corner k at (k & 1, k & 2, k & 4) -> +h, else -h; two triangles a
     * face, -z, +z, -y, +y, -x, +x */
    static const int tri[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                   {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                   {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    const box *b = shape;
    cl_status rc = cl_shape_surface_alloc(s, 8, 12, tri, err);
    if (rc)
        return rc;
    for (int k = 0; k < 8; k++)
        for (int i = 0; i < 3; i++)
            s->vert[3 * k + i] = b->c[i] + (k >> i & 1 ? b->h[i] : -b->h[i]);
    return CL_OK;
}

const cl_shape_type cl_shape_box = {
    .name = "box",
    .doc = "axis-aligned box: center (vector), size (three side lengths "
           "> 0)",
    .create = box_create,
    .query = box_query,
    .toi = box_toi,
    .surface = box_surface,
    .free = free,
};
