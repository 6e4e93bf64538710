/* symplectic-euler: semi-implicit (symplectic) Euler, velocity first, as in
 * the code of seed 000:
 *
 *   v_{k+1} = v_k + h M^-1 f(t_k, x_k, v_k)
 *   x_{k+1} = x_k + h v_{k+1},        t_k = t0 + k h,  h = opts->dt > 0.
 *
 * First order; symplectic for conservative forces (bounded energy error,
 * O(h), no drift); explicit, so stable only for h below ~2/omega_max.
 * One force evaluation per step.  After every step the state is checked to
 * be finite (CL_EBLOWUP with the time and the step otherwise).  Output times
 * must be whole multiples of h from t0 (cl_fixed_steps_to). */
#include "integrators/integrator.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const cl_system *sys;
    double t0, dt;
    long done;      /* steps taken */
    long nrhs;      /* force evaluations */
    double *x, *v;  /* current state (n each) */
    double *f;      /* force work array (n) */
    double *inv_mass;
} cl_symeuler;

static void se_free(void *state)
{
    cl_symeuler *s = state;
    if (!s)
        return;
    free(s->x);
    free(s->v);
    free(s->f);
    free(s->inv_mass);
    free(s);
}

static cl_status se_check_args(const cl_system *sys,
                               const cl_integrator_opts *o, double t0,
                               cl_error *err)
{
    if (!isfinite(o->dt) || !(o->dt > 0.0))
        return cl_error_set(err, CL_EINVAL,
                            "symplectic-euler: step dt = %g, must be "
                            "finite and > 0", o->dt);
    if (!isfinite(t0))
        return cl_error_set(err, CL_EINVAL,
                            "symplectic-euler: initial time %g", t0);
    for (size_t i = 0; i < sys->n; i++) {
        if (!isfinite(sys->mass[i]) || !(sys->mass[i] > 0.0))
            return cl_error_set(err, CL_EINVAL,
                                "symplectic-euler: mass[%zu] = %g, must be "
                                "finite and > 0", i, sys->mass[i]);
    }
    return CL_OK;
}

static cl_status se_create(const cl_system *sys, const cl_integrator_opts *o,
                           double t0, const double *x0, const double *v0,
                           void **state, cl_error *err)
{
    *state = NULL;
    cl_status st = se_check_args(sys, o, t0, err);
    if (st != CL_OK)
        return st;
    cl_symeuler *s = calloc(1, sizeof *s);
    size_t n = sys->n, bytes = (n ? n : 1) * sizeof(double);
    if (s) {
        s->x = malloc(bytes);
        s->v = malloc(bytes);
        s->f = malloc(bytes);
        s->inv_mass = malloc(bytes);
    }
    if (!s || !s->x || !s->v || !s->f || !s->inv_mass) {
        se_free(s);
        return cl_error_set(err, CL_ENOMEM, "symplectic-euler: out of memory");
    }
    s->sys = sys;
    s->t0 = t0;
    s->dt = o->dt;
    memcpy(s->x, x0, n * sizeof *s->x);
    memcpy(s->v, v0, n * sizeof *s->v);
    for (size_t i = 0; i < n; i++)
        s->inv_mass[i] = 1.0 / sys->mass[i];
    *state = s;
    return CL_OK;
}

static bool se_finite(const double *a, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(a[i]))
            return false;
    }
    return true;
}

/* One step from step `done`; CL_EBLOWUP if the force fails so or the new
 * state is not finite. */
static cl_status se_step(cl_symeuler *s, cl_error *err)
{
    const cl_system *sys = s->sys;
    double t = s->t0 + (double)s->done * s->dt, h = s->dt;
    cl_status st = sys->force(sys->data, t, s->x, s->v, s->f);
    s->nrhs++;
    if (st != CL_OK)
        return cl_error_set(err, st, "symplectic-euler: force evaluation "
                            "failed (%s) at t = %.9g (step %ld, dt = %g)",
                            cl_status_name(st), t, s->done, h);
    for (size_t i = 0; i < sys->n; i++) {
        s->v[i] += h * s->inv_mass[i] * s->f[i];
        s->x[i] += h * s->v[i];
    }
    s->done++;
    if (!se_finite(s->x, sys->n) || !se_finite(s->v, sys->n))
        return cl_error_set(err, CL_EBLOWUP,
                            "symplectic-euler: state not finite at t = %.9g "
                            "(step %ld, dt = %g)",
                            s->t0 + (double)s->done * h, s->done, h);
    return CL_OK;
}

static cl_status se_advance(void *state, double t_out, double *x, double *v,
                            cl_error *err)
{
    cl_symeuler *s = state;
    long nsteps = 0;
    cl_status st = cl_fixed_steps_to(t_out - s->t0, s->dt, s->done, &nsteps,
                                     err);
    for (long k = 0; st == CL_OK && k < nsteps; k++)
        st = se_step(s, err);
    memcpy(x, s->x, s->sys->n * sizeof *x);
    memcpy(v, s->v, s->sys->n * sizeof *v);
    return st;
}

static void se_stats(const void *state, cl_stats *out)
{
    const cl_symeuler *s = state;
    memset(out, 0, sizeof *out);
    out->steps = s->done;
    out->rhs_evals = s->nrhs;
}

const cl_integrator_type cl_integrator_symplectic_euler = {
    .name = "symplectic-euler",
    .doc = "symplectic Euler, v first then x (seed 000), fixed step dt",
    .fixed_step = true,
    .create = se_create,
    .advance = se_advance,
    .stats = se_stats,
    .free = se_free,
};
