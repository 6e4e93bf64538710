/* The penalty response of one particle to one obstacle (docs/model.md,
 * contact; the repulsion spring of Zischg, Chea and Aigner, "Cloth
 * Simulation", 2016, eq. 12, with damping and smoothed Coulomb friction
 * added).  Inside the band d < eps, with w = v - u the velocity relative to
 * the obstacle, w_n = w . n, v_t = w - w_n n:
 *
 *   f = k (eps - d) max(0, 1 - a w_n) n    repulsion, E = k (eps - d)^2 / 2,
 *                                          with Hunt and Crossley's damping
 *     - mu k (eps - d) v_t / sqrt(|v_t|^2 + v_s^2)   friction
 *
 * The damping (a in s/m) is proportional to the repulsion, as in Hunt and
 * Crossley, "Coefficient of restitution interpreted as damping in
 * vibroimpact" (1975), so the force is continuous where a particle enters
 * the band (a dashpot -c w_n n would jump there, and Newton's method of
 * the implicit fixed-step integrators cycles on a jump); its power
 * -a k (eps - d) w_n^2 is never positive.  The max keeps a particle that
 * leaves faster than 1/a from being pulled back (the power there
 * -k (eps - d) w_n).
 * The friction is Coulomb's law on the spring's force, mu k (eps - d),
 * opposite the sliding velocity,
 * smoothed below the speed v_s (so a block on a slope with mu > tan theta
 * creeps at about v_s tan theta / sqrt(mu^2 - tan^2 theta)).  Both
 * Jacobians are exact, curvature terms included: with G = dn/dx and
 * W = du/dx,
 *   d(k (eps - d) n)/dx = -k n n^T + k (eps - d) G,
 * and the damping and friction terms differentiate w_n and v_t through n
 * and u (penalty.c). */
#ifndef CL_PENALTY_H
#define CL_PENALTY_H

#include <stdbool.h>
#include <stddef.h>

#include "contact/obstacle.h"
#include "core/decls.h"

CL_BEGIN_DECLS

typedef struct {
    double f[3];          /* force on the particle */
    double dfdx[9];       /* row-major; only when asked for */
    double dfdv[9];
    double energy;        /* k (eps - d)^2 / 2 */
    double power;         /* (damping + friction) . w, <= 0 */
    double friction_power;
} cl_penalty_out;

/* false (and o untouched) outside the band d < eps; Jacobians only when
 * jac is true. */
bool cl_penalty_eval(const cl_response_params *r, const cl_contact_point *q,
                     const double v[3], bool jac, cl_penalty_out *o);

/* cl_penalty_eval without Jacobians of n contact points without
 * derivatives (obstacle.h), q[i] that of particle near[i] (velocity
 * v + 3 near[i]): those in the band add their force to f + 3 near[i]
 * (f may be NULL), their energy to *energy and their power to *power, in
 * order; the same numbers as cl_penalty_eval's, bit for bit.  One loop
 * with the law inlined, without a call a point. */
void cl_penalty_forces(const cl_response_params *r, const cl_contact_slim *q,
                       const size_t *near, size_t n, const double *v,
                       double *f, double *energy, double *power);

CL_END_DECLS

#endif
