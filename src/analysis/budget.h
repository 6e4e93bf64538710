/* Equal-budget study (`clothode budget`, docs/integrators.md, 9): one
 * budget of B constraint or Newton iterations per step of dt, spent as S
 * substeps of K = B / S iterations, for every divisor S of B; the question
 * of Macklin et al., "Small steps in physics simulation" (SCA 2019):
 * iterations or substeps at equal cost?
 *
 *   constraint methods (xpbd, pd; takes_iterations): step dt, substeps S,
 *     iterations K;
 *   methods with a Newton iteration (takes_newton_maxit: kinsol-*,
 *     arkode-*): step dt / S with at most K Newton iterations per step
 *     (newton_maxit; kinsol-be, kinsol-bdf2: K = 1 is one linearisation
 *     per step, semi-be's method);
 *   the other fixed-step methods (semi-*, explicit ones) make one linear
 *     solve or force evaluation per step whatever K: steps dt / S with
 *     K = 1, so that only S = B spends the budget (the smaller S are
 *     cheaper points of their error against cost).
 * h is dt / S for all: the step, or the constraint methods' substep.
 *
 * Every run goes from the model's initial state to T and is measured by
 *   err_x    max over free particles of |x - x_ref| at T (m), against the
 *            cvode-bdf reference of the convergence study
 *            (analysis/convergence.h), NAN without a reference (a model
 *            of hard constraints, which no force-based method integrates);
 *   stretch  the largest stretch d/L - 1 of the nearest neighbours at 100
 *            evenly spread checks (cl_trial), the constraint violation;
 *   energy   E(T) - E(0), the total energy change (J): numerical
 *            dissipation on a conservative model, to compare with the
 *            reference's on a damped one;
 * beside its CPU time and counters. */
#ifndef CL_BUDGET_H
#define CL_BUDGET_H

#include <stdbool.h>
#include <stdio.h>

#include "analysis/convergence.h"
#include "core/decls.h"

CL_BEGIN_DECLS

#define CL_BUDGET_MAX_SPLITS 32
#define CL_BUDGET_CHECKS 100

typedef struct {
    double t_end;
    double max_stretch;  /* a stretch d/L beyond it is a blow-up */
    long budget;         /* B, 1 .. 1000 */
} cl_budget_opts;

typedef struct {
    long S, K;           /* substeps (or steps per dt) and iterations */
    double h;            /* the integrator's step */
    cl_status rc;        /* CL_OK, or how the run failed ... */
    cl_error why;        /* ... and why */
    double err_x;        /* NAN without a reference or after a failure */
    double stretch;      /* max d/L - 1 at the checks */
    double energy;       /* E(T) - E(0) (J) */
    cl_stats stats;
} cl_budget_split;

typedef struct {
    const cl_integrator_type *type;
    const char *label;
    double dt;
    int n;
    cl_budget_split s[CL_BUDGET_MAX_SPLITS];
} cl_budget_result;

/* Whether a step of `type` spends K iterations: constraint or Newton
 * iterations (takes_iterations, takes_newton_maxit).  The others make one
 * linear solve or force evaluation a step, K = 1 at every split. */
bool cl_budget_takes_k(const cl_integrator_type *type);

/* Whether the splits of `type` can be run: CL_EINVAL for an adaptive
 * method, B outside 1 .. 1000, or T not a whole number of steps dt / S. */
cl_status cl_budget_check(const cl_integrator_type *type,
                          const cl_integrator_opts *io,
                          const cl_budget_opts *o, cl_error *err);

/* The splits of `type` (io: its options, io->dt the step of the budget)
 * against ref (NULL: none).  Failures of single splits are recorded in r,
 * not returned. */
cl_status cl_budget(cl_model *m, const cl_integrator_type *type,
                    const cl_integrator_opts *io, const cl_budget_opts *o,
                    const cl_conv_ref *ref, cl_budget_result *r,
                    cl_error *err);

/* E(T) - E(0) of the reference (its state at T), to compare the splits'
 * energy change with on a damped model; NAN if it cannot be evaluated. */
double cl_budget_reference_energy(cl_model *m, const cl_conv_ref *ref,
                                  double T);

/* One CSV row per split, header first when `header`:
 * integrator,dt,substeps,iterations,h,err_x,stretch,energy,steps,
 * rhs_evals,nonlin_iters,lin_solves,cpu,status. */
void cl_budget_write_rows(FILE *fp, const cl_budget_result *r, bool header);

CL_END_DECLS

#endif
