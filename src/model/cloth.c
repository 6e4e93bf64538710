/* Grid cloth: rest geometry, masses, pins and the free-particle numbering
 * (SPEC 2). */
#include "model/cloth.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

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
    c->X0 = malloc(3 * c->np * sizeof *c->X0);
    c->mass = malloc(c->np * sizeof *c->mass);
    if (!c->X0 || !c->mass) {
        cl_cloth_free(c);
        return cl_error_set(err, CL_ENOMEM, "out of memory (cloth)");
    }
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

cl_status cl_cloth_pin(cl_cloth *c, int i, int j, const double w[3],
                       double t_stop, cl_error *err)
{
    int ii = i < 0 ? c->nu + i : i, jj = j < 0 ? c->nv + j : j;
    if (ii < 0 || ii >= c->nu || jj < 0 || jj >= c->nv)
        return cl_error_set(err, CL_EINVAL,
                            "pin (%d, %d) lies outside the %d x %d grid "
                            "(allowed: 0..%d, 0..%d, or negative from the end)",
                            i, j, c->nu, c->nv, c->nu - 1, c->nv - 1);
    int p = cl_cloth_index(c, ii, jj);
    for (size_t k = 0; k < c->npin; k++) {
        const cl_pin *q = &c->pins[k];
        if (q->p != p)
            continue;
        bool still = !w[0] && !w[1] && !w[2];
        if (!memcmp(q->w, w, 3 * sizeof *w) && (still || q->t_stop == t_stop))
            return CL_OK; /* the same pin again (a row meeting a column) */
        return cl_error_set(err, CL_EINVAL,
                            "pin (%d, %d) is given twice with different "
                            "motions", ii, jj);
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

cl_status cl_cloth_finalize(cl_cloth *c, cl_error *err)
{
    free(c->dof);
    free(c->free_p);
    c->dof = malloc(c->np * sizeof *c->dof);
    c->free_p = malloc(c->np * sizeof *c->free_p);
    if (!c->dof || !c->free_p)
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
    return CL_OK;
}

void cl_cloth_free(cl_cloth *c)
{
    free(c->X0);
    free(c->mass);
    free(c->pins);
    free(c->dof);
    free(c->free_p);
    memset(c, 0, sizeof *c);
}

void cl_cloth_scatter(const cl_cloth *c, double t, const double *x,
                      const double *v, double *xfull, double *vfull)
{
    for (size_t k = 0; k < c->nfree; k++) {
        size_t p = (size_t)c->free_p[k];
        memcpy(xfull + 3 * p, x + 3 * k, 3 * sizeof *x);
        if (v)
            memcpy(vfull + 3 * p, v + 3 * k, 3 * sizeof *v);
    }
    for (size_t k = 0; k < c->npin; k++) {
        const cl_pin *pin = &c->pins[k];
        bool moving = t < pin->t_stop;
        double tm = moving ? t : pin->t_stop;
        for (int d = 0; d < 3; d++) {
            xfull[3 * pin->p + d] = c->X0[3 * pin->p + d] + pin->w[d] * tm;
            if (v)
                vfull[3 * pin->p + d] = moving ? pin->w[d] : 0.0;
        }
    }
}

void cl_cloth_gather(const cl_cloth *c, const double *full, double *freev)
{
    for (size_t k = 0; k < c->nfree; k++)
        memcpy(freev + 3 * k, full + 3 * (size_t)c->free_p[k],
               3 * sizeof *full);
}
