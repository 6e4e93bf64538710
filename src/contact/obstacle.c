/* Obstacles: a shape, its scripted rigid motion and its response (see
 * obstacle.h; docs/model.md, contact). */
#include "contact/obstacle.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- motion ----------------------------------------------------------- */

/* R = exp(theta [a]x) for the rotation vector w t (Rodrigues' formula). */
static void rotation(const double w[3], double t, double R[9])
{
    double th = t * sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double a[3] = {0.0, 0.0, 0.0};
    if (th > 0.0)
        for (int i = 0; i < 3; i++)
            a[i] = w[i] * t / th;
    double s = sin(th), c = 1.0 - cos(th);
    double K[9] = {0.0, -a[2], a[1], a[2], 0.0, -a[0], -a[1], a[0], 0.0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double kk = 0.0;
            for (int l = 0; l < 3; l++)
                kk += K[3 * i + l] * K[3 * l + j];
            R[3 * i + j] = (i == j) + s * K[3 * i + j] + c * kk;
        }
}

void cl_obstacle_pose(const cl_obstacle *o, double t, double R[9],
                      double s[3], double sdot[3])
{
    rotation(o->omega, t, R);
    memset(s, 0, 3 * sizeof *s);
    memset(sdot, 0, 3 * sizeof *sdot);
    if (o->nkey == 0)
        return;
    size_t k = 0;
    while (k + 1 < o->nkey && t >= o->key_t[k + 1])
        k++;
    if (t < o->key_t[0] || k + 1 == o->nkey) {
        memcpy(s, o->key_s[t < o->key_t[0] ? 0 : k], 3 * sizeof *s);
        return;
    }
    double dt = o->key_t[k + 1] - o->key_t[k];
    double a = (t - o->key_t[k]) / dt;
    for (int i = 0; i < 3; i++) {
        sdot[i] = (o->key_s[k + 1][i] - o->key_s[k][i]) / dt;
        s[i] = o->key_s[k][i] + a * (o->key_s[k + 1][i] - o->key_s[k][i]);
    }
}

/* ---- queries ---------------------------------------------------------- */

void cl_obstacle_query(const cl_obstacle *o, double t, const double x[3],
                       cl_contact_point *q)
{
    double R[9], s[3], sdot[3], r[3], X[3];
    cl_shape_query b;
    cl_obstacle_pose(o, t, R, s, sdot);
    for (int i = 0; i < 3; i++)
        r[i] = x[i] - o->pivot[i] - s[i];
    for (int i = 0; i < 3; i++) /* X = q + R^T (x - q - s) */
        X[i] = o->pivot[i] + R[i] * r[0] + R[3 + i] * r[1] + R[6 + i] * r[2];
    o->type->query(o->shape, X, &b);
    double cb[3] = {b.c[0] - o->pivot[0], b.c[1] - o->pivot[1],
                    b.c[2] - o->pivot[2]};
    q->d = b.d;
    for (int i = 0; i < 3; i++) {
        q->n[i] = R[3 * i] * b.n[0] + R[3 * i + 1] * b.n[1] +
                  R[3 * i + 2] * b.n[2];
        q->c[i] = o->pivot[i] + s[i] + R[3 * i] * cb[0] +
                  R[3 * i + 1] * cb[1] + R[3 * i + 2] * cb[2];
    }
    for (int i = 0; i < 3; i++) /* G = R Gb R^T */
        for (int j = 0; j < 3; j++) {
            double g = 0.0;
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++)
                    g += R[3 * i + k] * b.G[3 * k + l] * R[3 * j + l];
            q->G[3 * i + j] = g;
        }
    const double *w = o->omega; /* u = s' + w x r, du/dx = [w]x */
    q->u[0] = sdot[0] + w[1] * r[2] - w[2] * r[1];
    q->u[1] = sdot[1] + w[2] * r[0] - w[0] * r[2];
    q->u[2] = sdot[2] + w[0] * r[1] - w[1] * r[0];
    double W[9] = {0.0, -w[2], w[1], w[2], 0.0, -w[0], -w[1], w[0], 0.0};
    memcpy(q->W, W, sizeof W);
}

cl_status cl_obstacle_surface(const cl_obstacle *o, double t,
                              cl_shape_surface *s, cl_error *err)
{
    double R[9], d[3], sdot[3];
    cl_status rc = o->type->surface(o->shape, s, err);
    if (rc)
        return rc;
    cl_obstacle_pose(o, t, R, d, sdot);
    for (size_t k = 0; k < s->nvert; k++) {
        double *p = s->vert + 3 * k, r[3];
        for (int i = 0; i < 3; i++)
            r[i] = p[i] - o->pivot[i];
        for (int i = 0; i < 3; i++)
            p[i] = o->pivot[i] + d[i] + R[3 * i] * r[0] + R[3 * i + 1] * r[1] +
                   R[3 * i + 2] * r[2];
    }
    return CL_OK;
}

/* ---- configuration ---------------------------------------------------- */

static cl_status bad_value(cl_config *cfg, const char *sec, const char *key,
                           const char *value, const char *allowed,
                           cl_error *err)
{
    char where[256];
    return cl_error_set(err, CL_EINVAL, "%s: [%s] %s = \"%s\": %s",
                        cl_config_origin(cfg, sec, key, where, sizeof where),
                        sec, key, value, allowed);
}

static const char path_syntax[] =
    "expected keyframes \"t: x, y, z; t: x, y, z; ...\" with finite "
    "numbers and strictly increasing times";

/* Count the keyframes of a path ("t: x, y, z" separated by ';'). */
static size_t count_keys(const char *v)
{
    size_t n = 1;
    for (; *v; v++)
        n += *v == ';';
    return n;
}

/* One number of a keyframe, then its separator `sep` (or the end). */
static bool read_number(const char **p, char sep, double *out)
{
    char *end;
    *out = strtod(*p, &end);
    if (end == *p || !isfinite(*out))
        return false;
    while (isspace((unsigned char)*end))
        end++;
    if (sep && *end != sep)
        return false;
    *p = end + (sep != 0);
    return true;
}

static cl_status read_path(cl_config *cfg, const char *sec, cl_obstacle *o,
                           cl_error *err)
{
    const char *v = cl_config_string(cfg, sec, "path", NULL);
    if (!v)
        return CL_OK;
    size_t n = count_keys(v);
    o->key_t = malloc(n * sizeof *o->key_t);
    o->key_s = malloc(n * sizeof *o->key_s);
    if (!o->key_t || !o->key_s)
        return cl_error_set(err, CL_ENOMEM, "out of memory (path)");
    const char *p = v;
    for (size_t k = 0; k < n; k++) {
        char last = k + 1 < n ? ';' : 0;
        if (!read_number(&p, ':', &o->key_t[k]) ||
            !read_number(&p, ',', &o->key_s[k][0]) ||
            !read_number(&p, ',', &o->key_s[k][1]) ||
            !read_number(&p, last, &o->key_s[k][2]) ||
            (k > 0 && !(o->key_t[k] > o->key_t[k - 1])))
            return bad_value(cfg, sec, "path", v, path_syntax, err);
    }
    if (*p)
        return bad_value(cfg, sec, "path", v, path_syntax, err);
    o->nkey = n;
    return CL_OK;
}

static cl_status read_penalty(cl_config *cfg, const char *sec,
                              cl_response_params *r, cl_error *err)
{
    cl_status rc;
    if ((rc = cl_config_double(cfg, sec, "k", NAN, 1e-300, INFINITY, &r->k,
                               err)) ||
        (rc = cl_config_double(cfg, sec, "eps", 0.0, 0.0, INFINITY, &r->eps,
                               err)) ||
        (rc = cl_config_double(cfg, sec, "damping", 0.0, 0.0, INFINITY,
                               &r->damping, err)) ||
        (rc = cl_config_double(cfg, sec, "v_smooth", 1e-3, 1e-300, INFINITY,
                               &r->v_smooth, err)))
        return rc;
    if (isnan(r->k))
        return cl_error_set(err, CL_EINVAL, "[%s] response = penalty needs "
                            "its stiffness k (N/m, > 0)", sec);
    return CL_OK;
}

static cl_status read_project(cl_config *cfg, const char *sec,
                              cl_response_params *r, cl_error *err)
{
    cl_status rc;
    if ((rc = cl_config_double(cfg, sec, "offset", 0.0, 0.0, INFINITY,
                               &r->offset, err)) ||
        (rc = cl_config_bool(cfg, sec, "zero_velocity", false,
                             &r->zero_velocity, err)) ||
        (rc = cl_config_long(cfg, sec, "iterations", 1, 1, 1000,
                             &r->iterations, err)))
        return rc;
    return CL_OK;
}

static cl_status read_response(cl_config *cfg, const char *sec,
                               cl_response_params *r, cl_error *err)
{
    static const char *const kinds[] = {"penalty", "project", NULL};
    int k;
    cl_status rc;
    if (!cl_config_string(cfg, sec, "response", NULL))
        return cl_error_set(err, CL_EINVAL, "[%s] needs a response "
                            "(penalty or project)", sec);
    if ((rc = cl_config_choice(cfg, sec, "response", kinds, 0, &k, err)) ||
        (rc = cl_config_double(cfg, sec, "mu", 0.0, 0.0, INFINITY, &r->mu,
                               err)))
        return rc;
    r->kind = k == 0 ? CL_RESPONSE_PENALTY : CL_RESPONSE_PROJECT;
    return k == 0 ? read_penalty(cfg, sec, r, err)
                  : read_project(cfg, sec, r, err);
}

static cl_status read_shape(cl_config *cfg, const char *sec, cl_obstacle *o,
                            cl_error *err)
{
    const char *name = cl_config_string(cfg, sec, "shape", NULL);
    if (!name)
        return cl_error_set(err, CL_EINVAL, "[%s] needs a shape (sphere, "
                            "plane, box or mesh)", sec);
    o->type = cl_shape_find(name);
    if (!o->type) {
        char allowed[256] = "expected one of:";
        for (size_t k = 0; cl_shape_registry[k]; k++) {
            strncat(allowed, " ", sizeof allowed - strlen(allowed) - 1);
            strncat(allowed, cl_shape_registry[k]->name,
                    sizeof allowed - strlen(allowed) - 1);
        }
        return bad_value(cfg, sec, "shape", name, allowed, err);
    }
    return o->type->create(cfg, sec, o->pivot, &o->shape, err);
}

static bool valid_name(const char *s)
{
    if (!*s)
        return false;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '-' && *s != '_')
            return false;
    return true;
}

cl_status cl_obstacle_create(cl_config *cfg, const char *sec, cl_obstacle *o,
                             cl_error *err)
{
    const char *name = strchr(sec, '.');
    memset(o, 0, sizeof *o);
    name = name ? name + 1 : sec;
    if (!valid_name(name) || strlen(name) >= sizeof o->name)
        return cl_error_set(err, CL_EINVAL, "[%s]: an obstacle's name (after "
                            "\"obstacle.\") is 1 to %zu letters, digits, '-' "
                            "or '_'", sec, sizeof o->name - 1);
    strcpy(o->name, name);
    cl_status rc;
    if ((rc = read_shape(cfg, sec, o, err)) ||
        (rc = read_path(cfg, sec, o, err)) ||
        (rc = cl_config_vector(cfg, sec, "omega", 3, o->omega, err)) ||
        (rc = read_response(cfg, sec, &o->resp, err)))
        return rc;
    return CL_OK;
}

void cl_obstacle_free(cl_obstacle *o)
{
    if (o->type && o->shape)
        o->type->free(o->shape);
    free(o->key_t);
    free(o->key_s);
    memset(o, 0, sizeof *o);
}
