/* The shared fixed-step plumbing (integrators/fixed_step.c), checked for
 * every method built on it: exact step counting and force-evaluation
 * counts, output times on the step grid only, rejected dt, masses and
 * initial time, CL_EBLOWUP with time and step for NaN forces and for the
 * explicit instability, a failing force's status passed on with the state
 * left at the last good step, and the registry flags. */
#include <criterion/criterion.h>

#include "runint.h"

typedef struct {
    const char *name;
    long rhs_per_step, rhs_extra; /* rhs_evals = per_step * steps + extra */
} fs_case;

static const fs_case fs_table[] = {
    {"fe", 1, 0},
    {"symplectic-euler", 1, 0},
    {"symplectic-euler-x", 1, 0},
    {"verlet", 1, 0},
    {"velocity-verlet", 1, 1},
    {"rk4", 4, 0},
};

#define FS_N (sizeof fs_table / sizeof fs_table[0])

Test(fixed_step, registry_flags)
{
    for (size_t i = 0; i < FS_N; i++) {
        const cl_integrator_type *t = ri_find(fs_table[i].name);
        cr_expect(t->fixed_step, "%s", t->name);
        cr_expect(!t->takes_linsol, "%s", t->name);
        cr_expect_str_eq(t->name, fs_table[i].name);
        cr_expect_not_null(t->doc);
    }
}

static void counts_case(const fs_case *c)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3], v[3];
    ts_initial(&ts, x, v);
    const cl_integrator_type *it = ri_find(c->name);
    cl_integrator_opts o = {.dt = 0.1};
    void *st;
    cl_error err;
    cl_stats s;
    cr_assert_eq(it->create(&ts.sys, &o, 2.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(it->advance(st, 2.0, x, v, &err), CL_OK, "%s", err.msg);
    it->stats(st, &s);
    cr_expect_eq(s.steps + s.rhs_evals, 0, "%s", c->name);
    cr_assert_eq(it->advance(st, 2.3, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(it->advance(st, 2.3, x, v, &err), CL_OK);
    cr_assert_eq(it->advance(st, 3.0, x, v, &err), CL_OK);
    it->stats(st, &s);
    cr_expect_eq(s.steps, 10, "%s", c->name);
    cr_expect_eq(s.rhs_evals, c->rhs_per_step * 10 + c->rhs_extra, "%s",
                 c->name);
    cr_expect_eq(s.jac_evals + s.lin_setups + s.lin_solves + s.lin_iters +
                     s.nonlin_iters + s.nonlin_fails + s.err_fails +
                     s.symbolic_facts, 0, "%s", c->name);
    cr_expect_eq(it->advance(st, 3.05, x, v, &err), CL_EINVAL, "%s",
                 c->name);
    cr_expect_eq(it->advance(st, 2.5, x, v, &err), CL_EINVAL, "%s",
                 c->name);
    it->stats(st, &s);
    cr_expect_eq(s.steps, 10, "%s", c->name);
    it->free(st);
    ts_free(&ts);
}

Test(fixed_step, counts_steps_and_forces_exactly)
{
    for (size_t i = 0; i < FS_N; i++)
        counts_case(&fs_table[i]);
}

static void expect_create_fails(const char *name, ts_sys *ts,
                                const cl_integrator_opts *o, double t0,
                                const char *what)
{
    double x[3] = {0}, v[3] = {0};
    void *st = (void *)1;
    cl_error err = {0};
    cr_expect_eq(ri_find(name)->create(&ts->sys, o, t0, x, v, &st, &err),
                 CL_EINVAL, "%s: %s", name, what);
    cr_expect_null(st, "%s: %s", name, what);
    cr_expect_not_null(strstr(err.msg, name), "%s", err.msg);
}

Test(fixed_step, rejects_bad_dt_mass_and_time)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    const double bad[] = {0.0, -1e-3, NAN, INFINITY};
    for (size_t i = 0; i < FS_N; i++) {
        const char *name = fs_table[i].name;
        for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
            cl_integrator_opts o = {.dt = bad[k]};
            expect_create_fails(name, &ts, &o, 0.0, "bad dt");
        }
        cl_integrator_opts o = {.dt = 0.01};
        expect_create_fails(name, &ts, &o, NAN, "bad t0");
        ts.mass[1] = 0.0;
        expect_create_fails(name, &ts, &o, 0.0, "zero mass");
        ts.mass[1] = 1.0;
    }
    ts_free(&ts);
}

/* From t_bad = 1 on the force fails (fail kind, status want): advance to 2
 * must stop there with `want` and the time in the message. */
static void expect_failure(const char *name, int fail, cl_status want)
{
    ts_sys ts;
    double x[3], v[3];
    ri_failing_oscillator(&ts, fail, want, x, v);
    const cl_integrator_type *it = ri_find(name);
    cl_integrator_opts o = {.dt = 0.01};
    void *st;
    cl_error err;
    cl_stats s;
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(it->advance(st, 0.5, x, v, &err), CL_OK);
    cr_expect_eq(it->advance(st, 2.0, x, v, &err), want, "%s: %s", name,
                 err.msg);
    cr_expect_not_null(strstr(err.msg, "t = "), "%s", err.msg);
    cr_expect_not_null(strstr(err.msg, name), "%s", err.msg);
    it->stats(st, &s);
    cr_expect_lt(s.steps, 102, "%s ran on after the failure", name);
    if (fail == TS_FAIL_STATUS) {
        /* the state stays at the last good step, finite */
        cr_expect(isfinite(x[0]) && isfinite(v[0]), "%s", name);
        cr_expect_geq(s.steps, 99, "%s", name);
    }
    it->free(st);
    ts_free(&ts);
}

Test(fixed_step, nan_force_is_blowup)
{
    for (size_t i = 0; i < FS_N; i++)
        expect_failure(fs_table[i].name, TS_FAIL_NAN, CL_EBLOWUP);
}

Test(fixed_step, failing_force_status_passed_on)
{
    for (size_t i = 0; i < FS_N; i++) {
        expect_failure(fs_table[i].name, TS_FAIL_STATUS, CL_EBLOWUP);
        expect_failure(fs_table[i].name, TS_FAIL_STATUS, CL_EINVAL);
    }
}

/* omega = 100, h = 0.05: h omega = 5, beyond every method's stability
 * limit (2 for the symplectic ones, 2.83 for rk4, 0 for fe). */
Test(fixed_step, explicit_instability_detected)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, 1e4);
    for (size_t i = 0; i < FS_N; i++) {
        const cl_integrator_type *it = ri_find(fs_table[i].name);
        double x[3] = {1, 0, 0}, v[3] = {0, 0, 0};
        cl_integrator_opts o = {.dt = 0.05};
        void *st;
        cl_error err;
        cl_stats s;
        cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
        cr_expect_eq(it->advance(st, 500.0, x, v, &err), CL_EBLOWUP, "%s",
                     it->name);
        cr_expect_not_null(strstr(err.msg, "not finite"), "%s", err.msg);
        it->stats(st, &s);
        cr_expect_lt(s.steps, 10000, "%s", it->name);
        it->free(st);
    }
    ts_free(&ts);
}
