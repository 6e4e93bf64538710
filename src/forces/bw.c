/* Baraff-Witkin elements and the loops of their potential and damping parts
 * (BW98 section 4, condition functions and damping; docs/model.md 3.3);
 * the equations are in forces/bw.h. */
#include "forces/bw.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "forces/pairterm.h"
#include "model/pairs.h"

/* The connections (mesh edges) of an element, as vertex indices within it:
 * a triangle's three edges; a hinge's shared edge v0-v1 and the outer edges
 * of its triangles (v0, v1, v2) and (v1, v0, v3) (model/mesh.h). */
static const int tri_edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
static const int hinge_edges[5][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {3, 1}};

static size_t element_edges(const cl_bw_term *t, const int (**edges)[2])
{
    *edges = t->nv == 3 ? tri_edges : hinge_edges;
    return t->nv == 3 ? 3 : 5;
}

/* ---- triangles ----------------------------------------------------------- */

/* Rest constants from the rest (u, v) differences of a triangle. */
static bool tri_rest(double du1, double du2, double dv1, double dv2,
                     double rest[CL_BW_TRI_REST])
{
    double det = du1 * dv2 - du2 * dv1;
    memset(rest, 0, CL_BW_TRI_REST * sizeof *rest);
    if (det == 0.0 || !isfinite(det))
        return false;
    rest[CL_BW_DU1] = du1;
    rest[CL_BW_DU2] = du2;
    rest[CL_BW_DV1] = dv1;
    rest[CL_BW_DV2] = dv2;
    rest[CL_BW_DET] = det;
    rest[CL_BW_AREA] = 0.5 * fabs(det);
    rest[CL_BW_CU] = (dv1 - dv2) / det;
    rest[CL_BW_CU + 1] = dv2 / det;
    rest[CL_BW_CU + 2] = -dv1 / det;
    rest[CL_BW_CV] = (du2 - du1) / det;
    rest[CL_BW_CV + 1] = -du2 / det;
    rest[CL_BW_CV + 2] = du1 / det;
    return true;
}

bool cl_bw_tri_rest(const double *X0, const int tri[3],
                    double rest[CL_BW_TRI_REST])
{
    const double *Xi = X0 + 3 * tri[0], *Xj = X0 + 3 * tri[1],
                 *Xk = X0 + 3 * tri[2];
    return tri_rest(Xj[0] - Xi[0], Xk[0] - Xi[0], Xj[2] - Xi[2],
                    Xk[2] - Xi[2], rest);
}

bool cl_bw_tri_rest_plane(const double *X0, const int tri[3],
                          double rest[CL_BW_TRI_REST])
{
    const double *Xi = X0 + 3 * tri[0], *Xj = X0 + 3 * tri[1],
                 *Xk = X0 + 3 * tri[2];
    double e[3], f[3], ef = 0.0, ee = 0.0;
    for (int i = 0; i < 3; i++) {
        e[i] = Xj[i] - Xi[i];
        f[i] = Xk[i] - Xi[i];
        ee += e[i] * e[i];
        ef += e[i] * f[i];
    }
    double n[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                   e[0] * f[1] - e[1] * f[0]};
    double l = sqrt(ee), twice_area = sqrt(n[0] * n[0] + n[1] * n[1] +
                                           n[2] * n[2]);
    if (!(l > 0)) {
        memset(rest, 0, CL_BW_TRI_REST * sizeof *rest);
        return false;
    }
    return tri_rest(l, ef / l, 0.0, twice_area / l, rest);
}

/* Baraff and Witkin's expressions (BW98 section 4) as written: at rest
 * dx1, dx2 are du, dv bit for bit, so w_u and w_v are exactly the unit axes
 * there. */
void cl_bw_tri_w(const double *rest, const double *x, double wu[3],
                 double wv[3])
{
    double du1 = rest[CL_BW_DU1], du2 = rest[CL_BW_DU2];
    double dv1 = rest[CL_BW_DV1], dv2 = rest[CL_BW_DV2], det = rest[CL_BW_DET];
    for (int i = 0; i < 3; i++) {
        double dx1 = x[3 + i] - x[i], dx2 = x[6 + i] - x[i];
        wu[i] = (dx1 * dv2 - dx2 * dv1) / det;
        wv[i] = (-dx1 * du2 + dx2 * du1) / det;
    }
}

/* ---- building ------------------------------------------------------------ */

/* A grid with a side of one particle (a chain) has no triangles (a mesh
 * cloth always has some). */
static cl_status check_grid(cl_config *cfg, const cl_cloth *cloth,
                            const char *section, cl_error *err)
{
    char where[256];
    if (cloth->ntri > 0)
        return CL_OK;
    return cl_error_set(err, CL_EINVAL,
                        "%s: [%s] enabled: the Baraff-Witkin model needs a "
                        "grid of at least 2 x 2 particles, this one is "
                        "%d x %d (a chain has no triangles)",
                        cl_config_origin(cfg, section, "enabled", where,
                                         sizeof where),
                        section, cloth->nu, cloth->nv);
}

/* A copy of proto with room for nmax elements. */
static cl_bw_term *new_term(const cl_bw_term *proto, size_t nmax)
{
    cl_bw_term *t = malloc(sizeof *t);
    if (!t)
        return NULL;
    *t = *proto;
    t->n = 0;
    size_t nv = (size_t)t->nv;
    t->vert = malloc((nmax * nv + 1) * sizeof *t->vert);
    t->rest = malloc((nmax * (size_t)t->nrest + 1) * sizeof *t->rest);
    t->couple = malloc((nmax * nv * (nv - 1) / 2 + 1) * sizeof *t->couple);
    t->slot = NULL;
    if (!t->vert || !t->rest || !t->couple) {
        cl_bw_free(t);
        return NULL;
    }
    return t;
}

/* Every vertex pair of every element, once per element. */
static void set_couplings(cl_bw_term *t)
{
    size_t at = 0;
    for (size_t e = 0; e < t->n; e++) {
        const int *v = t->vert + e * (size_t)t->nv;
        for (int m = 0; m < t->nv; m++)
            for (int n = m + 1; n < t->nv; n++) {
                t->couple[at][0] = v[m];
                t->couple[at++][1] = v[n];
            }
    }
}

/* One element per mesh triangle of non-zero rest area; rest (u, v) from
 * the grid's (x, z), or on a mesh cloth from each triangle's own plane. */
static void add_triangles(const cl_cloth *cloth, const cl_mesh *mesh,
                          cl_bw_term *t)
{
    bool (*rest)(const double *, const int *, double *) =
        cloth->kind == CL_CLOTH_MESH ? cl_bw_tri_rest_plane : cl_bw_tri_rest;
    for (size_t k = 0; k < mesh->ntri; k++)
        if (rest(cloth->X0, mesh->tri[k], t->rest + t->n * (size_t)t->nrest))
            memcpy(t->vert + 3 * t->n++, mesh->tri[k], 3 * sizeof(int));
}

/* One element per interior edge that is not degenerate at rest. */
static void add_hinges(const cl_cloth *cloth, const cl_mesh *mesh,
                       const cl_bw_spec *spec, cl_bw_term *t)
{
    for (size_t k = 0; k < mesh->nedge; k++) {
        double x[12];
        for (int m = 0; m < 4; m++)
            memcpy(x + 3 * m, cloth->X0 + 3 * mesh->edge[k].v[m],
                   3 * sizeof *x);
        if (spec->hinge_rest(x, t->rest + t->n * (size_t)t->nrest))
            memcpy(t->vert + 4 * t->n++, mesh->edge[k].v, 4 * sizeof(int));
    }
}

static cl_status build(const cl_cloth *cloth, cl_diagonal diag,
                       const cl_bw_spec *spec, const cl_bw_term *proto,
                       void **state, cl_error *err)
{
    cl_mesh mesh;
    cl_status rc = cloth->kind == CL_CLOTH_MESH
                       ? cl_mesh_from_triangles(cloth->ntri,
                                                (const int(*)[3])cloth->tri,
                                                &mesh, err)
                       : cl_mesh_grid(cloth->nu, cloth->nv, diag, &mesh, err);
    if (rc)
        return rc;
    cl_bw_term *t = new_term(proto, spec->hinge_rest ? mesh.nedge : mesh.ntri);
    if (!t) {
        cl_mesh_free(&mesh);
        return cl_error_set(err, CL_ENOMEM, "out of memory (%s)",
                            spec->section);
    }
    if (spec->hinge_rest)
        add_hinges(cloth, &mesh, spec, t);
    else
        add_triangles(cloth, &mesh, t);
    set_couplings(t);
    cl_mesh_free(&mesh);
    *state = t;
    return CL_OK;
}

/* [section] key<suffix> in [lo, inf), default def. */
static cl_status read_coef(cl_config *cfg, const cl_bw_spec *spec,
                           const char *key, const char *suffix, double def,
                           double lo, double *out, cl_error *err)
{
    char name[32];
    snprintf(name, sizeof name, "%s%s", key, suffix ? suffix : "");
    return cl_config_double(cfg, spec->section, name, def, lo, INFINITY, out,
                            err);
}

/* k, kd and, per component, k<s>, kd<s>, b<s> into proto. */
static cl_status read_coefs(cl_config *cfg, const cl_bw_spec *spec,
                            bool damping, cl_bw_term *proto, cl_error *err)
{
    double k, kd, kc[2], kdc[2];
    cl_status rc;
    if ((rc = read_coef(cfg, spec, "k", NULL, spec->k_default, 0.0, &k,
                        err)) ||
        (rc = read_coef(cfg, spec, "kd", NULL, spec->kd_default, 0.0, &kd,
                        err)))
        return rc;
    for (int c = 0; c < spec->nc; c++) {
        const char *s = spec->nc > 1 ? spec->suffix[c] : NULL;
        kc[c] = k;
        kdc[c] = kd;
        proto->b[c] = 1.0;
        if (s && ((rc = read_coef(cfg, spec, "k", s, k, 0.0, &kc[c], err)) ||
                  (rc = read_coef(cfg, spec, "kd", s, kd, 0.0, &kdc[c],
                                  err)) ||
                  (rc = read_coef(cfg, spec, "b", s, 1.0, 1e-300,
                                  &proto->b[c], err))))
            return rc;
        proto->k[c] = damping ? kdc[c] : kc[c];
    }
    return CL_OK;
}

/* Tearing state of t: rest lengths of every element's connections. */
static cl_status setup_tearing(const cl_cloth *cloth, double cut,
                               cl_bw_term *t, cl_error *err)
{
    const int(*ed)[2];
    size_t ne = element_edges(t, &ed);
    t->cut = cut;
    t->edge_rest = malloc((t->n * ne + 1) * sizeof *t->edge_rest);
    t->torn = calloc(t->n + 1, sizeof *t->torn);
    t->broken = malloc((t->n * ne + 1) * sizeof *t->broken);
    if (!t->edge_rest || !t->torn || !t->broken)
        return cl_error_set(err, CL_ENOMEM, "out of memory (%s tearing)",
                            t->name);
    for (size_t e = 0; e < t->n; e++) {
        const int *v = t->vert + e * (size_t)t->nv;
        for (size_t k = 0; k < ne; k++)
            t->edge_rest[e * ne + k] = cl_dist(cloth->X0 + 3 * v[ed[k][0]],
                                               cloth->X0 + 3 * v[ed[k][1]]);
    }
    return CL_OK;
}

cl_status cl_bw_create(cl_config *cfg, const cl_cloth *cloth,
                       const cl_bw_spec *spec, const cl_term_opts *opts,
                       bool damping, void **state, cl_error *err)
{
    bool enabled;
    cl_diagonal d;
    cl_bw_term proto = {.name = spec->section, .nv = spec->nv,
                        .nc = spec->nc, .nrest = spec->nrest,
                        .cond = spec->cond, .damping = damping};
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_bool(cfg, spec->section, "enabled", false, &enabled,
                             err)) ||
        (rc = cl_mesh_read_diagonal(cfg, &d, err)) ||
        (rc = read_coefs(cfg, spec, damping, &proto, err)))
        return rc;
    bool any = false;
    for (int c = 0; c < spec->nc; c++)
        any = any || proto.k[c] != 0.0;
    if (!enabled || !any)
        return CL_OK;
    if ((rc = check_grid(cfg, cloth, spec->section, err)) ||
        (rc = build(cloth, d, spec, &proto, state, err)))
        return rc;
    if (opts->tear_cut > 0 &&
        (rc = setup_tearing(cloth, opts->tear_cut, *state, err))) {
        cl_bw_free(*state);
        *state = NULL;
    }
    return rc;
}

void cl_bw_free(void *state)
{
    cl_bw_term *t = state;
    if (!t)
        return;
    free(t->vert);
    free(t->rest);
    free(t->couple);
    free(t->slot);
    free(t->edge_rest);
    free(t->torn);
    free(t->broken);
    free(t);
}

/* ---- term hooks ---------------------------------------------------------- */

size_t cl_bw_couplings(const void *state, const int (**pairs)[2])
{
    const cl_bw_term *t = state;
    *pairs = (const int(*)[2])t->couple;
    return t->n * (size_t)(t->nv * (t->nv - 1) / 2);
}

cl_status cl_bw_bind(void *state, const cl_bpattern *pat, const int *dof,
                     cl_error *err)
{
    cl_bw_term *t = state;
    size_t nv = (size_t)t->nv;
    free(t->slot);
    t->slot = malloc((t->n * nv * nv + 1) * sizeof *t->slot);
    if (!t->slot)
        return cl_error_set(err, CL_ENOMEM, "out of memory (%s slots)",
                            t->name);
    for (size_t e = 0; e < t->n; e++) {
        const int *v = t->vert + e * nv;
        for (size_t m = 0; m < nv; m++)
            for (size_t n = 0; n < nv; n++)
                t->slot[(e * nv + m) * nv + n] =
                    cl_bpattern_find(pat, dof[v[m]], dof[v[n]]);
    }
    return CL_OK;
}

/* Blocks (m, n) of  a g g^T + b H  (H only if b != 0) into vals. */
static void add_blocks(double *vals, const long *slot, int nv, double a,
                       const double *g, double b, const double *H)
{
    for (int m = 0; m < nv; m++)
        for (int n = 0; n < nv; n++) {
            double B[9];
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    int r = 3 * m + i, c = 3 * n + j;
                    B[3 * i + j] = a * g[r] * g[c] +
                                   (b != 0.0 ? b * H[r * CL_BW_NX + c] : 0.0);
                }
            cl_block_add(vals, slot[m * nv + n], 1.0, B);
        }
}

/* f_m += s g_m over the element's vertices. */
static void add_force(double *f, const int *v, int nv, double s,
                      const double *g)
{
    for (int m = 0; m < nv; m++)
        for (int i = 0; i < 3; i++)
            f[3 * v[m] + i] += s * g[3 * m + i];
}

/* Potential part of component c: returns its energy k C^2 / 2. */
static double potential(const cl_bw_term *t, size_t e, const cl_bw_cond *q,
                        int c, cl_eval *ev)
{
    const int *v = t->vert + e * (size_t)t->nv;
    double k = t->k[c], C = q->C[c];
    if (ev->f)
        add_force(ev->f, v, t->nv, -k * C, q->g[c]);
    if (ev->dfdx)
        add_blocks(ev->dfdx, t->slot + e * (size_t)(t->nv * t->nv), t->nv, -k,
                   q->g[c], -k * C, q->H[c]);
    return 0.5 * k * C * C;
}

/* Damping part of component c at element velocities ve: returns its power
 * -kd C'^2. */
static double damping(const cl_bw_term *t, size_t e, const cl_bw_cond *q,
                      int c, const double *ve, cl_eval *ev)
{
    const int *v = t->vert + e * (size_t)t->nv;
    const long *slot = t->slot + e * (size_t)(t->nv * t->nv);
    double kd = t->k[c], Cdot = 0.0;
    for (int r = 0; r < 3 * t->nv; r++)
        Cdot += q->g[c][r] * ve[r];
    if (ev->f)
        add_force(ev->f, v, t->nv, -kd * Cdot, q->g[c]);
    if (ev->dfdv)
        add_blocks(ev->dfdv, slot, t->nv, -kd, q->g[c], 0.0, NULL);
    if (ev->dfdx)
        add_blocks(ev->dfdx, slot, t->nv, 0.0, q->g[c], -kd * Cdot, q->H[c]);
    return -kd * Cdot * Cdot;
}

void cl_bw_eval(void *state, cl_eval *ev)
{
    cl_bw_term *t = state;
    double sum = 0.0;
    for (size_t e = 0; e < t->n; e++) {
        if (t->torn && t->torn[e])
            continue;
        const int *v = t->vert + e * (size_t)t->nv;
        double xe[CL_BW_NX], ve[CL_BW_NX];
        for (int m = 0; m < t->nv; m++)
            for (int i = 0; i < 3; i++) {
                xe[3 * m + i] = ev->x[3 * v[m] + i];
                ve[3 * m + i] = ev->v[3 * v[m] + i];
            }
        cl_bw_cond q;
        t->cond(t->rest + e * (size_t)t->nrest, t->b, xe, ev->dfdx != NULL,
                &q);
        for (int c = 0; c < t->nc; c++)
            if (t->k[c] != 0.0)
                sum += t->damping ? damping(t, e, &q, c, ve, ev)
                                  : potential(t, e, &q, c, ev);
    }
    if (ev->want_energy) {
        ev->energy = t->damping ? 0.0 : sum;
        ev->power = t->damping ? sum : 0.0;
    }
}

/* Connections of element e over the cut, recorded in t->broken; returns
 * how many. */
static size_t record_over_cut(cl_bw_term *t, size_t e, const double *x)
{
    const int(*ed)[2];
    size_t ne = element_edges(t, &ed), over = 0;
    const int *p = t->vert + e * (size_t)t->nv;
    for (size_t k = 0; k < ne; k++) {
        int a = p[ed[k][0]], b = p[ed[k][1]];
        if (cl_dist(x + 3 * a, x + 3 * b) > t->cut * t->edge_rest[e * ne + k]) {
            t->broken[t->nbroken][0] = a;
            t->broken[t->nbroken++][1] = b;
            over++;
        }
    }
    return over;
}

/* An element with a connection over the cut breaks for good; each such
 * connection is reported (the model merges the duplicates). */
size_t cl_bw_step_done(void *state, const double *x, const double *v)
{
    cl_bw_term *t = state;
    size_t now = 0;
    (void)v;
    for (size_t e = 0; t->torn && e < t->n; e++) {
        if (t->torn[e])
            continue;
        size_t over = record_over_cut(t, e, x);
        t->torn[e] = over > 0;
        now += over;
    }
    return now;
}

size_t cl_bw_broken(const void *state, const int (**pairs)[2])
{
    const cl_bw_term *t = state;
    *pairs = (const int(*)[2])t->broken;
    return t->nbroken;
}
