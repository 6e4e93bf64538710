/* Helpers shared by the obstacle shapes (contact/shape_impl.h). */
#include "contact/shape_impl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec3.h"

cl_status cl_shape_bad_value(cl_config *cfg, const char *sec,
                             const char *key, const char *what,
                             cl_error *err)
{
    char why[256];
    snprintf(why, sizeof why, "expected %s", what);
    return cl_config_refuse(cfg, sec, key, CL_EINVAL, why, err);
}

cl_status cl_shape_positive(cl_config *cfg, const char *sec, const char *key,
                            double def, double *out, cl_error *err)
{
    if (isnan(def) && !cl_config_string(cfg, sec, key, NULL))
        return cl_config_missing(cfg, sec, key, "a number > 0", err);
    if (cl_config_double(cfg, sec, key, def, -INFINITY, INFINITY, out, NULL)
        || !(*out > 0))
        return cl_shape_bad_value(cfg, sec, key, "a number > 0", err);
    return CL_OK;
}

cl_status cl_shape_vector(cl_config *cfg, const char *sec, const char *key,
                          bool required, double out[3], cl_error *err)
{
    if (required && !cl_config_string(cfg, sec, key, NULL))
        return cl_config_missing(cfg, sec, key, "three numbers x, y, z",
                                 err);
    return cl_config_vector(cfg, sec, key, 3, out, err);
}

cl_status cl_shape_copy(const void *src, size_t size, const double at[3],
                        double pivot[3], void **shape, cl_error *err)
{
    memcpy(pivot, at, 3 * sizeof *pivot);
    *shape = malloc(size);
    if (!*shape)
        return cl_error_set(err, CL_ENOMEM, "out of memory (shape)");
    memcpy(*shape, src, size);
    return CL_OK;
}

bool cl_shape_answer(const double x[3], const double c[3], double sign,
                     const double n0[3], double tiny, cl_shape_query *q)
{
    double r[3];
    cl_v3_sub(x, c, r);
    double len = cl_v3_norm(r);
    bool away = len > tiny;
    q->d = sign * len;
    for (int i = 0; i < 3; i++) {
        q->c[i] = c[i];
        q->n[i] = away ? sign * r[i] / len : n0[i];
    }
    memset(q->G, 0, sizeof q->G);
    return away;
}

void cl_shape_hessian(const double n[3], const double *e, double rho,
                      double G[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            G[3 * i + j] = ((i == j) - n[i] * n[j] - (e ? e[i] * e[j] : 0))
                           / rho;
}

cl_status cl_shape_surface_alloc(cl_shape_surface *s, size_t nvert,
                                 size_t ntri, const int (*tri)[3],
                                 cl_error *err)
{
    s->nvert = nvert;
    s->ntri = ntri;
    s->vert = malloc((3 * nvert + 1) * sizeof *s->vert);
    s->tri = malloc((ntri + 1) * sizeof *s->tri);
    if (s->vert && s->tri) {
        memcpy(s->tri, tri, ntri * sizeof *tri);
        return CL_OK;
    }
    cl_shape_surface_free(s);
    return cl_error_set(err, CL_ENOMEM, "out of memory (surface of %zu "
                        "triangles)", ntri);
}
