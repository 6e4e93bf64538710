/* Stability limit of a fixed-step integrator (`clothode stability`,
 * README "Using it"): the largest step with which a run from the model's
 * initial state to T stays bounded.  Steps are dt = T / N for whole N, so
 * that every run ends exactly at T.
 *
 * A run is unstable when it blows up (CL_EBLOWUP: a non-finite state, or a
 * stretch d/L beyond max_stretch at one of `checks` evenly spread times,
 * analysis/trial.h), its solver gives up (CL_ESOLVER: e.g. KINSOL's
 * Newton iteration does not converge at that step) or it reaches a state
 * with a particle inside a barrier obstacle (CL_EINFEASIBLE, an explicit
 * method's end there; docs/model.md 4.6).  Any other failure
 * (bad options, no memory) ends the search with that error.
 *
 * Search: N_0 = ceil(T / dt_max).  If the runs at N_0 and 2 N_0 are
 * stable, the limit is at least dt_max.  Otherwise N doubles until a run
 * is stable and so is the run at twice its N (giving up below dt_min; a
 * stable step above an unstable one, such as symplectic Euler's h c = 1
 * on a damped spring started from rest length, whose first step lands on
 * the equilibrium, is not taken), then bisection on N between the largest
 * unstable and the smallest stable N until N_s - N_u <= max(1, rel N_u).
 * Stability
 * need not be monotone in dt (a method may survive a larger step and fail
 * a smaller one), so the result is the bracket the search found: dt_stable
 * = T / N_s and dt_unstable = T / N_u, with the reason the run at
 * dt_unstable failed; a stable island narrower than a factor 2 can
 * still be taken, and so, unconfirmed, is a stable run whose double
 * passes T / dt_min.  Every run is kept, with the largest stretch its
 * checks saw.
 *
 * Bounded to T is the test, so the limit depends on T: just above a
 * linear limit an instability grows slowly and may not reach max_stretch
 * by T (the stable end's stretch shows how far it got).  The limit found is
 * an upper bound of the step a longer run would keep. */
#ifndef CL_STABILITY_H
#define CL_STABILITY_H

#include <stdbool.h>
#include <stdio.h>

#include "analysis/trial.h"
#include "core/decls.h"
#include "integrators/integrator.h"
#include "system/model.h"

CL_BEGIN_DECLS

#define CL_STAB_MAX_TRIALS 128

typedef struct {
    double t_end;
    double dt_max, dt_min; /* search range, 0 < dt_min < dt_max <= t_end/10
                            * (at least 10 steps per run) */
    double rel;            /* bracket width, (0, 1) */
    long checks;           /* stretch tests per run, >= 1 */
    double max_stretch;
} cl_stab_opts;

typedef struct {
    double dt;
    long nsteps;
    cl_status rc;          /* CL_OK (stable), CL_EBLOWUP or CL_ESOLVER */
    cl_error why;
    cl_stats stats;
    double stretch;        /* the largest d/L at the run's checks (NaN:
                            * not known, a run of a sweep) */
} cl_stab_trial;

typedef struct {
    const cl_integrator_type *type;
    int ntrial;
    cl_stab_trial trial[CL_STAB_MAX_TRIALS];
    double dt_stable;      /* NAN: no stable step down to dt_min */
    double dt_unstable;    /* NAN: stable at dt_max */
    int failed;            /* index of the trial at dt_unstable, or -1 */
    int held;              /* index of the trial at dt_stable, or -1 */
    const char *label;     /* how rows name the method (type->name) */
} cl_stab_result;

/* Whether the search can be run: CL_EINVAL for an adaptive integrator or
 * options out of range; CL_EUNSUPPORTED for a model that tears (its runs
 * cannot be repeated). */
cl_status cl_stab_check(cl_model *m, const cl_integrator_type *type,
                        const cl_stab_opts *o, cl_error *err);

/* The search; cl_stab_check's refusals are returned, unstable runs are
 * recorded in r. */
cl_status cl_stability(cl_model *m, const cl_integrator_type *type,
                       const cl_integrator_opts *io, const cl_stab_opts *o,
                       cl_stab_result *r, cl_error *err);

/* One run of the search: `type` with nsteps steps (dt = t_end / nsteps) on
 * the trial t, recorded in *tr.  Returns 1 when the run is stable, 0 when
 * it is unstable (the definition above), or -1 with err set for any other
 * failure.  Other studies that ask whether a
 * run stays stable (`clothode contact`) use it, so that they mean what
 * `stability` means. */
int cl_stab_try(cl_trial *t, const cl_integrator_type *type,
                const cl_integrator_opts *io, const cl_stab_opts *o,
                long nsteps, cl_stab_trial *tr, cl_error *err);

/* One CSV row per run, header first when `header`:
 * integrator,dt,steps,stable,status,cpu,stretch,reason */
void cl_stab_write_rows(FILE *fp, const cl_stab_result *r, bool header);

CL_END_DECLS

#endif
