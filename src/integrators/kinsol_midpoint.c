/* kinsol-midpoint: fully implicit midpoint rule, fixed step h = opts->dt,
 * each step's nonlinear system solved by KINSOL Newton (kinsol_common.h):
 *
 *   x1 = x0 + h (v0 + v1)/2,
 *   R(v1) = M (v1 - v0) - h f(t0 + h/2, (x0 + x1)/2, (v0 + v1)/2) = 0,
 *   (x0 + x1)/2 = x0 + (h/4)(v0 + v1),
 *   dR/dv1 = M - (h/2) df/dv - (h^2/4) df/dx     (a = h/2, b = h^2/4).
 *
 * In the common form: vb = v0, c = h, alpha = h/4, ve0 = v0/2, beta = 1/2,
 * x1b = x0 + (h/2) v0, alpha1 = h/2, te = t0 + h/2.  Predictor v1 = -v0
 * (x0 + (h/4)(v0 + v1) = x0): the evaluation point is then (x0, 0), so
 * one Newton iteration is the linearly implicit midpoint rule
 *   (M - (h/2) df/dv - (h^2/4) df/dx) dv = h f0 + (h^2/2) df/dx v0,
 *   v1 = v0 + dv   (f0, df/dx, df/dv at (t0 + h/2, x0, v0)),
 * exactly when f is affine in v with a v-independent df/dx.  Second
 * order, symmetric, A-stable without damping (energy of linear
 * oscillators conserved; quadratic invariants conserved). */
#include "integrators/kinsol_common.h"

static void kin_prepare_midpoint(cl_kin_step *st)
{
    double h = st->h;
    for (size_t i = 0; i < st->n; i++) {
        double x = st->x[i], v = st->v[i];
        st->vb[i] = v;
        st->ve0[i] = 0.5 * v;
        st->x1b[i] = x + 0.5 * h * v;
        st->pred[i] = -v;
    }
}

static const cl_kin_scheme kin_midpoint = {
    .name = "kinsol-midpoint",
    .c = 1.0, .alpha = 0.25, .beta = 0.5, .alpha1 = 0.5, .te = 0.5,
    .prepare = kin_prepare_midpoint,
};

CL_KIN_INTEGRATOR(cl_integrator_kinsol_midpoint, kin_midpoint,
                  "kinsol-midpoint",
                  &cl_region_midpoint,
                  "implicit midpoint rule, KINSOL Newton + linsol (default "
                  "klu), fixed step dt", false);
