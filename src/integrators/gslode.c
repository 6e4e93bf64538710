/* GSL odeiv2 driver plumbing shared by gsl-rk8pd and gsl-msbdf (see
 * gslode.h): the first-order RHS
 *
 *   dy/dt = (v, M^-1 f(t, x, v)),   y = (x, v),
 *
 * tolerances and options, the driver, error mapping and statistics. */
#include "integrators/gslode.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "core/check.h"
#include "integrators/hint.h"

#define CL_GSL_RTOL 1e-6
#define CL_GSL_ATOL 1e-8
#define CL_GSL_HSTART 1e-6
#define CL_GSL_MAX_STEPS 10000000L

int cl_gslode_failed(cl_gslode *s, cl_status st, double t)
{
    s->fail = st;
    s->fail_t = t;
    return st == CL_EBLOWUP ? GSL_FAILURE : GSL_EBADFUNC;
}

static int gslode_rhs(double t, const double y[], double dydt[], void *params)
{
    cl_gslode *s = params;
    size_t n = s->n;
    const cl_system *sys = s->sys;
    cl_status st = sys->force(sys->data, t, y, y + n, dydt + n);
    s->nrhs++;
    if (st != CL_OK)
        return cl_gslode_failed(s, st, t);
    memcpy(dydt, y + n, n * sizeof *dydt);
    for (size_t i = 0; i < n; i++)
        dydt[n + i] *= s->inv_mass[i];
    if (!cl_all_finite(dydt + n, n))
        return cl_gslode_failed(s, CL_EBLOWUP, t);
    return GSL_SUCCESS;
}

void cl_gslode_free(void *state)
{
    cl_gslode *s = state;
    if (!s)
        return;
    if (s->drv)
        gsl_odeiv2_driver_free(s->drv);
    free(s->y);
    free(s->inv_mass);
    free(s->f);
    free(s->ft);
    free(s->dfdx);
    free(s->dfdv);
    free(s);
}

/* The method's size limit and Jacobian requirement. */
static cl_status gslode_check_system(const cl_gslode_method *m,
                                     const cl_system *sys, cl_error *err)
{
    if (m->max_n && sys->n > m->max_n)
        return cl_error_set(err, CL_EUNSUPPORTED, "%s: %zu unknowns (%zu "
                            "free particles) exceed its limit of %zu (%s)",
                            m->name, sys->n, sys->n / 3, m->max_n,
                            m->max_n_why);
    if (m->jacobian && (!sys->jacobian || !sys->pattern))
        return cl_error_set(err, CL_EINVAL, "%s: the system has no "
                            "Jacobian", m->name);
    cl_status st = cl_integrator_refuse_projection(m->name, sys, err);
    return st ? st : cl_integrator_refuse_constraints(m->name, sys, err);
}

static cl_status gslode_check_args(const char *name, const cl_system *sys,
                                   const cl_integrator_opts *o, double t0,
                                   cl_error *err)
{
    if (!isfinite(o->rtol) || o->rtol < 0.0 || !isfinite(o->atol) ||
        o->atol < 0.0)
        return cl_error_set(err, CL_EINVAL, "%s: tolerances rtol = %g, "
                            "atol = %g must be finite and >= 0 (0: default)",
                            name, o->rtol, o->atol);
    if (!isfinite(o->dt) || o->dt < 0.0)
        return cl_error_set(err, CL_EINVAL, "%s: initial step dt = %g must "
                            "be finite and >= 0 (0: default)", name, o->dt);
    if (o->max_steps < 0)
        return cl_error_set(err, CL_EINVAL, "%s: max_steps = %ld must be "
                            ">= 0 (0: default)", name, o->max_steps);
    if (!isfinite(t0))
        return cl_error_set(err, CL_EINVAL, "%s: initial time %g", name, t0);
    if (sys->n == 0)
        return cl_error_set(err, CL_EINVAL, "%s: the system has no "
                            "unknowns (no free particles)", name);
    return cl_check_masses(sys->mass, sys->n, name, err);
}

/* The state's arrays; false when out of memory. */
static bool gslode_alloc(cl_gslode *s, bool jac)
{
    size_t n = s->n;
    s->y = malloc(2 * n * sizeof *s->y);
    s->inv_mass = malloc(n * sizeof *s->inv_mass);
    if (!s->y || !s->inv_mass)
        return false;
    if (!jac)
        return true;
    size_t nval = 9 * s->sys->pattern->nnzb;
    s->f = malloc(n * sizeof *s->f);
    s->ft = malloc(n * sizeof *s->ft);
    s->dfdx = malloc((nval ? nval : 1) * sizeof *s->dfdx);
    s->dfdv = malloc((nval ? nval : 1) * sizeof *s->dfdv);
    return s->f && s->ft && s->dfdx && s->dfdv;
}

/* The driver with y-based error control, or CL_ENOMEM / CL_ESOLVER. */
static cl_status gslode_driver(cl_gslode *s, const cl_integrator_opts *o,
                               cl_error *err)
{
    const char *name = s->method->name;
    double rtol = o->rtol > 0.0 ? o->rtol : CL_GSL_RTOL;
    double atol = o->atol > 0.0 ? o->atol : CL_GSL_ATOL;
    double h0 = o->dt > 0.0 ? o->dt : CL_GSL_HSTART;
    long nmax = o->max_steps > 0 ? o->max_steps : CL_GSL_MAX_STEPS;
    s->gsys = (gsl_odeiv2_system){.function = gslode_rhs,
                                  .jacobian = s->method->jacobian,
                                  .dimension = 2 * s->n,
                                  .params = s};
    s->drv = gsl_odeiv2_driver_alloc_y_new(&s->gsys, *s->method->type, h0,
                                           atol, rtol);
    if (!s->drv)
        return cl_error_set(err, CL_ENOMEM, "%s: "
                            "gsl_odeiv2_driver_alloc_y_new failed (out of "
                            "memory?)", name);
    int rc = gsl_odeiv2_driver_set_nmax(s->drv, (unsigned long)nmax);
    if (rc != GSL_SUCCESS)
        return cl_error_set(err, CL_ESOLVER, "%s: "
                            "gsl_odeiv2_driver_set_nmax: %s", name,
                            gsl_strerror(rc));
    return CL_OK;
}

cl_status cl_gslode_create(const cl_gslode_method *m, const cl_system *sys,
                           const cl_integrator_opts *o, double t0,
                           const double *x0, const double *v0, void **state,
                           cl_error *err)
{
    *state = NULL;
    gsl_set_error_handler_off();
    cl_status st = gslode_check_system(m, sys, err);
    if (st == CL_OK)
        st = gslode_check_args(m->name, sys, o, t0, err);
    if (st != CL_OK)
        return st;
    cl_gslode *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", m->name);
    s->method = m;
    s->sys = sys;
    s->n = sys->n;
    s->t = t0;
    if (!gslode_alloc(s, m->jacobian != NULL)) {
        cl_gslode_free(s);
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", m->name);
    }
    memcpy(s->y, x0, s->n * sizeof *s->y);
    memcpy(s->y + s->n, v0, s->n * sizeof *s->y);
    for (size_t i = 0; i < s->n; i++)
        s->inv_mass[i] = 1.0 / sys->mass[i];
    if ((st = gslode_driver(s, o, err)) != CL_OK) {
        cl_gslode_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

/* Message and status for a failed gsl_odeiv2_driver_apply (code rc). */
static cl_status gslode_error(const cl_gslode *s, int rc, double t_out,
                              cl_error *err)
{
    const char *name = s->method->name;
    if (rc == GSL_EMAXITER)
        return cl_error_set(err, CL_ESOLVER, "%s: more than %lu steps in "
                            "one advance, stopped at t = %.9g on the way to "
                            "%.9g; to change: %s", name, s->drv->nmax, s->t,
                            t_out, cl_solver_hint("GSL_EMAXITER", false));
    if (s->fail != CL_OK)
        return cl_error_set(err, s->fail, "%s: %s at t = %.9g; the "
                            "integration stopped at t = %.9g on the way to "
                            "%.9g (GSL: %s)", name,
                            s->fail == CL_EBLOWUP ? "force not finite"
                                                  : "force evaluation failed",
                            s->fail_t, s->t, t_out, gsl_strerror(rc));
    return cl_error_set(err, CL_ESOLVER, "%s: gsl_odeiv2_driver_apply "
                        "failed at t = %.9g on the way to %.9g: %s (%d); to"
                        " change: %s", name, s->t, t_out, gsl_strerror(rc),
                        rc, cl_solver_hint(NULL, false));
}

/* Tearing at an output time: the system's step_done, and a driver reset
 * when the model changed. */
static cl_status gslode_step_done(cl_gslode *s, cl_error *err)
{
    bool changed = false;
    cl_status st = s->sys->step_done(s->sys->data, s->t, s->y, s->y + s->n,
                                     &changed);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: update after t = %.9g failed (%s)",
                            s->method->name, s->t, cl_status_name(st));
    int rc = GSL_SUCCESS;
    if (changed) {
        s->failed_before += (long)s->drv->e->failed_steps;
        rc = gsl_odeiv2_driver_reset(s->drv);
    }
    if (rc != GSL_SUCCESS)
        return cl_error_set(err, CL_ESOLVER, "%s: gsl_odeiv2_driver_reset "
                            "after t = %.9g failed: %s", s->method->name,
                            s->t, gsl_strerror(rc));
    return CL_OK;
}

cl_status cl_gslode_advance(void *state, double t_out, double *x, double *v,
                            cl_error *err)
{
    cl_gslode *s = state;
    int rc = GSL_SUCCESS;
    cl_status st = cl_output_time_check(s->method->name, t_out, s->t, err);
    if (st != CL_OK)
        return st;
    s->fail = CL_OK;
    if (t_out > s->t) {
        rc = gsl_odeiv2_driver_apply(s->drv, &s->t, t_out, s->y);
        /* the driver's n misses the step that exceeded nmax */
        s->steps += (long)s->drv->n + (rc == GSL_EMAXITER);
    }
    memcpy(x, s->y, s->n * sizeof *x);
    memcpy(v, s->y + s->n, s->n * sizeof *v);
    if (rc != GSL_SUCCESS)
        return gslode_error(s, rc, t_out, err);
    if (!cl_all_finite(s->y, 2 * s->n))
        return cl_error_set(err, CL_EBLOWUP, "%s: state not finite at "
                            "t = %.9g", s->method->name, s->t);
    st = cl_integrator_contact_at(s->method->name, s->sys, s->t, s->y,
                                  s->y + s->n, err);
    if (st != CL_OK)
        return st;
    return s->sys->step_done ? gslode_step_done(s, err) : CL_OK;
}

void cl_gslode_stats(const void *state, cl_stats *out)
{
    const cl_gslode *s = state;
    memset(out, 0, sizeof *out);
    out->steps = s->steps;
    out->rhs_evals = s->nrhs;
    out->jac_evals = s->njac;
    out->err_fails = s->failed_before + (long)s->drv->e->failed_steps;
    if (s->method->jacobian) /* implicit: Newton and LU inside GSL */
        out->lin_setups = out->lin_solves = out->nonlin_iters =
            out->nonlin_fails = CL_STAT_NA;
}
