/* What kinsol-be, kinsol-bdf2, kinsol-midpoint and kinsol-galpha share
 * (integrators/kinsol_common.c), checked for each of them: registry rows,
 * option checks, output times, one Newton iteration per step on a linear
 * model with one KLU symbolic analysis per run, the tolerance, the
 * iteration-cap rules (newton_maxit = 1 never fails; a capped solve that
 * does not converge stops the run with CL_ESOLVER and its time), failing
 * forces, other linear solvers; Rayleigh damping (kinsol-midpoint).
 * Helpers: kinsol_test.h. */
#include <criterion/criterion.h>

#include "kinsol_test.h"
#include "linalg/linsol.h"
#include "testsys.h"

static const char *const kt_methods[] = {"kinsol-be", "kinsol-bdf2",
                                         "kinsol-midpoint", "kinsol-galpha"};
enum { KT_NMETHODS = 4 };

/* A stiff, strongly nonlinear spring2: ks = 1e4 (w = 100) and a fast
 * transverse initial velocity that swings the spring round. */
static const char *const kt_stiff[] = {"type1.ks=1e4", "init.velocity=2,5,0",
                                       NULL};

typedef void (*kt_case_fn)(const char *name,
                           const cl_integrator_type *it,
                           const s2_problem *p);

/* fn for each method, on spring2 loaded with `sets` (NULL: as it is). */
static void kt_each(const char *const *sets, kt_case_fn fn)
{
    s2_problem p;
    st_load(&p, sets);
    for (int k = 0; k < KT_NMETHODS; k++) {
        const cl_integrator_type *it = cl_integrator_find(kt_methods[k]);
        cr_assert_not_null(it, "%s not registered", kt_methods[k]);
        fn(kt_methods[k], it, &p);
    }
    s2_free(&p);
}

static void registry_row(const char *name, const cl_integrator_type *it,
                         const s2_problem *p)
{
    (void)p;
    cr_assert(it->fixed_step && it->takes_linsol);
    cr_assert_str_eq(it->name, name);
}

Test(kinsol_common, registry_rows) { kt_each(NULL, registry_row); }

static void bad_options(const char *name, const cl_integrator_type *it,
                        const s2_problem *p)
{
    const cl_integrator_opts bad[] = {
        {.dt = 0.0},
        {.dt = -1e-3},
        {.dt = NAN},
        {.dt = 1e-3, .newton_tol = -1.0},
        {.dt = 1e-3, .newton_tol = INFINITY},
        {.dt = 1e-3, .newton_maxit = -1},
        {.dt = 1e-3, .linsol = "no-such-solver"},
    };
    for (size_t j = 0; j < sizeof bad / sizeof bad[0]; j++) {
        void *st = (void *)p;
        cl_error err = {0};
        cr_assert_eq(it->create(p->sys, &bad[j], 0.0, p->x0, p->v0, &st,
                                &err),
                     CL_EINVAL, "%s case %zu", name, j);
        cr_assert_null(st);
        cr_assert_not_null(strstr(err.msg, name), "%s", err.msg);
    }
}

Test(kinsol_common, bad_options) { kt_each(NULL, bad_options); }

static void output_times(const char *name, const cl_integrator_type *it,
                         const s2_problem *p)
{
    cl_integrator_opts o = {.dt = 0.01};
    double x[3], v[3], x2[3], v2[3];
    cl_error err = {0};
    cl_stats s;
    void *st = kt_create(name, p, &o);
    cr_assert_eq(it->advance(st, 0.0, x, v, &err), CL_OK);
    cr_assert_eq(kt_diff3(x, p->x0) + kt_diff3(v, p->v0), 0.0);
    cr_assert_eq(it->advance(st, 0.005, x, v, &err), CL_EINVAL);
    cr_assert_eq(it->advance(st, 0.1, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(it->advance(st, 0.1, x2, v2, &err), CL_OK);
    cr_assert_eq(kt_diff3(x, x2) + kt_diff3(v, v2), 0.0);
    cr_assert_eq(it->advance(st, 0.05, x, v, &err), CL_EINVAL);
    it->stats(st, &s);
    cr_assert_eq(s.steps, 10);
    it->free(st);
}

Test(kinsol_common, output_times) { kt_each(NULL, output_times); }

/* spring2 is linear: one full Newton step from any predictor solves each
 * step's system to round-off, so every step takes exactly one iteration,
 * one Jacobian, one factorisation, one solve and two force evaluations
 * (predictor and new iterate; kinsol-galpha one more at the start, its
 * initial acceleration); KLU analyses once for the whole run, over
 * several advance calls. */
static void linear_one_iteration(const char *name,
                                 const cl_integrator_type *it,
                                 const s2_problem *p)
{
    cl_integrator_opts o = {.dt = 0.01};
    void *st = kt_create(name, p, &o);
    double x[3], v[3];
    cl_error err = {0};
    cl_stats s;
    for (int q = 1; q <= 4; q++)
        cr_assert_eq(it->advance(st, 0.25 * q, x, v, &err), CL_OK, "%s",
                     err.msg);
    it->stats(st, &s);
    it->free(st);
    cr_log_info("%s linear: steps %ld rhs %ld jac %ld setups %ld solves %ld "
                "newton %ld symbolic %ld", name, s.steps, s.rhs_evals,
                s.jac_evals, s.lin_setups, s.lin_solves, s.nonlin_iters,
                s.symbolic_facts);
    /* T / dt = 1 / 0.01 steps */
    cr_assert_eq(s.steps, 100);
    cr_assert_eq(s.nonlin_iters, 100, "%s", name);
    cr_assert_eq(s.jac_evals, 100);
    cr_assert_eq(s.lin_setups, 100);
    cr_assert_eq(s.lin_solves, 100);
    /* kinsol-galpha: one more for its initial acceleration */
    cr_assert_eq(s.rhs_evals, 200 + !strcmp(name, "kinsol-galpha"));
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.nonlin_fails + s.err_fails + s.lin_iters, 0);
}

Test(kinsol_common, linear_problem_one_iteration_per_step)
{
    kt_each(NULL, linear_one_iteration);
}

/* Converged Newton on the stiff nonlinear case: several iterations per
 * step; a looser tolerance takes fewer and lands within it. */
static void tolerance(const char *name, const cl_integrator_type *it,
                      const s2_problem *p)
{
    cl_integrator_opts tight = {.dt = 0.01, .newton_tol = 1e-13};
    cl_integrator_opts loose = {.dt = 0.01, .newton_tol = 1e-3};
    double xt[3], vt[3], xl[3], vl[3];
    cl_stats st, sl;
    (void)it;
    kt_run(name, p, &tight, 0.1, xt, vt, &st);
    kt_run(name, p, &loose, 0.1, xl, vl, &sl);
    cr_log_info("%s stiff: newton %ld (tol 1e-13), %ld (tol 1e-3); |dv| "
                "%.3e", name, st.nonlin_iters, sl.nonlin_iters,
                kt_diff3(vt, vl));
    cr_assert_gt(st.nonlin_iters, 2 * st.steps);
    cr_assert_lt(sl.nonlin_iters, st.nonlin_iters);
    cr_assert_lt(kt_diff3(vt, vl), 0.05);
}

Test(kinsol_common, tolerance_controls_iterations)
{
    kt_each(kt_stiff, tolerance);
}

/* The iteration-cap rules on the stiff nonlinear case with a tight
 * tolerance.  newton_maxit = 1 is the linearly implicit method: one Newton
 * iteration per step, never a convergence failure.  newton_maxit = 2: the
 * first step cannot converge; the run stops with CL_ESOLVER naming the
 * step and its time, one failure counted, the state left at t = 0. */
static void iteration_cap(const char *name, const cl_integrator_type *it,
                          const s2_problem *p)
{
    cl_integrator_opts o = {.dt = 0.05, .newton_tol = 1e-14,
                            .newton_maxit = 1};
    double x[3], v[3];
    cl_error err = {0};
    cl_stats s;
    kt_run(name, p, &o, 0.5, x, v, &s);
    cr_assert(s.steps == 10 && s.nonlin_iters == 10 && s.jac_evals == 10 &&
              s.lin_solves == 10 && s.nonlin_fails == 0, "%s", name);
    o.newton_maxit = 2;
    void *st = kt_create(name, p, &o);
    cr_assert_eq(it->advance(st, 0.5, x, v, &err), CL_ESOLVER);
    cr_log_info("%s", err.msg);
    cr_assert_not_null(strstr(err.msg, name));
    cr_assert_not_null(strstr(err.msg, "step 1 (t = 0 -> 0.05"), "%s",
                       err.msg);
    cr_assert_not_null(strstr(err.msg, "KIN_MAXITER_REACHED"), "%s",
                       err.msg);
    cr_assert_eq(kt_diff3(x, p->x0) + kt_diff3(v, p->v0), 0.0);
    it->stats(st, &s);
    it->free(st);
    cr_assert(s.steps == 0 && s.nonlin_fails == 1 && s.nonlin_iters == 2);
}

Test(kinsol_common, iteration_cap_rules) { kt_each(kt_stiff, iteration_cap); }

/* A force that turns NaN from t = 0.3 on (testsys.h) stops the run with
 * CL_EBLOWUP and the time; the state stays at the last completed step. */
static void failing_force(const char *name, const cl_integrator_type *it,
                          const s2_problem *p)
{
    ts_sys ts;
    double x0[6], v0[6], x[6], v[6];
    cl_integrator_opts o = {.dt = 0.1};
    void *st = NULL;
    cl_error err = {0};
    cl_stats s;
    (void)p;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    ts.fail = TS_FAIL_NAN;
    ts.t_bad = 0.3;
    ts_initial(&ts, x0, v0);
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x0, v0, &st, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(it->advance(st, 1.0, x, v, &err), CL_EBLOWUP, "%s", name);
    cr_log_info("%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "t = "), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "not finite"), "%s", err.msg);
    it->stats(st, &s);
    it->free(st);
    ts_free(&ts);
    cr_assert_eq(s.nonlin_fails, 1);
    cr_assert(s.steps == 2 || s.steps == 3, "%ld", s.steps);
    for (int i = 0; i < 6; i++)
        cr_assert(isfinite(x[i]) && isfinite(v[i]));
}

Test(kinsol_common, failing_force_reports_time)
{
    kt_each(NULL, failing_force);
}

/* Every registered linear solver gives the trajectory of the default klu
 * on a nonlinear spring2. */
static void linear_solvers(const char *name, const cl_integrator_type *it,
                           const s2_problem *p)
{
    double xr[3], vr[3], x[3], v[3];
    cl_integrator_opts o = {.dt = 0.01, .newton_tol = 1e-12,
                            .lin_tol = 1e-13};
    cl_stats s;
    (void)it;
    kt_run(name, p, &o, 0.5, xr, vr, &s);
    for (size_t j = 1; cl_linsol_registry[j]; j++) {
        o.linsol = cl_linsol_registry[j]->name;
        kt_run(name, p, &o, 0.5, x, v, &s);
        cr_log_info("%s --linsol %s: |dx| %.3e |dv| %.3e, lin iters %ld",
                    name, o.linsol, kt_diff3(x, xr), kt_diff3(v, vr),
                    s.lin_iters);
        cr_assert_lt(kt_diff3(x, xr) + kt_diff3(v, vr), 1e-9);
    }
}

Test(kinsol_common, linear_solvers_agree)
{
    const char *const sets[] = {"init.velocity=1,0.8,0", NULL};
    kt_each(sets, linear_solvers);
}

/* spring2 with `sets` by kinsol-midpoint with Rayleigh damping (ra, rb)
 * to T = 1 in steps of dt into x, v. */
static void kt_rayleigh_run(const char *const *sets, double ra, double rb,
                            double dt, double *x, double *v)
{
    s2_problem p;
    st_load(&p, sets);
    cl_integrator_opts o = {.dt = dt, .rayleigh_alpha = ra,
                            .rayleigh_beta = rb, .newton_tol = 1e-13};
    cl_stats s;
    kt_run("kinsol-midpoint", &p, &o, 1.0, x, v, &s);
    s2_free(&p);
}

/* On spring2 (one particle, motion along the spring) Rayleigh damping is
 * Choi-Ko damping: alpha M v = kd v for kd = alpha m (m = 1 kg), and
 * beta K v = beta ks v along the axis, kd = beta ks (ks = 100 N/m). */
Test(kinsol_common, rayleigh_equals_pair_damping_on_spring2)
{
    const char *const kd07[] = {"damping.kd=0.7", NULL};
    const char *const kd05[] = {"damping.kd=0.5", NULL};
    double xa[3], va[3], xb[3], vb[3];
    kt_rayleigh_run(NULL, 0.7, 0.0, 0.01, xa, va);
    kt_rayleigh_run(kd07, 0.0, 0.0, 0.01, xb, vb);
    double da = fmax(kt_diff3(xa, xb), kt_diff3(va, vb));
    kt_rayleigh_run(NULL, 0.0, 0.005, 0.01, xa, va);
    kt_rayleigh_run(kd05, 0.0, 0.0, 0.01, xb, vb);
    double db = fmax(kt_diff3(xa, xb), kt_diff3(va, vb));
    cr_log_info("Rayleigh vs pair damping on spring2: alpha %.3e, beta "
                "%.3e (final v %.6f)", da, db, va[0]);
    cr_assert_lt(da, 1e-12);
    cr_assert_lt(db, 1e-12);
    cr_assert_lt(fabs(va[0]), 0.8, "damped: the undamped v(1) is -0.839");
}

/* With K frozen at the predicted midpoint the midpoint rule stays second
 * order: on spring2 swung round (K varies along the motion) the
 * differences between runs at dt and dt/2 fall by 4 per halving. */
Test(kinsol_common, rayleigh_midpoint_second_order)
{
    const char *const swing[] = {"init.velocity=1,3,0", NULL};
    double x[5][3], v[5][3], d[4];
    for (int k = 0; k < 5; k++)
        kt_rayleigh_run(swing, 0.3, 0.01, 0.02 / (1 << k), x[k], v[k]);
    for (int k = 0; k < 4; k++)
        d[k] = kt_diff3(x[k], x[k + 1]);
    for (int k = 1; k < 4; k++) {
        cr_log_info("Rayleigh midpoint: difference ratio %.3f",
                    d[k - 1] / d[k]);
        cr_assert(fabs(log2(d[k - 1] / d[k]) - 2.0) < 0.2, "%g",
                  d[k - 1] / d[k]);
    }
}

Test(kinsol_common, rayleigh_refused_elsewhere)
{
    s2_problem p;
    st_load(&p, NULL);
    cl_integrator_opts o = {.dt = 0.01, .rayleigh_beta = 0.01, .force = true};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(cl_integrator_create(cl_integrator_find("semi-be"), p.sys,
                                      &o, 0.0, p.x0, p.v0, &st, &err),
                 CL_EUNSUPPORTED);
    cr_assert_null(st);
    cr_assert(strstr(err.msg, "semi-be") && strstr(err.msg, "Rayleigh"),
              "%s", err.msg);
    o.rayleigh_beta = -1.0;
    cr_assert_eq(cl_integrator_create(cl_integrator_find("kinsol-midpoint"),
                                      p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                 CL_EINVAL);
    s2_free(&p);
}
