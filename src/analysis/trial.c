/* Checked runs from the initial state (see trial.h). */
#include "analysis/trial.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/diagnostics.h"
#include "core/clock.h"
#include "core/stop.h"

cl_status cl_trial_repeatable(cl_model *m, cl_error *err)
{
    if (cl_model_tears(m))
        return cl_error_set(err, CL_EUNSUPPORTED, "a model that tears ([tear] "
                            "cut) changes for good during a run, so runs "
                            "cannot be repeated from its initial state");
    return CL_OK;
}

cl_status cl_trial_whole_steps(const cl_integrator_type *type, double dt,
                               double T, cl_error *err)
{
    double steps = T / dt;
    if (cl_integrator_fixed(type, dt) &&
        !(dt > 0 && fabs(steps - round(steps)) <= 1e-9 * steps))
        return cl_error_set(err, CL_EINVAL, "t_end = %g is not a whole "
                            "number of steps dt = %g (%s takes fixed steps)",
                            T, dt, type->name);
    return CL_OK;
}

cl_status cl_trial_init(cl_trial *t, cl_model *m, cl_error *err)
{
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = cl_model_system(m)->n;
    memset(t, 0, sizeof *t);
    t->m = m;
    t->x = malloc(n * sizeof *t->x);
    t->v = malloc(n * sizeof *t->v);
    t->xf = malloc(3 * c->np * sizeof *t->xf);
    t->vf = malloc(3 * c->np * sizeof *t->vf);
    if (!t->x || !t->v || !t->xf || !t->vf)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    return cl_pairs_neighbours(c, &t->near, err);
}

void cl_trial_free(cl_trial *t)
{
    free(t->x);
    free(t->v);
    free(t->xf);
    free(t->vf);
    cl_pairs_free(&t->near);
    memset(t, 0, sizeof *t);
}

static cl_status check_stretch(cl_trial *t, double time, double max_stretch,
                               cl_error *err)
{
    cl_cloth_scatter(cl_model_cloth(t->m), time, t->x, t->v, t->xf, t->vf);
    double q = cl_max_stretch(&t->near, t->xf);
    /* a non-finite state counts as run away (fmax would skip its NaN) */
    t->stretch_seen = fmax(t->stretch_seen, isnan(q) ? INFINITY : q);
    if (!(q <= max_stretch))
        return cl_error_set(err, CL_EBLOWUP, "max stretch d/L = %.6g at "
                            "t = %g exceeds max_stretch = %g", q, time,
                            max_stretch);
    return CL_OK;
}

/* Check time k of `checks` of a run from t0 over T: a whole number of
 * steps for a fixed step. */
static double check_time(const cl_integrator_type *type, double dt,
                         double t0, double T, long k, long checks)
{
    if (!cl_integrator_fixed(type, dt))
        return k == checks ? t0 + T : t0 + T * (double)k / (double)checks;
    double steps = nearbyint(T / dt);
    return t0 + dt * nearbyint(steps * (double)k / (double)checks);
}

cl_status cl_trial_run(cl_trial *t, const cl_integrator_type *type,
                       const cl_integrator_opts *io, double T, long checks,
                       double max_stretch, cl_stats *s, cl_error *err)
{
    const cl_system *sys = cl_model_system(t->m);
    void *state = NULL;
    double t0 = cl_model_start_time(t->m);
    double c0 = cl_clock_cpu(), w0 = cl_clock_wall(), last = t0;
    cl_status rc = cl_model_initial_state(t->m, t->x, t->v);
    memset(s, 0, sizeof *s);
    t->stretch_seen = NAN; /* until a check */
    cl_model_contact_start(t->m, t0, t->contact_work);
    if (!rc && t->hook)
        rc = t->hook(t->hook_ctx, t0, t->x, t->v, err);
    if (!rc)
        rc = cl_integrator_create(type, sys, io, t0, t->x, t->v, &state,
                                  err);
    for (long k = 1; !rc && k <= checks; k++) {
        double tk = check_time(type, io->dt, t0, T, k, checks);
        if (tk <= last)
            continue;
        if (cl_stop_requested()) {
            rc = cl_stop_error(err, last, NAN);
            break;
        }
        if (!(rc = type->advance(state, tk, t->x, t->v, err)) &&
            !(rc = check_stretch(t, tk, max_stretch, err)) && t->hook)
            rc = t->hook(t->hook_ctx, tk, t->x, t->v, err);
        if (rc == CL_EINTR && cl_stop_requested())
            rc = cl_stop_error(err, last, tk);
        last = tk;
    }
    if (state) {
        type->stats(state, s);
        type->free(state);
    }
    s->cpu = cl_clock_cpu() - c0;
    s->wall = cl_clock_wall() - w0;
    return rc;
}
