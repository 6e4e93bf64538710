/* symplectic-euler against closed-form oscillators: first-order convergence
 * (error ratio ~2 when dt halves), bounded energy error without drift over
 * 1000 periods, exact step counting, rejected dt and output times, and
 * CL_EBLOWUP for NaN forces and for the explicit instability (h omega > 2). */
#include <criterion/criterion.h>

#include <math.h>

#include "integrators/integrator.h"
#include "runint.h"
#include "testsys.h"


static const cl_integrator_type *se(void)
{
    const cl_integrator_type *t = cl_integrator_find("symplectic-euler");
    cr_assert_not_null(t);
    return t;
}

/* Max error in x and v at T against the exact solution. */
static double run_error(ts_sys *ts, double dt, double T)
{
    double x0[12], v0[12], x[12], v[12], xe[12], ve[12];
    ts_initial(ts, x0, v0);
    cl_integrator_opts o = {.dt = dt};
    void *st;
    cl_error err;
    cr_assert_eq(se()->create(&ts->sys, &o, 0.0, x0, v0, &st, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(se()->advance(st, T, x, v, &err), CL_OK, "%s", err.msg);
    se()->free(st);
    ts_exact(ts, x0, v0, T, xe, ve);
    return fmax(ts_maxdiff(x, xe, ts->n), ts_maxdiff(v, ve, ts->n));
}

Test(symplectic_euler, first_order_convergence)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    double e[4];
    for (int i = 0; i < 4; i++)
        e[i] = run_error(&ts, 0.01 / (double)(1 << i), 2.0);
    for (int i = 0; i < 3; i++) {
        double ratio = e[i] / e[i + 1];
        cr_log_info("symplectic-euler dt=%g err=%.3e ratio=%.4f",
                    0.01 / (double)(1 << i), e[i], ratio);
        cr_assert(ratio > 1.85 && ratio < 2.15, "ratio %g (errors %g, %g)",
                  ratio, e[i], e[i + 1]);
    }
    cr_assert_lt(e[3], 0.01);
    ts_free(&ts);
}

Test(symplectic_euler, coupled_pair_converges)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    double e1 = run_error(&ts, 2e-3, 3.0), e2 = run_error(&ts, 1e-3, 3.0);
    cr_assert(e1 / e2 > 1.85 && e1 / e2 < 2.15, "errors %g %g", e1, e2);
    cr_assert_lt(e2, 0.02);
    ts_free(&ts);
}

/* Undamped oscillator, omega = 1, h = 0.01, 1000 periods: the energy
 * error is first order in h omega (2.05e-3 relative measured) and does
 * not drift. */
Test(symplectic_euler, bounded_energy_no_drift)
{
    ri_expect_bounded_energy("symplectic-euler", 0.01, 3e-3);
}

Test(symplectic_euler, counts_steps_exactly)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3], v[3];
    ts_initial(&ts, x, v);
    cl_integrator_opts o = {.dt = 0.1};
    void *st;
    cl_error err;
    cl_stats s;
    cr_assert_eq(se()->create(&ts.sys, &o, 2.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(se()->advance(st, 2.3, x, v, &err), CL_OK, "%s", err.msg);
    se()->stats(st, &s);
    cr_assert_eq(s.steps, 3);
    cr_assert_eq(se()->advance(st, 2.3, x, v, &err), CL_OK);
    cr_assert_eq(se()->advance(st, 3.0, x, v, &err), CL_OK);
    se()->stats(st, &s);
    cr_assert_eq(s.steps, 10);
    cr_assert_eq(s.rhs_evals, 10);
    cr_assert_eq(s.jac_evals + s.lin_setups + s.lin_solves, 0);
    cr_assert_eq(se()->advance(st, 3.05, x, v, &err), CL_EINVAL);
    cr_assert_eq(se()->advance(st, 2.5, x, v, &err), CL_EINVAL);
    se()->stats(st, &s);
    cr_assert_eq(s.steps, 10);
    se()->free(st);
    ts_free(&ts);
}

Test(symplectic_euler, rejects_bad_dt)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3] = {0}, v[3] = {0};
    const double bad[] = {0.0, -1e-3, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cl_integrator_opts o = {.dt = bad[i]};
        void *st = (void *)1;
        cl_error err;
        cr_assert_eq(se()->create(&ts.sys, &o, 0.0, x, v, &st, &err),
                     CL_EINVAL, "dt = %g", bad[i]);
        cr_assert_null(st);
    }
    ts_free(&ts);
}

static void expect_blowup(int fail, double t_bad, cl_status want)
{
    ts_sys ts;
    double x[3], v[3];
    ri_failing_oscillator_at(&ts, fail, want, t_bad, x, v);
    cl_integrator_opts o = {.dt = 0.01};
    void *st;
    cl_error err;
    cr_assert_eq(se()->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(se()->advance(st, 0.5, x, v, &err), CL_OK);
    cr_assert_eq(se()->advance(st, 2.0, x, v, &err), want, "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "t = "), "%s", err.msg);
    cl_stats s;
    se()->stats(st, &s);
    cr_assert_lt(s.steps, 200);
    se()->free(st);
    ts_free(&ts);
}

Test(symplectic_euler, nan_force_is_blowup)
{
    expect_blowup(TS_FAIL_NAN, 1.0, CL_EBLOWUP);
}

Test(symplectic_euler, failing_force_status_passed_on)
{
    expect_blowup(TS_FAIL_STATUS, 1.0, CL_EBLOWUP);
    expect_blowup(TS_FAIL_STATUS, 1.0, CL_EINVAL);
}

/* omega = 100, h = 0.05: h omega = 5 > 2, the amplification is ~23 per
 * step, and the state overflows within a few hundred steps. */
Test(symplectic_euler, explicit_instability_detected)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    for (int r = 0; r < 3; r++) {
        ts.mass[r] = 1.0;
        ts.k[r] = 1e4;
        ts.c[r] = 0.0;
    }
    double x[3] = {1, 0, 0}, v[3] = {0, 0, 0};
    cl_integrator_opts o = {.dt = 0.05};
    void *st;
    cl_error err;
    cr_assert_eq(se()->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(se()->advance(st, 100.0, x, v, &err), CL_EBLOWUP);
    cr_assert_not_null(strstr(err.msg, "not finite"), "%s", err.msg);
    cl_stats s;
    se()->stats(st, &s);
    cr_assert_lt(s.steps, 400);
    se()->free(st);
    ts_free(&ts);
}
