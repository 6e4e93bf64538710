/* The static equilibrium (analysis/equilibrium.c) against known answers:
 * spring2's particle hanging along its spring (x = L + m g / ks) and
 * spring-chain hanging along its length (spring j carries the weight of
 * the particles beyond it); too few steps are refused with the residual
 * reached. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "analysis/equilibrium.h"
#include "problem.h"

/* The free positions of p at its equilibrium (at most 6 particles). */
static cl_equilibrium_info eq_solve(pr_problem *p, double *x, int steps,
                                    cl_status want)
{
    const cl_system *sys = cl_model_system(p->m);
    double v[18];
    cl_error err = {0};
    cl_equilibrium_info info;
    cr_assert_leq(sys->n, 18);
    cr_assert_eq(cl_model_initial_state(p->m, x, v), CL_OK);
    cl_status rc = cl_equilibrium_find(p->m, 0.0, x, 1e-10, steps, &info,
                                       &err);
    cr_assert_eq(rc, want, "%s", err.msg);
    cr_log_info("%d steps, max |M^-1 f| = %.3g m/s^2%s%s", info.steps,
                info.residual, rc ? ": " : "", rc ? err.msg : "");
    return info;
}

Test(equilibrium, spring_along_gravity)
{
    pr_problem p;
    pr_load(&p, "problems/spring2.ini", "gravity.g=9.81,0,0",
            "init.velocity=0,0,0");
    double x[18];
    cl_equilibrium_info info = eq_solve(&p, x, 200, CL_OK);
    cr_assert_float_eq(x[0], 1.0 + 1.0 * 9.81 / 100.0, 1e-12);
    cr_assert_float_eq(x[1], 0.0, 1e-15);
    cr_assert_leq(info.residual, 1e-10);
    pr_free(&p);
}

Test(equilibrium, chain_carries_the_weight_below)
{
    pr_problem p;
    pr_load(&p, "problems/spring-chain.ini", "gravity.g=9.81,0,0", NULL);
    double x[18], want = 0.0;
    eq_solve(&p, x, 200, CL_OK);
    for (int k = 1; k <= 5; k++) {
        want += 0.2 + (6 - k) * 0.01 * 9.81 / 50.0;
        cr_assert_float_eq(x[3 * (k - 1)], want, 1e-12, "particle %d", k);
    }
    eq_solve(&p, x, 2, CL_ESOLVER);
    pr_free(&p);
}
