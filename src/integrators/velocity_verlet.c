/* velocity-verlet: kick-drift-kick velocity Verlet (leapfrog),
 *
 *   v_{k+1/2} = v_k + h/2 a_k
 *   x_{k+1}   = x_k + h v_{k+1/2}
 *   v*_{k+1}  = v_{k+1/2} + h/2 a_k          (= v_k + h a_k, predictor)
 *   a_{k+1}   = M^-1 f(t_{k+1}, x_{k+1}, v*_{k+1})
 *   v_{k+1}   = v_{k+1/2} + h/2 a_{k+1}
 *
 * h = opts->dt, t_k = t0 + k h, a_0 = M^-1 f(t0, x0, v0).  The
 * acceleration of the step's end is kept for the next step's first kick
 * (one force evaluation per step, plus one for a_0: rhs_evals = steps + 1),
 * except on a system with contact projections, which may move x_k after
 * the step: there a_k is evaluated again (two evaluations per step).
 * Velocity-dependent forces need v_{k+1} before it is known; they are
 * given the explicit predictor v*_{k+1} = v_k + h a_k, an O(h^2) estimate,
 * which keeps the method second order in x and v also with damping (the
 * half-step velocity v_{k+1/2} would be O(h) off and make v first order).
 * For forces independent of v this is exactly the standard velocity Verlet:
 * second order, symplectic, time-reversible, bounded energy error without
 * drift; explicit, stable for h < 2/omega_max.  State, output times and the
 * finite-state check: fixed_step.c; a failing force leaves the state at
 * step k. */
#include "integrators/fixed_step.h"

/* w[0]: a_k, w[1]: x_{k+1}, w[2]: v_{k+1/2}, w[3]: v*_{k+1},
 * w[4]: a_{k+1} (n each). */
static cl_status vv_step(cl_fixed *s, double t, double h, cl_error *err)
{
    double *a = s->w[0], *xn = s->w[1], *vh = s->w[2], *vp = s->w[3];
    double *an = s->w[4];
    /* a_k is the last step's a_{k+1}, unless contact projections may
     * have moved x_k since (then it is evaluated again) */
    cl_status st = s->done == 0 || s->sys->projects
                       ? cl_fixed_accel(s, t, s->x, s->v, a, err)
                       : CL_OK;
    if (st != CL_OK)
        return st;
    for (size_t i = 0; i < s->n; i++) {
        vh[i] = s->v[i] + 0.5 * h * a[i];
        xn[i] = s->x[i] + h * vh[i];
        vp[i] = vh[i] + 0.5 * h * a[i];
    }
    st = cl_fixed_accel(s, t + h, xn, vp, an, err);
    if (st != CL_OK)
        return st;
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = xn[i];
        s->v[i] = vh[i] + 0.5 * h * an[i];
    }
    s->w[0] = an; /* a_{k+1} becomes the next step's a_k */
    s->w[4] = a;
    return CL_OK;
}

CL_FIXED_INTEGRATOR(cl_integrator_velocity_verlet, "velocity-verlet",
                    &cl_region_velocity_verlet,
                    "velocity Verlet (kick-drift-kick), fixed step dt",
                    5, NULL, vv_step, false);
