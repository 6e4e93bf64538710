/* cvode-bdf against closed-form solutions: damped/undamped oscillators, the
 * coupled pair, a stiff overdamped set; statistics, one KLU symbolic
 * analysis over many advance calls (klu-full), the default solver's, blow-up and error reporting, options. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "integrators/integrator.h"
#include "runsun.h"
#include "testsys.h"

static const cl_integrator_type *cvb(void)
{
    return ri_find("cvode-bdf");
}

/* Integrate from 0 to T with nout outputs; max error in x and v over the
 * outputs relative to the solution's size; statistics at the end
 * (rs_exact_error). */
static double run(ts_sys *ts, const cl_integrator_opts *o, double T,
                  int nout, cl_stats *s)
{
    return rs_exact_error("cvode-bdf", ts, o, T, nout, s);
}

Test(cvode_bdf, oscillators_match_exact)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    double e = run(&ts, &o, 10.0, 20, NULL);
    cr_log_info("cvode-bdf oscillators rtol 1e-6: max rel. error %.3e", e);
    cr_assert_lt(e, 100 * o.rtol);
    o.rtol = 1e-9;
    o.atol = 1e-11;
    double e2 = run(&ts, &o, 10.0, 20, NULL);
    cr_log_info("cvode-bdf oscillators rtol 1e-9: max rel. error %.3e", e2);
    cr_assert_lt(e2, 100 * o.rtol);
    cr_assert_lt(e2, e);
    ts_free(&ts);
}

Test(cvode_bdf, coupled_pair_matches_exact)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    double e = run(&ts, &o, 10.0, 25, NULL);
    cr_log_info("cvode-bdf coupled pair rtol 1e-6: max rel. error %.3e", e);
    cr_assert_lt(e, 100 * o.rtol);
    ts_free(&ts);
}

/* max_order caps the BDF order: at rtol 1e-8 on the oscillators, order 1
 * needs many times the steps of order 2, which needs more than the
 * default (up to 5), both within 1e3 rtol; an order above BDF's 5 is
 * refused. */
Test(cvode_bdf, max_order_caps_the_order)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    cl_stats s[3];
    const int order[3] = {0, 2, 1};
    for (int k = 0; k < 3; k++) {
        cl_integrator_opts o = {.rtol = 1e-8, .atol = 1e-10,
                                .max_order = order[k]};
        double e = run(&ts, &o, 5.0, 5, &s[k]);
        cr_log_info("cvode-bdf max_order %d: %ld steps, error %.2e",
                    order[k], s[k].steps, e);
        if (order[k] != 1) /* first order accumulates more */
            cr_assert_lt(e, 1e3 * o.rtol);
    }
    cr_assert_gt(s[2].steps, 3 * s[1].steps);
    cr_assert_gt(s[1].steps, s[0].steps);
    cl_integrator_opts bad = {.rtol = 1e-6, .atol = 1e-8, .max_order = 6};
    double x0[RI_MAXN], v0[RI_MAXN];
    ts_initial(&ts, x0, v0);
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(cvb()->create(&ts.sys, &bad, 0.0, x0, v0, &st, &err),
                 CL_EINVAL);
    cr_assert_null(st);
    cr_assert(strstr(err.msg, "max_order = 6: above the method's highest "
                              "order"), "%s", err.msg);
    ts_free(&ts);
}

Test(cvode_bdf, default_tolerances)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    cl_integrator_opts o = {0};
    double e = run(&ts, &o, 5.0, 5, NULL);
    cr_assert_lt(e, 100 * 1e-6);
    ts_free(&ts);
}

/* Fast modes at -1e6 and -1e4, slow ones at ~-1: an explicit method would
 * need h < 2e-6; BDF's step follows the slow dynamics. */
Test(cvode_bdf, stiff_overdamped)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    for (int r = 0; r < 3; r++) {
        ts.mass[r] = 1.0;
        ts.k[r] = 1e6;
        ts.c[r] = 1e6 + 1.0;
        ts.k[3 + r] = 1e4 * (r + 1);
        ts.c[3 + r] = 1e4 * (r + 1) + 3.0;
        ts.mass[3 + r] = 1.0;
    }
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    cl_stats s;
    double e = run(&ts, &o, 10.0, 10, &s);
    cr_log_info("cvode-bdf stiff: max rel. error %.3e in %ld steps", e, s.steps);
    /* measured: 1.26 rtol in 289 steps */
    cr_assert_lt(e, 10 * o.rtol);
    cr_assert_lt(s.steps, 600);
    ts_free(&ts);
}

/* The baseline klu-full: KLU on the first-order matrix.  The force and
 * Jacobian evaluations reported are those the system saw; one KLU solve
 * per Newton iteration; one symbolic analysis for the whole run. */
Test(cvode_bdf, statistics_and_one_symbolic_analysis)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 1.0, 2.0, 4.0), 0);
    cl_integrator_opts o = {.rtol = 1e-7, .atol = 1e-9, .dt = 1e-4,
                            .linsol = "klu-full"};
    cl_stats s;
    run(&ts, &o, 20.0, 40, &s);
    cr_log_info("cvode-bdf stats: steps %ld rhs %ld jac %ld setups %ld "
                "solves %ld newton %ld ncf %ld etf %ld symbolic %ld",
                s.steps, s.rhs_evals, s.jac_evals, s.lin_setups,
                s.lin_solves, s.nonlin_iters, s.nonlin_fails, s.err_fails,
                s.symbolic_facts);
    cr_assert_eq(s.rhs_evals, ts.nforce);
    cr_assert_eq(s.jac_evals, ts.njac);
    cr_assert_eq(s.lin_solves, s.nonlin_iters);
    cr_assert_eq(s.lin_iters, 0);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_str_eq(s.linsol, "klu-full");
    ts_free(&ts);
}

/* The default half-size solver: the evaluations reported are those the
 * system saw, at most one solve per Newton iteration (an iterative solve
 * of a right-hand side already below CVODE's tolerance is skipped by
 * CVODE), the solver named. */
Test(cvode_bdf, statistics_default_linsol)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 1.0, 2.0, 4.0), 0);
    cl_integrator_opts o = {.rtol = 1e-7, .atol = 1e-9, .dt = 1e-4};
    cl_stats s;
    cr_assert_lt(run(&ts, &o, 20.0, 40, &s), 1000 * o.rtol);
    cr_log_info("cvode-bdf default: %s, setups %ld solves %ld newton %ld "
                "lin_iters %ld", s.linsol, s.lin_setups, s.lin_solves,
                s.nonlin_iters, s.lin_iters);
    cr_assert_eq(s.rhs_evals, ts.nforce);
    cr_assert_eq(s.jac_evals, ts.njac);
    cr_assert_gt(s.lin_solves, 0);
    cr_assert_leq(s.lin_solves, s.nonlin_iters);
    cr_assert_eq(strncmp(s.linsol, "auto:", 5), 0, "%s", s.linsol);
    ts_free(&ts);
}

Test(cvode_bdf, output_times)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x0[3], v0[3], x[3], v[3], x2[3], v2[3];
    ts_initial(&ts, x0, v0);
    cl_integrator_opts o = {0};
    void *st;
    cl_error err;
    cr_assert_eq(cvb()->create(&ts.sys, &o, 0.0, x0, v0, &st, &err), CL_OK);
    cr_assert_eq(cvb()->advance(st, 0.0, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(ts_maxdiff(x, x0, 3) + ts_maxdiff(v, v0, 3), 0.0);
    cr_assert_eq(cvb()->advance(st, 1.0, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cvb()->advance(st, 1.0, x2, v2, &err), CL_OK);
    cr_assert_eq(ts_maxdiff(x, x2, 3) + ts_maxdiff(v, v2, 3), 0.0);
    cr_assert_eq(cvb()->advance(st, 0.5, x, v, &err), CL_EINVAL);
    cr_assert_eq(cvb()->advance(st, NAN, x, v, &err), CL_EINVAL);
    cvb()->free(st);
    ts_free(&ts);
}

Test(cvode_bdf, max_steps_is_a_solver_failure)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3], v[3];
    ts_initial(&ts, x, v);
    cl_integrator_opts o = {.max_steps = 5};
    void *st;
    cl_error err;
    cr_assert_eq(cvb()->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    cr_assert_eq(cvb()->advance(st, 100.0, x, v, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "CV_TOO_MUCH_WORK"), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "t = "), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "to change: raise the steps allowed"
                                       " per output interval (--set"
                                       " run.max_steps=N"), "%s", err.msg);
    cvb()->free(st);
    ts_free(&ts);
}

/* A force failing from t_bad on: create succeeds, the advance to 0.5
 * succeeds when t_bad > 0.5, the advance to 3 reports `want` with the
 * time (rs_expect_failure). */
static void expect_failure(int fail, double t_bad, cl_status sys_status,
                           cl_status want)
{
    rs_expect_failure("cvode-bdf", fail, t_bad, sys_status, CL_OK, want);
}

Test(cvode_bdf, nan_from_the_start_is_blowup)
{
    expect_failure(TS_FAIL_NAN, -1.0, CL_OK, CL_EBLOWUP);
}

Test(cvode_bdf, nan_later_is_blowup)
{
    expect_failure(TS_FAIL_NAN, 1.0, CL_OK, CL_EBLOWUP);
}

Test(cvode_bdf, blowup_status_is_blowup)
{
    expect_failure(TS_FAIL_STATUS, 1.0, CL_EBLOWUP, CL_EBLOWUP);
}

Test(cvode_bdf, system_error_passed_on)
{
    expect_failure(TS_FAIL_STATUS, 1.0, CL_EINVAL, CL_EINVAL);
}

/* NaN forces at a few trial states are recovered from by smaller steps. */
Test(cvode_bdf, transient_nan_is_recovered)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    ts.fail = TS_FAIL_TRANSIENT;
    ts.t_bad = 1.0;
    ts.fail_left = 3;
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    cl_stats s;
    double e = run(&ts, &o, 5.0, 10, &s);
    cr_assert_eq(ts.fail_left, 0);
    cr_assert_gt(s.nonlin_fails, 0);
    cr_assert_lt(e, 100 * o.rtol);
    ts_free(&ts);
}

Test(cvode_bdf, rejects_bad_options)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3] = {0}, v[3] = {0};
    const cl_integrator_opts bad[] = {
        {.rtol = -1e-6}, {.atol = NAN}, {.dt = -1.0}, {.max_steps = -3},
        {.rtol = INFINITY}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        void *st = (void *)1;
        cl_error err;
        cr_assert_eq(cvb()->create(&ts.sys, &bad[i], 0.0, x, v, &st, &err),
                     CL_EINVAL, "case %zu", i);
        cr_assert_null(st);
    }
    cl_system empty = ts.sys;
    empty.n = 0;
    void *st;
    cl_error err;
    cl_integrator_opts o = {0};
    cr_assert_eq(cvb()->create(&empty, &o, 0.0, x, v, &st, &err), CL_EINVAL);
    cl_system nojac = ts.sys;
    nojac.jacobian = NULL;
    cr_assert_eq(cvb()->create(&nojac, &o, 0.0, x, v, &st, &err), CL_EINVAL);
    ts_free(&ts);
}
