/* verlet-pbd: position Verlet with velocity damping plus position-based
 * distance constraints, the loop of the Verlet-and-PBD report
 * (docs/integrators.md, 2; docs/model.md, 3.4; Mueller et al., "Position
 * based dynamics", 2007, algorithm 1 with Verlet's implicit velocity):
 *
 *   x~_{k+1} = x_k + (1 - d) (x_k - x_{k-1}) + h^2 M^-1 f(t_k, x_k, v_k)
 *   x_{k+1}  = P(t_{k+1}, x~_{k+1})     the system's `project` hook
 *   v_{k+1}  = (x_{k+1} - x_k) / h,
 *
 * where f are the forces of the system (gravity, springs, damping, ...:
 * every force term; the constraints themselves exert none), d =
 * opts->vdamp in [0, 1), and P the Gauss-Seidel projection of the `pbd`
 * term (forces/pbd.h: `iterations` sweeps, stiffness K, pinned particles
 * held at their prescribed positions at t_{k+1}).  The velocity formed
 * after the projection carries the constraint correction into the next
 * step (Verlet's state is (x_k, x_{k-1})), as the Verlet-and-PBD report
 * relies on: "a change in the actual position will result in a change in
 * velocity".  First step from (x0, v0) as verlet (integrators/verlet.c).
 *
 * The projection is not a force: the result is first order at best and
 * does not conserve energy; K = 1 with enough iterations holds the
 * constraint lengths to the projection's residual.  A system without
 * position-based constraints is refused (CL_EINVAL): set pbd.enabled =
 * true.  One force evaluation per step; output times, the finite-state
 * check and tearing after every step: fixed_step.c. */
#include "integrators/verlet.h"

static cl_status verlet_pbd_step(cl_fixed *s, double t, double h,
                                 cl_error *err)
{
    return cl_verlet_step(s, t, h, true, err);
}

static cl_status verlet_pbd_setup(cl_fixed *s, const cl_integrator_opts *o,
                                  cl_error *err)
{
    if (!s->sys->project)
        return cl_error_set(err, CL_EINVAL,
                            "verlet-pbd needs position-based constraints: "
                            "set pbd.enabled = true");
    return cl_verlet_setup(s, o, err);
}

CL_FIXED_INTEGRATOR(cl_integrator_verlet_pbd, "verlet-pbd",
                    &cl_region_projected,
                    "position Verlet with velocity damping vdamp and "
                    "position-based constraints (the Verlet-and-PBD "
                    "report), fixed step dt",
                    3, verlet_pbd_setup, verlet_pbd_step, true);
