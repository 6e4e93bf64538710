/* The projection response of one particle to one obstacle (docs/model.md,
 * contact): a particle closer than `offset` to the surface (d < offset) is
 * moved along the normal to d = offset (Jiao's sphere collision and
 * the collision offset of the Verlet-and-PBD "Cloth Simulation" report),
 * and its velocity relative
 * to the obstacle, w = v - u, loses its inward normal part:
 *   w_n = w . n < 0:  w <- w - w_n n,
 * then Coulomb's cone at the velocity level: the tangential part shrinks
 * by at most mu |w_n|, v_t <- v_t max(0, 1 - mu |w_n| / |v_t|), so a
 * particle sticks while the tangential speed a step adds stays within
 * mu times the normal speed it removes (on a slope: mu >= tan theta).
 * With zero_velocity (Jiao's code) the whole relative velocity is removed
 * instead. */
#ifndef CL_PROJECT_H
#define CL_PROJECT_H

#include <stdbool.h>
#include <stddef.h>

#include "contact/obstacle.h"
#include "core/decls.h"

CL_BEGIN_DECLS

typedef struct {
    size_t moved;           /* particles moved */
    double impulse;         /* sum of m |delta v| (N s) */
    double friction_energy; /* kinetic energy the friction removed (J, <= 0) */
} cl_project_tally;

/* Project the particle (mass m) at x with velocity v, in place; false (and
 * nothing changed) when d >= offset. */
bool cl_project_particle(const cl_response_params *r,
                         const cl_contact_point *q, double m, double x[3],
                         double v[3], cl_project_tally *t);

/* The same response whatever d (the particle moved to d = offset, also
 * from d > offset): for a particle that continuous detection stopped at
 * the surface (contact/obstacle.h, cl_obstacle_sweep). */
void cl_project_hit(const cl_response_params *r, const cl_contact_point *q,
                    double m, double x[3], double v[3], cl_project_tally *t);

CL_END_DECLS

#endif
