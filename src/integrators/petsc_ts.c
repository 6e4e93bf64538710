/* The petsc-ts family's library side (integrators/petsc_ts.h): option
 * checks, the callbacks the plug-in calls (the system's force and
 * Jacobian, with the blow-up policy of the SUNDIALS integrators: a force
 * that is not finite or a state inside a barrier obstacle is a step PETSc
 * retries smaller, any other failure ends the run), contact figures and
 * tearing at output times. */
#include "integrators/petsc_ts.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "integrators/petsc_ts_abi.h"
#include "linalg/petscenv.h"

#define CL_PTS_RTOL 1e-6
#define CL_PTS_ATOL 1e-8
#define CL_PTS_H0 1e-5
#define CL_PTS_MAX_ORDER 6 /* TSBDF's orders 1..6 */

typedef struct {
    const cl_petsc_ts_method *m;
    const cl_system *sys;
    void *ts;             /* the plug-in's integrator */
    clp_ts_advance_fn advance;
    clp_ts_restart_fn restart;
    clp_ts_stats_fn stats;
    clp_ts_free_fn free;
    cl_error fail;        /* why a callback failed (fail.code != CL_OK) */
    double fail_t;
    double t;
    double t0;
    double dt;            /* > 0: fixed steps of dt (TSAdapt none) */
    long done;            /* fixed steps taken */
} cl_pts;

/* ---- callbacks ------------------------------------------------------------ */

/* Record a failed system call: 1 for a state a smaller step may avoid, -1
 * for a failure that ends the run. */
static int pts_failed(cl_pts *s, cl_status st, double t, const char *what)
{
    s->fail_t = t;
    cl_error_set(&s->fail, st, "%s: %s at t = %.9g (%s)", s->m->name, what,
                 t, cl_status_name(st));
    return st == CL_EBLOWUP || st == CL_EINFEASIBLE ? 1 : -1;
}

static int pts_force(void *ctx, double t, const double *x, const double *v,
                     double *f)
{
    cl_pts *s = ctx;
    const cl_system *sys = s->sys;
    cl_status st = sys->force(sys->data, t, x, v, f);
    if (st == CL_OK && !cl_all_finite(f, sys->n))
        st = CL_EBLOWUP;
    return st == CL_OK ? 0 : pts_failed(s, st, t, "force not finite or "
                                                  "failed");
}

static int pts_jacobian(void *ctx, double t, const double *x,
                        const double *v, double *dfdx, double *dfdv)
{
    cl_pts *s = ctx;
    const cl_system *sys = s->sys;
    size_t nval = 9 * sys->pattern->nnzb;
    cl_status st = sys->jacobian(sys->data, t, x, v, NULL, dfdx, dfdv);
    if (st == CL_OK &&
        (!cl_all_finite(dfdx, nval) || !cl_all_finite(dfdv, nval)))
        st = CL_EBLOWUP;
    return st == CL_OK ? 0 : pts_failed(s, st, t, "Jacobian not finite or "
                                                  "failed");
}

/* ---- set-up --------------------------------------------------------------- */

static cl_status pts_check(const cl_petsc_ts_method *m, const cl_system *sys,
                           const cl_integrator_opts *o, double t0,
                           cl_error *err)
{
    if (!sys->jacobian || !sys->pattern)
        return cl_error_set(err, CL_EINVAL, "%s: the system has no Jacobian",
                            m->name);
    if (sys->n == 0)
        return cl_error_set(err, CL_EINVAL, "%s: the system has no unknowns "
                            "(no free particles)", m->name);
    if (!(o->rtol >= 0.0) || !isfinite(o->rtol) || !(o->atol >= 0.0) ||
        !isfinite(o->atol))
        return cl_error_set(err, CL_EINVAL, "%s: tolerances rtol = %g, atol "
                            "= %g must be finite and >= 0 (0: default)",
                            m->name, o->rtol, o->atol);
    if (!(o->dt >= 0.0) || !isfinite(o->dt) || !isfinite(t0))
        return cl_error_set(err, CL_EINVAL, "%s: dt = %g must be finite and "
                            ">= 0 (0: adaptive steps), t0 = %g finite",
                            m->name, o->dt, t0);
    if (o->max_order < 0 || o->max_order > CL_PTS_MAX_ORDER ||
        (o->max_order && !m->takes_order))
        return cl_error_set(err, CL_EINVAL, "%s: order %d: %s", m->name,
                            o->max_order, m->takes_order
                                              ? "TSBDF takes orders 1 .. 6 "
                                                "(0: PETSc's own, 2)"
                                              : "the method has no choice "
                                                "of order");
    cl_status st = cl_check_masses(sys->mass, sys->n, m->name, err);
    if (st == CL_OK)
        st = cl_integrator_refuse_projection(m->name, sys, err);
    return st ? st : cl_integrator_refuse_constraints(m->name, sys, err);
}

/* The plug-in's entry points. */
static cl_status pts_symbols(cl_pts *s, clp_ts_create_fn *create,
                             cl_error *err)
{
    void *sym[5];
    static const char *const names[5] = {"clp_ts_create", "clp_ts_advance",
                                         "clp_ts_restart", "clp_ts_stats",
                                         "clp_ts_free"};
    cl_status st = cl_petsc_start(err);
    for (int k = 0; st == CL_OK && k < 5; k++)
        st = cl_plugin_symbol("petsc", names[k], &sym[k], err);
    if (st != CL_OK)
        return st;
    *create = (clp_ts_create_fn)sym[0];
    s->advance = (clp_ts_advance_fn)sym[1];
    s->restart = (clp_ts_restart_fn)sym[2];
    s->stats = (clp_ts_stats_fn)sym[3];
    s->free = (clp_ts_free_fn)sym[4];
    return CL_OK;
}

static clp_ts_setup pts_setup(cl_pts *s, const cl_integrator_opts *o,
                              double t0, const double *x0, const double *v0)
{
    const cl_system *sys = s->sys;
    const cl_bpattern *pat = sys->pattern;
    return (clp_ts_setup){
        .name = s->m->name,
        .ts_type = s->m->ts_type,
        .second_order = s->m->second_order,
        .order = o->max_order,
        .n = sys->n,
        .mass = sys->mass,
        .nb = pat->nb,
        .nnzb = pat->nnzb,
        .rowptr = pat->rowptr,
        .col = pat->col,
        .diag = pat->diag,
        .t0 = t0,
        .x0 = x0,
        .v0 = v0,
        .dt = o->dt > 0.0 ? o->dt : CL_PTS_H0,
        .fixed = o->dt > 0.0,
        .rtol = o->rtol > 0.0 ? o->rtol : CL_PTS_RTOL,
        .atol = o->atol > 0.0 ? o->atol : CL_PTS_ATOL,
        .max_steps = o->max_steps,
        .options = o->petsc,
        .ctx = s,
        .force = pts_force,
        .jacobian = pts_jacobian,
    };
}

cl_status cl_petsc_ts_create(const cl_petsc_ts_method *m,
                             const cl_system *sys,
                             const cl_integrator_opts *o, double t0,
                             const double *x0, const double *v0,
                             void **state, cl_error *err)
{
    *state = NULL;
    cl_status st = pts_check(m, sys, o, t0, err);
    if (st != CL_OK)
        return st;
    cl_pts *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", m->name);
    s->m = m;
    s->sys = sys;
    s->t = t0;
    s->t0 = t0;
    s->dt = o->dt;
    clp_ts_create_fn create = NULL;
    if ((st = pts_symbols(s, &create, err)) != CL_OK) {
        free(s);
        return st;
    }
    clp_ts_setup setup = pts_setup(s, o, t0, x0, v0);
    cl_plugin_msg msg = {.text = ""};
    if (create(&setup, &s->ts, &msg) != 0) {
        free(s);
        return cl_error_set(err, CL_EINVAL, "%s", msg.text);
    }
    *state = s;
    return CL_OK;
}

/* ---- stepping ------------------------------------------------------------- */

/* Tearing at an output time: the system's step_done, and a restart of
 * the method's history when the force law changed. */
static cl_status pts_step_done(cl_pts *s, const double *x, const double *v,
                               cl_error *err)
{
    bool changed = false;
    cl_status st = s->sys->step_done(s->sys->data, s->t, x, v, &changed);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: update after t = %.9g failed (%s)",
                            s->m->name, s->t, cl_status_name(st));
    cl_plugin_msg msg = {.text = ""};
    if (changed && s->restart(s->ts, &msg) != 0)
        return cl_error_set(err, CL_ESOLVER, "%s", msg.text);
    return CL_OK;
}

/* One advance of the plug-in's TS to t_out (nsteps fixed steps of dt, 0
 * when adaptive), and the system's hooks there. */
static cl_status pts_advance(cl_pts *s, double t_out, long nsteps, double *x,
                             double *v, cl_error *err)
{
    cl_plugin_msg msg = {.text = ""};
    cl_error_clear(&s->fail);
    int bad = s->advance(s->ts, t_out, x, v, &msg);
    if (bad && s->fail.code != CL_OK)
        return cl_error_set(err, s->fail.code, "%s; %s", s->fail.msg,
                            msg.text);
    if (bad)
        return cl_error_set(err, bad == CLP_TS_BAD_OPTION ? CL_EINVAL
                                                          : CL_ESOLVER,
                            "%s", msg.text);
    s->t = t_out;
    s->done += nsteps;
    if (!cl_all_finite(x, s->sys->n) || !cl_all_finite(v, s->sys->n))
        return cl_error_set(err, CL_EBLOWUP, "%s: state not finite at t = "
                            "%.9g", s->m->name, s->t);
    cl_status st = cl_integrator_contact_at(s->m->name, s->sys, s->t, x, v,
                                            err);
    if (st != CL_OK)
        return st;
    return s->sys->step_done ? pts_step_done(s, x, v, err) : CL_OK;
}

/* With a dt, the system's hooks (contact figures, step_done: tearing)
 * follow every step, as for every fixed-step method (system/system.h):
 * the steps are then advanced one at a time, and the state is the same
 * whatever the output times. */
cl_status cl_petsc_ts_advance(void *state, double t_out, double *x,
                              double *v, cl_error *err)
{
    cl_pts *s = state;
    cl_status st = cl_output_time_check(s->m->name, t_out, s->t, err);
    if (st != CL_OK)
        return st;
    long nsteps = 0;
    if (s->dt > 0.0) {
        st = cl_fixed_steps_to(t_out - s->t0, s->dt, s->done, &nsteps,
                               err);
        if (st != CL_OK)
            return st;
    }
    if (nsteps <= 1 || !(s->sys->step_done || s->sys->contact))
        return pts_advance(s, t_out, nsteps, x, v, err);
    for (long k = 0; st == CL_OK && k < nsteps; k++)
        st = pts_advance(s, s->t0 + (double)(s->done + 1) * s->dt, 1, x, v,
                         err);
    return st;
}

void cl_petsc_ts_stats(const void *state, cl_stats *out)
{
    const cl_pts *s = state;
    s->stats(s->ts, out);
}

void cl_petsc_ts_free(void *state)
{
    cl_pts *s = state;
    if (!s)
        return;
    if (s->ts)
        s->free(s->ts);
    free(s);
}
