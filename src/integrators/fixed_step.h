/* Shared plumbing of the explicit fixed-step integrators
 * (docs/integrators.md, 2): fe, symplectic-euler, symplectic-euler-x,
 * verlet, velocity-verlet, rk4.
 *
 * A method supplies a cl_fixed_method (CL_FIXED_INTEGRATOR below defines it
 * with the integrator table): its name, how many work arrays of n doubles
 * it needs (its extra state, allocated once in create), an optional setup
 * hook that checks and takes method options, and its step function,
 * which updates the current state s->x, s->v in place from
 * t_k = t0 + k h to t_{k+1} (h = opts->dt > 0).  This module does the rest
 * for every method alike:
 *
 *   - create: checks dt, t0 and the masses (finite, > 0; CL_EINVAL),
 *     allocates the state and the work arrays, computes 1/mass;
 *   - advance: takes exactly the steps that lead to t_out, which must be a
 *     whole number of steps from t0 (cl_fixed_steps_to; the time after step
 *     k is t0 + k h, never accumulated); after every step the state is
 *     checked to be finite, CL_EBLOWUP with the time and the step otherwise;
 *     x and v receive the current state (also after a failure);
 *   - statistics: steps, and rhs_evals = force evaluations made through
 *     cl_fixed_accel; every other counter is 0;
 *   - forces: cl_fixed_accel evaluates a = M^-1 f(t, x, v), counts it, and
 *     turns a failing force into its status with the time and step.
 *
 * Nothing is allocated in the per-step path.
 *
 * The step loop of advance (output times, step counting, the finite-state
 * check, the copy-out) is cl_fixed_run, which the implicit fixed-step
 * integrators (kinsol_common.c, semi_common.c) share with their own state,
 * step function and statistics. */
#ifndef CL_FIXED_STEP_H
#define CL_FIXED_STEP_H

#include "core/decls.h"
#include "integrators/define.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

#define CL_FIXED_MAXWORK 6

typedef struct cl_fixed cl_fixed;

typedef struct {
    const char *name;   /* registry name, used in messages */
    size_t nwork;       /* work arrays of n doubles, <= CL_FIXED_MAXWORK */
    /* Check and take method-specific options (NULL: none). */
    cl_status (*setup)(cl_fixed *s, const cl_integrator_opts *o,
                       cl_error *err);
    /* One step of size h from time t = t0 + done h, in place; a step that
     * fails (a force error) leaves x and v at step `done`. */
    cl_status (*step)(cl_fixed *s, double t, double h, cl_error *err);
} cl_fixed_method;

struct cl_fixed {
    const cl_fixed_method *method;
    const cl_system *sys;
    size_t n;          /* sys->n */
    double t0, dt;
    long done;         /* steps taken */
    long nrhs;         /* force evaluations */
    double param;      /* method parameter set by setup (verlet: vdamp) */
    double *x, *v;     /* current state (n each) */
    double *inv_mass;  /* 1 / mass (n) */
    double *w[CL_FIXED_MAXWORK]; /* the method's work arrays (n each) */
};

cl_status cl_fixed_create(const cl_fixed_method *m, const cl_system *sys,
                          const cl_integrator_opts *o, double t0,
                          const double *x0, const double *v0, void **state,
                          cl_error *err);
cl_status cl_fixed_advance(void *state, double t_out, double *x, double *v,
                           cl_error *err);
void cl_fixed_stats(const void *state, cl_stats *out);
void cl_fixed_free(void *state);

/* ---- the step loop of every fixed-step integrator ---------------------- */

/* One step from t0 + done h to t0 + (done + 1) h, in place; `done` is
 * counted by cl_fixed_run after the step returns CL_OK. */
typedef cl_status (*cl_fixed_step_fn)(void *state, cl_error *err);

/* The clock and the current state of a fixed-step integrator. */
typedef struct {
    const char *name;   /* method name, used in messages */
    size_t n;           /* entries of x and of v */
    double t0, h;       /* time of step 0, step size */
    long *done;         /* steps taken */
    /* the current state (n each); a step may repoint it (history swap) */
    double *const *x, *const *v;
    /* the system, for its contact and step_done hooks (projections,
     * tearing); NULL: not called */
    const cl_system *sys;
} cl_fixed_clock;

/* Take the steps from *done to t_out, which must be a whole number of
 * steps from t0 (cl_fixed_steps_to): call step(state), count it in *done
 * and check that *x and *v are finite (CL_EBLOWUP with the time and the
 * step otherwise), then call sys->contact (contact figures and
 * projections, which move *x and *v in place) and sys->step_done (when the
 * clock has a system
 * with that hook: tearing after every accepted step), until t_out or a
 * failure.  x_out and v_out receive the current state, also after a
 * failure.
 *
 * A change reported by step_done (a connection tore) does not restart
 * anything: the multistep methods (verlet's x_{k-1}, semi-bdf2's and
 * kinsol-bdf2's x^{n-1}, v^{n-1}) keep their history and step across the
 * tear as across any non-smooth event, with a local error of the order of
 * the jump in force over one step. */
cl_status cl_fixed_run(const cl_fixed_clock *c, cl_fixed_step_fn step,
                       void *state, double t_out, double *x_out,
                       double *v_out, cl_error *err);

/* The checks every fixed-step method makes when created: dt finite and
 * > 0, t0 finite, the system's masses finite and > 0 (CL_EINVAL naming
 * the method). */
cl_status cl_fixed_check(const char *name, const cl_system *sys, double dt,
                         double t0, cl_error *err);

/* a = M^-1 f(t, x, v) (n entries), counted in rhs_evals.  A force that
 * fails returns its status with a message naming the method, the time and
 * the step. */
cl_status cl_fixed_accel(cl_fixed *s, double t, const double *x,
                         const double *v, double *a, cl_error *err);
/* f(t, x, v) alone, for a method that multiplies by s->inv_mass in its
 * own loop (the same a = f M^-1, entry by entry); counted and checked as
 * cl_fixed_accel. */
cl_status cl_fixed_force(cl_fixed *s, double t, const double *x,
                         const double *v, double *f, cl_error *err);

/* Define the fixed-step method (registry name name_, stability region
 * region_, nwork_ work arrays, setup hook setup_ or NULL, step function
 * step_, vdamp_ true when it reads opts->vdamp) and its integrator table
 * `ident`, with its create function. */
#define CL_FIXED_INTEGRATOR(ident, name_, region_, doc_, nwork_, setup_,    \
                            step_, vdamp_)                                  \
    static const cl_fixed_method ident##_method = {                         \
        .name = (name_),                                                    \
        .nwork = (nwork_),                                                  \
        .setup = (setup_),                                                  \
        .step = (step_),                                                    \
    };                                                                      \
    CL_INTEGRATOR_DEFINE(ident, ident##_method, cl_fixed_create, name_,     \
                         region_, doc_, true, false, false, false,          \
                         (vdamp_), cl_fixed_advance, cl_fixed_stats,        \
                         cl_fixed_free)

CL_END_DECLS

#endif
