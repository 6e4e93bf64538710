/* symplectic-euler-x: semi-implicit (symplectic) Euler, position first, as
 * in Zischg, Chea and Aigner, eqs. 1-7 (docs/integrators.md, 2): positions
 * move with the old velocity, the forces are evaluated "considering the
 * already updated values from x(t+h)" with the damping taken at the old
 * velocity v(t), then the velocity is updated:
 *
 *   x_{k+1} = x_k + h v_k                                   (eq. 1)
 *   v_{k+1} = v_k + h M^-1 f(t_{k+1}, x_{k+1}, v_k)         (eqs. 2-7)
 *
 * t_k = t0 + k h, h = opts->dt.  The force is evaluated at t_{k+1}, the
 * time of the positions it sees (so moving pins stay consistent with
 * x_{k+1}).  First order; the adjoint of symplectic-euler (v first): for
 * conservative forces the composition of a half step of each is velocity
 * Verlet.  Symplectic, bounded energy error without drift; explicit, stable
 * for h below ~2/omega_max.  One force evaluation per step.  State, output
 * times and the finite-state check: fixed_step.c; a failing force leaves
 * the state at step k. */
#include "integrators/fixed_step.h"

/* w[0]: acceleration M^-1 f, w[1]: x_{k+1} (n each); the state is
 * written only once the force has been evaluated. */
static cl_status sex_step(cl_fixed *s, double t, double h, cl_error *err)
{
    double *a = s->w[0], *xn = s->w[1];
    for (size_t i = 0; i < s->n; i++)
        xn[i] = s->x[i] + h * s->v[i];
    cl_status st = cl_fixed_accel(s, t + h, xn, s->v, a, err);
    if (st != CL_OK)
        return st;
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = xn[i];
        s->v[i] += h * a[i];
    }
    return CL_OK;
}

CL_FIXED_INTEGRATOR(cl_integrator_symplectic_euler_x, "symplectic-euler-x",
                    &cl_region_symplectic,
                    "symplectic Euler, x first then v (Zischg, Chea and "
                    "Aigner), fixed step dt",
                    2, NULL, sex_step, false);
