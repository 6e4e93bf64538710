/* Contact with obstacles: every [obstacle.NAME] section of a problem
 * (contact/obstacle.h), as one force term for the penalty responses, a
 * projection (with continuous detection where asked) for the `project`
 * responses and Baraff-Witkin constraints for the `constraint` responses
 * (docs/model.md, contact).
 *
 * cl_contact_term is a cl_term_type named "contact": its create reads the
 * obstacles (state NULL when there is none), its eval adds the penalty
 * and barrier forces of the free particles, their exact df/dx and df/dv
 * into the diagonal blocks, the penalty and barrier energy (series column
 * "contact") and the power of the penalty's damping and friction and of
 * the barrier's friction (power_diss).  A model adds
 * it after the registry's force terms. */
#ifndef CL_CONTACT_H
#define CL_CONTACT_H

#include <stdbool.h>
#include <stddef.h>

#include "contact/obstacle.h"
#include "core/decls.h"
#include "forces/term.h"

CL_BEGIN_DECLS

typedef struct cl_contact cl_contact;

extern const cl_term_type cl_contact_term;

typedef struct {
    size_t contacts;        /* particles in contact: d < eps (penalty) or
                             * d <= offset + 1e-9 m (project) */
    double max_penetration; /* max(0, -d) over particles and obstacles (m) */
    double force;           /* sum over particles of |contact force| (N):
                             * penalty forces, and for projections the
                             * impulses of the last projection divided by
                             * the time since the one before */
    double friction_power;  /* friction's power (W, <= 0), likewise */
    double min_distance;    /* least signed distance of a free particle to
                             * a barrier obstacle (m; INFINITY without
                             * barriers) */
} cl_contact_figures;

bool cl_contact_projects(const cl_contact *c);
/* Some projecting obstacle has friction (mu > 0) or zero_velocity. */
bool cl_contact_projects_friction(const cl_contact *c);
/* Some obstacle has response = constraint. */
bool cl_contact_constrains(const cl_contact *c);
size_t cl_contact_obstacles(const cl_contact *c);
const cl_obstacle *cl_contact_obstacle(const cl_contact *c, size_t k);

/* Forget the last projection (the next one's step, swept by ccd and
 * dividing its impulses into forces, begins at t0), the barriers' lagged
 * friction and every particle's memo of its distances (the start of a run
 * at t0: a study's runs follow each other on one model, and a memo left
 * by a run that blew up, at |x| ~ 1e78, screened the obstacles out of the
 * next one). */
void cl_contact_restart(cl_contact *c, double t0);

/* The figures at time t for full-particle positions and velocities. */
void cl_contact_measure(cl_contact *c, double t, const double *x,
                        const double *v, cl_contact_figures *f);

/* Deepest penetration max(0, -d) of a free particle into an obstacle. */
double cl_contact_penetration(cl_contact *c, double t, const double *x);

/* The `project` responses after a step to t: every free particle, every
 * projecting obstacle, `iterations` passes (the largest of theirs), in
 * place on full-particle arrays; returns the particles moved.  A `trial`
 * projects a step that may still be rejected (CVODE's, inside its steps):
 * it starts from the last accepted projection, as a retry of a rejected
 * step must, and counts once cl_contact_accept says its step was
 * accepted.  The figures' projection force and friction power are the
 * impulses and friction energy over the time since the projection before
 * (a second one at the same time adds its own over that interval). */
size_t cl_contact_project(cl_contact *c, double t, double *x, double *v,
                          bool trial);

/* The step to t, whose last trial projected it, was accepted: the next
 * projection counts from t. */
void cl_contact_accept(cl_contact *c, double t);

/* ---- barriers (contact/barrier.h) ---- */

/* Some obstacle has response = barrier. */
bool cl_contact_barriers(const cl_contact *c);

/* The last evaluation of the term found a free particle at d <= 0 of a
 * barrier obstacle: the state is infeasible (its barrier energy is
 * +infinity and its force meaningless). */
bool cl_contact_infeasible(const cl_contact *c);

/* Some barrier obstacle has friction (mu > 0): its lag changes the force
 * law after every step (cl_contact_lag). */
bool cl_contact_lags(const cl_contact *c);

/* Lag the barriers' friction: each free particle's normal force lambda
 * (barrier.h) at time t and full-particle positions x, kept for the
 * evaluations that follow (until the next call; 0 before the first). */
void cl_contact_lag(cl_contact *c, double t, const double *x);

/* The least signed distance of a free particle to a barrier obstacle at
 * time t (full-particle positions x); INFINITY without barriers. */
double cl_contact_min_distance(cl_contact *c, double t, const double *x);

/* The filter of a straight move of the free particles (3 * nfree each,
 * in the order of the cloth's free particles) from x0 at t0 to x1 at t1,
 * the barrier obstacles moving from their poses at t0 to those at t1:
 * 1 when no particle reaches a barrier obstacle, else CL_BARRIER_SAFETY
 * times the least time of impact (cl_obstacle_toi), a fraction in
 * [0, 1).  x0 must be feasible (every d > 0). */
double cl_contact_step_fraction(cl_contact *c, double t0, const double *x0,
                                double t1, const double *x1);
/* Baraff-Witkin constraints (contact/constraint.h; docs/model.md, eqs.
 * C10-C13) of the step of length h from (t, x, v), full-particle arrays:
 * every free particle's S, z, y, g (indexed by its dof) from the
 * constraint obstacle it touches (the nearest to its offset, if several),
 * laid out as cl_constraint_set (system/system.h). */
void cl_contact_constrain(cl_contact *c, double t, double h, const double *x,
                          const double *v, double *S, double *z, double *y,
                          double *g);

/* Release or demote the constraints by the impulses (per free particle)
 * the last solve needed; whether any changed. */
bool cl_contact_release(cl_contact *c, const double *impulse, double *S,
                        double *z, double *y, double *g);

CL_END_DECLS

#endif
