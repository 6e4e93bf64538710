/* Shared state, create/advance/stats/free of the explicit fixed-step
 * integrators, and the step loop with its finite-state check that every
 * fixed-step integrator uses (see fixed_step.h).
 *
 * Each method file states its own update formulas; here a step is only
 *   (x_k, v_k) -> method->step -> (x_{k+1}, v_{k+1}),  t_k = t0 + k h,
 * followed by the check that x_{k+1} and v_{k+1} are finite. */
#include "integrators/fixed_step.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

void cl_fixed_free(void *state)
{
    cl_fixed *s = state;
    if (!s)
        return;
    free(s->x);
    free(s->v);
    free(s->inv_mass);
    for (size_t k = 0; k < CL_FIXED_MAXWORK; k++)
        free(s->w[k]);
    free(s);
}

cl_status cl_fixed_check(const char *name, const cl_system *sys, double dt,
                         double t0, cl_error *err)
{
    if (!isfinite(dt) || !(dt > 0.0))
        return cl_error_set(err, CL_EINVAL,
                            "%s: step dt = %g, must be finite and > 0",
                            name, dt);
    if (!isfinite(t0))
        return cl_error_set(err, CL_EINVAL, "%s: initial time %g", name,
                            t0);
    return cl_check_masses(sys->mass, sys->n, name, err);
}

/* The state with all its arrays, or NULL when out of memory. */
static cl_fixed *fixed_alloc(const cl_fixed_method *m, size_t n)
{
    cl_fixed *s = calloc(1, sizeof *s);
    size_t bytes = (n ? n : 1) * sizeof(double);
    if (!s)
        return NULL;
    s->x = malloc(bytes);
    s->v = malloc(bytes);
    s->inv_mass = malloc(bytes);
    bool ok = s->x && s->v && s->inv_mass;
    for (size_t k = 0; k < m->nwork; k++)
        ok = (s->w[k] = calloc(n ? n : 1, sizeof(double))) != NULL && ok;
    if (!ok) {
        cl_fixed_free(s);
        return NULL;
    }
    return s;
}

cl_status cl_fixed_create(const cl_fixed_method *m, const cl_system *sys,
                          const cl_integrator_opts *o, double t0,
                          const double *x0, const double *v0, void **state,
                          cl_error *err)
{
    *state = NULL;
    if (m->nwork > CL_FIXED_MAXWORK)
        return cl_error_set(err, CL_EINVAL, "%s: %zu work arrays, at most "
                            "%d", m->name, m->nwork, CL_FIXED_MAXWORK);
    cl_status st = cl_fixed_check(m->name, sys, o->dt, t0, err);
    if (st == CL_OK)
        st = cl_integrator_refuse_constraints(m->name, sys, err);
    if (st != CL_OK)
        return st;
    size_t n = sys->n;
    cl_fixed *s = fixed_alloc(m, n);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", m->name);
    s->method = m;
    s->sys = sys;
    s->n = n;
    s->t0 = t0;
    s->dt = o->dt;
    memcpy(s->x, x0, n * sizeof *s->x);
    memcpy(s->v, v0, n * sizeof *s->v);
    for (size_t i = 0; i < n; i++)
        s->inv_mass[i] = 1.0 / sys->mass[i];
    st = m->setup ? m->setup(s, o, err) : CL_OK;
    if (st != CL_OK) {
        cl_fixed_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

/* a *= w, elementwise. */
static void scale(size_t n, const double *restrict w, double *restrict a)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        a[i] *= w[i];
}

cl_status cl_fixed_force(cl_fixed *s, double t, const double *x,
                         const double *v, double *f, cl_error *err)
{
    const cl_system *sys = s->sys;
    cl_status st = sys->force(sys->data, t, x, v, f);
    s->nrhs++;
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: force evaluation failed (%s) at "
                            "t = %.9g (step %ld, dt = %g)", s->method->name,
                            cl_status_name(st), t, s->done, s->dt);
    return CL_OK;
}

cl_status cl_fixed_accel(cl_fixed *s, double t, const double *x,
                         const double *v, double *a, cl_error *err)
{
    cl_status st = cl_fixed_force(s, t, x, v, a, err);
    if (st == CL_OK)
        scale(s->n, s->inv_mass, a);
    return st;
}

/* The system's hooks after step `done`, if it has them: contact (the
 * projections move the state in place), then step_done (tearing). */
static cl_status fixed_step_done(const cl_fixed_clock *c, long done,
                                 cl_error *err)
{
    bool changed = false;
    double t = c->t0 + (double)done * c->h;
    cl_status st = CL_OK;
    if (c->sys && c->sys->contact &&
        (st = c->sys->contact(c->sys->data, t, *c->x, *c->v,
                              CL_CONTACT_RECORD | CL_CONTACT_PROJECT)) !=
            CL_OK)
        return cl_error_set(err, st, "%s: contact after the step failed "
                            "(%s) at t = %.9g (step %ld)", c->name,
                            cl_status_name(st), t, done);
    if (!c->sys || !c->sys->step_done)
        return CL_OK;
    st = c->sys->step_done(c->sys->data, t, *c->x, *c->v, &changed);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: update after the step failed "
                            "(%s) at t = %.9g (step %ld)", c->name,
                            cl_status_name(st), t, done);
    return CL_OK;
}

cl_status cl_fixed_run(const cl_fixed_clock *c, cl_fixed_step_fn step,
                       void *state, double t_out, double *x_out,
                       double *v_out, cl_error *err)
{
    long nsteps = 0;
    cl_status st = cl_fixed_steps_to(t_out - c->t0, c->h, *c->done, &nsteps,
                                     err);
    for (long k = 0; st == CL_OK && k < nsteps; k++) {
        st = step(state, err);
        if (st != CL_OK)
            break;
        long done = ++*c->done;
        if (!cl_all_finite(*c->x, c->n) || !cl_all_finite(*c->v, c->n))
            st = cl_error_set(err, CL_EBLOWUP, "%s: state not finite at "
                              "t = %.9g (step %ld, dt = %g)", c->name,
                              c->t0 + (double)done * c->h, done, c->h);
        else
            st = fixed_step_done(c, done, err);
    }
    memcpy(x_out, *c->x, c->n * sizeof *x_out);
    memcpy(v_out, *c->v, c->n * sizeof *v_out);
    return st;
}

/* The method's step from step `done`. */
static cl_status fixed_step(void *state, cl_error *err)
{
    cl_fixed *s = state;
    return s->method->step(s, s->t0 + (double)s->done * s->dt, s->dt, err);
}

cl_status cl_fixed_advance(void *state, double t_out, double *x, double *v,
                           cl_error *err)
{
    cl_fixed *s = state;
    cl_fixed_clock c = {s->method->name, s->n, s->t0, s->dt, &s->done,
                        &s->x, &s->v, s->sys};
    return cl_fixed_run(&c, fixed_step, s, t_out, x, v, err);
}

void cl_fixed_stats(const void *state, cl_stats *out)
{
    const cl_fixed *s = state;
    memset(out, 0, sizeof *out);
    out->steps = s->done;
    out->rhs_evals = s->nrhs;
}
