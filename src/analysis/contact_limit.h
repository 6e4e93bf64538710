/* The explicit stability limit of a model with contact beside the
 * spectrum's prediction (`clothode contact --k`, README "Using it").
 * Penalty contact adds k (eps - d) n to a particle in the band: a spring
 * of stiffness k along the normal, usually the stiffest force of the
 * model, so the limit of an explicit method falls like 1/sqrt(k) (for
 * symplectic Euler alone on a particle of mass m, h < 2 sqrt(m / k)).  The
 * measured limit is the stability search (analysis/stability.h); the
 * prediction is the integrator's region applied to the spectrum of the
 * model linearised at a given state (analysis/spectrum.h), whose Jacobian
 * includes the contact term's: linearised at a state in contact (a cloth
 * resting on a floor, the end state of a draped run) it counts the
 * contact springs, at a state out of contact (a cloth about to fall) it
 * does not. */
#ifndef CL_CONTACT_LIMIT_H
#define CL_CONTACT_LIMIT_H

#include <stdbool.h>
#include <stdio.h>

#include "analysis/stability.h"
#include "core/decls.h"

CL_BEGIN_DECLS

typedef struct {
    const char *label;    /* the integrator as named in rows */
    double k;             /* the stiffness of the variant (N/m) */
    cl_stab_result stab;  /* the search */
    double predicted;     /* the spectrum's limit (NaN: no prediction) */
    double w_max;         /* sqrt(mu_max) at the initial state (rad/s) */
} cl_climit_result;

/* The prediction (r->predicted, r->w_max) at the free state (x, v) at
 * time t for `type`; the search (r->stab) is cl_stability's from m's
 * initial state, or the sweep's (cl_stab_from_sweep). */
cl_status cl_climit_predict(cl_model *m, const cl_integrator_type *type,
                            double t, const double *x, const double *v,
                            cl_climit_result *r, cl_error *err);

/* One line of the table a study prints: integrator, k, stable dt,
 * unstable dt, predicted dt, w_max, runs. */
void cl_climit_print(FILE *fp, const cl_climit_result *r);

/* One CSV row, header first when `header`:
 * integrator,k,dt_stable,dt_unstable,predicted,w_max,runs */
void cl_climit_write_row(FILE *fp, const cl_climit_result *r, bool header);

CL_END_DECLS

#endif
