/* cvode-adams against closed-form solutions (oscillators, coupled pair);
 * statistics of the fixed-point iteration (no Jacobian, no linear solver);
 * on a stiff system it needs far more steps than cvode-bdf (it is the
 * non-stiff reference); blow-up reporting. */
#include <criterion/criterion.h>

#include "runsun.h"

#define AN "cvode-adams"

Test(cvode_adams, closed_form_solutions)
{
    rs_check_closed_forms(AN, false);
}

Test(cvode_adams, statistics)
{
    cl_stats s;
    rs_check_pair(AN, 1.0, 2.0, 4.0, 1e-7, &s, true);
    cr_assert_eq(s.jac_evals, 0);
    cr_assert_eq(s.lin_setups, 0);
    cr_assert_eq(s.lin_solves, 0);
    cr_assert_eq(s.lin_iters, 0);
    cr_assert_eq(s.symbolic_facts, 0);
}

/* Damping 1e4 on unit masses: the fast mode at about -1e4 bounds the
 * Adams step near 1e-4 however slow the solution; BDF follows the slow
 * mode. */
Test(cvode_adams, stiff_needs_many_more_steps_than_bdf)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    for (int r = 0; r < 3; r++) {
        ts.mass[r] = 1.0;
        ts.k[r] = 1e4 * (r + 1);
        ts.c[r] = 1e4 * (r + 1) + 3.0;
    }
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    cl_stats sa, sb;
    cr_assert_lt(rs_exact_error(AN, &ts, &o, 5.0, 5, &sa), 100 * o.rtol);
    cr_assert_lt(rs_exact_error("cvode-bdf", &ts, &o, 5.0, 5, &sb),
                 100 * o.rtol);
    cr_log_info("stiff: adams %ld steps, bdf %ld steps", sa.steps, sb.steps);
    cr_assert_gt(sa.steps, 10 * sb.steps);
    ts_free(&ts);
}

/* NaN forces are blow-ups, system errors are passed on. */
Test(cvode_adams, failures_reported)
{
    rs_check_failures(AN, false);
}
