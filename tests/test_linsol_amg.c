/* Tests for the algebraic-multigrid solvers amg and amg-hypre
 * (linalg/linsol_amg.c, on PETSc in the plug-in clothode-petsc.so):
 *  - on the Newton matrix A = M - a df/dv - b df/dx of BDF2 (a = 2h/3,
 *    b = 4h^2/9, h = 1e-2) of hang, bw-hang and drape-sphere at n = 16,
 *    at the state semi-bdf2 reaches at t = 0.3 s (drape-sphere: on the
 *    sphere), their solutions equal KLU's to the solver tolerance: true
 *    relative residual <= 1e-10 (lin_tol's default), and |x - x_klu| <=
 *    1e-7 |x_klu| (the residual times A's condition number, measured
 *    below 1e-8);
 *  - the hierarchy is built once over setups whose values change slowly
 *    (only the finest smoother refreshed), its coarse operators recomputed
 *    when the iterations grow (statistics: symbolic_facts = builds);
 *    amg-hypre's built at every setup; a first recompute on a new
 *    interpolation that did not lower the iterations (a growth the
 *    problem's own) moves the rebuild's reference, and every recompute
 *    that did not raises the recompute's factor;
 *  - a setup refreshing only the finest smoother solves hang's matrix to
 *    the tolerance, equal to KLU's solution;
 *  - the products by two threads give the solution of one, bit for bit;
 *  - a stop (core/stop.h) ends a solve at once, with CL_EINTR;
 *  - a solve whose preconditioner is made indefinite by bad eigenvalue
 *    bounds on the coarser levels (one estimate step, through
 *    PETSC_OPTIONS) is recovered: redone
 *    on a hierarchy rebuilt with careful bounds, equal to KLU's solution,
 *    counted once (lin_recoveries);
 *  - an indefinite A is CL_ESOLVER saying so, and so is one whose
 *    diagonal blocks are not positive definite, at the setup. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"
#include "lscase.h"
#include "problem.h"

#define AM_H 1e-2
#define AM_T 0.3

/* The Newton matrix of `problem` at t = AM_T of semi-bdf2, AM_H. */
typedef struct {
    pr_problem p;
    const cl_system *sys;
    double *dfdx, *dfdv, *rhs, *x, *xk;
} am_case;

static void am_load(am_case *c, const char *problem)
{
    char path[256];
    snprintf(path, sizeof path, "problems/%s.ini", problem);
    pr_load(&c->p, path, "cloth.n=16", NULL);
    c->sys = cl_model_system(c->p.m);
    size_t n = c->sys->n, nval = 9 * c->sys->pattern->nnzb;
    double *v = malloc(n * sizeof *v), *f = malloc(n * sizeof *f);
    c->x = malloc(n * sizeof *c->x);
    c->xk = malloc(n * sizeof *c->xk);
    c->rhs = malloc(n * sizeof *c->rhs);
    c->dfdx = malloc(nval * sizeof *c->dfdx);
    c->dfdv = malloc(nval * sizeof *c->dfdv);
    cr_assert(v && f && c->x && c->xk && c->rhs && c->dfdx && c->dfdv);
    cl_error err = {0};
    cr_assert_eq(cl_model_initial_state(c->p.m, c->x, v), CL_OK);
    const cl_integrator_type *it = cl_integrator_find("semi-bdf2");
    cl_integrator_opts io = {.dt = AM_H};
    void *st = NULL;
    cr_assert_eq(it->create(c->sys, &io, 0.0, c->x, v, &st, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(it->advance(st, AM_T, c->x, v, &err), CL_OK, "%s",
                 err.msg);
    it->free(st);
    cr_assert_eq(c->sys->jacobian(c->sys->data, AM_T, c->x, v, f, c->dfdx,
                                  c->dfdv), CL_OK);
    unsigned long seed = 5;
    for (size_t i = 0; i < n; i++)
        c->rhs[i] = ls_rand(&seed);
    free(v);
    free(f);
}

static void am_free(am_case *c)
{
    free(c->dfdx);
    free(c->dfdv);
    free(c->rhs);
    free(c->x);
    free(c->xk);
    pr_free(&c->p);
}

/* Set up solver `name` (its products by `threads`) for A and solve
 * A x = rhs into out. */
static void am_solve_threads(am_case *c, const char *name, int threads,
                             double *out, cl_stats *s)
{
    const cl_linsol_type *t = ls_find(name);
    const double a = 2.0 * AM_H / 3.0, b = 4.0 * AM_H * AM_H / 9.0;
    cl_linsol_opts o = {.threads = threads};
    cl_error err = {0};
    void *st = NULL;
    cr_assert_eq(t->create(c->sys->pattern, c->sys->mass, &o, &st, &err),
                 CL_OK, "%s", err.msg);
    cl_linsol_jacobian(t, st, c->dfdx, c->dfdv);
    cr_assert_eq(t->setup(st, a, b, c->dfdx, c->dfdv, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(t->solve(st, c->rhs, out, &err), CL_OK, "%s", err.msg);
    *s = (cl_stats){0};
    t->stats(st, s);
    t->free(st);
}

static void am_solve(am_case *c, const char *name, double *out,
                     cl_stats *s)
{
    am_solve_threads(c, name, 1, out, s);
}

static double am_norm(const double *a, const double *b, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += (a[i] - (b ? b[i] : 0.0)) * (a[i] - (b ? b[i] : 0.0));
    return sqrt(s);
}

/* Solve `problem`'s system by KLU and by `name`: the latter's solution
 * equals KLU's to the solver tolerance; its statistics into sa. */
static void am_klu_run(const char *problem, const char *name, cl_stats *sa)
{
    am_case c;
    am_load(&c, problem);
    size_t n = c.sys->n;
    cl_stats sk;
    am_solve(&c, "klu", c.xk, &sk);
    am_solve(&c, name, c.x, sa);
    double *y = malloc(n * sizeof *y);
    cr_assert_not_null(y);
    const double a = 2.0 * AM_H / 3.0, b = 4.0 * AM_H * AM_H / 9.0;
    cl_reduced_matvec(c.sys->pattern, c.sys->mass, a, b, c.dfdx, c.dfdv,
                      c.x, y);
    double res = am_norm(c.rhs, y, n) / am_norm(c.rhs, NULL, n);
    double diff = am_norm(c.x, c.xk, n) / am_norm(c.xk, NULL, n);
    cr_log_info("%s %s: %ld solves, %ld iterations, residual %.3e, |x - "
                "x_klu| / |x_klu| %.3e", problem, name, sa->lin_solves,
                sa->lin_iters, res, diff);
    cr_assert_leq(res, 1e-10);
    cr_assert_leq(diff, 1e-7);
    free(y);
    am_free(&c);
}

static void am_equals_klu(const char *problem, const char *name)
{
    cl_stats sa;
    am_klu_run(problem, name, &sa);
    cr_assert_eq(sa.lin_setups, 1);
    cr_assert_eq(sa.symbolic_facts, 1);
    cr_assert_eq(sa.lin_recoveries, 0);
    cr_assert_gt(sa.lin_iters, 0);
}

Test(linsol_amg, hang_equals_klu) { am_equals_klu("hang", "amg"); }
Test(linsol_amg, bw_hang_equals_klu) { am_equals_klu("bw-hang", "amg"); }
Test(linsol_amg, drape_sphere_equals_klu)
{
    am_equals_klu("drape-sphere", "amg");
}
Test(linsol_amg, hypre_hang_equals_klu)
{
    am_equals_klu("hang", "amg-hypre");
}

/* The products by two threads are bitwise those by one (linalg/bsym.h),
 * so are CG's iterates: the same solution, bit for bit, in as many
 * iterations. */
Test(linsol_amg, threads_give_the_same_solution)
{
    am_case c;
    am_load(&c, "hang");
    size_t n = c.sys->n;
    double *x2 = malloc(n * sizeof *x2);
    cr_assert_not_null(x2);
    cl_stats s1, s2;
    am_solve_threads(&c, "amg", 1, c.x, &s1);
    am_solve_threads(&c, "amg", 2, x2, &s2);
    cr_assert_eq(s2.lin_iters, s1.lin_iters);
    cr_assert_eq(memcmp(c.x, x2, n * sizeof *x2), 0);
    free(x2);
    am_free(&c);
}

/* Setups k = 0..5 with df/dx scaled by 1.01 each time, then three with b
 * 1e5 times larger (a far stiffer A, whose true residual is held to 1e-8
 * only: the CG recurrence's 1e-10 times its condition); returns the
 * builds (symbolic_facts) and the CG iterations of each solve. */
static void am_reuse_run(const char *name, long *builds, long *its)
{
    ls_case c;
    ls_init(&c, 21);
    const cl_linsol_type *t = ls_find(name);
    cl_linsol_opts o = {0};
    void *st = ls_create(t, &c, &o);
    cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
    double rhs[LS_N], x[LS_N];
    size_t nval = 9 * c.pat.nnzb;
    long done = 0;
    for (int k = 0; k < 9; k++) {
        for (size_t i = 0; i < nval; i++)
            c.dfdx[i] *= 1.0 + 0.01 * (k > 0 && k < 6);
        double b = k < 6 ? 1e-4 : 10.0;
        cr_assert_leq(ls_setup_solve(t, st, &c, 1e-2, b, 30 + k, rhs, x),
                      k < 6 ? 1e-10 : 1e-8);
        cl_stats s = {0};
        t->stats(st, &s);
        cr_assert_eq(s.lin_setups, k + 1);
        cr_assert_eq(s.lin_solves, k + 1);
        builds[k] = s.symbolic_facts;
        its[k] = s.lin_iters - done;
        done = s.lin_iters;
    }
    cr_log_info("%s iterations: %ld %ld %ld %ld %ld %ld, stiffer %ld %ld "
                "%ld; builds after the last %ld", name, its[0], its[1],
                its[2], its[3], its[4], its[5], its[6], its[7], its[8],
                builds[8]);
    t->free(st);
    ls_free(&c);
}

/* amg: one build, then only the finest smoother refreshed while the
 * iterations stay within 1.1 times the build's; on the stiffer A the
 * refreshed smoother alone takes more than 1.5 times as many, so the
 * next setup recomputes the coarse operators on the kept interpolation
 * (no new hierarchy, and fewer iterations), and the one after builds a
 * new hierarchy if and only if that still took more than 1.5 times the
 * build's. */
Test(linsol_amg, coarse_operators_recomputed_when_iterations_grow)
{
    long builds[9], its[9];
    am_reuse_run("amg", builds, its);
    for (int k = 0; k < 8; k++)
        cr_assert_eq(builds[k], 1);
    for (int k = 1; k < 6; k++)
        cr_assert_leq((double)its[k], 1.1 * (double)its[0]);
    cr_assert_gt((double)its[6], 1.5 * (double)its[0]);
    cr_assert_lt(its[7], its[6]);
    cr_assert_eq(builds[8],
                 (double)its[7] > 1.5 * (double)its[0] ? 2 : 1);
}

/* One matrix, one right-hand side, solved to tolerances 10^-e[k] after
 * setup k: the iterations grow because the tolerance tightens, and no
 * recompute can help, since the coarse operators recomputed on the same
 * matrix are the same.  Each growth past the coarse operators' factor
 * (1.1, then 1.2 and 1.4 as recomputes fail to help) recomputes them, and
 * the next solve takes as many iterations.  The first, on the new
 * interpolation, moves the rebuild's reference to its count (setup 2),
 * so that no new hierarchy is built at setup 5, where the rule before
 * built one (its count more than 1.5 times the build's); the later ones
 * do not move it, so the next growth past 1.5 times the moved reference
 * builds (setup 7). */
Test(linsol_amg, recompute_that_did_not_help_moves_the_reference)
{
    static const int e[9] = {1, 2, 2, 3, 3, 5, 5, 10, 10};
    static const long built[9] = {1, 1, 1, 1, 1, 1, 1, 2, 2};
    ls_case c;
    ls_init(&c, 21);
    const cl_linsol_type *t = ls_find("amg");
    cl_linsol_opts o = {0};
    void *st = ls_create(t, &c, &o);
    cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
    double rhs[LS_N], x[LS_N], w[LS_N];
    ls_rhs(30, rhs);
    for (size_t i = 0; i < LS_N; i++)
        w[i] = 1.0;
    long its[9], done = 0;
    for (int k = 0; k < 9; k++) {
        cl_error err = {0};
        cr_assert_eq(t->setup(st, 1e-2, 1e-4, c.dfdx, c.dfdv, &err), CL_OK);
        cr_assert_eq(t->solve_tol(st, rhs, x, w, pow(10.0, -e[k]), &err),
                     CL_OK, "%s", err.msg);
        cl_stats s = {0};
        t->stats(st, &s);
        its[k] = s.lin_iters - done;
        done = s.lin_iters;
        cr_assert_eq(s.symbolic_facts, built[k], "setup %d", k);
    }
    /* the premises: the same tolerance, the same iterations; each growth
     * past the factor it was planned for; setup 5 past 1.5 times the
     * build's count, setup 7 past 1.5 times setup 2's and not past 1.5
     * times setups 4's or 6's */
    for (int k = 2; k < 7; k += 2)
        cr_assert_eq(its[k], its[k - 1]);
    const double factor[3] = {1.1, 1.2, 1.4};
    for (int k = 1, f = 0; k < 7; k += 2, f++)
        cr_assert_gt((double)its[k], factor[f] * (double)its[k - 1],
                     "its %ld after %ld", its[k], its[k - 1]);
    cr_assert_gt((double)its[4], 1.5 * (double)its[0]);
    cr_assert_gt((double)its[6], 1.5 * (double)its[2]);
    cr_assert_leq((double)its[6], 1.5 * (double)its[4]);
    t->free(st);
    ls_free(&c);
}

/* A stop requested (SIGTERM here) ends a solve at its first product with
 * A (NaN then, which ends PETSc's CG): CL_EINTR naming the signal, and no
 * recovery on a rebuilt hierarchy (before: the solve ran to its
 * tolerance first). */
static void am_stopped(const char *name)
{
    am_case c;
    am_load(&c, "hang");
    const cl_linsol_type *t = cl_linsol_find(name);
    cr_assert_not_null(t);
    cl_linsol_opts o = {0};
    cl_error err = {0};
    void *st = NULL;
    const double a = 2.0 * AM_H / 3.0, b = 4.0 * AM_H * AM_H / 9.0;
    cr_assert_eq(t->create(c.sys->pattern, c.sys->mass, &o, &st, &err),
                 CL_OK, "%s", err.msg);
    cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
    cr_assert_eq(t->setup(st, a, b, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    ls_solve_stopped(t, st, name, c.rhs, c.x);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.lin_recoveries, 0);
    cr_assert_leq(s.lin_iters, 1);
    t->free(st);
    am_free(&c);
}

Test(linsol_amg, stopped) { am_stopped("amg"); }
Test(linsol_amg, hypre_stopped) { am_stopped("amg-hypre"); }

/* amg-hypre builds BoomerAMG at every setup (kept, its finest relaxation
 * would sweep the old matrix) and solves each to the tolerance
 * (am_reuse_run) without a second attempt. */
Test(linsol_amg, hypre_built_at_every_setup)
{
    long builds[9], its[9];
    am_reuse_run("amg-hypre", builds, its);
    for (int k = 0; k < 9; k++)
        cr_assert_eq(builds[k], k + 1);
}

/* A hierarchy built on hang's Newton matrix with df/dx and df/dv scaled
 * by 0.9, then a setup on the matrix itself that refreshes only the finest
 * smoother (the coarse operators those of the scaled matrix): the solution
 * equals KLU's to the solver tolerance as a fresh build's does, in at most
 * 1.5 times its iterations. */
Test(linsol_amg, smoother_refresh_equals_klu)
{
    am_case c;
    am_load(&c, "hang");
    size_t n = c.sys->n, nval = 9 * c.sys->pattern->nnzb;
    cl_stats sk, sf;
    am_solve(&c, "klu", c.xk, &sk);
    am_solve(&c, "amg", c.x, &sf);
    const cl_linsol_type *t = ls_find("amg");
    const double a = 2.0 * AM_H / 3.0, b = 4.0 * AM_H * AM_H / 9.0;
    cl_linsol_opts o = {0};
    cl_error err = {0};
    void *st = NULL;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    cr_assert(x && y);
    cr_assert_eq(t->create(c.sys->pattern, c.sys->mass, &o, &st, &err),
                 CL_OK, "%s", err.msg);
    cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
    for (size_t i = 0; i < nval; i++) {
        c.dfdx[i] *= 0.9;
        c.dfdv[i] *= 0.9;
    }
    cr_assert_eq(t->setup(st, a, b, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    for (size_t i = 0; i < nval; i++) {
        c.dfdx[i] /= 0.9;
        c.dfdv[i] /= 0.9;
    }
    cr_assert_eq(t->setup(st, a, b, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(t->solve(st, c.rhs, x, &err), CL_OK, "%s", err.msg);
    cl_stats s = {0};
    t->stats(st, &s);
    cl_reduced_matvec(c.sys->pattern, c.sys->mass, a, b, c.dfdx, c.dfdv, x,
                      y);
    double res = am_norm(c.rhs, y, n) / am_norm(c.rhs, NULL, n);
    double diff = am_norm(x, c.xk, n) / am_norm(c.xk, NULL, n);
    cr_log_info("refreshed: %ld iterations (fresh %ld), residual %.3e, "
                "|x - x_klu| / |x_klu| %.3e", s.lin_iters, sf.lin_iters,
                res, diff);
    cr_assert_eq(s.lin_setups, 2);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_solves, 1);
    cr_assert_leq(res, 1e-10);
    cr_assert_leq(diff, 1e-7);
    cr_assert_leq((double)s.lin_iters, 1.5 * (double)sf.lin_iters);
    t->free(st);
    free(x);
    free(y);
    am_free(&c);
}

/* Chebyshev's bounds from one Lanczos step each (the Rayleigh quotient of
 * a noisy vector, far below the largest eigenvalue of D^-1 A) on the
 * coarser levels, which a coarsest level of at most 10 equations makes
 * several at n = 16 (the finest level is smoothed by block Gauss-Seidel,
 * which has no bound): those smoothers amplify the upper modes and CG
 * finds the cycle indefinite at the first solve; the recovery rebuilds
 * the hierarchy with CLP_AMG_RECOVER_STEPS steps per estimate (the option
 * notwithstanding) and solves to the tolerance, equal to KLU's solution.
 * The options are read when PETSc starts, in this test's own process. */
Test(linsol_amg, bad_bound_recovered)
{
    cr_assert_eq(setenv("PETSC_OPTIONS",
                        "-clamg_mg_levels_ksp_chebyshev_esteig_steps 1 "
                        "-clamg_pc_gamg_coarse_eq_limit 10", 1),
                 0);
    cl_stats sa;
    am_klu_run("hang", "amg", &sa);
    cr_assert_eq(sa.lin_recoveries, 1);
    cr_assert_eq(sa.lin_setups, 1);
    cr_assert_eq(sa.lin_solves, 2);
    cr_assert_eq(sa.symbolic_facts, 2);
}

/* The indefinite chain of lscase.h. */
Test(linsol_amg, indefinite_reported)
{
    ls_case c;
    ls_init(&c, 9);
    ls_fill_indefinite_chain(&c);
    const cl_linsol_type *t = ls_find("amg");
    cl_linsol_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
    cl_status rc = t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err);
    if (rc == CL_OK) {
        ls_rhs(3, rhs);
        rc = t->solve(st, rhs, x, &err);
    }
    cr_log_info("%s", err.msg);
    cr_assert_eq(rc, CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "amg: "), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "not positive definite"), "%s",
                       err.msg);
    /* the solve was redone once, on a rebuilt hierarchy, before failing */
    cr_assert_not_null(strstr(err.msg, "(also on a hierarchy rebuilt with "
                              "careful eigenvalue bounds)"), "%s", err.msg);
    cl_stats sa = {0};
    t->stats(st, &sa);
    cr_assert_eq(sa.lin_recoveries, 1);
    cr_assert_eq(sa.symbolic_facts, 2);
    t->free(st);
    ls_free(&c);
}

/* df/dx of the wrong sign, b = 1: every diagonal block M - b df/dx is
 * negative definite, and amg's setup, which inverts them for the finest
 * smoother, says so. */
Test(linsol_amg, negative_diagonal_block_refused)
{
    ls_case c;
    ls_init(&c, 4);
    ls_fill(&c, 4, -1.0);
    const cl_linsol_type *t = ls_find("amg");
    cl_linsol_opts o = {0};
    cl_error err = {0};
    void *st = ls_create(t, &c, &o);
    cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_ESOLVER);
    cr_assert_str_eq(err.msg, "amg: the diagonal block of particle row 0 of "
                     "M - a df/dv - b df/dx is not positive definite "
                     "(determinant not positive)");
    t->free(st);
    ls_free(&c);
}

Test(linsol_amg, solve_needs_a_setup)
{
    ls_case c;
    ls_init(&c, 4);
    const cl_linsol_type *t = ls_find("amg");
    cl_linsol_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    ls_rhs(1, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "amg: solve without a successful setup");
    t->free(st);
    ls_free(&c);
}
