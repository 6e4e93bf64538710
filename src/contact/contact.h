/* Contact with obstacles: every [obstacle.NAME] section of a problem
 * (contact/obstacle.h), as one force term for the penalty responses, a
 * projection (with continuous detection where asked) for the `project`
 * responses and Baraff-Witkin constraints for the `constraint` responses
 * (docs/model.md, contact).
 *
 * cl_contact_term is a cl_term_type named "contact": its create reads the
 * obstacles (state NULL when there is none), its eval adds the penalty
 * forces of the free particles, their exact df/dx and df/dv into the
 * diagonal blocks, the penalty energy (series column "contact") and the
 * power of the penalty's damping and friction (power_diss).  A model adds
 * it after the registry's force terms. */
#ifndef CL_CONTACT_H
#define CL_CONTACT_H

#include <stdbool.h>
#include <stddef.h>

#include "contact/obstacle.h"
#include "forces/term.h"

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
} cl_contact_figures;

bool cl_contact_projects(const cl_contact *c);
/* Some projecting obstacle has friction (mu > 0) or zero_velocity. */
bool cl_contact_projects_friction(const cl_contact *c);
/* Some obstacle has response = constraint. */
bool cl_contact_constrains(const cl_contact *c);
size_t cl_contact_obstacles(const cl_contact *c);
const cl_obstacle *cl_contact_obstacle(const cl_contact *c, size_t k);

/* Forget the last projection (the start of a run). */
void cl_contact_restart(cl_contact *c);

/* The figures at time t for full-particle positions and velocities. */
void cl_contact_measure(cl_contact *c, double t, const double *x,
                        const double *v, cl_contact_figures *f);

/* Deepest penetration max(0, -d) of a free particle into an obstacle. */
double cl_contact_penetration(cl_contact *c, double t, const double *x);

/* The `project` responses after a step to t: every free particle, every
 * projecting obstacle, `iterations` passes (the largest of theirs), in
 * place on full-particle arrays; returns the particles moved. */
size_t cl_contact_project(cl_contact *c, double t, double *x, double *v);

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

#endif
