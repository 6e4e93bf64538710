/* semi-bdf2 (Choi-Ko semi-implicit BDF2, Jiao, eq. 15): second-order
 * convergence on spring2 (closed form) with klu, pcg and pcg-jacobi, with a
 * pin moving at constant velocity (f depends on t), and on the damped and
 * coupled systems of testsys.h; on a linear damped oscillator it is exactly
 * BDF2 (x' = v, M v' = f) started by one backward-Euler step; its first
 * step is the semi-be step; the reduced `hang` run's statistics; with pcg
 * on 1, 2 and 3 threads bitwise the same steps (vectors of several
 * chunks: every threaded part of a step); options and failures. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "runint.h"
#include "semitest.h"

#define SBDF2 "semi-bdf2"

static void sbdf2_order(const char *linsol)
{
    st_expect_order(SBDF2, linsol, NULL, 0.0, 2e-3, 2.0);
}

Test(semi_bdf2, second_order_spring2_klu) { sbdf2_order("klu"); }
Test(semi_bdf2, second_order_spring2_pcg) { sbdf2_order("pcg"); }
Test(semi_bdf2, second_order_spring2_pcg_jacobi)
{
    sbdf2_order("pcg-jacobi");
}

/* f(t, x, v) depends on t through the pin: second order needs f at
 * t_{n+1} (see semi_bdf2.c). */
Test(semi_bdf2, second_order_spring2_moving_pin)
{
    const char *const sets[] = {"pins.velocity=0.5,0,0", NULL};
    st_expect_order(SBDF2, "klu", sets, 0.5, 2e-3, 2.0);
}

Test(semi_bdf2, second_order_damped_and_coupled)
{
    st_expect_ratios_osc_pair(SBDF2, 4e-3, 3.7, 4.3);
}

/* BDF2 for m x'' = -k x - c x' in first-order form, from (x0, x1, v0, v1):
 *   (m + 2h/3 c + 4h^2/9 k) v2 = m (4 v1 - v0)/3 - 2h/3 k (4 x1 - x0)/3,
 *   x2 = (4 x1 - x0)/3 + 2h/3 v2. */
static void bdf2_ref(double m, double k, double c, double h, double *x,
                     double *v)
{
    double v2 = (m * (4 * v[1] - v[0]) / 3 -
                 2 * h / 3 * k * (4 * x[1] - x[0]) / 3) /
                (m + 2 * h / 3 * c + 4 * h * h / 9 * k);
    double x2 = (4 * x[1] - x[0]) / 3 + 2 * h / 3 * v2;
    x[0] = x[1];
    v[0] = v[1];
    x[1] = x2;
    v[1] = v2;
}

Test(semi_bdf2, exact_bdf2_on_linear_system)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    double x[9], v[9], x0[9], v0[9];
    ri_start(&ts, x0, v0, x, v);
    const double h = 0.05;
    const int nsteps = 4;
    cl_integrator_opts o = {.dt = h};
    ri_run(SBDF2, &ts.sys, &o, 0.0, nsteps * h, x, v, NULL);
    for (size_t i = 0; i < ts.n; i++) {
        double m = ts.mass[i], k = ts.k[i], c = ts.c[i];
        double xr[2] = {x0[i], 0}, vr[2] = {v0[i], 0};
        vr[1] = (m * v0[i] - h * k * x0[i]) / (m + h * c + h * h * k);
        xr[1] = x0[i] + h * vr[1];
        for (int s = 1; s < nsteps; s++)
            bdf2_ref(m, k, c, h, xr, vr);
        cr_assert_float_eq(x[i], xr[1], 1e-13, "x[%zu]: %.17g vs %.17g", i,
                           x[i], xr[1]);
        cr_assert_float_eq(v[i], vr[1], 1e-13 * (1 + fabs(vr[1])),
                           "v[%zu]: %.17g vs %.17g", i, v[i], vr[1]);
    }
    ts_free(&ts);
}

Test(semi_bdf2, first_step_is_semi_be)
{
    s2_problem p;
    const char *const sets[] = {"init.velocity=1,2,0.5", NULL};
    st_load(&p, sets);
    double xb[3], vb[3], xe[3], ve[3];
    memcpy(xb, p.x0, sizeof xb);
    memcpy(vb, p.v0, sizeof vb);
    memcpy(xe, p.x0, sizeof xe);
    memcpy(ve, p.v0, sizeof ve);
    cl_integrator_opts o = {.dt = 0.01};
    ri_run(SBDF2, p.sys, &o, 0.0, 0.01, xb, vb, NULL);
    ri_run("semi-be", p.sys, &o, 0.0, 0.01, xe, ve, NULL);
    cr_assert_arr_eq(xb, xe, sizeof xb);
    cr_assert_arr_eq(vb, ve, sizeof vb);
    s2_free(&p);
}

Test(semi_bdf2, hang_statistics_klu) { st_expect_hang_stats(SBDF2, "klu"); }
Test(semi_bdf2, hang_statistics_pcg) { st_expect_hang_stats(SBDF2, "pcg"); }
/* hang at n = 56 (9402 unknowns: two chunks of the vector operations,
 * linalg/nvec.h), 20 steps with pcg: forces, Jacobians, the
 * Newton matrix, the preconditioner and every PCG operation threaded;
 * the states and the iteration counts agree bit for bit. */
Test(semi_bdf2, pcg_threads_bitwise)
{
    double *x1, *v1, *xt, *vt;
    size_t n;
    cl_stats s1 = {0}, st = {0};
    st_hang_run(SBDF2, "pcg", "cloth.n=56", 1, 0.02, &x1, &v1, &n, &s1);
    cr_assert_eq(n, 3 * (56 * 56 - 2));
    cr_assert_gt(s1.lin_iters, 20);
    for (int t = 2; t <= 3; t++) {
        st_hang_run(SBDF2, "pcg", "cloth.n=56", t, 0.02, &xt, &vt, &n, &st);
        cr_assert_eq(memcmp(x1, xt, n * sizeof *xt), 0, "%d threads", t);
        cr_assert_eq(memcmp(v1, vt, n * sizeof *vt), 0, "%d threads", t);
        cr_assert_eq(st.lin_iters, s1.lin_iters);
        free(xt);
        free(vt);
    }
    free(x1);
    free(v1);
}

Test(semi_bdf2, registry_row) { st_expect_registry_row(SBDF2); }

Test(semi_bdf2, rejects_unknown_linsol)
{
    st_expect_unknown_linsol(SBDF2, "superlu");
    st_expect_bad_dt(SBDF2, -1.0);
}

Test(semi_bdf2, failing_force_reported_after_start)
{
    ts_sys ts;
    double x[3], v[3];
    ri_failing_oscillator_at(&ts, TS_FAIL_NAN, CL_OK, 0.495, x, v);
    cl_integrator_opts o = {.dt = 0.01};
    void *st = NULL;
    cl_error err = {0};
    const cl_integrator_type *t = ri_find(SBDF2);
    cr_assert_eq(t->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(t->advance(st, 1.0, x, v, &err), CL_EBLOWUP);
    cr_assert_not_null(strstr(err.msg, "not finite"), "%s", err.msg);
    cl_stats s;
    t->stats(st, &s);
    /* BDF2 evaluates f at t_{n+1}: step 49 -> 50 already sees t = 0.5 */
    cr_assert_eq(s.steps, 49);
    t->free(st);
    ts_free(&ts);
}
