/* Tests of the petsc-ts integrators (integrators/petsc_ts.h): observed
 * orders at fixed steps on spring2 through the convergence study
 * (analysis/convergence.h), an adaptive run on hang-smooth against
 * cvode-bdf at the same tolerances, the energy of TSALPHA2 with
 * rho_inf = 1 on spring2, and the refusals. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/convergence.h"
#include "problem.h"
#include "runcli.h"
#include "spring2.h"

/* The fitted order of `name` on spring2 to T = 1 at dt = 1e-2 .. 1.25e-3,
 * every level exactly 100 * 2^k steps: a dt > 0 makes a petsc-* run take
 * fixed steps (cl_integrator_fixed), and the convergence study halves it. */
static double order_on_spring2(const char *name, const char *petsc)
{
    pr_problem p;
    cl_error err = {0};
    pr_load(&p, "problems/spring2.ini", NULL, NULL);
    cl_conv_opts o = {.t_end = 1.0, .max_stretch = 10, .ref_rtol = 1e-11,
                      .ref_linsol = ""};
    cl_conv_ref ref;
    cr_assert_eq(cl_conv_reference(p.m, &o, &ref, &err), CL_OK, "%s",
                 err.msg);
    const cl_integrator_type *t = cl_integrator_find(name);
    cl_integrator_opts io = {.dt = 1e-2, .petsc = petsc};
    cl_conv_result r;
    cr_assert_eq(cl_convergence(p.m, t, &io, 4, &o, &ref, &r, &err), CL_OK,
                 "%s: %s", name, err.msg);
    for (int k = 0; k < r.nlev; k++) {
        cr_log_info("%s dt %g: err_x %.3e err_v %.3e order %.3f steps %ld",
                    name, r.lev[k].param, r.lev[k].err_x, r.lev[k].err_v,
                    r.lev[k].order, r.lev[k].stats.steps);
        cr_assert_eq(r.lev[k].rc, CL_OK, "%s: %s", name, r.lev[k].why.msg);
        cr_assert_eq(r.lev[k].stats.steps, 100L << k, "%s", name);
    }
    cr_assert_eq(r.nfit, 4);
    cl_conv_ref_free(&ref);
    pr_free(&p);
    return r.slope_x;
}

/* TSBDF at its default order 2 (measured slope 2.00). */
Test(petsc_ts, bdf2_is_second_order_on_spring2)
{
    double q = order_on_spring2("petsc-bdf", "");
    cr_assert_lt(fabs(q - 2.0), 0.2, "slope %.3f", q);
}

/* TSALPHA2 at rho_inf = 0.5, with numerical dissipation (measured slope
 * 2.00; PETSc's default rho_inf = 1 is tested for its energy below). */
Test(petsc_ts, alpha2_is_second_order_on_spring2)
{
    double q = order_on_spring2("petsc-alpha2", "-ts_alpha_radius 0.5");
    cr_assert_lt(fabs(q - 2.0), 0.2, "slope %.3f", q);
}

/* Generalized-alpha with rho_inf = 1 has no numerical dissipation: on the
 * linear spring its energy is that of the start to the Newton tolerance
 * (the method is then the trapezoidal rule on M x'' = -K x, which
 * conserves the quadratic energy exactly), over 1000 steps of 1e-2 s
 * (16 periods). */
Test(petsc_ts, alpha2_with_radius_1_conserves_energy_on_spring2)
{
    s2_problem p;
    s2_load(&p);
    cl_integrator_opts o = {.dt = 1e-2, .petsc = "-ts_alpha_radius 1"};
    const cl_integrator_type *t = cl_integrator_find("petsc-alpha2");
    void *st = NULL;
    cl_error err = {0};
    double x[3], v[3];
    cl_energy e0, e1;
    cr_assert_eq(p.sys->energy(p.sys->data, 0.0, p.x0, p.v0, &e0), CL_OK);
    cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(t->advance(st, 10.0, x, v, &err), CL_OK, "%s", err.msg);
    t->free(st);
    cr_assert_eq(p.sys->energy(p.sys->data, 10.0, x, v, &e1), CL_OK);
    double drift = fabs(e1.total - e0.total) / e0.total;
    cr_log_info("energy %.12g -> %.12g, relative %.3e", e0.total, e1.total,
                drift);
    cr_assert_lt(drift, 1e-9);
    /* with rho_inf = 0.5 the same run loses energy */
    o.petsc = "-ts_alpha_radius 0.5";
    cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(t->advance(st, 10.0, x, v, &err), CL_OK, "%s", err.msg);
    t->free(st);
    cr_assert_eq(p.sys->energy(p.sys->data, 10.0, x, v, &e1), CL_OK);
    cr_log_info("rho_inf 0.5: energy %.12g", e1.total);
    cr_assert_lt(e1.total, 0.999 * e0.total);
    s2_free(&p);
}

/* Final state of `name` on hang-smooth (8 x 8) at T = 0.2 s, rtol 1e-6,
 * atol 1e-8. */
static void hang_smooth_final(const char *name, const char *petsc, double *x,
                              double *v, cl_stats *s)
{
    pr_problem p;
    cl_error err = {0};
    pr_load(&p, "problems/hang-smooth.ini", "cloth.n=8", NULL);
    const cl_system *sys = cl_model_system(p.m);
    double *x0 = malloc(sys->n * sizeof *x0), *v0 = malloc(sys->n * sizeof *v0);
    cr_assert(x0 && v0);
    cl_model_initial_state(p.m, x0, v0);
    const cl_integrator_type *t = cl_integrator_find(name);
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8, .petsc = petsc};
    void *st = NULL;
    cr_assert_eq(t->create(sys, &o, 0.0, x0, v0, &st, &err), CL_OK, "%s: %s",
                 name, err.msg);
    for (int k = 1; k <= 4; k++)
        cr_assert_eq(t->advance(st, 0.05 * k, x, v, &err), CL_OK, "%s: %s",
                     name, err.msg);
    t->stats(st, s);
    t->free(st);
    free(x0);
    free(v0);
    pr_free(&p);
}

/* petsc-bdf (order 2) and petsc-rosw against cvode-bdf, all at rtol 1e-6:
 * the final positions within 2e-5 m (measured 4.1e-6 and 7.7e-7 m; the
 * cloth's corners have fallen about 0.2 m), and PETSc's counters
 * filled. */
Test(petsc_ts, adaptive_runs_agree_with_cvode_on_hang_smooth)
{
    enum { N = 3 * 62 };
    double xc[N], vc[N], xp[N], vp[N];
    cl_stats sc, sp;
    hang_smooth_final("cvode-bdf", NULL, xc, vc, &sc);
    static const char *const names[] = {"petsc-bdf", "petsc-rosw"};
    for (int m = 0; m < 2; m++) {
        hang_smooth_final(names[m], "", xp, vp, &sp);
        double d = 0.0;
        for (int i = 0; i < N; i++)
            d = fmax(d, fabs(xp[i] - xc[i]));
        cr_log_info("%s: |x - x_cvode| %.3e, %ld steps (cvode %ld), %ld "
                    "rhs, %ld jac, %ld solves, %ld rejected", names[m], d,
                    sp.steps, sc.steps, sp.rhs_evals, sp.jac_evals,
                    sp.lin_solves, sp.err_fails);
        cr_assert_lt(d, 2e-5, "%s", names[m]);
        cr_assert_gt(sp.steps, 0);
        cr_assert_geq(sp.rhs_evals, sp.steps);
        cr_assert_gt(sp.jac_evals, 0);
        cr_assert_gt(sp.lin_solves, 0);
        cr_assert_str_eq(sp.linsol, "petsc:preonly+lu");
    }
}

/* With --dt the steps are fixed: whole steps of dt to each output time,
 * however many (3000 summed steps of 1e-3 s end half a step from the
 * rounding that once cut a 1e-19 s step and kept it), and an output time
 * between steps is refused rather than reached by a cut step. */
Test(petsc_ts, fixed_steps_are_whole_steps_of_dt)
{
    s2_problem p;
    s2_load(&p);
    const char *names[] = {"petsc-bdf", "petsc-alpha2"};
    for (int k = 0; k < 2; k++) {
        const cl_integrator_type *t = cl_integrator_find(names[k]);
        cr_assert(cl_integrator_fixed(t, 1e-3) && !cl_integrator_fixed(t, 0));
        cl_integrator_opts o = {.dt = 1e-3};
        void *st = NULL;
        cl_error err = {0};
        double x[3], v[3];
        cl_stats s;
        cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                     CL_OK, "%s", err.msg);
        cr_assert_eq(t->advance(st, 3.0, x, v, &err), CL_OK, "%s", err.msg);
        cr_assert_eq(t->advance(st, 3.001, x, v, &err), CL_OK, "%s",
                     err.msg);
        t->stats(st, &s);
        cr_assert_eq(s.steps, 3001, "%s: %ld steps", names[k], s.steps);
        cr_assert_eq(t->advance(st, 3.0015, x, v, &err), CL_EINVAL);
        cr_assert(strstr(err.msg, "not a multiple"), "%s", err.msg);
        t->free(st);
    }
    s2_free(&p);
}

/* A bad PETSc option, a step that is no step and an order TSBDF does not
 * have are refused with a message naming the integrator. */
Test(petsc_ts, refuses_bad_options_and_orders)
{
    s2_problem p;
    s2_load(&p);
    void *st = NULL;
    cl_error err = {0};
    const cl_integrator_type *t = cl_integrator_find("petsc-bdf");
    cl_integrator_opts o = {.petsc = "-ts_bdf_order 9"};
    cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                 CL_EINVAL);
    cr_assert_null(st);
    cr_assert(strstr(err.msg, "petsc-bdf"), "%s", err.msg);
    /* a step PETSc would take and fail with as a blow-up */
    o = (cl_integrator_opts){.petsc = "-ts_dt nan"};
    cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "-ts_dt nan: expected a finite number > 0"),
              "%s", err.msg);
    o = (cl_integrator_opts){.max_order = 7};
    cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "1 .. 6"), "%s", err.msg);
    o = (cl_integrator_opts){.max_order = 3};
    t = cl_integrator_find("petsc-alpha2");
    cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                 CL_EINVAL);
    s2_free(&p);
}

/* Options that would leave clothode's steps are refused: with fixed steps
 * a step or adaptivity of PETSc's own (the run ended 0.005 s before its
 * output time, or after it, labelled with the output time), TSBDF above
 * order 2 (its start holds fixed steps to order 2: orders 3 .. 6 measured
 * 2.0); without, no adaptivity (1.2e8 steps to 0.1 s); in either mode an
 * end of the output interval other than clothode's (interpolate crashed
 * in TSSolve). */
Test(petsc_ts, refuses_options_that_leave_the_steps)
{
    s2_problem p;
    s2_load(&p);
    static const struct {
        double dt;
        int order;
        const char *petsc, *why;
    } bad[] = {
        {1e-2, 0, "-ts_adapt_type basic", "may not change the step"},
        {1e-2, 0, "-ts_dt 0.03", "may not change the step"},
        {1e-2, 3, "", "TSBDF order 3 at fixed steps"},
        {1e-2, 0, "-ts_bdf_order 4", "TSBDF order 4 at fixed steps"},
        {1e-2, 0, "-ts_exact_final_time interpolate", "-ts_exact_final_time"},
        {0.0, 0, "-ts_exact_final_time stepover", "-ts_exact_final_time"},
        {0.0, 0, "-ts_exact_final_time interpolate", "-ts_exact_final_time"},
        {0.0, 0, "-ts_adapt_type none", "adaptive steps need an adaptor"}};
    const cl_integrator_type *t = cl_integrator_find("petsc-bdf");
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        cl_integrator_opts o = {.dt = bad[k].dt, .max_order = bad[k].order,
                                .petsc = bad[k].petsc};
        void *st = NULL;
        cl_error err = {0};
        cr_assert_eq(t->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                     CL_EINVAL, "%s", bad[k].petsc);
        cr_assert(strstr(err.msg, bad[k].why), "%s", err.msg);
    }
    s2_free(&p);
}

/* Counters that do not change the work: PETSc's linearly implicit
 * Rosenbrock method (4 stages) and TSBDF with SNESKSPONLY evaluate the
 * residual once per stage (8 and 2 per step when a monitor counted the
 * Newton iterations); TSALPHA2 with SNESKSPONLY keeps its one extra
 * evaluation at the solution, where it sets the stage velocity (without
 * it every velocity stayed 0), and ends where its Newton iteration does. */
Test(petsc_ts, counting_does_not_change_the_work)
{
    pr_problem p;
    pr_load(&p, "problems/hang-smooth.ini", "cloth.n=4", NULL);
    const cl_system *sys = cl_model_system(p.m);
    double x0[48], v0[48], x[48], v[48], xn[48], vn[48];
    cr_assert_eq(sys->n, 42);
    cl_model_initial_state(p.m, x0, v0);
    static const struct {
        const char *name, *petsc;
        long rhs;
    } c[] = {{"petsc-rosw", "", 400},
             {"petsc-bdf", "-snes_type ksponly", 101},
             {"petsc-alpha2", "-snes_type ksponly", 204},
             {"petsc-alpha2", "", 0}};
    for (int k = 0; k < 4; k++) {
        const cl_integrator_type *t = cl_integrator_find(c[k].name);
        cl_integrator_opts o = {.dt = 1e-3, .petsc = c[k].petsc};
        void *st = NULL;
        cl_error err = {0};
        cl_stats s;
        cr_assert_eq(t->create(sys, &o, 0.0, x0, v0, &st, &err), CL_OK,
                     "%s", err.msg);
        cr_assert_eq(t->advance(st, 0.1, k < 3 ? x : xn, k < 3 ? v : vn,
                                &err), CL_OK, "%s", err.msg);
        t->stats(st, &s);
        t->free(st);
        cr_log_info("%s %s: %ld steps, %ld rhs, %ld newton", c[k].name,
                    c[k].petsc, s.steps, s.rhs_evals, s.nonlin_iters);
        cr_assert_eq(s.steps, 100);
        if (c[k].rhs)
            cr_assert_eq(s.rhs_evals, c[k].rhs, "%s", c[k].name);
    }
    /* alpha2: one linearisation against Newton's iteration, 0.1 s in */
    double dx = 0.0, vmax = 0.0;
    for (int i = 0; i < 42; i++) {
        dx = fmax(dx, fabs(x[i] - xn[i]));
        vmax = fmax(vmax, fabs(vn[i]));
    }
    cr_log_info("alpha2 ksponly against newton: %.3e m (|v| up to %.3f)",
                dx, vmax);
    cr_assert_gt(vmax, 0.5);
    cr_assert_lt(dx, 1e-4);
    pr_free(&p);
}

/* A failed step says where and what to change, as the other integrators'
 * failures do: petsc-alpha2 at dt = 0.05 on hang (n = 8) loses its Newton
 * iteration in the first step. */
Test(petsc_ts, failed_step_says_where_and_what_to_change)
{
    char dir[512];
    tmp_mkdtemp(dir, sizeof dir, "petscfail");
    cli_result r;
    cli_run(&r, "run", "hang", "--integrator", "petsc-alpha2", "--dt", "0.05",
            "--t-end", "0.1", "--set", "cloth.n=8", "--out", dir, "--quiet",
            NULL);
    cr_assert(r.exited && r.status == 3, "%s: %s", r.cmd, r.err);
    cr_assert(strstr(r.err, "DIVERGED_NONLINEAR_SOLVE"), "%s", r.err);
    cr_assert(strstr(r.err, "(at t = 0); to change: reduce --dt"), "%s",
              r.err);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}

/* convergence of petsc-bdf on spring2 from --dt 1e-2 (two levels) or
 * --from-sweep TABLE: the levels dt = 1e-2 and 5e-3 at fixed steps (100
 * and 200, order 2.01). */
static void bdf_fixed_levels(const char *option, const char *value,
                             const char *dir)
{
    cli_result r;
    bool dt = !strcmp(option, "--dt");
    cli_run(&r, "convergence", "spring2", "--integrator", "petsc-bdf",
            option, value, "--out", dir, dt ? "--levels" : NULL, "2", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "petsc-bdf           1.000e-02  2.990e-03") &&
              strstr(r.out, "    2.01       200 "), "%s", r.out);
    cli_result_free(&r);
}

/* The command line's studies take a petsc-* method given --dt at fixed
 * steps too (they ran it adaptively at the problem's rtol before, 255k
 * steps at convergence's last level), and a tolerance that a fixed-step
 * petsc-* run would not read is refused. */
Test(petsc_ts, studies_take_dt_as_fixed_steps)
{
    char dir[512];
    tmp_mkdtemp(dir, sizeof dir, "petscdt");
    cli_result r;
    bdf_fixed_levels("--dt", "1e-2", dir);
    /* energy says so; convergence reads a sweep's petsc-* rows by dt */
    cli_run(&r, "energy", "spring2", "--integrator", "petsc-alpha2", "--dt",
            "1e-2", "--samples", "10", "--out", dir, NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "\nfixed      dt = 0.01 s\n") &&
              !strstr(r.out, "adaptive"), "%s", r.out);
    cli_result_free(&r);
    char sweep[600], table[600];
    cli_sweep_through(dir, "[sweep]\nproblem = problems/spring2.ini\n"
                           "integrator = petsc-bdf\ndt = 0.01, 0.005\n"
                           "t_end = 1\nreference = 1e-11\n",
                      sweep, table, sizeof table);
    bdf_fixed_levels("--from-sweep", table, dir);
    cli_run(&r, "energy", "spring2", "--integrator", "petsc-bdf",
            "--from-sweep", table, "--out", dir, NULL);
    cli_assert_error(&r, 0, "the sweep ran petsc-bdf at fixed steps "
                     "(run.dt): give --dt to pick its run", NULL);
    cli_result_free(&r);
    cli_run(&r, "run", "spring2", "--integrator", "petsc-bdf", "--dt",
            "1e-2", "--rtol", "1e-3", "--out", dir, NULL);
    cli_assert_error(&r, 0, "[run] rtol = \"1e-3\"", "integrator petsc-bdf "
                     "reads no rtol", NULL);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}

/* An option no PETSc object has read after the first step, which PETSc
 * would ignore, ends the run there as a bad input: a
 * misspelt one (petsc-alpha2 ran "-ts_alpha_radius=0.5" at radius 1), one
 * for another method, a global one. */
Test(petsc_ts, unread_options_are_refused)
{
    char dir[512];
    tmp_mkdtemp(dir, sizeof dir, "petscleft");
    static const char *const bad[][3] = {
        {"petsc-alpha2", "-ts_alpha_radius=0.5", "-ts_alpha_radius=0.5"},
        {"petsc-rosw", "-ts_monitor -ts_bdf_order 3", "-ts_bdf_order"},
        {"petsc-bdf", "-log_view", "-log_view"}};
    for (int k = 0; k < 3; k++) {
        cli_result r;
        cli_run(&r, "run", "spring2", "--integrator", bad[k][0], "--dt",
                "1e-2", "--petsc", bad[k][1], "--out", dir, "--quiet", NULL);
        cr_assert(r.exited && r.status == 2, "%s: %s", r.cmd, r.err);
        char want[160];
        snprintf(want, sizeof want, "no PETSc object of %s read %s:",
                 bad[k][0], bad[k][2]);
        cr_assert(strstr(r.err, want), "%s", r.err);
        cli_result_free(&r);
    }
    tmp_rm_rf(dir);
}

/* PETSc's rejections and failures are counts over the whole run: the same
 * adaptive run to 0.5 s in one advance and in 50 reports about as many
 * (they were added up after every advance: 12442 rejections for 4985
 * residuals on hang 6 x 6 with 200 outputs). */
Test(petsc_ts, counts_do_not_grow_with_the_outputs)
{
    pr_problem p;
    pr_load(&p, "problems/hang.ini", "cloth.n=6", NULL);
    const cl_system *sys = cl_model_system(p.m);
    double x0[108], v0[108], x[108], v[108];
    cr_assert_eq(sys->n, 102);
    cl_model_initial_state(p.m, x0, v0);
    const cl_integrator_type *t = cl_integrator_find("petsc-bdf");
    cl_stats s[2];
    for (int k = 0; k < 2; k++) {
        int outputs = k ? 50 : 1;
        cl_integrator_opts o = {.rtol = 1e-4, .atol = 1e-6};
        void *st = NULL;
        cl_error err = {0};
        cr_assert_eq(t->create(sys, &o, 0.0, x0, v0, &st, &err), CL_OK,
                     "%s", err.msg);
        for (int i = 1; i <= outputs; i++)
            cr_assert_eq(t->advance(st, 0.5 * i / outputs, x, v, &err),
                         CL_OK, "%s", err.msg);
        t->stats(st, &s[k]);
        t->free(st);
        cr_log_info("%d outputs: %ld steps, %ld rhs, %ld rejected", outputs,
                    s[k].steps, s[k].rhs_evals, s[k].err_fails);
        cr_assert_lt(s[k].err_fails, s[k].steps);
    }
    cr_assert_lt(s[1].err_fails, 2 * s[0].err_fails + 10);
    pr_free(&p);
}
