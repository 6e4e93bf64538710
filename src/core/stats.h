/* The counters every integrator reports (integrators/integrator.h), to
 * which the linear solvers (linalg/linsol.h) add their own. */
#ifndef CL_STATS_H
#define CL_STATS_H

#include "core/decls.h"

CL_BEGIN_DECLS

/* The statistics every integrator reports. Counters a method does
 * not have stay 0; counters it has but its library does not expose (the
 * Newton iterations and LU factorisations inside GSL's msbdf) are
 * CL_STAT_NA, printed "n/a" (CSV: "NA"), never a made-up 0. */
#define CL_STAT_NA (-1L)

typedef struct {
    long steps;
    long rhs_evals;
    long jac_evals;
    long lin_setups;     /* matrix factorisations or preconditioner setups */
    long lin_solves;
    long lin_iters;      /* Krylov iterations */
    long nonlin_iters;   /* iterations of a Newton solver, also one held
                          * to one (semi-*, linear by construction: 0) */
    long nonlin_fails;   /* nonlinear convergence failures */
    long err_fails;      /* local error test failures */
    long symbolic_facts; /* symbolic factorisations (KLU analyse) */
    long lin_fallbacks;  /* setups a linear solver handed to another one
                          * (cholmod: matrix not SPD -> klu; auto: pcg
                          * failed -> direct) */
    long lin_recoveries; /* failed linear solves redone on a rebuilt
                          * preconditioner (amg); reported only if > 0 */
    char linsol[32];     /* linear solver(s) that did the work, '+'-joined
                          * ("klu-full", "cholmod+klu", "auto:pcg"); "" if
                          * none or not reported */
    double wall;         /* seconds spent inside advance (wall clock) */
    double cpu;          /* seconds spent inside advance (process CPU) */
} cl_stats;

CL_END_DECLS

#endif
