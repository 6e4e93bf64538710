/* Convergence study (`clothode convergence`, README "Using it"): one
 * integrator run at a sequence of levels from the model's initial state to T,
 *   fixed-step methods at dt_k = dt_0 / 2^k,
 *   adaptive methods at rtol_k = rtol_0 / 10^k (atol_k = atol_0 / 10^k),
 * k = 0 .. levels-1, each final state measured against a reference:
 * cvode-bdf at rtol_ref, atol_ref = rtol_ref / 100 (default rtol_ref 1e-11).
 *
 * Errors: e_x = max over free particles of |x - x_ref| (m), e_v likewise for
 * the velocities (m/s).  The reference's floors are the distances, in
 * positions and in velocities, to a second reference run at 10 rtol_ref
 * (about 10x the reference's own error when the error follows the
 * tolerance, 5.5x measured on spring2): a level whose e_x is below
 * CL_CONV_FLOOR_MARGIN times the position floor is too close to the
 * reference's error (at 1.4 floors, rk4's e_x on spring2 is 12 % off the
 * closed form's, its order from the level before 4.19 instead of 4.02,
 * and the fit over three levels 4.11 instead of 4.03) and enters neither
 * fit; one whose e_v alone is below that margin over the velocity floor
 * enters the position fit only (a reference's velocities can be less
 * accurate than its positions).  A level that
 * failed (blow-up, solver failure, or a final state stretched beyond
 * max_stretch, the blow-up test of `run`) has no error and enters no fit.  A model
 * that tears changes for good during a run and is refused.
 *
 * Orders: between levels k-1 and k, p_k = log(e_{k-1} / e_k) / log(q),
 * q = 2 for dt, 10 for rtol; over all fitted levels, the least-squares
 * slope of log e against log dt (or log rtol; gsl_fit_linear).  For a
 * fixed-step method the slope is its observed order; for an adaptive one
 * it is its tolerance proportionality (1 when the global error follows the
 * tolerance).  Problems that forget their initial state (hang at n = 10
 * beyond 0.25 s) show it as slopes far below 1 with errors well above
 * rtol. */
#ifndef CL_CONVERGENCE_H
#define CL_CONVERGENCE_H

#include <stdbool.h>
#include <stdio.h>

#include "core/decls.h"
#include "integrators/integrator.h"
#include "system/model.h"

CL_BEGIN_DECLS

#define CL_CONV_MAX_LEVELS 20
/* A level enters a fit with an error more than this many floors: the
 * reference's error then a few % of it at most. */
#define CL_CONV_FLOOR_MARGIN 3.0

typedef struct {
    double t_end;
    double max_stretch;   /* a final max d/L beyond it is a blow-up */
    double ref_rtol;      /* reference tolerance, 1e-15 .. 1e-4 */
    const char *ref_linsol; /* reference's linear solver ("" default) */
} cl_conv_opts;

/* The reference solution at t_end and an estimate of its error. */
typedef struct {
    size_t n;             /* sys->n */
    double *x, *v;        /* free state at t_end */
    double err_x, err_v;  /* floors: distances to the run at 10 rtol_ref */
    cl_stats stats;       /* of the rtol_ref run */
} cl_conv_ref;

typedef struct {
    double param;         /* dt or rtol of this level */
    cl_status rc;         /* CL_OK, or how the run failed ... */
    cl_error why;         /* ... and why */
    double err_x, err_v;  /* NAN after a failure */
    double order;         /* p_k against the previous level (NAN if none) */
    bool fitted;          /* in the position fit */
    bool fitted_v;        /* in the velocity fit */
    cl_stats stats;
} cl_conv_level;

typedef struct {
    const cl_integrator_type *type;
    bool fixed;           /* param is dt (else rtol) */
    int nlev;
    cl_conv_level lev[CL_CONV_MAX_LEVELS];
    int nfit, nfit_v;     /* levels in the position and velocity fits */
    double slope_x, slope_v; /* fitted orders (NAN if nfit, nfit_v < 2) */
    const char *label;    /* how rows name the method (type->name) */
} cl_conv_result;

/* Run the reference (allocates ref->x, ref->v; free with
 * cl_conv_ref_free). */
cl_status cl_conv_reference(cl_model *m, const cl_conv_opts *o,
                            cl_conv_ref *ref, cl_error *err);
void cl_conv_ref_free(cl_conv_ref *ref);

/* Whether the levels of `type` can be run: CL_EINVAL for levels outside
 * 2 .. CL_CONV_MAX_LEVELS, an rtol that would go below 1e-15, or a T that
 * is not a multiple of a fixed step. */
cl_status cl_conv_check(const cl_integrator_type *type,
                        const cl_integrator_opts *io, int levels,
                        const cl_conv_opts *o, cl_error *err);

/* The levels of `type` (io: its options, dt or rtol/atol of level 0).
 * cl_conv_check's refusals are returned; failures of single levels are
 * recorded in r, not returned. */
cl_status cl_convergence(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, int levels,
                         const cl_conv_opts *o, const cl_conv_ref *ref,
                         cl_conv_result *r, cl_error *err);

/* The orders between consecutive levels (over the ratio of their
 * parameters) and the least-squares fit over the fitted levels, from
 * r->lev[0 .. nlev) with param, rc, err_x, err_v, fitted and fitted_v
 * set. */
void cl_conv_fit(cl_conv_result *r);

/* Work-precision: the least CPU time of the levels that ran and reached
 * e_x <= target (NAN if none did). */
double cl_conv_cheapest(const cl_conv_result *r, double target);

/* One CSV row per level, header first when `header`:
 * integrator,param,value,err_x,err_v,order,fitted,fitted_v,steps,
 * rhs_evals,cpu,fit_x,fit_v,status (fit_x, fit_v: the method's fitted
 * orders, repeated on each of its rows). */
void cl_conv_write_rows(FILE *fp, const cl_conv_result *r, bool header);

CL_END_DECLS

#endif
