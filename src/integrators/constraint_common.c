/* The substep loop of the constraint-based integrators: see
 * constraint_common.h. */
#include "integrators/constraint_common.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/fixed_step.h"

void cl_cdyn_free(void *state)
{
    cl_cdyn *s = state;
    if (!s)
        return;
    if (s->own)
        s->method->free(s->own);
    free(s->x);
    free(s->v);
    free(s->inv_mass);
    free(s->xn);
    free(s->y);
    free(s->xa);
    free(s);
}

static cl_status cdyn_check(const cl_cdyn_method *m, const cl_system *sys,
                            const cl_integrator_opts *o, double t0,
                            cl_error *err)
{
    cl_status st = cl_fixed_check(m->name, sys, o->dt, t0, err);
    if (st || (st = cl_integrator_refuse_constraints(m->name, sys, err)))
        return st;
    if (o->substeps < 0 || o->iterations < 0)
        return cl_error_set(err, CL_EINVAL, "%s: substeps = %ld, iterations "
                            "= %ld (need >= 0; 0: the default)", m->name,
                            o->substeps, o->iterations);
    if (!sys->distances)
        return cl_error_set(err, CL_EINVAL, "%s needs distance constraints: "
                            "a springs or pbd term (springs.enabled or "
                            "pbd.enabled = true) and no tearing (tear.cut "
                            "= 0)", m->name);
    return CL_OK;
}

static cl_status cdyn_alloc(cl_cdyn *s, size_t n, size_t na, cl_error *err)
{
    size_t bytes = (n ? n : 1) * sizeof(double);
    s->x = malloc(bytes);
    s->v = malloc(bytes);
    s->inv_mass = malloc(bytes);
    s->xn = malloc(bytes);
    s->y = malloc(bytes);
    s->xa = malloc((3 * na + 1) * sizeof(double));
    if (!s->x || !s->v || !s->inv_mass || !s->xn || !s->y || !s->xa)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory",
                            s->method->name);
    return CL_OK;
}

cl_status cl_cdyn_create(const cl_cdyn_method *m, const cl_system *sys,
                         const cl_integrator_opts *o, double t0,
                         const double *x0, const double *v0, void **state,
                         cl_error *err)
{
    *state = NULL;
    cl_status st = cdyn_check(m, sys, o, t0, err);
    if (st)
        return st;
    cl_cdyn *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", m->name);
    *s = (cl_cdyn){.method = m, .sys = sys, .dc = sys->distances,
                   .n = sys->n, .t0 = t0, .dt = o->dt,
                   .substeps = o->substeps ? o->substeps : 1,
                   .iterations = o->iterations ? o->iterations
                                               : m->default_iterations};
    s->h = s->dt / (double)s->substeps;
    if ((st = cdyn_alloc(s, s->n, s->dc->nanchor, err)) == CL_OK) {
        memcpy(s->x, x0, s->n * sizeof *s->x);
        memcpy(s->v, v0, s->n * sizeof *s->v);
        for (size_t i = 0; i < s->n; i++)
            s->inv_mass[i] = 1.0 / sys->mass[i];
        st = m->setup ? m->setup(s, err) : CL_OK;
    }
    if (st) {
        cl_cdyn_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

/* One substep from t to t + h (docs/integrators.md, 9). */
static cl_status cdyn_substep(cl_cdyn *s, double t, cl_error *err)
{
    const cl_system *sys = s->sys;
    double h = s->h, *a = s->y; /* f_other into y, read before y is set */
    cl_status st = sys->force_other(sys->data, t, s->x, s->v, a);
    s->nrhs++;
    if (st)
        return cl_error_set(err, st, "%s: force evaluation failed (%s) at "
                            "t = %.9g (step %ld, dt = %g)", s->method->name,
                            cl_status_name(st), t, s->done, s->dt);
    for (size_t i = 0; i < s->n; i++) {
        s->v[i] += h * s->inv_mass[i] * a[i];
        s->xn[i] = s->x[i];
        s->y[i] = s->x[i] + h * s->v[i];
        s->x[i] = s->y[i];
    }
    sys->anchors(sys->data, t + h, s->xa);
    if ((st = s->method->solve(s, t + h, h, err)))
        return st;
    s->sweeps += s->iterations;
    for (size_t i = 0; i < s->n; i++)
        s->v[i] = (s->x[i] - s->xn[i]) / h;
    return CL_OK;
}

static cl_status cdyn_step(void *state, cl_error *err)
{
    cl_cdyn *s = state;
    double t = s->t0 + (double)s->done * s->dt;
    cl_status st = CL_OK;
    for (long k = 0; st == CL_OK && k < s->substeps; k++)
        st = cdyn_substep(s, t + (double)k * s->h, err);
    return st;
}

cl_status cl_cdyn_advance(void *state, double t_out, double *x, double *v,
                          cl_error *err)
{
    cl_cdyn *s = state;
    cl_fixed_clock c = {s->method->name, s->n, s->t0, s->dt, &s->done,
                        &s->x, &s->v, s->sys};
    return cl_fixed_run(&c, cdyn_step, s, t_out, x, v, err);
}

void cl_cdyn_stats(const void *state, cl_stats *out)
{
    const cl_cdyn *s = state;
    memset(out, 0, sizeof *out);
    out->steps = s->done;
    out->rhs_evals = s->nrhs;
    out->nonlin_iters = s->sweeps;
    out->lin_setups = s->lin_setups;
    /* pd's one setup is CHOLMOD's analysis and factorisation */
    out->symbolic_facts = s->lin_setups;
    out->lin_solves = s->lin_solves;
    if (s->lin_setups)
        snprintf(out->linsol, sizeof out->linsol, "cholmod");
}
