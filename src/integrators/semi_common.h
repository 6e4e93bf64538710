/* Shared machinery of the semi-implicit (linearised) integrators semi-be
 * and semi-bdf2 (docs/integrators.md, 3): the state, the force/Jacobian
 * evaluation, the reduced linear system
 *
 *     (M - a df/dv - b df/dx) y = rhs        (linalg/linsol.h)
 *
 * solved by the solver named in opts->linsol, fixed-step bookkeeping
 * (time after step k is t0 + k h, the loop of cl_fixed_run), statistics,
 * and the Baraff-Witkin linearised backward-Euler step, which is semi-be's
 * step and semi-bdf2's first step:
 *
 *     (M - h df/dv - h^2 df/dx) dv = h (f0 + h df/dx v0),
 *     v1 = v0 + dv,   x1 = x0 + h v1,
 *
 * f0 = f(t0, x0, v0) and the Jacobians at (t0, x0, v0) (Baraff & Witkin
 * 1998, section 2.3; docs/integrators.md, 3.1); and the filtered solve of
 * a system with Baraff-Witkin constraints (section 5; docs/integrators.md,
 * 3.4).  Every array is allocated
 * at creation; a step allocates nothing (the KLU fall-back
 * refactorisation excepted, see linalg/linsol_klu.c). */
#ifndef CL_SEMI_COMMON_H
#define CL_SEMI_COMMON_H

#include "core/decls.h"
#include "integrators/fixed_step.h"
#include "integrators/integrator.h"
#include "linalg/linsol.h"

CL_BEGIN_DECLS

typedef struct {
    const char *name;           /* method name, for messages */
    const cl_system *sys;
    const cl_linsol_type *lst;  /* linear solver type */
    void *ls;                   /* its state */
    size_t n;                   /* 3 * free particles */
    double t0, h;
    long done;                  /* steps taken */
    long nlin;                  /* force + Jacobian evaluations */
    double *x, *v;              /* state after `done` steps */
    double *f;                  /* force at the last linearisation */
    double *dfdx, *dfdv;        /* its Jacobians (9 nnzb each) */
    double *rhs, *sol, *work;   /* n each */
    /* Baraff-Witkin constraints (sys->constrain, else all NULL): */
    cl_constraint_set cs;       /* the step's S (9 nb), z, y, g (n each) */
    double *fdx, *fdv;          /* the filtered Jacobians S K S, S D S */
    double *pres, *imp;         /* prescribed part of sol, constraint
                                 * impulses A sol - rhs - g (n each) */
} cl_semi;

/* Fills s->rhs for the method's linear system (may use s->work, s->sol). */
typedef void (*cl_semi_rhs_fn)(void *state);

/* Check the arguments (dt > 0, finite t0, n = 3 nb, force and Jacobian
 * present, masses finite > 0), pick the linear solver by opts->linsol
 * (CL_EINVAL naming the known ones if unknown), allocate and copy the
 * initial state.  On failure everything is released. */
cl_status cl_semi_init(cl_semi *s, const char *name, const cl_system *sys,
                       const cl_integrator_opts *o, double t0,
                       const double *x0, const double *v0, cl_error *err);
void cl_semi_release(cl_semi *s);

/* f, df/dx, df/dv at (t, s->x, s->v); CL_EBLOWUP if not finite, or the
 * system's own failure, with time and step in the message. */
cl_status cl_semi_linearise(cl_semi *s, double t, cl_error *err);

/* Set up the solver for a, b with the current Jacobians and solve for
 * s->sol from s->rhs; a solver failure (CL_ESOLVER, ...) is passed on with
 * the method, time and step prefixed. */
cl_status cl_semi_solve(cl_semi *s, double a, double b, cl_error *err);

/* The filtered step of a problem with barrier obstacles (contact/
 * barrier.h; docs/integrators.md, 3.3): the fraction a in [0, 1] of the
 * step's move x -> x + dx (n entries; from t_n to t_n + h) that keeps
 * every particle outside every barrier obstacle (IPC's filter with its
 * safety factor), by which the method scales its step; 1 without
 * barriers (dx not read).  Uses s->work. */
double cl_semi_filter(cl_semi *s, const double *dx);

/* The linear solve of a step under the system's constraints (docs/
 * integrators.md, 3.4; none: fill_rhs(state), then cl_semi_solve).  The
 * constraints of the step from (t, s->x, s->v); then, until no constraint
 * is released or demoted, fill_rhs(state) and the filtered solve
 *     S A S w = S (rhs + g - A p),   sol = p + S w,
 *     p = coef[0] (I - S) v + coef[1] z + coef[2] y,
 * (S, z, y, g: s->cs) whose impulses A sol - rhs - g go to the system. */
cl_status cl_semi_solve_constrained(cl_semi *s, double t, void *state,
                                    cl_semi_rhs_fn fill_rhs, double a,
                                    double b, const double coef[3],
                                    cl_error *err);

/* A constrained particle's velocity after a step whose unknown is the
 * position change (semi-bdf2): v_i = S_i v_i + (I - S_i)(vold_i + z_i),
 * its constrained part that of semi-be's step (nothing without
 * constraints). */
void cl_semi_hold_velocity(cl_semi *s, const double *vold);

/* The history of a two-step method (x^n, v^n in xprev, vprev) made that
 * of a uniform motion in a constrained particle's constrained part,
 * x^n = x^{n+1} - h v^{n+1}, v^n = v^{n+1}, so that the next step does not
 * carry the velocity jump the constraint made (nothing without
 * constraints). */
void cl_semi_hold_history(cl_semi *s, double *xprev, double *vprev);

/* One linearised backward-Euler step of x, v in place (done unchanged):
 * v_{n+1} = a (v_n + dv), x_{n+1} = x_n + h v_{n+1} (+ y under
 * constraints), a = 1 but for a filtered step (cl_semi_filter). */
cl_status cl_semi_be_step(cl_semi *s, cl_error *err);

/* Take the steps up to t_out with `step` (one step of s->x, s->v in
 * place, given `state`) through the fixed-step loop (cl_fixed_run: step
 * counting, CL_EBLOWUP if x or v is not finite), then copy x, v out (also
 * on failure: the last state). */
cl_status cl_semi_advance(cl_semi *s, void *state, cl_fixed_step_fn step,
                          double t_out, double *x, double *v, cl_error *err);

/* steps, rhs_evals, jac_evals and the linear solver's counters. */
void cl_semi_stats(const cl_semi *s, cl_stats *out);

CL_END_DECLS

#endif
