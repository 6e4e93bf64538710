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

/* Per constraint (dc->n each): lambda, and alpha~ = 1 / (k h^2), fixed
 * for the run (0 for a hard constraint). */
typedef struct {
    double *lambda, *a_tilde;
} xpbd_state;

static void xpbd_free(void *own)
{
    xpbd_state *x = own;
    free(x->lambda);
    free(x->a_tilde);
    free(x);
}

static cl_status xpbd_setup(cl_cdyn *s, cl_error *err)
{
    size_t n = s->dc->n;
    xpbd_state *x = calloc(1, sizeof *x);
    if (!x)
        return cl_error_set(err, CL_ENOMEM, "xpbd: out of memory");
    s->own = x;
    x->lambda = malloc((n + 1) * sizeof *x->lambda);
    x->a_tilde = malloc((n + 1) * sizeof *x->a_tilde);
    if (!x->lambda || !x->a_tilde)
        return cl_error_set(err, CL_ENOMEM, "xpbd: out of memory");
    for (size_t j = 0; j < n; j++)
        x->a_tilde[j] = 1.0 / (s->dc->stiffness[j] * s->h * s->h);
    return CL_OK;
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
    (void)t, (void)h, (void)err;
    xpbd_state *x = s->own;
    memset(x->lambda, 0, s->dc->n * sizeof *x->lambda);
    for (long it = 0; it < s->iterations; it++)
        for (size_t j = 0; j < s->dc->n; j++)
            xpbd_constraint(s, j, x->a_tilde[j], &x->lambda[j]);
    return CL_OK;
}

static const cl_cdyn_method xpbd_method = {
    .name = "xpbd",
    .default_iterations = 1,
    .setup = xpbd_setup,
    .solve = xpbd_solve,
    .free = xpbd_free,
};

CL_CDYN_INTEGRATOR(cl_integrator_xpbd, xpbd_method, "xpbd",
                   "XPBD (Macklin, Mueller and Chentanez) on the distance "
                   "constraints, compliance 1/k, substeps S and iterations "
                   "K (Small steps), fixed step dt");
