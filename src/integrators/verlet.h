/* The position Verlet step with velocity damping (the Verlet-and-PBD
 * report; docs/integrators.md, 2), shared by verlet (integrators/verlet.c,
 * where the update formulas are derived) and verlet-pbd
 * (integrators/verlet_pbd.c), which adds a projection of the new positions
 * onto position-based constraints before the velocity is formed.
 * Both are cl_fixed methods with 3 work arrays (acceleration, x_{k-1},
 * x_{k+1}) and s->param = vdamp. */
#ifndef CL_VERLET_H
#define CL_VERLET_H

#include <stdbool.h>

#include "core/decls.h"
#include "integrators/fixed_step.h"

CL_BEGIN_DECLS

/* One step from t = t_k to t_k + h: x_{k+1} from the damped Verlet update,
 * then (project) x_{k+1} <- sys->project(t_{k+1}, x_{k+1}), then
 * v_{k+1} = (x_{k+1} - x_k)/h.  A failure leaves x, v at step k. */
cl_status cl_verlet_step(cl_fixed *s, double t, double h, bool project,
                         cl_error *err);

/* Check and take opts->vdamp in [0, 1) (CL_EINVAL otherwise). */
cl_status cl_verlet_setup(cl_fixed *s, const cl_integrator_opts *o,
                          cl_error *err);

CL_END_DECLS

#endif
