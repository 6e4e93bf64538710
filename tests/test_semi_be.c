/* semi-be (Baraff-Witkin linearised backward Euler): first-order
 * convergence on spring2 (closed form) with klu, pcg and pcg-jacobi, and on
 * the damped and coupled closed-form systems of testsys.h; one step equals
 * backward Euler exactly on a linear damped oscillator; the reduced `hang`
 * run's statistics; option errors, failing forces, and a linear solver
 * failure (pcg on an indefinite matrix) reported with the time. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "runint.h"
#include "semitest.h"

#define SBE "semi-be"

static void sbe_order(const char *linsol)
{
    st_expect_order(SBE, linsol, NULL, 0.0, 1e-3, 1.0);
}

Test(semi_be, first_order_spring2_klu) { sbe_order("klu"); }
Test(semi_be, first_order_spring2_pcg) { sbe_order("pcg"); }
Test(semi_be, first_order_spring2_pcg_jacobi) { sbe_order("pcg-jacobi"); }

Test(semi_be, first_order_spring2_moving_pin)
{
    const char *const sets[] = {"pins.velocity=0.5,0,0", NULL};
    st_expect_order(SBE, "klu", sets, 0.5, 1e-3, 1.0);
}

Test(semi_be, first_order_damped_and_coupled)
{
    st_expect_ratios_osc_pair(SBE, 2e-3, 1.85, 2.15);
}

/* Linear forces: the linearisation is exact, so one step is backward
 * Euler:  (m + h c + h^2 k) v1 = m v0 - h k x0,  x1 = x0 + h v1. */
Test(semi_be, one_step_is_backward_euler_on_linear_system)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    double x[9], v[9], x0[9], v0[9];
    ri_start(&ts, x0, v0, x, v);
    const double h = 0.05;
    cl_integrator_opts o = {.dt = h};
    ri_run(SBE, &ts.sys, &o, 1.0, 1.0 + h, x, v, NULL);
    for (size_t i = 0; i < ts.n; i++) {
        double m = ts.mass[i], k = ts.k[i], c = ts.c[i];
        double v1 = (m * v0[i] - h * k * x0[i]) / (m + h * c + h * h * k);
        cr_assert_float_eq(v[i], v1, 1e-14 * (1 + fabs(v1)), "v[%zu]", i);
        cr_assert_float_eq(x[i], x0[i] + h * v1, 1e-14, "x[%zu]", i);
    }
    ts_free(&ts);
}

Test(semi_be, hang_statistics_klu) { st_expect_hang_stats(SBE, "klu"); }
Test(semi_be, hang_statistics_pcg) { st_expect_hang_stats(SBE, "pcg"); }
Test(semi_be, registry_row) { st_expect_registry_row(SBE); }

Test(semi_be, rejects_unknown_linsol_and_bad_dt)
{
    st_expect_unknown_linsol(SBE, "umfpack");
    const double bad[] = {0.0, -1e-3, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        st_expect_bad_dt(SBE, bad[i]);
}

static void sbe_expect_fail(int fail, cl_status sys_status, cl_status want)
{
    ts_sys ts;
    double x[3], v[3];
    ri_failing_oscillator(&ts, fail, sys_status, x, v);
    cl_integrator_opts o = {.dt = 0.01};
    void *st = NULL;
    cl_error err = {0};
    const cl_integrator_type *t = ri_find(SBE);
    cr_assert_eq(t->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(t->advance(st, 0.5, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(t->advance(st, 2.0, x, v, &err), want, "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "t = 1"), "%s", err.msg);
    cl_stats s;
    t->stats(st, &s);
    cr_assert_eq(s.steps, 100);
    for (int r = 0; r < 3; r++)
        cr_assert(isfinite(x[r]) && isfinite(v[r]));
    t->free(st);
    ts_free(&ts);
}

Test(semi_be, failing_force_reported)
{
    sbe_expect_fail(TS_FAIL_NAN, CL_OK, CL_EBLOWUP);
    sbe_expect_fail(TS_FAIL_STATUS, CL_EINVAL, CL_EINVAL);
}

/* k = -1e6, h = 0.01: A = m - h^2 k = -99 m < 0, not SPD: pcg refuses
 * (state unchanged), klu solves: backward Euler's v1 = h f(x0) / (1 - h^2
 * 1e6) and x1 = x0 + h v1 = x0 / (1 - h^2 1e6). */
Test(semi_be, linear_solver_failure_reported)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, -1e6);
    double x[3] = {1e-3, 0, 0}, v[3] = {0};
    cl_integrator_opts o = {.dt = 0.01, .linsol = "pcg"};
    void *st = NULL;
    cl_error err = {0};
    const cl_integrator_type *t = ri_find(SBE);
    cr_assert_eq(t->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(t->advance(st, 0.01, x, v, &err), CL_ESOLVER);
    cr_log_info("%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "semi-be: linear solve failed at "
                                       "t = 0 (step 0"), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "not positive definite"), "%s",
                       err.msg);
    cr_assert_eq(x[0], 1e-3);
    t->free(st);
    o.linsol = "klu";
    cr_assert_eq(t->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(t->advance(st, 0.01, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_float_eq(x[0], 1e-3 / (1 - 100), 1e-18, "x1 = %.17g", x[0]);
    cr_assert_float_eq(v[0], 0.01 * 1e3 / (1 - 100), 1e-15, "v1 = %.17g",
                       v[0]);
    t->free(st);
    ts_free(&ts);
}
