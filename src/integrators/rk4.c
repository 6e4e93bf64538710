/* rk4: the classical fourth-order Runge-Kutta method on y = (x, v),
 * y' = F(t, y) = (v, M^-1 f(t, x, v)),  h = opts->dt,  t_k = t0 + k h:
 *
 *   stage j = 1..4 at c = (0, 1/2, 1/2, 1):
 *     X_1 = x_k,                 V_1 = v_k
 *     X_j = x_k + c_j h V_{j-1}, V_j = v_k + c_j h A_{j-1}     (j > 1)
 *     A_j = M^-1 f(t_k + c_j h, X_j, V_j)
 *   x_{k+1} = x_k + h/6 (V_1 + 2 V_2 + 2 V_3 + V_4)
 *   v_{k+1} = v_k + h/6 (A_1 + 2 A_2 + 2 A_3 + A_4)
 *
 * Fourth order, not symplectic: on an undamped oscillator the energy
 * decays by |R(i h w)|^2 = 1 - (h w)^6/72 + (h w)^8/576 per step; explicit,
 * stable for h w < 2.83 on oscillators.  Four force evaluations per step
 * (rhs_evals = 4 steps).  State, output times and the finite-state check:
 * fixed_step.c; the state is written only at the end of a step. */
#include "integrators/fixed_step.h"

static const double rk4_c[4] = {0.0, 0.5, 0.5, 1.0};
static const double rk4_b[4] = {1.0 / 6, 2.0 / 6, 2.0 / 6, 1.0 / 6};

/* w[0], w[1]: stage X, V; w[2]: stage A; w[3], w[4]: sums of b_j V_j and
 * b_j A_j (n each). */
static cl_status rk4_step(cl_fixed *s, double t, double h, cl_error *err)
{
    double *xs = s->w[0], *vs = s->w[1], *as = s->w[2];
    double *sx = s->w[3], *sv = s->w[4];
    for (size_t i = 0; i < s->n; i++) {
        xs[i] = s->x[i];
        vs[i] = s->v[i];
        sx[i] = sv[i] = 0.0;
    }
    for (int j = 0; j < 4; j++) {
        cl_status st = cl_fixed_accel(s, t + rk4_c[j] * h, xs, vs, as, err);
        if (st != CL_OK)
            return st;
        double cn = j < 3 ? rk4_c[j + 1] * h : 0.0;
        for (size_t i = 0; i < s->n; i++) {
            sx[i] += rk4_b[j] * vs[i];
            sv[i] += rk4_b[j] * as[i];
            xs[i] = s->x[i] + cn * vs[i];
            vs[i] = s->v[i] + cn * as[i];
        }
    }
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] += h * sx[i];
        s->v[i] += h * sv[i];
    }
    return CL_OK;
}

CL_FIXED_INTEGRATOR(cl_integrator_rk4, "rk4",
                    &cl_region_taylor4,
                    "classical Runge-Kutta 4, fixed step dt",
                    5, NULL, rk4_step, false);
