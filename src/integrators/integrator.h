/* The integrator interface (docs/integrators.md, 1): one file per method,
 * one row in the registry of integrators/registry.c.  An integrator sees
 * only a cl_system.
 *
 * Fixed-step methods take steps of exactly opts->dt; the time after step k is
 * k*dt (no accumulated round-off), and `advance` must be given output times
 * that are multiples of dt (cl_fixed_steps_to checks this).  Adaptive
 * methods (CVODE, ...) return the state interpolated at t_out (CVODE BDF
 * on a system that projects: the end of a step, sun_adapter.h). */
#ifndef CL_INTEGRATOR_H
#define CL_INTEGRATOR_H

#include <stdbool.h>
#include <stdio.h>

#include "core/decls.h"
#include "core/error.h"
#include "core/stats.h"
#include "integrators/region.h"
#include "linalg/linsol.h"
#include "system/system.h"

CL_BEGIN_DECLS

typedef struct {
    double dt;        /* fixed step, or initial step hint (0: solver's own) */
    double rtol;      /* relative tolerance (adaptive methods; >= 0, 0
                       * for 1e-6, the command line's default: a pure
                       * absolute control is not offered) */
    double atol;      /* absolute tolerance (adaptive methods; >= 0, 0
                       * for 1e-8) */
    long max_steps;   /* per advance call, 0 for the solver's default */
    const char *linsol;  /* linear solver name (--linsol); NULL or "" for
                          * the method's default */
    double newton_tol;   /* nonlinear solve tolerance, fixed-step implicit
                          * methods (0: method default) */
    long newton_maxit;   /* Newton iterations per step (0: method default) */
    double lin_tol;      /* iterative linear solver tolerance (0: default) */
    long lin_maxit;      /* iterative linear solver iterations (0: default) */
    double vdamp;        /* Verlet velocity damping factor in [0, 1)
                          * (the Verlet-and-PBD report; 0: none) */
    int max_order;       /* highest order of the variable-order methods
                          * (takes_max_order; 0: the solver's own, 5 for
                          * BDF, 12 for Adams) */
    bool force;          /* skip the memory guard (memguard.h; --force) */
    double rho_inf;      /* kinsol-galpha's spectral radius at infinite
                          * step, in [0, 1] (1: no numerical damping;
                          * [run] rho_inf, default 0.5; a zero-initialised
                          * opts means 0, the most damping) */
    double rayleigh_alpha; /* Rayleigh damping -(alpha M + beta K) v of the
                            * KINSOL methods (takes_rayleigh; 1/s, >= 0) */
    double rayleigh_beta;  /* ... its stiffness part (s, >= 0); 0 and 0:
                            * none (kinsol_common.h, "Rayleigh damping") */
    long substeps;       /* substeps per step of the constraint-based
                          * methods (takes_iterations; 0: 1) */
    long iterations;     /* their constraint iterations per substep
                          * (0: the method's default) */
    const char *table;   /* Butcher table of the ARKODE methods (--table;
                          * takes_table); NULL or "" for the default */
    const char *petsc;   /* PETSc options of the petsc-ts integrators
                          * (takes_petsc; --petsc); NULL or "" for none */
} cl_integrator_opts;

/* The linear solver's part of the options (threads: the system's). */
static inline cl_linsol_opts cl_integrator_linsol_opts(
    const cl_integrator_opts *o, const cl_system *sys)
{
    cl_linsol_opts lo = {o->lin_tol, o->lin_maxit, sys->threads};
    return lo;
}


typedef struct {
    const char *name;
    const char *doc;     /* one line for `clothode list` */
    bool fixed_step;     /* true: needs dt; false: uses rtol/atol */
    bool dt_fixes_step;  /* adaptive, but a dt > 0 in the options means
                          * fixed steps of dt (the petsc-ts family);
                          * cl_integrator_fixed */
    bool takes_linsol;   /* accepts opts->linsol (cl_linsol registry) */
    const char *linsol_default; /* the linear solver an empty opts->linsol
                                 * gives, NULL for the registry's first */
    bool takes_max_order; /* accepts opts->max_order */
    bool takes_iterations; /* accepts opts->substeps, opts->iterations */
    bool takes_newton_maxit; /* a Newton iteration opts->newton_maxit caps */
    bool newton_per_stage; /* ... that of each stage (ARKODE's DIRK and
                            * IMEX methods), with failed stage solves
                            * retried: no cap on the step's iterations */
    bool takes_table;    /* accepts opts->table */
    bool dense_jacobian; /* factorises a dense 2n x 2n Newton matrix */
    bool takes_rayleigh; /* accepts opts->rayleigh_alpha, rayleigh_beta */
    bool takes_petsc;    /* accepts opts->petsc (integrators/petsc_ts.h) */
    bool takes_rho_inf;  /* reads opts->rho_inf (kinsol-galpha) */
    bool takes_vdamp;    /* reads opts->vdamp (the Verlet methods) */
    bool takes_lin_tol;  /* reads opts->lin_tol: in a Krylov solver of its
                          * own (and lin_maxit; without takes_linsol:
                          * cvode-bdf-gmres), or through its cl_linsol when
                          * that is iterative (semi-*, kinsol-*); SUNDIALS'
                          * integrators set an iterative cl_linsol's
                          * tolerance themselves (solve_tol) and read
                          * lin_maxit only */
    const cl_region *region; /* linear stability region (region.h) */
    /* A run from (t0, x0, v0), t0 any finite time; on a cl_model's
     * system, after cl_model_contact_start(m, t0, ...) (system/model.h:
     * a model carries one run at a time). */
    cl_status (*create)(const cl_system *sys, const cl_integrator_opts *o,
                        double t0, const double *x0, const double *v0,
                        void **state, cl_error *err);
    /* Advance to t_out; x and v (sys->n each) receive the state there. */
    cl_status (*advance)(void *state, double t_out, double *x, double *v,
                         cl_error *err);
    /* Counters so far (wall and cpu are filled by the caller). */
    void (*stats)(const void *state, cl_stats *s);
    void (*free)(void *state);
} cl_integrator_type;

extern const cl_integrator_type *const cl_integrator_registry[];

/* Whether a run of `type` with the option dt takes fixed steps of dt, so
 * that its output times must be multiples of it (cl_fixed_steps_to). */
static inline bool cl_integrator_fixed(const cl_integrator_type *type,
                                       double dt)
{
    return type->fixed_step || (type->dt_fixes_step && dt > 0.0);
}

/* type->create behind the memory guard (memguard.h): refused with the
 * estimate when it exceeds the available memory, unless o->force; and
 * refused (CL_EINVAL) when the system has barriers and the initial state
 * has a particle at d <= 0 of one, or when type, sys or o is NULL (as
 * cl_integrator_find gives for an unknown name).  An option the type does
 * not take (its takes_* flag false: a linsol of rk4, a table of
 * cvode-bdf, ...) is ignored, not refused: that check is the caller's, as
 * the command line makes it. */
cl_status cl_integrator_create(const cl_integrator_type *type,
                               const cl_system *sys,
                               const cl_integrator_opts *o, double t0,
                               const double *x0, const double *v0,
                               void **state, cl_error *err);

/* Registry lookup by name; NULL if unknown. */
const cl_integrator_type *cl_integrator_find(const char *name);

/* The check of an adaptive method's output time t_out against its
 * current time t_now: CL_EINVAL naming the method `name` when t_out is
 * not finite or lies behind t_now. */
cl_status cl_output_time_check(const char *name, double t_out, double t_now,
                               cl_error *err);

/* Number of fixed steps of size dt that lead from step `done` to t_out.
 * CL_EINVAL if t_out is not a multiple of dt (to 1e-9 relative) or lies
 * behind step `done`. */
cl_status cl_fixed_steps_to(double t_out, double dt, long done, long *nsteps,
                            cl_error *err);

/* Contact (system/system.h) for an adaptive method that cannot project:
 * CL_EUNSUPPORTED naming the method if the system projects. */
cl_status cl_integrator_refuse_projection(const char *name,
                                          const cl_system *sys,
                                          cl_error *err);

/* Baraff-Witkin constraints (system/system.h, constrain): CL_EUNSUPPORTED
 * naming the method if the system has them; every integrator but semi-be
 * and semi-bdf2 calls it when created. */
cl_status cl_integrator_refuse_constraints(const char *name,
                                           const cl_system *sys,
                                           cl_error *err);

/* The system's contact hook at an output time t of an adaptive method, if
 * it has one (CL_CONTACT_RECORD | CL_CONTACT_PROJECT): the contact
 * figures, and for CVODE BDF, whose outputs are the ends of steps it
 * projected inside (sun_adapter.h), the projections again (moving
 * nothing but round-off). */
cl_status cl_integrator_contact_at(const char *name, const cl_system *sys,
                                   double t, double *x, double *v,
                                   cl_error *err);

/* Write the statistics as an aligned human-readable block (human = true) or
 * as "name,value" CSV rows without header and without the wall and CPU
 * times (human = false). */
void cl_stats_print(const cl_stats *s, FILE *fp, bool human);

CL_END_DECLS

#endif
