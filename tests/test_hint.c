/* Tests for integrators/hint: every solver failure flag maps to the
 * options that address it. */
#include <criterion/criterion.h>

#include <string.h>

#include "integrators/hint.h"

static void expect_hint(const char *flag, const char *want)
{
    const char *h = cl_solver_hint(flag, false);
    cr_assert_not_null(strstr(h, want), "%s: \"%s\" lacks \"%s\"", flag, h,
                       want);
}

Test(hint, cvode_and_ida_flags_name_their_options)
{
    expect_hint("CV_TOO_MUCH_WORK", "--set run.max_steps=N");
    expect_hint("IDA_TOO_MUCH_WORK", "--set run.max_steps=N");
    expect_hint("CV_TOO_MUCH_ACC", "--rtol/--atol");
    expect_hint("CV_ERR_FAILURE", "--rtol/--atol");
    expect_hint("CV_CONV_FAILURE", "--linsol (klu)");
    expect_hint("IDA_CONV_FAIL", "--rtol");
    expect_hint("CV_LSETUP_FAIL", "--linsol klu");
    expect_hint("IDA_LSOLVE_FAIL", "run.lin_maxit");
    expect_hint("CV_TOO_CLOSE", "--t-end");
    expect_hint("CV_ILL_INPUT", "--max-order");
}

Test(hint, kinsol_and_gsl_flags_name_their_options)
{
    expect_hint("KIN_LINESEARCH_NONCONV", "reduce --dt");
    expect_hint("KIN_MAXITER_REACHED", "run.newton_maxit");
    expect_hint("KIN_MXNEWT_5X_EXCEEDED", "reduce --dt");
    expect_hint("KIN_LSETUP_FAIL", "--linsol klu");
    expect_hint("GSL_EMAXITER", "run.max_steps");
}

Test(hint, unknown_flags_get_the_general_advice)
{
    const char *general = cl_solver_hint(NULL, false);
    cr_assert_str_eq(cl_solver_hint("CV_SOMETHING_NEW", false), general);
    cr_assert_str_eq(cl_solver_hint("noprefix", true), general);
    cr_assert_not_null(strstr(general, "--rtol/--atol, --dt, --linsol"));
}

/* A fixed step is not retried smaller: ARKODE's Newton failure at a fixed
 * step names --dt and --max-newton, not the tolerances; the flags without
 * a fixed-step reading keep theirs. */
Test(hint, fixed_steps_name_the_step)
{
    const char *h = cl_solver_hint("ARK_CONV_FAILURE", true);
    cr_assert_not_null(strstr(h, "reduce --dt"), "%s", h);
    cr_assert_not_null(strstr(h, "--max-newton"), "%s", h);
    cr_assert_null(strstr(h, "--rtol"), "%s", h);
    cr_assert_str_eq(cl_solver_hint("ARK_LSETUP_FAIL", true),
                     cl_solver_hint("CV_LSETUP_FAIL", false));
}
