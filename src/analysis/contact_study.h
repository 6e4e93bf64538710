/* Contact at a list of steps (`clothode contact`, README "Using it"): one
 * fixed-step integrator on one model (its obstacles with the response
 * under study) run from the initial state to T at every step dt of a
 * list, each run a trial of the stability search (analysis/stability.h,
 * cl_stab_try), so that "stable" means what `clothode stability` means: no
 * non-finite state, no stretch d/L beyond max_stretch at any of `checks`
 * evenly spread times, no solver that gives up.  Every run records
 *  - the worst penetration max(0, -d) of a free particle into an obstacle,
 *    and when: the contact hook looks after every accepted step, before
 *    any projection moves the particle back (cl_model_contact_worst);
 *  - the penetration at rest: the deepest at T, in the end state (after
 *    the last projection), and the number of particles in contact there
 *    (cl_model_contact_figures); NaN and -1 when the run did not reach T;
 *  - the largest stretch d/L seen at the checks (cl_trial.stretch_seen);
 *  - the integrator's statistics (Newton iterations, CPU time).
 * The dt must each divide T into whole steps (cl_trial_whole_steps). */
#ifndef CL_CONTACT_STUDY_H
#define CL_CONTACT_STUDY_H

#include <stdbool.h>
#include <stdio.h>

#include "analysis/stability.h"
#include "core/decls.h"

CL_BEGIN_DECLS

#define CL_CSTUDY_MAX_DT 64

typedef struct {
    cl_stab_trial run;     /* dt, steps, status, reason, statistics */
    double worst_pen;      /* m */
    double worst_t;        /* s */
    double rest_pen;       /* m, NaN: T not reached */
    long rest_contacts;    /* -1: T not reached */
    double stretch_max;
} cl_cstudy_row;

typedef struct {
    const char *label;     /* the integrator as named in rows */
    const char *response;  /* the response studied ("problem": the file's) */
    int n;
    cl_cstudy_row row[CL_CSTUDY_MAX_DT];
    /* the smallest dt of the list whose run is unstable (NaN: none), and
     * the largest stable dt below it, or of all when none is unstable
     * (NaN: none) */
    double dt_unstable, dt_stable;
} cl_cstudy_result;

/* Whether the runs can be made: CL_EINVAL for an adaptive integrator, a
 * model without obstacles, no dt or more than CL_CSTUDY_MAX_DT, a dt that
 * does not divide T, checks < 1; CL_EUNSUPPORTED for a model that tears. */
cl_status cl_cstudy_check(cl_model *m, const cl_integrator_type *type,
                          const cl_stab_opts *o, const double *dt, int ndt,
                          cl_error *err);

/* The runs at dt[0..ndt-1] (o: t_end, checks, max_stretch; its dt range
 * and rel are not used).  Unstable runs are rows; any other failure is
 * returned. */
cl_status cl_cstudy_run(cl_model *m, const cl_integrator_type *type,
                        const cl_integrator_opts *io, const cl_stab_opts *o,
                        const double *dt, int ndt, cl_cstudy_result *r,
                        cl_error *err);

/* r->dt_unstable and r->dt_stable from its rows. */
void cl_cstudy_bracket(cl_cstudy_result *r);

/* One CSV row per run, header first when `header`:
 * integrator,response,dt,steps,stable,status,worst_penetration,worst_t,
 * rest_penetration,rest_contacts,max_stretch,newton_iters,cpu,reason */
void cl_cstudy_write_rows(FILE *fp, const cl_cstudy_result *r, bool header);

CL_END_DECLS

#endif
