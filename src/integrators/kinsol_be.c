/* kinsol-be: fully implicit backward Euler, fixed step h = opts->dt, each
 * step's nonlinear system solved by KINSOL Newton (kinsol_common.h):
 *
 *   x1 = x0 + h v1,
 *   R(v1) = M (v1 - v0) - h f(t1, x0 + h v1, v1) = 0,     t1 = t0 + h,
 *   dR/dv1 = M - h df/dv - h^2 df/dx                 (a = h, b = h^2).
 *
 * In the common form: vb = v0, c = h, alpha = h, ve0 = 0, beta = 1,
 * x1b = x0, alpha1 = h, te = t1.  Predictor v1 = 0 (x0 + h v1 = x0), so
 * that f and its Jacobian are first evaluated at x0: one Newton iteration
 * (newton_maxit = 1) is then Baraff-Witkin's linearised backward Euler
 *   (M - h df/dv - h^2 df/dx) dv = h (f0 + h df/dx v0),   v1 = v0 + dv,
 * with f0, df/dx, df/dv at (x0, v0), exactly when f is affine in v with a
 * v-independent df/dx (and on any linear model).  First order, L-stable:
 * damps every mode, numerically dissipative. */
#include "integrators/kinsol_common.h"

static void kin_prepare_be(cl_kin_step *st)
{
    for (size_t i = 0; i < st->n; i++) {
        st->vb[i] = st->v[i];
        st->ve0[i] = 0.0;
        st->x1b[i] = st->x[i];
        st->pred[i] = 0.0;
    }
}

const cl_kin_scheme cl_kin_scheme_be = {
    .name = "kinsol-be",
    .c = 1.0, .alpha = 1.0, .beta = 1.0, .alpha1 = 1.0, .te = 1.0,
    .prepare = kin_prepare_be,
};

CL_KIN_INTEGRATOR(cl_integrator_kinsol_be, cl_kin_scheme_be, "kinsol-be",
                  &cl_region_be,
                  "backward Euler, fully implicit, KINSOL Newton + linsol "
                  "(default klu), fixed step dt", false);
