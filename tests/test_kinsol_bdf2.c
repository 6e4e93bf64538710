/* kinsol-bdf2: second order on spring2 (dt = 5e-3 halved 4 times, also
 * with a moving pin); its first step is kinsol-be's; one Newton iteration
 * (newton_maxit = 1) per step equals Jiao's eq. (15) (after a
 * Baraff-Witkin first step) on a nonlinear, damped spring2
 * (kinsol_test.h). */
#include <criterion/criterion.h>

#include "kinsol_test.h"

Test(kinsol_bdf2, second_order_on_spring2)
{
    kt_check_order("kinsol-bdf2", 2.0, 5e-3);
}

Test(kinsol_bdf2, first_step_is_backward_euler)
{
    s2_problem p;
    const char *const sets[] = {"init.velocity=1,0.8,0", NULL};
    st_load(&p, sets);
    cl_integrator_opts o = {.dt = 0.05};
    double x[2][3], v[2][3];
    const char *names[2] = {"kinsol-be", "kinsol-bdf2"};
    cl_stats s;
    for (int k = 0; k < 2; k++)
        kt_run(names[k], &p, &o, 0.05, x[k], v[k], &s);
    cr_assert_eq(kt_diff3(x[0], x[1]) + kt_diff3(v[0], v[1]), 0.0);
    s2_free(&p);
}

/* Step 0: Baraff-Witkin.  Later steps, eq. (15) times M:
 *   (M - (2h/3) D - (4h^2/9) K) dx = M (x0 - xp)/3 + (h/9) M (8 v0 - 2 vp)
 *       + (4h^2/9)(f0 - D v0) - (2h/9) D (x0 - xp),
 *   x1 = x0 + dx,  v1 = (3 x1 - 4 x0 + xp)/(2h). */
static void eq15_step(const s2_problem *p, double t, double h, double *x,
                      double *v, double *xp, double *vp, int k)
{
    double f[3], K[9], D[9], A[9], rhs[3], y[3];
    const double *m = p->sys->mass;
    kt_linearise(p, t, x, v, f, K, D);
    if (k == 0) {
        kt_newton_matrix(p, h, h * h, K, D, A);
        for (int r = 0; r < 3; r++)
            rhs[r] = h * (f[r] + h * (K[3 * r] * v[0] + K[3 * r + 1] * v[1] +
                                      K[3 * r + 2] * v[2]));
    } else {
        kt_newton_matrix(p, 2 * h / 3, 4 * h * h / 9, K, D, A);
        for (int r = 0; r < 3; r++) {
            double Dv = 0, Ddx = 0;
            for (int c = 0; c < 3; c++) {
                Dv += D[3 * r + c] * v[c];
                Ddx += D[3 * r + c] * (x[c] - xp[c]);
            }
            rhs[r] = m[r] * (x[r] - xp[r]) / 3 +
                     h / 9 * m[r] * (8 * v[r] - 2 * vp[r]) +
                     4 * h * h / 9 * (f[r] - Dv) - 2 * h / 9 * Ddx;
        }
    }
    kt_solve3(A, rhs, y);
    for (int r = 0; r < 3; r++) {
        double x1 = k == 0 ? x[r] + h * (v[r] + y[r]) : x[r] + y[r];
        double v1 = k == 0 ? v[r] + y[r]
                           : (3 * x1 - 4 * x[r] + xp[r]) / (2 * h);
        xp[r] = x[r];
        vp[r] = v[r];
        x[r] = x1;
        v[r] = v1;
    }
}

Test(kinsol_bdf2, one_iteration_is_eq15)
{
    kt_check_one_iteration("kinsol-bdf2", eq15_step);
}
