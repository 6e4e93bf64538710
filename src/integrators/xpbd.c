/* xpbd: extended position-based dynamics (Macklin, Mueller and Chentanez,
 * "XPBD: position-based simulation of compliant constrained dynamics",
 * MIG 2016) with substepping (Macklin et al., "Small steps in physics
 * simulation", SCA 2019); docs/integrators.md, 9.
 *
 * Every distance constraint C_j(x) = |x_a - x_b| - L_j of the system
 * (system/system.h, cl_distances) has compliance alpha_j = 1 / k_j, so
 * that its potential C_j^2 / (2 alpha_j) is the spring energy
 * k_j (d - L_j)^2 / 2 of the force model (0 for a hard pbd constraint).
 * Each substep of h (constraint_common.h: predictor with the other forces,
 * anchors at t + h) starts from lambda = 0 and makes K Gauss-Seidel sweeps
 * over the constraints, each one (XPBD eqs. 17-18, with
 * alpha~ = alpha / h^2 and n = (x_a - x_b) / |x_a - x_b|):
 *
 *   dlambda = (-C_j - alpha~ lambda_j) / (w_a + w_b + alpha~)
 *   x_a += w_a dlambda n,  x_b -= w_b dlambda n,  lambda_j += dlambda,
 *
 * w the inverse masses (0 for an anchor).  As K grows the substep
 * converges to the minimiser of |x - y|_M^2 / (2 h^2) + sum_j
 * C_j^2 / (2 alpha_j), the backward Euler step of the springs with the
 * other forces explicit (XPBD, section 4: the first-order
 * linearisation's error is in the dropped geometric stiffness term).
 * Default K = 1 (Small steps: many substeps of one iteration). */
#include "integrators/constraint_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* lambda per constraint (dc->n) */
static cl_status xpbd_setup(cl_cdyn *s, cl_error *err)
{
    s->own = calloc(s->dc->n + 1, sizeof(double));
    return s->own ? CL_OK : cl_error_set(err, CL_ENOMEM, "xpbd: out of "
                                         "memory");
}

/* One constraint update (the equations above); a_tilde = alpha / h^2. */
static void xpbd_constraint(cl_cdyn *s, size_t j, double a_tilde,
                            double *lambda)
{
    const int *e = s->dc->end[j];
    double *xa = cl_cdyn_pos(s, e[0]), *xb = cl_cdyn_pos(s, e[1]);
    double wa = cl_cdyn_w(s, e[0]), wb = cl_cdyn_w(s, e[1]);
    double dx[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
    double d = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    double den = wa + wb + a_tilde;
    if (!(d > 0) || !(den > 0))
        return;
    double dl = (-(d - s->dc->rest[j]) - a_tilde * *lambda) / den;
    *lambda += dl;
    for (int i = 0; i < 3; i++) {
        double c = dl * dx[i] / d;
        xa[i] += wa * c;
        xb[i] -= wb * c;
    }
}

static cl_status xpbd_solve(cl_cdyn *s, double t, double h, cl_error *err)
{
    (void)t, (void)err;
    double *lambda = s->own;
    memset(lambda, 0, s->dc->n * sizeof *lambda);
    for (long it = 0; it < s->iterations; it++)
        for (size_t j = 0; j < s->dc->n; j++)
            xpbd_constraint(s, j, 1.0 / (s->dc->stiffness[j] * h * h),
                            &lambda[j]);
    return CL_OK;
}

static const cl_cdyn_method xpbd_method = {
    .name = "xpbd",
    .default_iterations = 1,
    .setup = xpbd_setup,
    .solve = xpbd_solve,
    .free = free,
};

CL_CDYN_INTEGRATOR(cl_integrator_xpbd, xpbd_method, "xpbd",
                   "XPBD (Macklin, Mueller and Chentanez) on the distance "
                   "constraints, compliance 1/k, substeps S and iterations "
                   "K (Small steps), fixed step dt");
