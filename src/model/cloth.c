/* Cloth (grid or mesh): rest geometry, masses, triangles, pins and the
 * free-particle numbering (docs/model.md 2). */
#include "model/cloth.h"

#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/frames.h"
#include "model/mesh.h"

cl_status cl_cloth_grid(int nu, int nv, double su, double sv,
                        double particle_mass, cl_cloth *c, cl_error *err)
{
    memset(c, 0, sizeof *c);
    if (nu < 1 || nv < 1 || (long)nu * nv < 2)
        return cl_error_set(err, CL_EINVAL,
                            "cloth grid %d x %d: need at least two particles "
                            "(a 1 x n grid is a chain)", nu, nv);
    if (!(su > 0) || !(sv > 0) || !isfinite(su) || !isfinite(sv))
        return cl_error_set(err, CL_EINVAL,
                            "cloth size %g x %g: need positive, finite sides",
                            su, sv);
    if (!(particle_mass > 0) || !isfinite(particle_mass))
        return cl_error_set(err, CL_EINVAL,
                            "particle mass %g: need positive, finite",
                            particle_mass);
    c->nu = nu;
    c->nv = nv;
    c->np = (size_t)nu * (size_t)nv;
    c->hu = nu > 1 ? su / (nu - 1) : 0.0;
    c->hv = nv > 1 ? sv / (nv - 1) : 0.0;
    c->ntri = cl_grid_triangles(nu, nv, NULL);
    c->X0 = malloc(3 * c->np * sizeof *c->X0);
    c->mass = malloc(c->np * sizeof *c->mass);
    c->tri = malloc((c->ntri + 1) * sizeof *c->tri);
    if (!c->X0 || !c->mass || !c->tri) {
        cl_cloth_free(c);
        return cl_error_set(err, CL_ENOMEM, "out of memory (cloth)");
    }
    cl_grid_triangles(nu, nv, c->tri);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double *X = c->X0 + 3 * (size_t)cl_cloth_index(c, i, j);
            X[0] = i * c->hu;
            X[1] = 0.0;
            X[2] = j * c->hv;
        }
    for (size_t p = 0; p < c->np; p++)
        c->mass[p] = particle_mass;
    return CL_OK;
}

/* The rest area of triangle t; false for a vertex out of range, a
 * repeated vertex or a zero area. */
static bool triangle_area(const double *X0, size_t np, const int t[3],
                          double *area)
{
    for (int k = 0; k < 3; k++)
        if (t[k] < 0 || (size_t)t[k] >= np || t[k] == t[(k + 1) % 3])
            return false;
    const double *a = X0 + 3 * t[0], *b = X0 + 3 * t[1], *d = X0 + 3 * t[2];
    double e[3], f[3];
    for (int i = 0; i < 3; i++) {
        e[i] = b[i] - a[i];
        f[i] = d[i] - a[i];
    }
    double n[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                   e[0] * f[1] - e[1] * f[0]};
    *area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    return *area > 0 && isfinite(*area);
}

/* mass[i] = mass A_i / A from the triangles' vertex areas. */
static cl_status area_masses(cl_cloth *c, double mass, cl_error *err)
{
    double total = 0.0;
    memset(c->mass, 0, c->np * sizeof *c->mass);
    for (size_t t = 0; t < c->ntri; t++) {
        double a;
        const int *v = c->tri[t];
        if (!triangle_area(c->X0, c->np, v, &a))
            return cl_error_set(err, CL_EINVAL,
                                "mesh triangle %zu (%d, %d, %d): needs three "
                                "distinct vertices among 0..%zu and a "
                                "non-zero area", t, v[0], v[1], v[2],
                                c->np - 1);
        for (int k = 0; k < 3; k++)
            c->mass[v[k]] += a / 3.0;
        total += a;
    }
    for (size_t p = 0; p < c->np; p++) {
        if (c->mass[p] == 0.0)
            return cl_error_set(err, CL_EINVAL,
                                "mesh vertex %zu belongs to no triangle (a "
                                "particle's mass comes from its triangles' "
                                "areas)", p);
        c->mass[p] *= mass / total;
    }
    return CL_OK;
}

cl_status cl_cloth_mesh(size_t np, const double *X0, size_t ntri,
                        const int (*tri)[3], double mass, cl_cloth *c,
                        cl_error *err)
{
    memset(c, 0, sizeof *c);
    c->kind = CL_CLOTH_MESH;
    if (np < 3 || np > INT_MAX || ntri == 0)
        return cl_error_set(err, CL_EINVAL,
                            "mesh of %zu vertices and %zu triangles: need at "
                            "least one triangle and at most %d vertices",
                            np, ntri, INT_MAX);
    if (!(mass > 0) || !isfinite(mass))
        return cl_error_set(err, CL_EINVAL,
                            "cloth mass %g: need positive, finite", mass);
    for (size_t k = 0; k < 3 * np; k++)
        if (!isfinite(X0[k]))
            return cl_error_set(err, CL_EINVAL, "mesh vertex %zu: "
                                "coordinates must be finite", k / 3);
    c->np = np;
    c->ntri = ntri;
    c->X0 = malloc(3 * np * sizeof *c->X0);
    c->mass = malloc(np * sizeof *c->mass);
    c->tri = malloc(ntri * sizeof *c->tri);
    if (!c->X0 || !c->mass || !c->tri) {
        cl_cloth_free(c);
        return cl_error_set(err, CL_ENOMEM, "out of memory (cloth)");
    }
    memcpy(c->X0, X0, 3 * np * sizeof *X0);
    memcpy(c->tri, tri, ntri * sizeof *tri);
    cl_mesh mesh; /* built only to check: at most two triangles an edge */
    cl_status rc = area_masses(c, mass, err);
    if (rc == CL_OK)
        rc = cl_mesh_from_triangles(ntri, tri, &mesh, err);
    if (rc == CL_OK)
        cl_mesh_free(&mesh);
    else
        cl_cloth_free(c);
    return rc;
}

const char *cl_cloth_shape(const cl_cloth *c, char *buf, size_t len)
{
    if (c->kind == CL_CLOTH_MESH)
        snprintf(buf, len, "%zu particles, %zu triangles", c->np, c->ntri);
    else
        snprintf(buf, len, "%d x %d particles", c->nu, c->nv);
    return buf;
}

/* Pin particle p (in range), called `name` in messages. */
static cl_status add_pin(cl_cloth *c, int p, const double w[3],
                         double t_stop, const char *name, cl_error *err)
{
    for (size_t k = 0; k < c->npin; k++) {
        const cl_pin *q = &c->pins[k];
        if (q->p != p)
            continue;
        bool still = !w[0] && !w[1] && !w[2];
        if (!memcmp(q->w, w, 3 * sizeof *w) && (still || q->t_stop == t_stop))
            return CL_OK; /* the same pin again (a row meeting a column) */
        return cl_error_set(err, CL_EINVAL,
                            "pin %s is given twice with different motions",
                            name);
    }
    cl_pin *np = realloc(c->pins, (c->npin + 1) * sizeof *np);
    if (!np)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pins)");
    c->pins = np;
    c->pins[c->npin].p = p;
    memcpy(c->pins[c->npin].w, w, 3 * sizeof *w);
    c->pins[c->npin].t_stop = t_stop;
    c->npin++;
    return CL_OK;
}

cl_status cl_cloth_pin(cl_cloth *c, int i, int j, const double w[3],
                       double t_stop, cl_error *err)
{
    int ii = i < 0 ? c->nu + i : i, jj = j < 0 ? c->nv + j : j;
    if (ii < 0 || ii >= c->nu || jj < 0 || jj >= c->nv)
        return cl_error_set(err, CL_EINVAL,
                            "pin (%d, %d) lies outside the %d x %d grid "
                            "(allowed: 0..%d, 0..%d, or negative from the end)",
                            i, j, c->nu, c->nv, c->nu - 1, c->nv - 1);
    char name[64];
    snprintf(name, sizeof name, "(%d, %d)", ii, jj);
    return add_pin(c, cl_cloth_index(c, ii, jj), w, t_stop, name, err);
}

cl_status cl_cloth_pin_particle(cl_cloth *c, int p, const double w[3],
                                double t_stop, cl_error *err)
{
    long n = (long)c->np, q = p < 0 ? n + p : p;
    if (q < 0 || q >= n)
        return cl_error_set(err, CL_EINVAL,
                            "pin p=%d lies outside the %ld particles "
                            "(allowed: 0..%ld, or negative from the end)",
                            p, n, n - 1);
    char name[64];
    snprintf(name, sizeof name, "p=%ld", q);
    return add_pin(c, (int)q, w, t_stop, name, err);
}

/* The runs of consecutive free particles (cl_cloth.run), at most one
 * more than the pins. */
static void find_runs(cl_cloth *c)
{
    c->nrun = 0;
    for (size_t k = 0; k < c->nfree; k++) {
        size_t p = (size_t)c->free_p[k];
        cl_cloth_run *r = &c->run[c->nrun - (c->nrun > 0)];
        if (c->nrun > 0 && r->p + r->n == p)
            r->n++;
        else
            c->run[c->nrun++] = (cl_cloth_run){k, p, 1};
    }
}

cl_status cl_cloth_finalize(cl_cloth *c, cl_error *err)
{
    free(c->dof);
    free(c->free_p);
    free(c->run);
    c->dof = malloc(c->np * sizeof *c->dof);
    c->free_p = malloc(c->np * sizeof *c->free_p);
    c->run = malloc((c->npin + 1) * sizeof *c->run);
    if (!c->dof || !c->free_p || !c->run)
        return cl_error_set(err, CL_ENOMEM, "out of memory (dof map)");
    for (size_t p = 0; p < c->np; p++)
        c->dof[p] = 0;
    for (size_t k = 0; k < c->npin; k++)
        c->dof[c->pins[k].p] = -1;
    c->nfree = 0;
    for (size_t p = 0; p < c->np; p++)
        if (c->dof[p] == 0) {
            c->dof[p] = (int)c->nfree;
            c->free_p[c->nfree++] = (int)p;
        }
    if (c->nfree == 0)
        return cl_error_set(err, CL_EINVAL,
                            "every particle is pinned: nothing to simulate");
    find_runs(c);
    return CL_OK;
}

void cl_cloth_free(cl_cloth *c)
{
    free(c->X0);
    free(c->mass);
    free(c->pins);
    free(c->dof);
    free(c->free_p);
    free(c->run);
    free(c->tri);
    memset(c, 0, sizeof *c);
}

void cl_cloth_scatter(const cl_cloth *c, double t, const double *x,
                      const double *v, double *xfull, double *vfull)
{
    for (size_t j = 0; j < c->nrun; j++) {
        const cl_cloth_run *r = &c->run[j];
        memcpy(xfull + 3 * r->p, x + 3 * r->k, 3 * r->n * sizeof *x);
        if (v)
            memcpy(vfull + 3 * r->p, v + 3 * r->k, 3 * r->n * sizeof *v);
    }
    for (size_t k = 0; k < c->npin; k++) {
        const cl_pin *pin = &c->pins[k];
        cl_cloth_pin_position(c, k, t, xfull + 3 * pin->p);
        if (v)
            for (int d = 0; d < 3; d++)
                vfull[3 * pin->p + d] = t < pin->t_stop ? pin->w[d] : 0.0;
    }
}

void cl_cloth_pin_position(const cl_cloth *c, size_t k, double t,
                           double x[3])
{
    const cl_pin *pin = &c->pins[k];
    double tm = t < pin->t_stop ? t : pin->t_stop;
    for (int d = 0; d < 3; d++)
        x[d] = c->X0[3 * pin->p + d] + pin->w[d] * tm;
}

void cl_cloth_gather(const cl_cloth *c, const double *full, double *freev)
{
    for (size_t j = 0; j < c->nrun; j++) {
        const cl_cloth_run *r = &c->run[j];
        memcpy(freev + 3 * r->k, full + 3 * r->p, 3 * r->n * sizeof *full);
    }
}
