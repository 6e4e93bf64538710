/* The ARKODE integrators (integrators/arkode_common.h): observed orders of
 * the DIRK tables and IMEX pairs on spring2 through the convergence study
 * (analysis/convergence.h), tolerance proportionality of the adaptive
 * ones on hang-smooth, backward Euler equal to kinsol-be (converged, and
 * with one linearisation to Baraff-Witkin's step, the one-iteration
 * kinsol-be), the IMEX split through the term mask against the full
 * force, and the refused tables. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/convergence.h"
#include "io/config.h"
#include "problem.h"

/* ---- orders on spring2 -------------------------------------------------- */

typedef struct {
    const char *name;  /* integrator */
    const char *table;
    double dt0;        /* first step (fixed) or rtol (adaptive) */
    double order;      /* expected slope */
} ak_case;

/* The fitted slope in x of `c` on spring2 (with the assignment `set`) over
 * 4 levels, T = 1, against cvode-bdf at rtol 1e-13. */
static double ak_slope(const ak_case *c, const char *set)
{
    pr_problem p;
    cl_error err = {0};
    pr_load(&p, "problems/spring2.ini", set, NULL);
    cl_conv_opts o = {.t_end = 1.0, .max_stretch = 10, .ref_rtol = 1e-13,
                      .ref_linsol = ""};
    cl_conv_ref ref;
    cr_assert_eq(cl_conv_reference(p.m, &o, &ref, &err), CL_OK, "%s",
                 err.msg);
    const cl_integrator_type *type = cl_integrator_find(c->name);
    cr_assert_not_null(type, "%s", c->name);
    /* fixed steps: tight Newton weights (rtol, atol weigh its test) */
    cl_integrator_opts io = {.dt = type->fixed_step ? c->dt0 : 0.0,
                             .rtol = type->fixed_step ? 1e-12 : c->dt0,
                             .atol = type->fixed_step ? 1e-14 : c->dt0 / 100,
                             .table = c->table};
    cl_conv_result r;
    cr_assert_eq(cl_convergence(p.m, type, &io, 4, &o, &ref, &r, &err),
                 CL_OK, "%s %s: %s", c->name, c->table, err.msg);
    for (int k = 0; k < r.nlev; k++)
        cr_log_info("%s %s %g: err_x %.3e order %.3f fitted %d", c->name,
                    c->table, r.lev[k].param, r.lev[k].err_x,
                    r.lev[k].order, r.lev[k].fitted);
    cr_assert_geq(r.nfit, 3, "%s %s: %d levels fitted", c->name, c->table,
                  r.nfit);
    cl_conv_ref_free(&ref);
    pr_free(&p);
    return r.slope_x;
}

static void ak_check_orders(const ak_case *cs, size_t n, const char *set)
{
    for (size_t i = 0; i < n; i++) {
        double q = ak_slope(&cs[i], set);
        cr_log_info("%s %s: observed order %.3f, theory %g", cs[i].name,
                    cs[i].table, q, cs[i].order);
        cr_expect(fabs(q - cs[i].order) < 0.2, "%s %s: observed %.3f, "
                  "theory %g", cs[i].name, cs[i].table, q, cs[i].order);
    }
}

/* Each table's order (the last digit but one of SUNDIALS' names: stages,
 * embedding, order), at steps where the error lies well above the
 * reference's floor and in the asymptotic range. */
Test(arkode, dirk_orders_on_spring2)
{
    static const ak_case cs[] = {
        {"arkode-dirk-fixed", "BACKWARD_EULER_1_1", 2e-3, 1},
        {"arkode-dirk-fixed", "IMPLICIT_MIDPOINT_1_2", 1e-2, 2},
        {"arkode-dirk-fixed", "SDIRK_2_1_2", 1e-2, 2},
        {"arkode-dirk-fixed", "BILLINGTON_3_3_2", 1e-2, 2},
        {"arkode-dirk-fixed", "TRBDF2_3_3_2", 1e-2, 2},
        {"arkode-dirk-fixed", "KVAERNO_4_2_3", 2e-2, 3},
        {"arkode-dirk-fixed", "ARK324L2SA_DIRK_4_2_3", 2e-2, 3},
        {"arkode-dirk-fixed", "ARK436L2SA_DIRK_6_3_4", 5e-2, 4},
    };
    ak_check_orders(cs, sizeof cs / sizeof *cs, NULL);
}

/* The pairs with the spring explicit (the implicit half then holds
 * x' = v alone), so that the coupling of the two halves is what
 * converges. */
Test(arkode, imex_orders_on_spring2)
{
    static const ak_case cs[] = {
        {"arkode-imex-fixed", "ARK324L2SA", 2e-2, 3},
        {"arkode-imex-fixed", "ARK436L2SA", 5e-2, 4},
        {"arkode-imex-fixed", "ARK548L2SA", 2.5e-2, 5},
    };
    ak_check_orders(cs, sizeof cs / sizeof *cs, "type1.imex=explicit");
}

/* ---- tolerance proportionality ----------------------------------------- */

/* The adaptive methods on hang-smooth (n = 8, T = 0.2 s) at rtol 1e-4 ..
 * 1e-7 (atol rtol / 100): the error follows the tolerance, slope 1.05
 * measured for both (gravity, the one explicit term there, is constant:
 * the pair's halves share their nodes and weights, so the IMEX run equals
 * the DIRK run). */
Test(arkode, adaptive_error_follows_rtol)
{
    const char *const names[] = {"arkode-dirk", "arkode-imex"};
    pr_problem p;
    cl_error err = {0};
    pr_load(&p, "problems/hang-smooth.ini", "cloth.n=8", NULL);
    cl_conv_opts o = {.t_end = 0.2, .max_stretch = 10, .ref_rtol = 1e-11,
                      .ref_linsol = ""};
    cl_conv_ref ref;
    cr_assert_eq(cl_conv_reference(p.m, &o, &ref, &err), CL_OK, "%s",
                 err.msg);
    for (size_t i = 0; i < 2; i++) {
        cl_integrator_opts io = {.rtol = 1e-4, .atol = 1e-6};
        cl_conv_result r;
        cr_assert_eq(cl_convergence(p.m, cl_integrator_find(names[i]), &io,
                                    4, &o, &ref, &r, &err),
                     CL_OK, "%s: %s", names[i], err.msg);
        cr_log_info("%s: slope %.3f over %d levels, errors %.3e .. %.3e",
                    names[i], r.slope_x, r.nfit, r.lev[0].err_x,
                    r.lev[3].err_x);
        cr_expect_eq(r.nfit, 4, "%s", names[i]);
        cr_expect(fabs(r.slope_x - 1.0) < 0.2, "%s: slope %.3f", names[i],
                  r.slope_x);
    }
    cl_conv_ref_free(&ref);
    pr_free(&p);
}

/* ---- backward Euler against kinsol-be ---------------------------------- */

/* `steps` steps of o->dt of `name` with options o on p from rest into x,
 * v. */
static void ak_steps(pr_problem *p, const char *name,
                     const cl_integrator_opts *o, long steps, double *x,
                     double *v)
{
    const cl_system *sys = cl_model_system(p->m);
    const cl_integrator_type *type = cl_integrator_find(name);
    double *x0 = malloc(sys->n * sizeof *x0), *v0 = malloc(sys->n * sizeof *v0);
    cr_assert(x0 && v0 && type);
    cl_model_initial_state(p->m, x0, v0);
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(type->create(sys, o, 0.0, x0, v0, &st, &err), CL_OK,
                 "%s: %s", name, err.msg);
    cr_assert_eq(type->advance(st, steps * o->dt, x, v, &err), CL_OK,
                 "%s: %s", name, err.msg);
    cl_stats s = {0};
    type->stats(st, &s);
    cr_assert_eq(s.steps, steps, "%s: %ld steps", name, s.steps);
    cr_log_info("%s: %ld Newton iterations, %ld Jacobians", name,
                s.nonlin_iters, s.jac_evals);
    type->free(st);
    free(x0);
    free(v0);
}

/* max |a - b| / max |a| over n entries. */
static double ak_reldiff(const double *a, const double *b, size_t n)
{
    double d = 0, m = 0;
    for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        m = fmax(m, fabs(a[i]));
    }
    return d / m;
}

/* kinsol-be with options ko against arkode-dirk-fixed with ao, `steps`
 * steps each on hang at n = 8 from rest: the relative differences of the
 * positions and velocities into d[0], d[1]. */
static void ak_versus_kinsol_be(const cl_integrator_opts *ko,
                                const cl_integrator_opts *ao, long steps,
                                double d[2])
{
    pr_problem p;
    pr_load(&p, "problems/hang.ini", "cloth.n=8", NULL);
    size_t n = cl_model_system(p.m)->n;
    double *xk = malloc(n * sizeof *xk), *vk = malloc(n * sizeof *vk);
    double *xa = malloc(n * sizeof *xa), *va = malloc(n * sizeof *va);
    cr_assert(xk && vk && xa && va);
    ak_steps(&p, "kinsol-be", ko, steps, xk, vk);
    ak_steps(&p, "arkode-dirk-fixed", ao, steps, xa, va);
    d[0] = ak_reldiff(xk, xa, n);
    d[1] = ak_reldiff(vk, va, n);
    free(xk);
    free(vk);
    free(xa);
    free(va);
    pr_free(&p);
}

/* arkode-dirk-fixed with the table BACKWARD_EULER_1_1 against kinsol-be
 * (tight Newton on both sides), and both at one Newton iteration
 * (Baraff-Witkin's linearised step): positions and velocities agree to
 * 1e-10 relative (measured 6e-15 and 3e-12), and to round-off (2e-15)
 * with one linearisation on KLU. */
static void ak_check_be(long maxit, double tol, const char *linsol)
{
    cl_integrator_opts ko = {.dt = 1e-3, .newton_tol = 1e-12,
                             .newton_maxit = maxit};
    cl_integrator_opts ao = {.dt = 1e-3, .rtol = 1e-10, .atol = 1e-10,
                             .newton_tol = 1e-3,
                             .newton_maxit = maxit ? maxit : 50,
                             .linsol = linsol, .table = "BACKWARD_EULER_1_1"};
    double d[2];
    ak_versus_kinsol_be(&ko, &ao, 10, d);
    cr_log_info("newton_maxit %ld, %s: relative differences x %.3e, v %.3e",
                maxit, linsol[0] ? linsol : "auto", d[0], d[1]);
    cr_expect_leq(d[0], tol);
    cr_expect_leq(d[1], tol);
}

/* On the undamped spring (spring2, T = 1 s, 1.6 periods) the adaptive
 * methods end within 10 rtol of the closed form at rtol 1e-4 (measured
 * 1.8e-4 m): with ARKODE's default Newton matrix, set up every 20 steps,
 * their stages were solved to errors the embedded estimate does not see,
 * 2.4e-2 m (24 % of the amplitude). */
Test(arkode, adaptive_error_on_the_undamped_spring)
{
    const char *const names[] = {"arkode-dirk", "arkode-imex"};
    pr_problem p;
    pr_load(&p, "problems/spring2.ini", NULL, NULL);
    const cl_system *sys = cl_model_system(p.m);
    double x0[6], v0[6], x[6], v[6];
    cr_assert_eq(sys->n, 3);
    cl_model_initial_state(p.m, x0, v0);
    for (size_t i = 0; i < 2; i++) {
        const cl_integrator_type *t = cl_integrator_find(names[i]);
        cl_integrator_opts io = {.rtol = 1e-4, .atol = 1e-10};
        void *st = NULL;
        cl_error err = {0};
        cr_assert_eq(t->create(sys, &io, 0.0, x0, v0, &st, &err), CL_OK,
                     "%s", err.msg);
        cr_assert_eq(t->advance(st, 1.0, x, v, &err), CL_OK, "%s", err.msg);
        t->free(st);
        double e = fabs(x[0] - (1.0 + 0.1 * sin(10.0)));
        cr_log_info("%s: |x - x(1)| %.3e", names[i], e);
        cr_assert_lt(e, 1e-3, "%s", names[i]);
    }
    pr_free(&p);
}

Test(arkode, backward_euler_equals_kinsol_be)
{
    ak_check_be(0, 1e-10, "klu");
}

Test(arkode, one_linearisation_equals_baraff_witkin)
{
    /* the iterative solvers too (auto: pcg), at their own tolerance */
    ak_check_be(1, 1e-13, "klu");
    ak_check_be(1, 1e-10, "");
}

/* hang at n = 8, 100 steps of 2e-3 with the default Newton settings (the
 * problem's rtol 1e-4, atol 1e-6): the stages cross the kinks of the
 * Choi-Ko pair forces, where the modified Newton iteration diverges and
 * the full one (sun_newton.h) converges.  Backward Euler through ARKODE
 * reaches the end and agrees with kinsol-be within ARKODE's Newton
 * tolerance (rtol 1e-4): 1e-5 relative in x, 1e-4 in v (measured 1.9e-7
 * and 8.7e-6); SDIRK_2_1_2 reaches the end too. */
Test(arkode, fixed_steps_across_the_kinks)
{
    cl_integrator_opts ko = {.dt = 2e-3};
    cl_integrator_opts ao = {.dt = 2e-3, .rtol = 1e-4, .atol = 1e-6,
                             .table = "BACKWARD_EULER_1_1"};
    double d[2];
    ak_versus_kinsol_be(&ko, &ao, 100, d);
    cr_log_info("relative differences x %.3e, v %.3e", d[0], d[1]);
    cr_expect_leq(d[0], 1e-5);
    cr_expect_leq(d[1], 1e-4);
    ao.table = "SDIRK_2_1_2"; /* its 100 steps: ak_steps asserts them */
    ak_versus_kinsol_be(&ko, &ao, 100, d);
}

/* ---- refusals ---------------------------------------------------------- */

static void ak_refused(const char *name, const char *table,
                       const char *needle)
{
    pr_problem p;
    pr_load(&p, "problems/spring2.ini", NULL, NULL);
    const cl_system *sys = cl_model_system(p.m);
    double x0[3], v0[3];
    cl_model_initial_state(p.m, x0, v0);
    cl_integrator_opts o = {.dt = 1e-2, .table = table};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(cl_integrator_find(name)->create(sys, &o, 0.0, x0, v0, &st,
                                                  &err),
                 CL_EINVAL, "%s %s", name, table);
    cr_assert_null(st);
    cr_assert_not_null(strstr(err.msg, needle), "\"%s\" lacks \"%s\"",
                       err.msg, needle);
    pr_free(&p);
}

/* Unknown names list the known ones; the tables without an embedded
 * estimate take fixed steps only; a DIRK table is no IMEX pair. */
Test(arkode, refused_tables)
{
    ak_refused("arkode-dirk", "NO_SUCH", "expected one of SDIRK_2_1_2");
    ak_refused("arkode-dirk", "BACKWARD_EULER_1_1", "no embedded");
    ak_refused("arkode-imex-fixed", "SDIRK_2_1_2", "ARK548L2SA)");
    ak_refused("arkode-dirk-fixed", "ARK436L2SA", "IMPLICIT_MIDPOINT_1_2");
}
