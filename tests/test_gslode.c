/* The shared GSL odeiv2 plumbing (integrators/gslode.c), checked for both
 * GSL methods: registry flags, rejected options and output times, exact
 * stops at several output times, counters, CL_EBLOWUP for NaN forces, a
 * failing force's status passed on, recovery from transient failures, and
 * CL_ESOLVER when max_steps is exceeded. */
#include <criterion/criterion.h>

#include "runint.h"

static const char *const gsl_names[] = {"gsl-rk8pd", "gsl-msbdf"};

#define GSL_N (sizeof gsl_names / sizeof gsl_names[0])

Test(gslode, registry_flags)
{
    for (size_t i = 0; i < GSL_N; i++) {
        const cl_integrator_type *t = ri_find(gsl_names[i]);
        cr_expect(!t->fixed_step, "%s", t->name);
        cr_expect(!t->takes_linsol, "%s", t->name);
    }
}

Test(gslode, rejects_bad_options)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3] = {0}, v[3] = {0};
    const cl_integrator_opts bad[] = {
        {.rtol = -1e-6}, {.atol = NAN}, {.rtol = INFINITY}, {.dt = -0.1},
        {.dt = NAN}, {.max_steps = -1},
    };
    for (size_t i = 0; i < GSL_N; i++) {
        for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
            void *st = (void *)1;
            cl_error err;
            cr_expect_eq(ri_find(gsl_names[i])->create(&ts.sys, &bad[k], 0.0,
                                                       x, v, &st, &err),
                         CL_EINVAL, "%s: case %zu", gsl_names[i], k);
            cr_expect_null(st);
        }
    }
    ts_free(&ts);
}

/* Outputs at 0 (no step), 0.25, ..., 2: each state matches the exact
 * solution; going back is CL_EINVAL. */
static void outputs_case(const char *name)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    double x0[6], v0[6], x[6], v[6], xe[6], ve[6];
    ts_initial(&ts, x0, v0);
    const cl_integrator_type *it = ri_find(name);
    cl_integrator_opts o = {.rtol = 1e-10, .atol = 1e-10};
    void *st;
    cl_error err;
    cl_stats s;
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x0, v0, &st, &err), CL_OK);
    for (int k = 0; k <= 8; k++) {
        double t = 0.25 * k;
        cr_assert_eq(it->advance(st, t, x, v, &err), CL_OK, "%s", err.msg);
        ts_exact(&ts, x0, v0, t, xe, ve);
        cr_expect_lt(ts_maxdiff(x, xe, 6), 1e-6, "%s t = %g", name, t);
        cr_expect_lt(ts_maxdiff(v, ve, 6), 1e-6, "%s t = %g", name, t);
    }
    cr_expect_eq(it->advance(st, 1.5, x, v, &err), CL_EINVAL, "%s", name);
    it->stats(st, &s);
    cr_expect_gt(s.steps, 0);
    cr_expect_geq(s.rhs_evals, s.steps);
    /* msbdf's Newton iterations and LU work happen inside GSL: not
     * reported; rk8pd has none. */
    long hidden = it == ri_find("gsl-msbdf") ? CL_STAT_NA : 0;
    cr_expect_eq(s.lin_setups, hidden, "%s", name);
    cr_expect_eq(s.lin_solves, hidden, "%s", name);
    cr_expect_eq(s.nonlin_iters, hidden, "%s", name);
    cr_expect_eq(s.nonlin_fails, hidden, "%s", name);
    cr_expect_eq(s.lin_iters + s.symbolic_facts + s.lin_fallbacks, 0, "%s",
                 name);
    it->free(st);
    ts_free(&ts);
}

Test(gslode, exact_stops_at_output_times)
{
    for (size_t i = 0; i < GSL_N; i++)
        outputs_case(gsl_names[i]);
}

/* Force failing from t = 1 on (kind fail): advance to 2 gives want. */
static void failure_case(const char *name, int fail, cl_status want)
{
    ts_sys ts;
    double x[3], v[3];
    ri_failing_oscillator(&ts, fail, want, x, v);
    const cl_integrator_type *it = ri_find(name);
    cl_integrator_opts o = {.rtol = 1e-8, .atol = 1e-8};
    void *st;
    cl_error err = {0};
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(it->advance(st, 0.5, x, v, &err), CL_OK, "%s", err.msg);
    cr_expect_eq(it->advance(st, 2.0, x, v, &err), want, "%s: %s", name,
                 err.msg);
    if (want != CL_OK) {
        cr_expect_not_null(strstr(err.msg, "t = "), "%s", err.msg);
        cr_expect_not_null(strstr(err.msg, name), "%s", err.msg);
    }
    it->free(st);
    ts_free(&ts);
}

Test(gslode, failures)
{
    for (size_t i = 0; i < GSL_N; i++) {
        failure_case(gsl_names[i], TS_FAIL_NAN, CL_EBLOWUP);
        failure_case(gsl_names[i], TS_FAIL_STATUS, CL_EBLOWUP);
        failure_case(gsl_names[i], TS_FAIL_STATUS, CL_EINVAL);
        failure_case(gsl_names[i], TS_FAIL_TRANSIENT, CL_OK);
    }
}

Test(gslode, max_steps_exceeded)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3], v[3];
    ts_initial(&ts, x, v);
    for (size_t i = 0; i < GSL_N; i++) {
        const cl_integrator_type *it = ri_find(gsl_names[i]);
        cl_integrator_opts o = {.rtol = 1e-10, .atol = 1e-10,
                                .max_steps = 5};
        void *st;
        cl_error err;
        cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
        cr_expect_eq(it->advance(st, 10.0, x, v, &err), CL_ESOLVER, "%s",
                     gsl_names[i]);
        cr_expect_not_null(strstr(err.msg, "steps"), "%s", err.msg);
        it->free(st);
    }
    ts_free(&ts);
}
