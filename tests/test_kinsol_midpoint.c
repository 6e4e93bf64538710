/* kinsol-midpoint: second order on spring2 (dt = 1e-2 halved 4 times, also
 * with a moving pin: f is evaluated at t + h/2); energy conserved on the
 * undamped linear spring (the midpoint rule keeps quadratic invariants);
 * one Newton iteration (newton_maxit = 1) equals the linearly implicit
 * midpoint rule on a nonlinear, damped spring2 (kinsol_test.h). */
#include <criterion/criterion.h>

#include "kinsol_test.h"

Test(kinsol_midpoint, second_order_on_spring2)
{
    kt_check_order("kinsol-midpoint", 2.0, 1e-2);
}

Test(kinsol_midpoint, energy_conserved_on_linear_spring)
{
    s2_problem p;
    s2_load(&p);
    const cl_integrator_type *it = cl_integrator_find("kinsol-midpoint");
    cl_integrator_opts o = {.dt = 0.05};
    void *st = kt_create("kinsol-midpoint", &p, &o);
    cl_error err = {0};
    cl_energy e0, e;
    double x[3], v[3], worst = 0;
    cr_assert_eq(p.sys->energy(p.sys->data, 0, p.x0, p.v0, &e0), CL_OK);
    for (int k = 1; k <= 40; k++) {
        cr_assert_eq(it->advance(st, 0.5 * k, x, v, &err), CL_OK);
        cr_assert_eq(p.sys->energy(p.sys->data, 0.5 * k, x, v, &e), CL_OK);
        worst = fmax(worst, fabs(e.total - e0.total) / e0.total);
    }
    cr_log_info("kinsol-midpoint: relative energy error over 400 steps "
                "(w h = 0.5): %.3e", worst);
    cr_assert_lt(worst, 1e-12);
    it->free(st);
    s2_free(&p);
}

/* (M - (h/2) D - (h^2/4) K) dv = h f0 + (h^2/2) K v0, v1 = v0 + dv,
 * x1 = x0 + h (v0 + v1)/2 (f0, K, D at t0 + h/2, x0, v0). */
static void limp_step(const s2_problem *p, double t, double h, double *x,
                      double *v, double *xp, double *vp, int k)
{
    double f[3], K[9], D[9], A[9], rhs[3], dv[3];
    (void)xp, (void)vp, (void)k;
    kt_linearise(p, t + h / 2, x, v, f, K, D);
    kt_newton_matrix(p, h / 2, h * h / 4, K, D, A);
    for (int r = 0; r < 3; r++) {
        rhs[r] = h * f[r];
        for (int c = 0; c < 3; c++)
            rhs[r] += h * h / 2 * K[3 * r + c] * v[c];
    }
    kt_solve3(A, rhs, dv);
    for (int r = 0; r < 3; r++) {
        x[r] += h * (v[r] + dv[r] / 2);
        v[r] += dv[r];
    }
}

Test(kinsol_midpoint, one_iteration_is_linearly_implicit_midpoint)
{
    kt_check_one_iteration("kinsol-midpoint", limp_step);
}
