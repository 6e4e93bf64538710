/* Linear solvers of the reduced matrix A = M - a df/dv - b df/dx
 * (linalg/linsol.h): registry; klu, pcg and pcg-jacobi solve random SPD
 * block systems (spring-like Laplacians of random SPD 3x3 couplings) to a
 * true relative residual of 1e-10; KLU analyses once over many setups;
 * failures are reported as CL_ESOLVER: pcg on an indefinite A (caught in
 * the preconditioner setup, or by the curvature check during the
 * iteration), pcg at its iteration cap, KLU on a singular A; a stop
 * (core/stop.h) ends a pcg solve with CL_EINTR, and auto does not fall
 * back to a factorisation then. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"
#include "lscase.h"
#include "problem.h"

/* The names, in the registry's order, each found by its name: the seven
 * known ones among them in this order (a solver added to the registry
 * lists too). */
Test(linsol, registry)
{
    static const char *const known[] = {"klu", "pcg", "pcg-jacobi",
                                        "cholmod", "auto", "amg",
                                        "amg-hypre"};
    char buf[512];
    size_t next = 0;
    cl_linsol_names(buf, sizeof buf);
    for (char *save, *name = strtok_r(buf, ", ", &save); name;
         name = strtok_r(NULL, ", ", &save)) {
        cr_assert_str_eq(ls_find(name)->name, name);
        if (next < 7 && !strcmp(name, known[next]))
            next++;
    }
    cr_assert_eq(next, 7, "the known seven not all listed, in order");
    cr_assert_str_eq(cl_linsol_find(NULL)->name, "klu");
    cr_assert_str_eq(cl_linsol_find("")->name, "klu");
    cr_assert_null(cl_linsol_find("lu"));
    char tiny[8];
    cr_assert_str_eq(cl_linsol_names(tiny, sizeof tiny), "klu, pc");
}

/* The lookup the integrators share: the solver, or one message naming
 * the integrator, the name and every name accepted. */
Test(linsol, get_or_refuse)
{
    const cl_linsol_type *lt = NULL;
    cl_error err = {0};
    char names[512], want[640];
    cl_linsol_names(names, sizeof names);
    cr_assert_eq(cl_linsol_get("semi-be", "cholmod", NULL, &lt, &err), CL_OK);
    cr_assert_str_eq(lt->name, "cholmod");
    cr_assert_eq(cl_linsol_get("semi-be", "lu", NULL, &lt, &err), CL_EINVAL);
    snprintf(want, sizeof want, "semi-be: unknown linear solver \"lu\" "
             "(known: %s)", names);
    cr_assert_str_eq(err.msg, want);
    cr_assert_eq(cl_linsol_get("ida", "lu", "klu-full", &lt, &err),
                 CL_EINVAL);
    snprintf(want, sizeof want, "ida: unknown linear solver \"lu\" "
             "(known: klu-full, %s)", names);
    cr_assert_str_eq(err.msg, want);
}

static void ls_solve_spd(const char *name)
{
    ls_case c;
    ls_init(&c, 2024);
    const cl_linsol_type *t = ls_find(name);
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    const double h = 1e-2, ab[][2] = {{h, h * h},
                                      {2 * h / 3, 4 * h * h / 9},
                                      {0.1, 0.01}};
    double rhs[LS_N], x[LS_N];
    /* Untold, then told of the (symmetric) Jacobian: pcg multiplies by
     * every block, then by the halves (linalg/bsym.h). */
    for (int told = 0; told < 2; told++) {
        if (told)
            cl_linsol_jacobian(t, st, c.dfdx, c.dfdv);
        for (size_t k = 0; k < 3; k++) {
            double res = ls_setup_solve(t, st, &c, ab[k][0], ab[k][1],
                                        100 + k, rhs, x);
            cr_log_info("%s (told %d): a = %g, b = %g: relative residual "
                        "%.3e", name, told, ab[k][0], ab[k][1], res);
            cr_assert_leq(res, 1e-10, "%s: residual %g", name, res);
        }
    }
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.lin_setups, 6);
    cr_assert_eq(s.lin_solves, 6);
    if (strcmp(name, "klu") == 0 || strcmp(name, "cholmod") == 0) {
        cr_assert_eq(s.symbolic_facts, 1);
        cr_assert_eq(s.lin_iters, 0);
    } else if (strcmp(name, "auto") == 0) {
        cr_log_info("auto: %s, %ld iterations", s.linsol, s.lin_iters);
    } else {
        cr_assert_eq(s.symbolic_facts, 0);
        cr_assert_gt(s.lin_iters, 6);
        cr_log_info("%s: %ld iterations for 6 solves", name, s.lin_iters);
    }
    t->free(st);
    ls_free(&c);
}

Test(linsol, klu_solves_spd) { ls_solve_spd("klu"); }
Test(linsol, pcg_solves_spd) { ls_solve_spd("pcg"); }
Test(linsol, pcg_jacobi_solves_spd) { ls_solve_spd("pcg-jacobi"); }
Test(linsol, cholmod_solves_spd) { ls_solve_spd("cholmod"); }
Test(linsol, auto_solves_spd) { ls_solve_spd("auto"); }

/* solve_tol stops at ||w .* r||_2 <= delta, whatever lin_tol says. */
Test(linsol, pcg_weighted_tolerance)
{
    ls_case c;
    ls_init(&c, 21);
    const cl_linsol_type *t = ls_find("pcg");
    void *st = ls_create(t, &c, &(cl_linsol_opts){.tol = 1e-14});
    cl_error err = {0};
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK);
    double rhs[LS_N], x[LS_N], y[LS_N], w[LS_N], wr = 0.0, wb = 0.0;
    ls_rhs(22, rhs);
    for (size_t i = 0; i < LS_N; i++) {
        w[i] = 1.0 + (double)(i % 5);
        wb += w[i] * w[i] * rhs[i] * rhs[i];
    }
    const double delta = 1e-3 * sqrt(wb);
    cr_assert_eq(t->solve_tol(st, rhs, x, w, delta, &err), CL_OK, "%s",
                 err.msg);
    cl_reduced_matvec(&c.pat, c.mass, 0.1, 0.01, c.dfdx, c.dfdv, x, y);
    for (size_t i = 0; i < LS_N; i++)
        wr += w[i] * w[i] * (rhs[i] - y[i]) * (rhs[i] - y[i]);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_log_info("pcg weighted: |w r| = %.3e <= %.3e in %ld iterations",
                sqrt(wr), delta, s.lin_iters);
    cr_assert_leq(sqrt(wr), delta * 1.0001);
    cr_assert_gt(sqrt(wr), 1e-9 * delta, "stopped at delta, not lin_tol");
    /* weights must be positive and finite (before: zero weights gave x = 0
     * and CL_OK), and so must delta */
    w[5] = 0.0;
    cr_assert_eq(t->solve_tol(st, rhs, x, w, delta, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "pcg: weight 5 is 0: the weights must be "
                     "positive and finite");
    w[5] = 1.0;
    cr_assert_eq(t->solve_tol(st, rhs, x, w, NAN, &err), CL_EINVAL);
    cr_assert_str_eq(err.msg, "pcg: delta = nan: must be positive and "
                     "finite");
    cr_assert_null(ls_find("klu")->solve_tol);
    cr_assert_null(ls_find("cholmod")->solve_tol);
    t->free(st);
    ls_free(&c);
}

/* auto: pcg while its solves are cheap (small a, b: A close to M); after a
 * setup whose 8 solves took many iterations (large a, b, lin_tol 1e-10),
 * more than a factorisation and 8 direct solves cost, cholmod; statistics
 * name what was used. */
Test(linsol, auto_picks_by_cost)
{
    ls_case c;
    ls_init(&c, 23);
    const cl_linsol_type *t = ls_find("auto");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    cr_assert_leq(ls_setup_solve(t, st, &c, 1e-6, 1e-12, 1, rhs, x), 1e-10);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_str_eq(s.linsol, "auto:pcg");
    cr_assert_eq(s.symbolic_facts, 0);
    cl_error err = {0};
    for (int k = 0; k < 2; k++) {
        cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK);
        for (unsigned long q = 0; q < 8; q++) {
            ls_rhs(q, rhs);
            cr_assert_eq(t->solve(st, rhs, x, &err), CL_OK, "%s", err.msg);
            cr_assert_leq(ls_residual(&c, 0.1, 0.01, rhs, x), 1e-10);
        }
        memset(&s, 0, sizeof s);
        t->stats(st, &s);
        cr_log_info("auto after hard setup %d: %s, %ld iterations", k,
                    s.linsol, s.lin_iters);
    }
    cr_assert_gt(s.lin_iters, 20 * 8, "the hard A must be hard for pcg");
    cr_assert_str_eq(s.linsol, "auto:pcg+cholmod");
    cr_assert_eq(s.lin_setups, 3);
    cr_assert_eq(s.lin_solves, 17);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_fallbacks, 0);
    t->free(st);
    ls_free(&c);
}

/* semi-bdf2 on hang at n = `n`, dt = 1e-2, to t = 0.03 (three steps) with
 * linear solver `linsol`: the positions (len of them), the statistics. */
static double *ls_hang_run(int n, const char *linsol, cl_stats *st,
                           size_t *len)
{
    char set[32];
    snprintf(set, sizeof set, "cloth.n=%d", n);
    pr_problem p;
    pr_load(&p, "problems/hang.ini", set, NULL);
    const cl_system *sys = cl_model_system(p.m);
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    cr_assert(x && v);
    cr_assert_eq(cl_model_initial_state(p.m, x, v), CL_OK);
    *len = sys->n;
    const cl_integrator_type *it = cl_integrator_find("semi-bdf2");
    cl_integrator_opts io = {.dt = 1e-2, .linsol = linsol};
    cl_error err = {0};
    void *state = NULL;
    cr_assert_eq(it->create(sys, &io, 0.0, x, v, &state, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(it->advance(state, 0.03, x, v, &err), CL_OK, "%s",
                 err.msg);
    *st = (cl_stats){0};
    it->stats(state, st);
    it->free(state);
    free(v);
    pr_free(&p);
    return x;
}

/* On hang at n = 128, dt = 1e-2, pcg's solves take 400-500 iterations
 * from the second step on: auto goes to amg (CL_AUTO_AMG_*), which solves to
 * the same tolerance: the positions agree with pcg's run to 1e-9. */
Test(linsol, auto_goes_to_amg_on_long_pcg_solves)
{
    cl_stats sa, sp;
    size_t n;
    double *xa = ls_hang_run(128, "auto", &sa, &n);
    double *xp = ls_hang_run(128, "pcg", &sp, &n);
    cr_log_info("auto: %s, %ld iterations in %ld solves; pcg: %ld in %ld",
                sa.linsol, sa.lin_iters, sa.lin_solves, sp.lin_iters,
                sp.lin_solves);
    cr_assert_str_eq(sa.linsol, "auto:pcg+amg");
    cr_assert_eq(sa.lin_setups, 3);
    cr_assert_eq(sa.lin_fallbacks, 0);
    cr_assert_lt(sa.lin_iters, sp.lin_iters);
    double d = 0.0, m = 0.0;
    for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(xa[i] - xp[i]));
        m = fmax(m, fabs(xp[i]));
    }
    cr_assert_leq(d, 1e-9 * m, "max |x_auto - x_pcg| %.3g (max |x| %.3g)",
                  d, m);
    free(xa);
    free(xp);
}

/* With one solve per setup a factorisation does not pay: auto stays with
 * pcg however many iterations (within reason) its solves take. */
Test(linsol, auto_keeps_pcg_for_single_solves)
{
    ls_case c;
    ls_init(&c, 25);
    const cl_linsol_type *t = ls_find("auto");
    void *st = ls_create(t, &c, &(cl_linsol_opts){.tol = 1e-6});
    double rhs[LS_N], x[LS_N];
    for (unsigned long k = 0; k < 4; k++)
        cr_assert_leq(ls_setup_solve(t, st, &c, 0.01, 1e-4, k, rhs, x),
                      1e-6);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_log_info("auto single solves: %s, %ld iterations in 4 solves",
                s.linsol, s.lin_iters);
    cr_assert_str_eq(s.linsol, "auto:pcg");
    t->free(st);
    ls_free(&c);
}

/* A pcg solve that fails (iteration cap 1) is redone by the direct solver:
 * the answer is exact and the fallback counted. */
Test(linsol, auto_falls_back_when_pcg_fails)
{
    ls_case c;
    ls_init(&c, 24);
    const cl_linsol_type *t = ls_find("auto");
    void *st = ls_create(t, &c, &(cl_linsol_opts){.maxit = 1});
    double rhs[LS_N], x[LS_N];
    cr_assert_leq(ls_setup_solve(t, st, &c, 1e-4, 1e-8, 3, rhs, x), 1e-10);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_log_info("auto fallback: %s, %ld fallbacks", s.linsol,
                s.lin_fallbacks);
    cr_assert_str_eq(s.linsol, "auto:pcg+cholmod");
    cr_assert_eq(s.lin_fallbacks, 1);
    t->free(st);
    ls_free(&c);
}

/* klu also solves a nonsymmetric A (pcg need not). */
Test(linsol, klu_solves_nonsymmetric)
{
    ls_case c;
    ls_init(&c, 77);
    unsigned long seed = 5;
    size_t nval = 9 * c.pat.nnzb;
    for (size_t q = 0; q < nval; q++)
        c.dfdx[q] += 10.0 * ls_rand(&seed);
    const cl_linsol_type *t = ls_find("klu");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    cr_assert_leq(ls_setup_solve(t, st, &c, 0.01, 1e-4, 9, rhs, x), 1e-12);
    t->free(st);
    ls_free(&c);
}

Test(linsol, klu_analyses_once_over_many_setups)
{
    ls_case c;
    ls_init(&c, 31);
    const cl_linsol_type *t = ls_find("klu");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    const int nset = 60;
    for (int k = 0; k < nset; k++) {
        double h = 1e-3 * (1.0 + k % 7);
        ls_fill(&c, 1000 + (unsigned long)k, 1.0);
        x[0] = NAN;
        cr_assert_leq(ls_setup_solve(t, st, &c, h, h * h, (unsigned long)k,
                                     rhs, x), 1e-12);
    }
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_setups, nset);
    cr_assert_eq(s.lin_solves, nset);
    t->free(st);
    ls_free(&c);
}

/* The stiffness sign flipped: A = M - b L with L >= 0 large, so every
 * diagonal block is negative definite: the preconditioner setup fails. */
static void ls_indefinite_diag(const char *name)
{
    ls_case c;
    ls_init(&c, 8);
    ls_fill(&c, 8, -1.0);
    const cl_linsol_type *t = ls_find(name);
    cl_linsol_opts o = {0};
    cl_error err = {0};
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "not positive definite"), "%s",
                       err.msg);
    double rhs[LS_N], x[LS_N];
    ls_rhs(1, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_EINVAL, "%s", err.msg);
    t->free(st);
    ls_free(&c);
}

Test(linsol, pcg_indefinite_fails_setup) { ls_indefinite_diag("pcg"); }
Test(linsol, pcg_jacobi_indefinite_fails_setup)
{
    ls_indefinite_diag("pcg-jacobi");
}

/* Positive diagonal blocks (M), coupling blocks 2 m I between neighbours
 * on the chain: A = M (I + 2 P) with P the path adjacency, whose smallest
 * eigenvalue is ~ 1 - 4 < 0.  Only CG's curvature check can tell. */
static void ls_indefinite_coupling(const char *name)
{
    ls_case c;
    ls_init(&c, 9);
    ls_fill_indefinite_chain(&c);
    const cl_linsol_type *t = ls_find(name);
    cl_linsol_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    ls_rhs(3, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_ESOLVER);
    cr_log_info("%s: %s", name, err.msg);
    cr_assert_not_null(strstr(err.msg, "not positive definite"), "%s",
                       err.msg);
    cr_assert_not_null(strstr(err.msg, "p^T A p"), "%s", err.msg);
    /* KLU solves the same (nonsingular, indefinite) matrix */
    const cl_linsol_type *k = ls_find("klu");
    void *kst = ls_create(k, &c, &o);
    cr_assert_leq(ls_setup_solve(k, kst, &c, 0.0, 1.0, 3, rhs, x), 1e-12);
    k->free(kst);
    t->free(st);
    ls_free(&c);
}

Test(linsol, pcg_indefinite_fails_solve) { ls_indefinite_coupling("pcg"); }
Test(linsol, pcg_jacobi_indefinite_fails_solve)
{
    ls_indefinite_coupling("pcg-jacobi");
}

Test(linsol, pcg_iteration_cap_reported)
{
    ls_case c;
    ls_init(&c, 12);
    const cl_linsol_type *t = ls_find("pcg-jacobi");
    cl_linsol_opts o = {.maxit = 2};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK);
    ls_rhs(4, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "no convergence in 2 iterations"),
                       "%s", err.msg);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.lin_iters, 2);
    t->free(st);
    ls_free(&c);
}

/* A stop requested (SIGTERM here) ends the solve at its first product:
 * CL_EINTR naming the signal, in the first iteration (for auto: pcg's);
 * auto passes it on
 * instead of repeating the solve by a factorisation (before: a long solve
 * held up a stop until it converged). */
static void ls_stopped(const char *name)
{
    ls_case c;
    ls_init(&c, 14);
    const cl_linsol_type *t = ls_find(name);
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    ls_setup_solve(t, st, &c, 0.1, 0.01, 5, rhs, x);
    cl_stats before = {0}, after = {0};
    t->stats(st, &before);
    ls_solve_stopped(t, st, "pcg", rhs, x);
    t->stats(st, &after);
    cr_assert_eq(after.lin_iters, before.lin_iters + 1);
    cr_assert_eq(after.lin_fallbacks, 0);
    t->free(st);
    ls_free(&c);
}

Test(linsol, pcg_stopped) { ls_stopped("pcg"); }
Test(linsol, auto_stopped_without_a_fallback) { ls_stopped("auto"); }

/* Every solver solves in place (linsol.h: x may be rhs), to the same
 * solution as into another array, bit for bit (before: amg and amg-hypre
 * returned x = 0, their zero first guess written over the right-hand
 * side). */
Test(linsol, every_solver_solves_in_place)
{
    ls_case c;
    ls_init(&c, 15);
    for (size_t k = 0; cl_linsol_registry[k]; k++) {
        const cl_linsol_type *t = cl_linsol_registry[k];
        double rhs[LS_N], x[LS_N], y[LS_N];
        void *st = ls_create(t, &c, &(cl_linsol_opts){0});
        ls_setup_solve(t, st, &c, 0.1, 0.01, 7, rhs, x);
        memcpy(y, rhs, sizeof y);
        cl_error err = {0};
        cr_assert_eq(t->solve(st, y, y, &err), CL_OK, "%s: %s", t->name,
                     err.msg);
        cr_expect(!memcmp(x, y, sizeof x), "%s: in place, another solution",
                  t->name);
        t->free(st);
    }
    ls_free(&c);
}

/* Every solver refuses a Newton matrix with an entry that is not finite
 * (CL_ESOLVER), and a solve after it (CL_EINVAL: no successful setup),
 * though an earlier setup succeeded (before: klu and cholmod factorised
 * it and solved to NaN with CL_OK, or with the earlier factors). */
Test(linsol, every_solver_refuses_a_matrix_not_finite)
{
    ls_case c;
    ls_init(&c, 16);
    for (size_t k = 0; cl_linsol_registry[k]; k++) {
        const cl_linsol_type *t = cl_linsol_registry[k];
        double rhs[LS_N], x[LS_N];
        void *st = ls_create(t, &c, &(cl_linsol_opts){0});
        ls_setup_solve(t, st, &c, 0.1, 0.01, 8, rhs, x);
        double keep = c.dfdx[4];
        c.dfdx[4] = NAN;
        cl_error err = {0};
        cr_expect_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err),
                     CL_ESOLVER, "%s: %s", t->name, err.msg);
        cr_expect_eq(t->solve(st, rhs, x, &err), CL_EINVAL, "%s: %s",
                     t->name, err.msg);
        c.dfdx[4] = keep;
        t->free(st);
    }
    ls_free(&c);
}

Test(linsol, pcg_tolerance_option)
{
    ls_case c;
    ls_init(&c, 13);
    const cl_linsol_type *t = ls_find("pcg");
    double rhs[LS_N], x[LS_N], res[2];
    long iters[2];
    const double tol[2] = {1e-4, 1e-11};
    for (int k = 0; k < 2; k++) {
        void *st = ls_create(t, &c, &(cl_linsol_opts){.tol = tol[k]});
        res[k] = ls_setup_solve(t, st, &c, 0.1, 0.01, 6, rhs, x);
        cl_stats s = {0};
        t->stats(st, &s);
        iters[k] = s.lin_iters;
        t->free(st);
        cr_log_info("pcg lin_tol %g: residual %.3e in %ld iterations",
                    tol[k], res[k], iters[k]);
        cr_assert_leq(res[k], tol[k] * 1.01);
    }
    cr_assert_lt(iters[0], iters[1]);
    ls_free(&c);
}

Test(linsol, pcg_zero_rhs_gives_zero)
{
    ls_case c;
    ls_init(&c, 14);
    const cl_linsol_type *t = ls_find("pcg");
    cl_linsol_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N] = {0}, x[LS_N];
    for (size_t i = 0; i < LS_N; i++)
        x[i] = 1.0;
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_OK, "%s", err.msg);
    for (size_t i = 0; i < LS_N; i++)
        cr_assert_eq(x[i], 0.0);
    t->free(st);
    ls_free(&c);
}

/* First A diagonally dominant (KLU pivots on the diagonal), then every
 * diagonal block zero: the refactorisation in the old pivot order meets an
 * exact zero pivot, and the setup must fall back to a fresh factorisation
 * (same symbolic analysis) that pivots off the diagonal. */
Test(linsol, klu_bad_refactor_falls_back)
{
    ls_case c;
    ls_init(&c, 17);
    const cl_linsol_type *t = ls_find("klu");
    cl_linsol_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.01, 1e-4, c.dfdx, c.dfdv, &err), CL_OK);
    unsigned long seed = 17;
    size_t nval = 9 * c.pat.nnzb;
    memset(c.dfdv, 0, nval * sizeof *c.dfdv);
    for (size_t k = 0; k < nval; k++)
        c.dfdx[k] = ls_rand(&seed);
    for (size_t i = 0; i < LS_NB; i++)
        for (int q = 0; q < 9; q++)
            c.dfdx[9 * c.pat.diag[i] + q] = q % 4 == 0 ? c.mass[3 * i + q / 4]
                                                       : 0.0;
    double res = ls_setup_solve(t, st, &c, 0.0, 1.0, 17, rhs, x);
    cr_log_info("klu after fall-back: relative residual %.3e", res);
    cr_assert_leq(res, 1e-10);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_setups, 2);
    t->free(st);
    ls_free(&c);
}

Test(linsol, klu_singular_reported)
{
    ls_case c;
    ls_init(&c, 15);
    size_t nval = 9 * c.pat.nnzb;
    memset(c.dfdx, 0, nval * sizeof *c.dfdx);
    memset(c.dfdv, 0, nval * sizeof *c.dfdv);
    /* A = M - 1 * diag(m): the zero matrix on block 5 */
    for (size_t i = 0; i < LS_NB; i++)
        for (int r = 0; r < 3; r++)
            c.dfdx[9 * c.pat.diag[i] + 4 * r] = i == 5 ? c.mass[3 * i + r]
                                                       : 0.0;
    const cl_linsol_type *t = ls_find("klu");
    cl_linsol_opts o = {0};
    cl_error err = {0};
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "singular"), "%s", err.msg);
    /* a regular matrix afterwards factorises again */
    ls_fill(&c, 15, 1.0);
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.symbolic_facts, 1);
    t->free(st);
    ls_free(&c);
}

Test(linsol, rejects_bad_options)
{
    ls_case c;
    ls_init(&c, 16);
    cl_error err = {0};
    void *st = (void *)1;
    cl_linsol_opts o = {.tol = -1.0};
    cr_assert_eq(ls_find("pcg")->create(&c.pat, c.mass, &o, &st, &err),
                 CL_EINVAL);
    cr_assert_null(st);
    o = (cl_linsol_opts){.maxit = -3};
    cr_assert_eq(ls_find("pcg-jacobi")->create(&c.pat, c.mass, &o, &st,
                                               &err), CL_EINVAL);
    c.mass[7] = 0.0;
    o = (cl_linsol_opts){0};
    for (size_t k = 0; cl_linsol_registry[k]; k++) {
        st = (void *)1;
        cr_assert_eq(cl_linsol_registry[k]->create(&c.pat, c.mass, &o, &st,
                                                    &err), CL_EINVAL);
        cr_assert_null(st);
        cr_assert_not_null(strstr(err.msg, "mass[7]"), "%s", err.msg);
    }
    ls_free(&c);
}
