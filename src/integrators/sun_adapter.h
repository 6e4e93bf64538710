/* The SUNDIALS adapter (docs/integrators.md, 7): the one place where
 * clothode meets SUNDIALS' objects.  The packages plug into it:
 *
 * - CVODE (cvode-bdf, cvode-bdf-dense, cvode-bdf-gmres, cvode-adams),
 *   IDA (ida) and ARKODE's ARKStep (arkode-*) through a package table
 *   (cl_sun_api: CVODE's is cl_sun_cvode_api, IDA's is in ida.c,
 *   ARKStep's in arkode_common.c) and
 *   the integrator state cl_sun below, whose create, advance, statistics
 *   and free serve every such integrator;
 * - KINSOL (kinsol_common.c) and the half-size Newton solvers of CVODE and
 *   IDA (sun_reduced.c) through the shell objects: every SUNLinearSolver
 *   and SUNMatrix clothode implements itself is made here, by
 *   cl_sun_shell_linsol from a table of the solver's own functions
 *   (cl_sun_lsdef) and by cl_sun_shell_matrix, a matrix that holds no
 *   values (the cl_linsol behind the solver keeps its own);
 * - a linear solver with state of its own beside SUNDIALS' objects hangs
 *   on the integrator state as a plug (cl_sun_plug: its counters, its
 *   last failure, its release), so that the integrator's table entries
 *   stay cl_sun_advance, cl_sun_stats and cl_sun_free.
 *
 * The CVODE, IDA and ARKODE integrators integrate y = (x, v), 2n unknowns, in a serial N_Vector
 * under one SUNContext, and share:
 *
 * - options: scalar tolerances opts->rtol, opts->atol (defaults when 0:
 *   rtol 1e-6, atol 1e-8), at most opts->max_steps internal steps per
 *   advance (default 10^7), initial step opts->dt when > 0; output by
 *   interpolation at t_out (CV_NORMAL / IDA_NORMAL), but for CVODE BDF on
 *   a system that projects, whose outputs are steps' ends (contact,
 *   below);
 * - failures: every SUNDIALS call is checked; a failure returns CL_ESOLVER
 *   naming the function, its flag and the time reached.  The solver's own
 *   messages are captured (its error handler), never printed;
 * - the blow-up policy: a force or Jacobian that is not finite (or a system
 *   call returning CL_EBLOWUP) makes the user function return 1
 *   (recoverable: the solver retries with a smaller step, which cures a
 *   trial state that went too far) unless the step has collapsed to
 *   round-off during this advance (CVODE warned that t + h = t, its only
 *   warning, code CV_WARNING, or the
 *   solver's current step is below 100 ulp of t): then retrying would only
 *   crawl towards the singularity until max_steps, and it returns -1; any
 *   other system error returns -1 (unrecoverable).  After a -1 every later
 *   force and Jacobian call of the same advance returns -1 at once without
 *   evaluating (SUNDIALS' fixed-point solver passes a -1 back to CVODE as
 *   a recoverable failure; latched, CVODE stops after its limit of
 *   convergence failures instead of crawling).  If the solver gives up,
 *   advance reports CL_EBLOWUP (or the system's status) with the times
 *   reached, not a generic solver failure;
 * - statistics (cl_stats): steps, nonlin_iters, nonlin_fails, err_fails,
 *   jac_evals, lin_setups, lin_iters are the solver's counters; rhs_evals
 *   = its RHS / residual evaluations plus the linear solver's (difference
 *   quotients) plus force evaluations made outside the solver (s->own_rhs);
 *   with a direct solver wrapped by the counting shell
 *   (cl_sun_attach_direct), lin_solves = solve calls (one per Newton
 *   iteration) and symbolic_facts = KLU analyses (setups that ran KLU's
 *   symbolic analysis: the first setup after each SUNLinSolInitialize,
 *   which CVODE and IDA call at their first step after an Init or ReInit,
 *   retried until one succeeds; 1 for a whole run with a fixed pattern);
 *   a plug then overrides what its solver counts itself;
 * - tearing (docs/model.md, 3.4): the system's step_done hook is called at
 *   the end of every advance, i.e. at output times only (a run with tearing
 *   should ask for many samples); when it reports a change, the solver is
 *   re-initialised at t_out from the current state (api->reinit: CVodeReInit;
 *   IDAReInit with a consistent y' = (v, M^-1 f)), which drops its history
 *   and step size, and the pattern stays (a torn pair's blocks are zeros),
 *   so KLU only analyses once more.  The solver's counters, which a
 *   re-initialisation resets, are carried over in the statistics;
 * - contact (system/system.h): CVODE BDF applies the `project` responses
 *   inside every step through its projection interface (CVodeSetProjFn:
 *   after the Newton iteration converges, before the error test; the
 *   correction enters the Nordsieck history).  The error estimate is
 *   projected too (CVODE's default): a moved particle's error loses its
 *   part along the move, the normal, in positions and velocities, so the
 *   error test judges the motion the contact leaves free and does not
 *   shrink the step to resolve the jumps of a particle resting on a
 *   surface.  Projection with friction (mu > 0, zero_velocity) is refused:
 *   it cuts the tangential velocity after the step while the step itself
 *   slid the particle frictionlessly, an error that grows with CVODE's
 *   step and that its error test never sees.  A problem that projects is
 *   stepped one step at a time to each output time as CVODE's stop time
 *   (CVodeSetStopTime, CV_ONE_STEP): its outputs are steps' ends, never
 *   interpolated across a projection (the interpolant would spread the
 *   correction over the whole step: a particle falling onto a floor was
 *   seen slowing down in mid-air), and after each accepted step the
 *   state before its projection is recorded (the deepest penetration,
 *   system.h's CL_CONTACT_RECORD).  CVODE Adams and IDA refuse a problem
 *   that projects; without projections every method calls the contact
 *   hook at its output times, for the contact figures only.
 *
 * Usage: an integrator's state struct has a cl_sun as its FIRST member, so
 * the one pointer the solver passes to every callback (user data and error
 * handler data) is both (most need no more: the state is the cl_sun).
 * create: cl_sun_cvode_create (CVODE), or cl_sun_alloc (argument checks,
 * state, masses, context, vectors) and the integrator's own memory
 * creation with cl_sun_created + its Init + cl_sun_configure (IDA); then
 * the solvers, stored in s->A, s->ls, s->inner, s->nls or as a plug so
 * that cl_sun_free releases everything in order; then cl_sun_finish.
 * docs/integrators.md, 7, adds an integrator step by step. */
#ifndef CL_SUN_ADAPTER_H
#define CL_SUN_ADAPTER_H

#include <stdbool.h>
#include <stdint.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_nonlinearsolver.h>

#include "core/decls.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

/* ---- shell objects ------------------------------------------------------ */

/* A SUNLinearSolver of clothode's own: its operations call these functions
 * with the data given to cl_sun_shell_linsol.  Return values are
 * SUNDIALS' (SUNLS_SUCCESS, > 0 recoverable, < 0 not).  An optional entry
 * left NULL leaves the operation out of the solver, as SUNDIALS expects of
 * a solver that lacks it (initialize then has nothing to do). */
typedef struct {
    SUNLinearSolver_Type type;   /* DIRECT or MATRIX_ITERATIVE */
    int (*setup)(void *data, SUNMatrix A);
    int (*solve)(void *data, SUNMatrix A, N_Vector x, N_Vector b,
                 sunrealtype tol);
    int (*initialize)(void *data);                 /* optional */
    sunindextype (*lastflag)(void *data);          /* optional */
    int (*space)(void *data, long *lrw, long *liw); /* optional */
    /* matrix-iterative solvers: the integrator's weights (s2 unused), the
     * iterations of the last solve, its residual vector (optional) */
    int (*scaling)(void *data, N_Vector s1, N_Vector s2);
    int (*numiters)(void *data);
    N_Vector (*resid)(void *data);
    void (*free)(void *data); /* optional: data owned by the solver */
} cl_sun_lsdef;

/* The solver of table def (static storage) on data (SUNLINEARSOLVER_CUSTOM;
 * SUNLinSolFree releases it and, with def->free, its data), or NULL if
 * out of memory (data is then not freed). */
SUNLinearSolver cl_sun_shell_linsol(const cl_sun_lsdef *def, void *data,
                                    SUNContext ctx);

/* A SUNMATRIX_CUSTOM matrix without values for the matrix-based solvers
 * whose matrix lives elsewhere: zero, copy and scale-add-identity do
 * nothing, clone gives another shell; NULL if out of memory. */
SUNMatrix cl_sun_shell_matrix(SUNContext ctx);

/* ---- CVODE, IDA, ARKODE: the integrator state ------------------------- */

typedef struct cl_sun cl_sun;

typedef void (*cl_sun_errfn)(int code, const char *module,
                             const char *function, char *msg, void *data);
typedef int (*cl_sun_getter)(void *mem, long *value);
/* The Jacobian function of the packages on y' = f(t, y) (CVLsJacFn,
 * ARKLsJacFn: one signature). */
typedef int (*cl_sun_jacfn)(sunrealtype t, N_Vector y, N_Vector fy,
                            SUNMatrix J, void *data, N_Vector t1,
                            N_Vector t2, N_Vector t3);

/* The solver package: CVODE and IDA name their functions alike and give
 * them the same signatures. */
typedef struct {
    const char *pkg;        /* "CVode" / "IDA": prefix of the names below */
    const char *solve_name; /* "CVode" / "IDASolve" */
    bool has_yp;            /* the solver needs y' (IDA) */
    int (*set_err_handler)(void *mem, cl_sun_errfn fn, void *data);
    int (*set_user_data)(void *mem, void *data);
    int (*sstolerances)(void *mem, sunrealtype rtol, sunrealtype atol);
    int (*set_max_num_steps)(void *mem, long mxsteps);
    int (*set_init_step)(void *mem, sunrealtype h);
    int (*set_max_ord)(void *mem, int maxord); /* NULL: no choice */
    int (*set_linear_solver)(void *mem, SUNLinearSolver ls, SUNMatrix A);
    int (*get_current_time)(void *mem, sunrealtype *t);
    int (*get_current_step)(void *mem, sunrealtype *h);
    /* y' = f packages (CVODE, ARKODE): the Newton matrix I - gamma J's
     * gamma, and the Jacobian function's setter (NULL for IDA) */
    int (*get_gamma)(void *mem, sunrealtype *gamma);
    int (*set_jac_fn)(void *mem, cl_sun_jacfn jac);
    char *(*flag_name)(long flag);
    int collapse_warning;   /* code of the "t + h = t" warning (0: none) */
    void (*free_mem)(void **mem);
    int (*solve)(cl_sun *s, double t_out); /* one advance to t_out */
    /* restart at t from the current s->y (NULL: never restarted) */
    cl_status (*reinit)(cl_sun *s, double t, cl_error *err);
    /* counters (a getter that fails, e.g. without a linear solver, leaves
     * its counter 0) */
    cl_sun_getter steps, rhs, lin_rhs, jac, setups, lin_iters, nl_iters,
        nl_fails, err_fails;
} cl_sun_api;

extern const cl_sun_api cl_sun_cvode_api;

/* A linear solver's own state on an integrator (see the head). */
typedef struct {
    /* after the solver's counters: what the linear solver counts itself */
    void (*stats)(const void *data, cl_stats *out);
    /* message of its last failure, "" if none (NULL: never any) */
    const char *(*last_error)(const void *data);
    void (*free)(void *data);
} cl_sun_plug;

/* The counting shell around a direct solver (cl_sun_attach_direct). */
typedef struct {
    SUNLinearSolver inner; /* the wrapped direct solver */
    bool analyse;          /* KLU analyses at its next setup */
    long solves, analyses;
} cl_sun_count;

struct cl_sun {
    const char *name;        /* integrator name: prefix of every message */
    const cl_sun_api *api;
    const cl_system *sys;
    SUNContext ctx;
    N_Vector y;              /* (x, v) */
    N_Vector yp;             /* (x', v') when api->has_yp, else NULL */
    void *mem;               /* CVODE or IDA memory */
    SUNMatrix A;             /* NULL: matrix-free or no linear solver */
    SUNLinearSolver ls;      /* attached to mem (NULL: none) */
    SUNLinearSolver inner;   /* direct solver wrapped by ls, or NULL */
    SUNNonlinearSolver nls;  /* own nonlinear solver, or NULL */
    cl_sun_count cnt;        /* counters of the wrapper */
    const cl_sun_plug *plug; /* the linear solver's own state, or NULL */
    void *plug_data;
    double *inv_mass;        /* n */
    double *proj;            /* 4n: the last trial's projected state and
                              * the state before it (contact), or NULL */
    bool trial;              /* a trial projected the step under way */
    long max_steps;          /* internal steps per advance at most */
    double *dfdx, *dfdv;     /* block values, 9 nnzb each (need_jac) */
    size_t nval;             /* 9 nnzb */
    long njac;               /* system Jacobian evaluations */
    long own_rhs;            /* force evaluations outside the solver */
    double t_last;           /* last output time */
    cl_status fail_rhs;      /* status of the last failed force call, or OK */
    cl_status fail_jac;      /* same for the Jacobian */
    bool collapsed;          /* CVODE warned t + h = t in this advance */
    bool fixed_steps;        /* ARKODE at a fixed step (cl_solver_hint) */
    bool fatal;              /* a user function returned -1 (latched) */
    double fail_t;           /* time of that failure */
    bool fail_nonfinite;     /* it was our finiteness check that failed */
    char msg[512];           /* last error message of the solver */
    cl_stats before;         /* solver counters before re-initialisations */
    bool split;              /* the Jacobian is that of the terms in
                              * `implicit` alone (IMEX, system.h) */
    uint64_t implicit;
};

/* Check the arguments, allocate a zeroed state of `size` bytes (a struct
 * starting with a cl_sun), masses, block-value arrays (need_jac), context
 * and vectors y = (x0, v0) (and y' = 0 for IDA).  `projects`: whether the
 * method can apply contact projections; CL_EUNSUPPORTED for a system that
 * has them if it cannot.  On failure *out is NULL and everything is
 * freed. */
cl_status cl_sun_alloc(size_t size, const char *name, const cl_sun_api *api,
                       const cl_system *sys, const cl_integrator_opts *o,
                       double t0, const double *x0, const double *v0,
                       bool need_jac, bool projects, cl_sun **out,
                       cl_error *err);

/* Store freshly created solver memory (fn names the creator for the
 * message if mem is NULL) and install the error handler. */
cl_status cl_sun_created(cl_sun *s, void *mem, const char *fn,
                         cl_error *err);

/* User data, tolerances, max steps, initial step (after the Init call). */
cl_status cl_sun_configure(cl_sun *s, const cl_integrator_opts *o,
                           cl_error *err);

/* cl_sun_alloc, then CVODE with multistep method lmm (CV_BDF, CV_ADAMS):
 * create, error handler, CVodeInit with cl_sun_cvode_rhs, the contact
 * projection (BDF only; Adams refuses a system that projects),
 * cl_sun_configure.  If the allocation succeeded, *out is the state even
 * when a later call failed (for cl_sun_finish to free). */
cl_status cl_sun_cvode_create(size_t size, const char *name, int lmm,
                              bool need_jac, const cl_system *sys,
                              const cl_integrator_opts *o, double t0,
                              const double *x0, const double *v0,
                              cl_sun **out, cl_error *err);

/* End of an integrator's create: on success *state = s, otherwise s (if
 * any) is released by free_fn and *state stays NULL; returns st. */
cl_status cl_sun_finish(cl_sun *s, cl_status st, void (*free_fn)(void *),
                        void **state);

/* Attach matrix A and direct solver `inner` (both owned by s from now on,
 * even on failure) through the counting shell. */
cl_status cl_sun_attach_direct(cl_sun *s, SUNMatrix A, SUNLinearSolver inner,
                               cl_error *err);

/* A size x size CSC matrix with room for nnz entries and SUNLinSol_KLU on
 * it with AMD ordering (SUNLinSol_KLUSetOrdering(LS, 0)), attached by
 * cl_sun_attach_direct. */
cl_status cl_sun_attach_klu(cl_sun *s, sunindextype size, sunindextype nnz,
                            cl_error *err);

/* Hang plug p with data on s (released by cl_sun_free from now on). */
void cl_sun_plug_in(cl_sun *s, const cl_sun_plug *p, void *data);

/* A solver call returned flag < 0 (fn: the full function name). */
cl_status cl_sun_fail(cl_sun *s, const char *fn, int flag, cl_error *err);
/* A constructor returned NULL (flag 0) or a SUNLinSol/SUNMat call a flag. */
cl_status cl_sun_sunfail(const cl_sun *s, const char *fn, int flag,
                         cl_error *err);

/* The system's force f(t, x, v): 0, or the user-function return code
 * (1 recoverable, -1 not) after recording the failure. */
int cl_sun_force(cl_sun *s, double t, const double *x, const double *v,
                 double *f);
/* Finiteness of a user function's output: 0 (and the last force failure
 * is forgotten), or the blow-up return code. */
int cl_sun_rhs_finite(cl_sun *s, const double *out, size_t len, double t);
/* cl_sun_force over the terms of mask alone (system.h force_terms). */
int cl_sun_force_terms(cl_sun *s, uint64_t mask, double t, const double *x,
                       const double *v, double *f);
/* The system's block Jacobians at (t, x, v) into s->dfdx, s->dfdv (of the
 * terms in s->implicit alone when s->split): 0 or the user-function
 * return code; counts s->njac. */
int cl_sun_jacobian(cl_sun *s, double t, const double *x, const double *v);

/* CVODE's right-hand side y' = (v, M^-1 f(t, x, v)). */
int cl_sun_cvode_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data);

/* The integrator-table entries (state: a struct starting with cl_sun).
 * A failure's message ends with the plug's last failure, if any. */
cl_status cl_sun_advance(void *state, double t_out, double *x, double *v,
                         cl_error *err);
void cl_sun_stats(const void *state, cl_stats *out);
void cl_sun_free(void *state);

CL_END_DECLS

#endif
