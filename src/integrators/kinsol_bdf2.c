/* kinsol-bdf2: fully implicit BDF2, fixed step h = opts->dt, each step's
 * nonlinear system solved by KINSOL Newton (kinsol_common.h).
 *
 * Derivation.  BDF2 with constant step for y' = F(y) reads
 *   y1 - (4/3) y0 + (1/3) y_{-1} = (2h/3) F(y1).
 * Applied to x' = v and M v' = f(t, x, v):
 *   x1 = (4 x0 - x_{-1})/3 + (2h/3) v1,                              (1)
 *   M (3 v1 - 4 v0 + v_{-1}) = 2h f(t1, x1, v1),     t1 = t0 + h.    (2)
 * Eliminating x1 with (1) and dividing (2) by 3 gives the velocity form
 *   R(v1) = M (v1 - (4 v0 - v_{-1})/3)
 *           - (2h/3) f(t1, (4 x0 - x_{-1})/3 + (2h/3) v1, v1) = 0,
 * whose Jacobian, with dx1/dv1 = (2h/3) I, is
 *   dR/dv1 = M - (2h/3) df/dv - (2h/3)^2 df/dx
 *          = M - (2h/3) df/dv - (4h^2/9) df/dx      (a = 2h/3, b = 4h^2/9),
 * M times the matrix of Jiao's eq. (15).  Common form:
 * vb = (4 v0 - v_{-1})/3, c = 2h/3, x1b = (4 x0 - x_{-1})/3,
 * alpha = alpha1 = 2h/3, ve0 = 0, beta = 1, te = t1.
 *
 * Predictor.  v1 = (x_{-1} - x0)/(2h), the v1 for which (1) gives
 * x1 = x0.  With dx = x1 - x0, (1) is v1 = (3 dx - (x0 - x_{-1}))/(2h),
 * and one Newton step from there linearises f about x0:
 *   f(x1, v1) ~ f(x0, v^(0)) + df/dx dx + df/dv (v1 - v^(0))
 *             = f0 + df/dx dx + df/dv (v1 - v0)
 * when f is affine in v with a v-independent df/dx (f0 and the Jacobians
 * at (x0, v0)).  Substituting v1 and the linearised f into
 *   dx = (x0 - x_{-1})/3 + (2h/9)(4 v0 - v_{-1}) + (4h^2/9) M^-1 f1
 * (which is (1) with (2) inserted) gives exactly eq. (15):
 *   (I - (2h/3) M^-1 df/dv - (4h^2/9) M^-1 df/dx) dx
 *     = (x0 - x_{-1})/3 + (h/9)(8 v0 - 2 v_{-1})
 *       + (4h^2/9) M^-1 (f0 - df/dv v0) - (2h/9) M^-1 df/dv (x0 - x_{-1}),
 * and v1 = (3 x1 - 4 x0 + x_{-1})/(2h), the velocity semi-bdf2 takes.  So
 * newton_maxit = 1 reproduces semi-bdf2 (exactly on such forces and on
 * every linear model).
 *
 * Start: the first step (no x_{-1} yet) is kinsol-be's backward Euler step
 * (predictor v1 = 0), as semi-bdf2 starts with semi-be.  Second order,
 * A-stable and L-stable (damps high frequencies, less than backward
 * Euler). */
#include "integrators/kinsol_common.h"

static void kin_prepare_bdf2(cl_kin_step *st)
{
    double h = st->h;
    for (size_t i = 0; i < st->n; i++) {
        double x = st->x[i], xp = st->xp[i];
        st->vb[i] = (4.0 * st->v[i] - st->vp[i]) / 3.0;
        st->ve0[i] = 0.0;
        st->x1b[i] = (4.0 * x - xp) / 3.0;
        st->pred[i] = (xp - x) / (2.0 * h);
    }
}

static const cl_kin_scheme kin_bdf2 = {
    .name = "kinsol-bdf2",
    .c = 2.0 / 3.0, .alpha = 2.0 / 3.0, .beta = 1.0, .alpha1 = 2.0 / 3.0,
    .te = 1.0,
    .start = &cl_kin_scheme_be,
    .prepare = kin_prepare_bdf2,
};

CL_KIN_INTEGRATOR(cl_integrator_kinsol_bdf2, kin_bdf2, "kinsol-bdf2",
                  &cl_region_bdf2,
                  "BDF2 (first step backward Euler), fully implicit, KINSOL "
                  "Newton + linsol (default klu), fixed step dt", false);
