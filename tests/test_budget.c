/* The equal-budget study (analysis/budget.c, `clothode budget`): on the
 * hard-constraint chain problems/xpbd-chain.ini, every divisor S of the
 * budget is a split, each spends the same B iterations per step, and the
 * constraint violation and the energy lost fall as S grows (Macklin et
 * al., "Small steps in physics simulation"); a Newton method's split S
 * takes steps dt / S with K Newton iterations, semi-be steps dt / S with
 * its one solve (K = 1); adaptive methods are
 * refused; the command writes budget.csv. */
#include <criterion/criterion.h>

#include "analysis/budget.h"
#include "problem.h"
#include "runcli.h"

/* Measured (B = 4, dt = 0.01, T = 1): S = 1 stretch 0.2593, energy
 * -0.3269 J; S = 2 0.1513, -0.2199; S = 4 0.0866, -0.1354. */
Test(budget, chain_substeps_beat_iterations)
{
    pr_problem p;
    pr_load(&p, "problems/xpbd-chain.ini", NULL, NULL);
    cl_budget_opts o = {.t_end = 1.0, .max_stretch = 10, .budget = 4};
    cl_integrator_opts io = {.dt = 0.01};
    cl_budget_result r;
    cl_error err = {0};
    cr_assert_eq(cl_budget(p.m, cl_integrator_find("xpbd"), &io, &o, NULL,
                           &r, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(r.n, 3);
    /* the measured values (above), to 1 % */
    static const double stretch[3] = {0.2593, 0.1513, 0.0866},
                        energy[3] = {-0.3269, -0.2199, -0.1354};
    for (int k = 0; k < r.n; k++) {
        const cl_budget_split *s = &r.s[k];
        cr_assert_float_eq(s->stretch, stretch[k], 0.01 * stretch[k],
                           "S = %ld: stretch %g", s->S, s->stretch);
        cr_assert_float_eq(s->energy, energy[k], -0.01 * energy[k],
                           "S = %ld: energy %g", s->S, s->energy);
        cr_log_info("S = %ld K = %ld: stretch %.3e, energy %.3e", s->S, s->K,
                    s->stretch, s->energy);
        cr_assert_eq(s->rc, CL_OK, "%s", s->why.msg);
        cr_assert_eq(s->S * s->K, 4);
        cr_assert_eq(s->stats.nonlin_iters, 400, "B per step, 100 steps");
        cr_assert(isnan(s->err_x), "no reference");
        cr_assert_lt(s->energy, 0.0, "XPBD dissipates");
        if (k > 0) {
            cr_assert_lt(s->stretch, r.s[k - 1].stretch);
            cr_assert_gt(s->energy, r.s[k - 1].energy);
        }
    }
    pr_free(&p);
}

/* Measured err_x (spring-chain, dt = 0.01, T = 0.1, B = 8): S = 1 5.0e-3,
 * 2 2.5e-3, 4 1.2e-3, 8 6.2e-4, backward Euler's first order. */
Test(budget, newton_splits_take_smaller_steps)
{
    pr_problem p;
    pr_load(&p, "problems/spring-chain.ini", NULL, NULL);
    cl_budget_opts o = {.t_end = 0.1, .max_stretch = 10, .budget = 8};
    cl_integrator_opts io = {.dt = 0.01};
    cl_conv_opts co = {.t_end = 0.1, .max_stretch = 10, .ref_rtol = 1e-9,
                       .ref_linsol = ""};
    cl_conv_ref ref;
    cl_budget_result r;
    cl_error err = {0};
    cr_assert_eq(cl_conv_reference(p.m, &co, &ref, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_budget(p.m, cl_integrator_find("kinsol-be"), &io, &o,
                           &ref, &r, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(r.n, 4);
    for (int k = 0; k < r.n; k++) {
        const cl_budget_split *s = &r.s[k];
        cr_assert_eq(s->rc, CL_OK, "%s", s->why.msg);
        cr_assert_eq(s->h, 0.01 / (double)s->S);
        cr_assert_eq(s->stats.steps, 10 * s->S);
        cr_assert_leq(s->stats.nonlin_iters, 10 * s->S * s->K);
        if (k > 0)
            cr_assert(s->err_x < 0.6 * r.s[k - 1].err_x, "%g after %g",
                      s->err_x, r.s[k - 1].err_x);
    }
    cr_assert_float_eq(r.s[3].err_x, 6.23e-4, 1e-5);
    /* semi-be solves once a step whatever K: K = 1 in every split, and
     * only S = 8 spends the budget (8 solves a step dt, as kinsol-be's
     * one linearisation at S = 8) */
    cl_budget_result q;
    cr_assert_eq(cl_budget(p.m, cl_integrator_find("semi-be"), &io, &o, &ref,
                           &q, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(q.n, 4);
    for (int k = 0; k < q.n; k++) {
        cr_assert_eq(q.s[k].K, 1);
        cr_assert_eq(q.s[k].stats.lin_solves, 10 * q.s[k].S);
    }
    cr_assert_float_eq(q.s[3].err_x, r.s[3].err_x, 1e-9);
    io = (cl_integrator_opts){.rtol = 1e-6, .atol = 1e-8};
    cr_assert_eq(cl_budget_check(cl_integrator_find("cvode-bdf"), &io, &o,
                                 &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "chooses its own steps"), "%s", err.msg);
    cl_conv_ref_free(&ref);
    pr_free(&p);
}

Test(budget, command_writes_budget_csv)
{
    char dir[512], out[600], csv[700];
    tmp_mkdtemp(dir, sizeof dir, "budget");
    snprintf(out, sizeof out, "%s/o", dir);
    cli_result r;
    cli_run(&r, "budget", "xpbd-chain", "--integrator", "xpbd,pd", "--budget",
            "2", "--dt", "0.01", "--t-end", "0.1", "--ref-rtol", "0",
            "--out", out, "--quiet", NULL);
    cr_assert(r.exited && r.status == 2, "%s: pd refuses hard constraints: "
              "%s", r.cmd, r.err);
    cr_assert(strstr(r.err, "pbd.enabled = false"), "%s", r.err);
    cli_result_free(&r);
    cli_run(&r, "budget", "xpbd-chain", "--integrator", "xpbd", "--budget",
            "2", "--dt", "0.01", "--t-end", "0.1", "--ref-rtol", "0",
            "--out", out, "--quiet", NULL);
    cr_assert(r.exited && r.status == 0, "%s: %s", r.cmd, r.err);
    snprintf(csv, sizeof csv, "%s/budget.csv", out);
    char text[4096];
    tmp_slurp(csv, text, sizeof text);
    cr_assert(strncmp(text, "integrator,dt,substeps,iterations,h,err_x,", 42)
              == 0, "%s", text);
    /* S = 2 substeps of K = 1 iteration: h = dt / 2 */
    cr_assert(strstr(text, "\nxpbd,0.01,2,1,0.005"), "%s", text);
    cli_result_free(&r);
    /* what the splits set, and a method a split cannot hold to K, are
     * refused (before: --substeps was ignored, arkode-dirk-fixed took 236
     * iterations for a budget of 40) */
    static const char *const split_keys[] = {
        "run.substeps=3", "run.iterations=2", "run.newton_maxit=1"};
    for (int k = 0; k < 3; k++) {
        cli_run(&r, "budget", "xpbd-chain", "--integrator", "xpbd",
                "--budget", "2", "--dt", "0.01", "--t-end", "0.1",
                "--ref-rtol", "0", "--set", split_keys[k], "--out", out,
                NULL);
        cli_assert_error(&r, 0, "clothode budget does not read it", NULL);
        cli_result_free(&r);
    }
    cli_run(&r, "budget", "xpbd-chain", "--substeps", "3", NULL);
    cli_assert_error(&r, 1, "unknown or ambiguous option '--substeps'",
                     NULL);
    cli_result_free(&r);
    cli_run(&r, "budget", "ms-hang", "--set", "cloth.n=4", "--set",
            "pbd.enabled=false", "--integrator", "arkode-dirk-fixed",
            "--budget", "2", "--dt", "0.01", "--t-end", "0.1", "--out", out,
            NULL);
    cli_assert_error(&r, 0, "arkode-dirk-fixed caps the Newton iterations "
                     "of each stage", NULL);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}
