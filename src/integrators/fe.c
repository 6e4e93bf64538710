/* fe: forward (explicit) Euler on the first-order form y = (x, v):
 *
 *   x_{k+1} = x_k + h v_k
 *   v_{k+1} = v_k + h M^-1 f(t_k, x_k, v_k),   t_k = t0 + k h,  h = opts->dt.
 *
 * First order.  Not symplectic: on an undamped oscillator of frequency w
 * the energy grows by exactly (1 + h^2 w^2) per step, so it is unstable for
 * every h > 0 without damping; included as the baseline every other method
 * is compared with.  One force evaluation per step (rhs_evals = steps).
 * State, output times and the finite-state check: fixed_step.c. */
#include "integrators/fixed_step.h"

/* w[0]: acceleration M^-1 f (n) */
static cl_status fe_step(cl_fixed *s, double t, double h, cl_error *err)
{
    double *a = s->w[0];
    cl_status st = cl_fixed_accel(s, t, s->x, s->v, a, err);
    if (st != CL_OK)
        return st;
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] += h * s->v[i];
        s->v[i] += h * a[i];
    }
    return CL_OK;
}

CL_FIXED_INTEGRATOR(cl_integrator_fe, "fe",
                    &cl_region_taylor1,
                    "forward Euler, fixed step dt",
                    1, NULL, fe_step, false);
