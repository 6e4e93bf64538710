/* Shared plumbing of the GSL odeiv2 reference integrators
 * (docs/integrators.md, 6): gsl-rk8pd and gsl-msbdf.
 *
 * Both integrate the first-order form
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * with gsl_odeiv2_driver_alloc_y_new (error control on y: every component
 * of the local error estimate must stay below atol + rtol |y_i|) and
 * gsl_odeiv2_driver_apply, which steps adaptively and stops exactly at
 * t_out (no interpolation).  A method supplies a cl_gslode_method
 * (CL_GSLODE_INTEGRATOR below defines it with the integrator table): its
 * name, the GSL step type, for implicit steppers the Jacobian function of
 * the gsl_odeiv2_system (the block Jacobians are then allocated here, and
 * a system without a Jacobian is refused), and an optional size limit
 * (larger systems: CL_EUNSUPPORTED).
 *
 * Options: opts->rtol, opts->atol (>= 0, finite; 0 selects the defaults
 * rtol 1e-6, atol 1e-8, as cvode-bdf), opts->dt the initial step (0: 1e-6),
 * opts->max_steps the driver's nmax per advance (0: 10^7; GSL fails once
 * an advance needs more than nmax + 1 steps).
 *
 * Failures: GSL's abort-on-error handler is switched off
 * (gsl_set_error_handler_off) and every return is checked.  A force that
 * is not finite or returns CL_EBLOWUP makes the RHS return GSL_FAILURE,
 * which GSL treats as recoverable (the step is halved and retried); when
 * the step can shrink no further, advance reports CL_EBLOWUP with the time
 * of the failing call and the time reached.  Any other system status makes
 * the RHS return GSL_EBADFUNC (GSL stops at once) and is passed on.  Too
 * many steps: CL_ESOLVER.
 *
 * Statistics: steps = accepted steps (the driver's per-call counts,
 * summed), rhs_evals = force evaluations through the RHS wrapper and the
 * Jacobian's time difference, jac_evals = Jacobian wrapper calls,
 * err_fails = GSL's evolve->failed_steps (steps rejected by the error test
 * plus step halvings after a failed stepper call).  GSL does not expose
 * msbdf's Newton iterations, Newton failures or LU factorisations and
 * solves: for a method with a Jacobian those four are CL_STAT_NA ("n/a"),
 * not 0.  The other counters are 0: neither method has them.
 *
 * Tearing (docs/model.md, 3.4): the system's step_done hook is called at
 * the end of every advance, i.e. at output times only (use many samples);
 * when the model changed, gsl_odeiv2_driver_reset drops the stepper's
 * history (msbdf) and the solver continues from the current state. */
#ifndef CL_GSLODE_H
#define CL_GSLODE_H

#include <gsl/gsl_odeiv2.h>

#include "core/decls.h"
#include "integrators/define.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

typedef struct {
    const char *name;                 /* registry name, for messages */
    /* the GSL step type, e.g. &gsl_odeiv2_step_rk8pd */
    const gsl_odeiv2_step_type *const *type;
    /* gsl_odeiv2_system's Jacobian (params: the cl_gslode), or NULL */
    int (*jacobian)(double t, const double y[], double *dfdy, double dfdt[],
                    void *params);
    size_t max_n;          /* largest sys->n accepted (0: no limit) ... */
    const char *max_n_why; /* ... and why, for the CL_EUNSUPPORTED message */
} cl_gslode_method;

typedef struct {
    const cl_gslode_method *method;
    const cl_system *sys;
    size_t n;               /* sys->n; the GSL system has 2n unknowns */
    gsl_odeiv2_system gsys;
    gsl_odeiv2_driver *drv;
    double t;               /* time of y */
    double *y;              /* 2n: (x, v) */
    double *inv_mass;       /* n */
    double *f, *ft;         /* n each: forces at t and t + dt (Jacobian) */
    double *dfdx, *dfdv;    /* 9 nnzb each (only with a Jacobian) */
    long steps, nrhs, njac;
    long failed_before;     /* failed steps before driver resets (tearing) */
    cl_status fail;         /* last failing system status in this advance */
    double fail_t;          /* and the time of that call */
} cl_gslode;

cl_status cl_gslode_create(const cl_gslode_method *m, const cl_system *sys,
                           const cl_integrator_opts *o, double t0,
                           const double *x0, const double *v0, void **state,
                           cl_error *err);
cl_status cl_gslode_advance(void *state, double t_out, double *x, double *v,
                            cl_error *err);
void cl_gslode_stats(const void *state, cl_stats *out);
void cl_gslode_free(void *state);

/* Record a failing system call (status st at time t) and return the GSL
 * code for it: GSL_FAILURE (recoverable) for CL_EBLOWUP, else
 * GSL_EBADFUNC. */
int cl_gslode_failed(cl_gslode *s, cl_status st, double t);

/* Define the GSL method (registry name name_, stability region region_,
 * step type type_ such as &gsl_odeiv2_step_rk8pd, Jacobian function jac_
 * or NULL, size limit max_n_ (0: none) and its reason why_) and its
 * integrator table `ident`, with its create function. */
#define CL_GSLODE_INTEGRATOR(ident, name_, region_, doc_, type_, jac_,      \
                             max_n_, why_)                                  \
    static const cl_gslode_method ident##_method = {                        \
        .name = (name_),                                                    \
        .type = (type_),                                                    \
        .jacobian = (jac_),                                                 \
        .max_n = (max_n_),                                                  \
        .max_n_why = (why_),                                                \
    };                                                                      \
    CL_INTEGRATOR_DEFINE(ident, ident##_method, cl_gslode_create, name_,    \
                         region_, doc_, false, false, (jac_) != NULL, false,\
                         false, cl_gslode_advance,                          \
                         cl_gslode_stats, cl_gslode_free)

CL_END_DECLS

#endif
