/* A checked run, the unit of the convergence and stability studies: a fresh
 * integrator from the model's initial state, at its start time t0
 * (cl_model_start_time), over a span T to t0 + T, stopping at `checks`
 * evenly spread times (whole steps for fixed-step methods) where the
 * largest stretch d/L of the nearest neighbours (cl_pairs_neighbours:
 * Type1's pairs on a grid, the triangle edges on a mesh cloth) is tested
 * against max_stretch.  A stretch beyond it is a blow-up (CL_EBLOWUP), the test
 * `run` applies at its samples; so is a non-finite state, which the
 * integrators report themselves. */
#ifndef CL_TRIAL_H
#define CL_TRIAL_H

#include "core/decls.h"
#include "integrators/integrator.h"
#include "system/model.h"
#include "model/pairs.h"

CL_BEGIN_DECLS

/* Called at t0 and after every passed check with the free state. */
typedef cl_status (*cl_trial_hook)(void *ctx, double t, const double *x,
                                   const double *v, cl_error *err);

typedef struct {
    cl_model *m;
    cl_pairset near;      /* nearest neighbours */
    double *x, *v;        /* free state at the end of the last run */
    double *xf, *vf;      /* full-particle scratch */
    cl_trial_hook hook;   /* optional (NULL), with its context */
    void *hook_ctx;
    bool contact_work;    /* account the contact projections' energy
                           * (cl_model_contact_start) */
    double stretch_seen;  /* the largest stretch d/L at the checks of the
                           * last run: INFINITY after a non-finite state,
                           * NaN before the first check */
} cl_trial;

/* Whether runs of m can be repeated from its initial state:
 * CL_EUNSUPPORTED for a model that tears (a tear changes it for good). */
cl_status cl_trial_repeatable(cl_model *m, cl_error *err);

/* Whether a run of `type` with step dt can span exactly T: CL_EINVAL if it
 * takes fixed steps and T is not a whole number of them (to 1e-9). */
cl_status cl_trial_whole_steps(const cl_integrator_type *type, double dt,
                               double T, cl_error *err);

cl_status cl_trial_init(cl_trial *t, cl_model *m, cl_error *err);
void cl_trial_free(cl_trial *t);

/* Run `type` with options io from t0 to t0 + T; statistics (with CPU and
 * wall time)
 * into *s.  The final state is in t->x, t->v (up to the failure after
 * one). */
cl_status cl_trial_run(cl_trial *t, const cl_integrator_type *type,
                       const cl_integrator_opts *io, double T, long checks,
                       double max_stretch, cl_stats *s, cl_error *err);

CL_END_DECLS

#endif
