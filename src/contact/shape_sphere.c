/* The sphere (docs/model.md, eq. C1): d = |x - q| - r, n = (x - q)/|x - q|,
 * G = (I - n n^T)/|x - q|.  Keys: center (m, default 0), radius (m, > 0,
 * required). */
#include <math.h>
#include <stdlib.h>

#include "contact/shape.h"

#define SLICES 32 /* drawing: around the axis */
#define STACKS 16 /* drawing: pole to pole */

typedef struct {
    double c[3], r;
} sphere;

static cl_status sphere_create(cl_config *cfg, const char *sec,
                               double pivot[3], void **shape, cl_error *err)
{
    sphere s = {{0.0, 0.0, 0.0}, NAN};
    cl_status rc;
    if ((rc = cl_config_vector(cfg, sec, "center", 3, s.c, err)) ||
        (rc = cl_config_double(cfg, sec, "radius", NAN, 1e-300, INFINITY,
                               &s.r, err)))
        return rc;
    if (isnan(s.r))
        return cl_error_set(err, CL_EINVAL, "[%s] shape = sphere needs its "
                            "radius (m, > 0)", sec);
    sphere *p = malloc(sizeof *p);
    if (!p)
        return cl_error_set(err, CL_ENOMEM, "out of memory (sphere)");
    *p = s;
    for (int i = 0; i < 3; i++)
        pivot[i] = s.c[i];
    *shape = p;
    return CL_OK;
}

static void sphere_query(const void *shape, const double x[3],
                         cl_shape_query *q)
{
    const sphere *s = shape;
    double r[3] = {x[0] - s->c[0], x[1] - s->c[1], x[2] - s->c[2]};
    double len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int i = 0; i < 3; i++)
        q->n[i] = len > 0.0 ? r[i] / len : (i == 1);
    q->d = len - s->r;
    for (int i = 0; i < 3; i++) {
        q->c[i] = s->c[i] + s->r * q->n[i];
        for (int j = 0; j < 3; j++)
            q->G[3 * i + j] =
                len > 0.0 ? ((i == j) - q->n[i] * q->n[j]) / len : 0.0;
    }
}

/* A UV sphere: STACKS - 1 rings of SLICES vertices and the two poles. */
static cl_status sphere_surface(const void *shape, cl_shape_surface *out,
                                cl_error *err)
{
    const sphere *s = shape;
    size_t nv = (STACKS - 1) * SLICES + 2, nt = 2 * SLICES * (STACKS - 1);
    out->vert = malloc(3 * nv * sizeof *out->vert);
    out->tri = malloc(nt * sizeof *out->tri);
    if (!out->vert || !out->tri)
        return cl_error_set(err, CL_ENOMEM, "out of memory (sphere)");
    out->nvert = nv;
    out->ntri = 0;
    double *v = out->vert;
    for (int k = 0; k < 3; k++) {
        v[k] = s->c[k] + (k == 1 ? s->r : 0.0);
        v[3 * (nv - 1) + k] = s->c[k] - (k == 1 ? s->r : 0.0);
    }
    for (int a = 1; a < STACKS; a++)
        for (int b = 0; b < SLICES; b++) {
            double th = M_PI * a / STACKS, ph = 2 * M_PI * b / SLICES;
            double *p = v + 3 * (1 + (size_t)(a - 1) * SLICES + (size_t)b);
            p[0] = s->c[0] + s->r * sin(th) * cos(ph);
            p[1] = s->c[1] + s->r * cos(th);
            p[2] = s->c[2] - s->r * sin(th) * sin(ph);
        }
    for (int a = 0; a < STACKS; a++)
        for (int b = 0; b < SLICES; b++) {
            int b1 = (b + 1) % SLICES;
            int up0 = a == 0 ? 0 : 1 + (a - 1) * SLICES + b;
            int up1 = a == 0 ? 0 : 1 + (a - 1) * SLICES + b1;
            int lo0 = a == STACKS - 1 ? (int)nv - 1 : 1 + a * SLICES + b;
            int lo1 = a == STACKS - 1 ? (int)nv - 1 : 1 + a * SLICES + b1;
            if (a > 0) {
                int *t = out->tri[out->ntri++];
                t[0] = up0, t[1] = lo0, t[2] = up1;
            }
            if (a < STACKS - 1) {
                int *t = out->tri[out->ntri++];
                t[0] = up1, t[1] = lo0, t[2] = lo1;
            }
        }
    return CL_OK;
}

const cl_shape_type cl_shape_sphere = {
    .name = "sphere",
    .doc = "sphere: center, radius",
    .create = sphere_create,
    .query = sphere_query,
    .surface = sphere_surface,
    .free = free,
};
