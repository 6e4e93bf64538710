/* symplectic-euler: semi-implicit (symplectic) Euler, velocity first, as in
 * Jiao's own code (docs/integrators.md, 2):
 *
 *   v_{k+1} = v_k + h M^-1 f(t_k, x_k, v_k)
 *   x_{k+1} = x_k + h v_{k+1},        t_k = t0 + k h,  h = opts->dt > 0.
 *
 * First order; symplectic for conservative forces (bounded energy error,
 * O(h), no drift); explicit, so stable only for h below ~2/omega_max.
 * One force evaluation per step (rhs_evals = steps).  State, step counting,
 * output times (whole multiples of h from t0) and the finite-state check
 * (CL_EBLOWUP with the time and the step) are the shared fixed-step
 * plumbing of integrators/fixed_step.c.  Its mirror image, x first, is
 * symplectic-euler-x (symplectic_euler_x.c). */
#include "integrators/fixed_step.h"

/* v += h a with a = f M^-1 (im: the inverse masses), then x += h v. */
static void se_update(size_t n, double h, const double *restrict f,
                      const double *restrict im, double *restrict x,
                      double *restrict v)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++) {
        v[i] += h * (f[i] * im[i]);
        x[i] += h * v[i];
    }
}

/* w[0]: the force f (n) */
static cl_status se_step(cl_fixed *s, double t, double h, cl_error *err)
{
    double *f = s->w[0];
    cl_status st = cl_fixed_force(s, t, s->x, s->v, f, err);
    if (st != CL_OK)
        return st;
    se_update(s->n, h, f, s->inv_mass, s->x, s->v);
    return CL_OK;
}

CL_FIXED_INTEGRATOR(cl_integrator_symplectic_euler, "symplectic-euler",
                    &cl_region_symplectic,
                    "symplectic Euler, v first then x (Jiao's own code), "
                    "fixed step dt",
                    1, NULL, se_step, false);
