/* kinsol-be: first order on spring2 (dt = 1e-3 halved 4 times, also with
 * a moving pin), and one Newton iteration (newton_maxit = 1) equals
 * Baraff-Witkin's linearised backward Euler step on a nonlinear, damped
 * spring2 (kinsol_test.h). */
#include <criterion/criterion.h>

#include "kinsol_test.h"

Test(kinsol_be, first_order_on_spring2)
{
    kt_check_order("kinsol-be", 1.0, 1e-3);
}

/* (M - h D - h^2 K) dv = h (f0 + h K v0), v1 = v0 + dv, x1 = x0 + h v1. */
static void bw_step(const s2_problem *p, double t, double h, double *x,
                    double *v, double *xp, double *vp, int k)
{
    double f[3], K[9], D[9], A[9], rhs[3], dv[3];
    (void)xp, (void)vp, (void)k;
    kt_linearise(p, t, x, v, f, K, D);
    kt_newton_matrix(p, h, h * h, K, D, A);
    for (int r = 0; r < 3; r++) {
        rhs[r] = f[r];
        for (int c = 0; c < 3; c++)
            rhs[r] += h * K[3 * r + c] * v[c];
        rhs[r] *= h;
    }
    kt_solve3(A, rhs, dv);
    for (int r = 0; r < 3; r++) {
        v[r] += dv[r];
        x[r] += h * v[r];
    }
}

Test(kinsol_be, one_iteration_is_baraff_witkin)
{
    kt_check_one_iteration("kinsol-be", bw_step);
}
