/* Obstacles: a shape, its scripted rigid motion and its response (see
 * obstacle.h; docs/model.md, contact). */
#include "contact/obstacle.h"

#include "contact/screen.h"
#include "core/vec3.h"

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

void cl_obstacle_pose(const cl_obstacle *o, double t, cl_pose *P)
{
    P->t = t;
    static const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    P->rotates = o->omega[0] != 0.0 || o->omega[1] != 0.0 ||
                 o->omega[2] != 0.0;
    if (P->rotates)
        rotation(o->omega, t, P->R);
    else /* what rotation() gives for omega = 0, without sin and cos */
        memcpy(P->R, identity, sizeof identity);
    const double *w = o->omega;
    double W[9] = {0.0, -w[2], w[1], w[2], 0.0, -w[0], -w[1], w[0], 0.0};
    memcpy(P->W, W, sizeof W);
    memset(P->s, 0, sizeof P->s);
    memset(P->sdot, 0, sizeof P->sdot);
    if (o->nkey == 0)
        return;
    size_t k = 0;
    while (k + 1 < o->nkey && t >= o->key_t[k + 1])
        k++;
    if (t < o->key_t[0] || k + 1 == o->nkey) {
        memcpy(P->s, o->key_s[t < o->key_t[0] ? 0 : k], sizeof P->s);
        return;
    }
    double dt = o->key_t[k + 1] - o->key_t[k];
    double a = (t - o->key_t[k]) / dt;
    for (int i = 0; i < 3; i++) {
        P->sdot[i] = (o->key_s[k + 1][i] - o->key_s[k][i]) / dt;
        P->s[i] = o->key_s[k][i] + a * (o->key_s[k + 1][i] - o->key_s[k][i]);
    }
}

/* ---- queries ---------------------------------------------------------- */

/* The shape-frame point X of the world point x (docs/model.md, eq. C2):
 * X = q + R^T (x - q - s), with r = x - q - s. */
static inline void to_shape(const cl_obstacle *o, const cl_pose *P,
                     const double x[3], double r[3], double X[3])
{
    const double *R = P->R;
    double y[3];
    cl_v3_sub(x, o->pivot, r);
    cl_v3_sub(r, P->s, r);
    if (P->rotates) {
        y[0] = R[0] * r[0] + R[3] * r[1] + R[6] * r[2];
        y[1] = R[1] * r[0] + R[4] * r[1] + R[7] * r[2];
        y[2] = R[2] * r[0] + R[5] * r[1] + R[8] * r[2];
    } else {
        memcpy(y, r, sizeof y);
    }
    cl_v3_add(o->pivot, y, X);
}

/* y = R b (b itself when the obstacle does not rotate). */
static inline void rotate(const cl_pose *P, const double b[3], double y[3])
{
    if (!P->rotates) {
        memcpy(y, b, 3 * sizeof *y);
        return;
    }
    for (int i = 0; i < 3; i++)
        y[i] = P->R[3 * i] * b[0] + P->R[3 * i + 1] * b[1] +
               P->R[3 * i + 2] * b[2];
}

/* G = R Gb R^T */
static void rotate_hessian(const cl_pose *P, const double Gb[9],
                           double G[9])
{
    const double *R = P->R;
    double T[9];
    if (!P->rotates) {
        memcpy(G, Gb, 9 * sizeof *G);
        return;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            T[3 * i + j] = R[3 * i] * Gb[j] + R[3 * i + 1] * Gb[3 + j] +
                           R[3 * i + 2] * Gb[6 + j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            G[3 * i + j] = T[3 * i] * R[3 * j] + T[3 * i + 1] * R[3 * j + 1] +
                           T[3 * i + 2] * R[3 * j + 2];
}


/* Whether the memo m shows d >= dmax at X = (X0, X1, X2):
 * d(X) >= m.d - |X - m.X|. */
static inline bool memo_far_at(const cl_contact_memo *m, double X0,
                               double X1, double X2, double dmax)
{
    double margin = m->d - dmax;
    double e0 = X0 - m->X[0], e1 = X1 - m->X[1], e2 = X2 - m->X[2];
    return margin > 0.0 && e0 * e0 + e1 * e1 + e2 * e2 <= margin * margin;
}

/* The obstacle's velocity u = s' + w x r at r = x - q - s (du/dx =
 * [w]x). */
static void velocity_at(const cl_obstacle *o, const cl_pose *P,
                        const double r[3], double u[3])
{
    const double *w = o->omega;
    u[0] = P->sdot[0] + w[1] * r[2] - w[2] * r[1];
    u[1] = P->sdot[1] + w[2] * r[0] - w[0] * r[2];
    u[2] = P->sdot[2] + w[0] * r[1] - w[1] * r[0];
}

void cl_obstacle_velocity(const cl_obstacle *o, const cl_pose *P,
                          const double x[3], double u[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = x[i] - o->pivot[i] - P->s[i];
    velocity_at(o, P, r, u);
}

/* The contact point of x (r = x - q - s) from the shape's answer b. */
static void point_of(const cl_obstacle *o, const cl_pose *P,
                     const double r[3], const cl_shape_query *b,
                     cl_contact_point *q)
{
    double cb[3], c[3], qs[3];
    cl_v3_sub(b->c, o->pivot, cb);
    q->d = b->d;
    rotate(P, b->n, q->n); /* a copy when the obstacle does not turn */
    rotate(P, cb, c);
    cl_v3_add(o->pivot, P->s, qs);    /* q + s + c */
    cl_v3_add(qs, c, q->c);
    rotate_hessian(P, b->G, q->G);
    velocity_at(o, P, r, q->u);
    memcpy(q->W, P->W, sizeof q->W);
}

/* The shape's answer b at the shape-frame point X, unless the memo (if
 * not NULL) or the shape's lower bound of d shows d >= dmax; whether it
 * was queried.  A point that was within dmax at its last query (a
 * particle in contact) is queried without the shape's lower bound, which
 * would not skip it (a mesh's box holds the surface near it).  The memo
 * keeps the answer, or the bound. */
static bool shape_at(const cl_obstacle *o, const double X[3], double dmax,
                     cl_contact_memo *memo, cl_shape_query *b)
{
    if (memo && memo_far_at(memo, X[0], X[1], X[2], dmax))
        return false;
    bool touched = memo && memo->exact && memo->d < dmax;
    double low = o->type->lower_bound && !touched
                     ? o->type->lower_bound(o->shape, X)
                     : -INFINITY;
    if (low < dmax)
        o->type->query(o->shape, X, memo ? memo->cache : NULL, b);
    if (memo) {
        memcpy(memo->X, X, sizeof memo->X);
        memo->d = low < dmax ? b->d : low;
        memo->exact = low < dmax;
    }
    return low < dmax;
}

/* cl_obstacle_near at the shape-frame point X of x (r = x - q - s); q is
 * set whenever the shape was queried. */
static bool near_at(const cl_obstacle *o, const cl_pose *P,
                    const double r[3], const double X[3], double dmax,
                    cl_contact_memo *memo, cl_contact_point *q)
{
    cl_shape_query b;
    if (!shape_at(o, X, dmax, memo, &b))
        return false;
    point_of(o, P, r, &b, q);
    return q->d < dmax;
}

bool cl_obstacle_near(const cl_obstacle *o, const cl_pose *P,
                      const double x[3], double dmax, cl_contact_memo *memo,
                      cl_contact_point *q)
{
    double r[3], X[3];
    to_shape(o, P, x, r, X);
    return near_at(o, P, r, X, dmax, memo, q);
}

/* cl_obstacle_near_slim of a half-space that does not rotate: d = n .
 * (X - p), the shape's query itself (shape.h), without the memos. */
static size_t halfspace_slim(const cl_obstacle *o, const cl_pose *P,
                             const double *x, double dmax, size_t *near,
                             size_t n, cl_contact_slim *q)
{
    double nrm[3], at[3];
    size_t kept = 0;
    o->type->halfspace(o->shape, nrm, at);
    for (size_t i = 0; i < n; i++) {
        size_t p = near[i];
        double r[3], X[3], e[3];
        to_shape(o, P, x + 3 * p, r, X);
        cl_v3_sub(X, at, e);
        double d = cl_v3_dot(nrm, e);
        if (!(d < dmax))
            continue;
        q[kept].d = d;
        memcpy(q[kept].n, nrm, sizeof nrm);
        velocity_at(o, P, r, q[kept].u);
        near[kept++] = p;
    }
    return kept;
}

size_t cl_obstacle_near_slim(const cl_obstacle *o, const cl_pose *P,
                             const double *x, double dmax,
                             cl_contact_memo *memo, size_t *near, size_t n,
                             cl_contact_slim *q)
{
    if (!P->rotates && o->type->halfspace)
        return halfspace_slim(o, P, x, dmax, near, n, q);
    size_t kept = 0;
    for (size_t i = 0; i < n; i++) {
        size_t p = near[i];
        double r[3], X[3];
        cl_shape_query b;
        to_shape(o, P, x + 3 * p, r, X);
        if (!shape_at(o, X, dmax, &memo[p], &b) || !(b.d < dmax))
            continue;
        q[kept].d = b.d;
        rotate(P, b.n, q[kept].n);
        velocity_at(o, P, r, q[kept].u);
        near[kept++] = p;
    }
    return kept;
}

bool cl_obstacle_depth(const cl_obstacle *o, const cl_pose *P,
                       const double x[3], double dmax, cl_contact_memo *memo,
                       double *d)
{
    double r[3], X[3];
    to_shape(o, P, x, r, X);
    if (memo->exact && memo->X[0] == X[0] && memo->X[1] == X[1] &&
        memo->X[2] == X[2]) {
        *d = memo->d;
        return *d < dmax;
    }
    cl_contact_point q;
    bool near = near_at(o, P, r, X, dmax, memo, &q);
    *d = near ? q.d : INFINITY;
    return near;
}

/* The screen of a half-space that does not rotate (shape.h): d = n . x -
 * (c + n . s) in the world frame, a dot product a point, which differs
 * from the query's n . (q + (x - q - s) - p) by rounding only, far less
 * than the slack allowed for it (relative to the magnitudes involved,
 * contact/screen.h); NaN points are near, as with the memos. */
static size_t screen_halfspace(const cl_obstacle *o, const cl_pose *P,
                               const double *x, size_t np, double dmax,
                               size_t *near)
{
    double nrm[3], at[3];
    o->type->halfspace(o->shape, nrm, at);
    double c = cl_v3_dot(nrm, at), cw = c + cl_v3_dot(nrm, P->s);
    double scale = fabs(c) + fabs(cw) + cl_v3_norm(P->s) +
                   cl_v3_norm(o->pivot);
    return cl_screen_halfspace(x, np, nrm, cw, scale, dmax, near);
}

size_t cl_obstacle_screen(const cl_obstacle *o, const cl_pose *P,
                          const double *x, size_t np, double dmax,
                          const cl_contact_memo *memo, size_t *near)
{
    size_t n = 0;
    if (!P->rotates && o->type->halfspace)
        return screen_halfspace(o, P, x, np, dmax, near);
    if (!P->rotates) /* to_shape without the rotation, in the same order */
        return cl_screen_memos(x, np, o->pivot, P->s, memo, dmax, near);
    for (size_t p = 0; p < np; p++) {
        double r[3], X[3];
        to_shape(o, P, x + 3 * p, r, X);
        if (!memo_far_at(&memo[p], X[0], X[1], X[2], dmax))
            near[n++] = p;
    }
    return n;
}

double cl_obstacle_toi(const cl_obstacle *o, const cl_pose *P0,
                       const double x0[3], const cl_pose *P1,
                       const double x1[3], double offset)
{
    double r[3], X0[3], X1[3];
    to_shape(o, P0, x0, r, X0);
    to_shape(o, P1, x1, r, X1);
    return o->type->toi(o->shape, X0, X1, offset);
}

bool cl_obstacle_sweep(const cl_obstacle *o, const cl_pose *P0,
                       const double x0[3], const cl_pose *P1,
                       const double x1[3], double offset, double *s,
                       double xhit[3])
{
    *s = cl_obstacle_toi(o, P0, x0, P1, x1, offset);
    if (!(*s <= 1.0))
        return false;
    double r[3], X0[3], X1[3], X[3], y[3];
    to_shape(o, P0, x0, r, X0);
    to_shape(o, P1, x1, r, X1);
    cl_shape_query q;
    o->type->query(o->shape, X0, NULL, &q);
    if (q.d <= offset + CL_ON_SURFACE)
        return false;
    for (int i = 0; i < 3; i++)
        X[i] = X0[i] + *s * (X1[i] - X0[i]) - o->pivot[i];
    rotate(P1, X, y);
    for (int i = 0; i < 3; i++)
        xhit[i] = o->pivot[i] + P1->s[i] + y[i];
    return true;
}

cl_status cl_obstacle_surface(const cl_obstacle *o, double t,
                              cl_shape_surface *s, cl_error *err)
{
    cl_pose P;
    cl_status rc = o->type->surface(o->shape, s, err);
    if (rc)
        return rc;
    cl_obstacle_pose(o, t, &P);
    for (size_t k = 0; k < s->nvert; k++) {
        double *p = s->vert + 3 * k, r[3], y[3];
        for (int i = 0; i < 3; i++)
            r[i] = p[i] - o->pivot[i];
        rotate(&P, r, y);
        for (int i = 0; i < 3; i++)
            p[i] = o->pivot[i] + P.s[i] + y[i];
    }
    return CL_OK;
}

/* ---- configuration ---------------------------------------------------- */

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
            return cl_config_refuse(cfg, sec, "path", CL_EINVAL,
                                    path_syntax, err);
    }
    if (*p)
        return cl_config_refuse(cfg, sec, "path", CL_EINVAL, path_syntax,
                                err);
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
        return cl_config_missing(cfg, sec, "k", "response = penalty's "
                                 "stiffness, N/m, > 0", err);
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
                             &r->iterations, err)) ||
        (rc = cl_config_bool(cfg, sec, "ccd", false, &r->ccd, err)))
        return rc;
    return CL_OK;
}

static cl_status read_barrier(cl_config *cfg, const char *sec,
                              cl_response_params *r, cl_error *err)
{
    cl_status rc;
    if ((rc = cl_config_double(cfg, sec, "kappa", NAN, 1e-300, INFINITY,
                               &r->kappa, err)) ||
        (rc = cl_config_double(cfg, sec, "dhat", NAN, 1e-300, INFINITY,
                               &r->dhat, err)) ||
        (rc = cl_config_double(cfg, sec, "eps_v", 1e-3, 1e-300, INFINITY,
                               &r->eps_v, err)) ||
        (rc = cl_config_bool(cfg, sec, "psd", true, &r->psd, err)))
        return rc;
    if (isnan(r->kappa) || isnan(r->dhat))
        return cl_config_missing(cfg, sec, isnan(r->kappa) ? "kappa" : "dhat",
                                 isnan(r->kappa)
                                     ? "response = barrier's stiffness, "
                                       "J/m^2, > 0"
                                     : "response = barrier's reach, m, > 0",
                                 err);
    return CL_OK;
}

static cl_status read_constraint(cl_config *cfg, const char *sec,
                                 cl_response_params *r, cl_error *err)
{
    return cl_config_double(cfg, sec, "offset", 0.0, 0.0, INFINITY,
                            &r->offset, err);
}

static cl_status read_response(cl_config *cfg, const char *sec,
                               cl_response_params *r, cl_error *err)
{
    static const char *const kinds[] = {"penalty", "project", "barrier",
                                        "constraint", NULL};
    static cl_status (*const read[])(cl_config *, const char *,
                                      cl_response_params *, cl_error *) = {
        read_penalty, read_project, read_barrier, read_constraint};
    int k;
    cl_status rc;
    if (!cl_config_string(cfg, sec, "response", NULL))
        return cl_config_missing(cfg, sec, "response", "penalty, project, "
                                 "barrier or constraint", err);
    if ((rc = cl_config_choice(cfg, sec, "response", kinds, 0, &k, err)) ||
        (rc = cl_config_double(cfg, sec, "mu", 0.0, 0.0, INFINITY, &r->mu,
                               err)))
        return rc;
    r->kind = (cl_response)k; /* the order of kinds[] */
    return read[k](cfg, sec, r, err);
}

static cl_status read_shape(cl_config *cfg, const char *sec, cl_obstacle *o,
                            cl_error *err)
{
    const char *name = cl_config_string(cfg, sec, "shape", NULL);
    if (!name)
        return cl_config_missing(cfg, sec, "shape", "sphere, plane, box or "
                                 "mesh", err);
    o->type = cl_shape_find(name);
    if (!o->type) {
        char allowed[256] = "expected one of:";
        for (size_t k = 0; cl_shape_registry[k]; k++) {
            strncat(allowed, " ", sizeof allowed - strlen(allowed) - 1);
            strncat(allowed, cl_shape_registry[k]->name,
                    sizeof allowed - strlen(allowed) - 1);
        }
        return cl_config_refuse(cfg, sec, "shape", CL_EINVAL, allowed, err);
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
    /* far beyond any cloth's, and |omega| t stays finite */
    for (int i = 0; i < 3; i++)
        if (!(fabs(o->omega[i]) <= 1e9))
            return cl_config_refuse(cfg, sec, "omega", CL_EINVAL, "each "
                                    "component at most 1e9 rad/s in size",
                                    err);
    if (o->resp.kind == CL_RESPONSE_BARRIER && !o->type->toi)
        return cl_error_set(err, CL_EINVAL, "[%s] response = barrier: shape "
                            "%s has no time of impact (continuous collision "
                            "detection)", sec, o->type->name);
    if (o->resp.ccd && !o->type->toi)
        return cl_config_refuse(cfg, sec, "ccd", CL_EINVAL, "false: this "
                                "shape has no continuous detection", err);
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
