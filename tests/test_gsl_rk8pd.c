/* gsl-rk8pd: reaches its tolerance on spring2 (global error at T = 1
 * below 2 tol for tol = 1e-6 .. 1e-10, measured 0.7-0.9 tol, shrinking
 * with tol), no Jacobian,
 * 12 to 13 force evaluations per attempted step (13 stages, the first
 * reused from the previous step's end).  Options and failures:
 * test_gslode.c. */
#include <criterion/criterion.h>

#include "spring2.h"

Test(gsl_rk8pd, reaches_tolerance_on_spring2)
{
    s2_check_tolerance("gsl-rk8pd", (const double[3]){2, 2, 2});
}

Test(gsl_rk8pd, counters)
{
    s2_problem p;
    s2_load(&p);
    cl_integrator_opts o = {.rtol = 1e-8, .atol = 1e-8};
    cl_stats s;
    s2_run(&p, "gsl-rk8pd", &o, 1.0, &s);
    long attempts = s.steps + s.err_fails;
    cr_expect_eq(s.jac_evals, 0);
    cr_expect(s.rhs_evals >= 12 * attempts && s.rhs_evals <= 14 * attempts,
              "%ld force evaluations for %ld attempted steps", s.rhs_evals,
              attempts);
    s2_free(&p);
}
