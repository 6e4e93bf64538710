/* The supernodal Cholesky linear solver `cholmod` (linalg/linsol_cholmod.c)
 * on the random block systems of lscase.h: SPD systems solved to a true
 * relative residual of 1e-10 over many setups with one symbolic analysis;
 * an indefinite A (CHOLMOD_NOT_POSDEF) and a nonsymmetric A detected and
 * handed to klu for that setup (exact solve, fallback counted and named),
 * CHOLMOD taking over again at the next SPD setup; a solve without a
 * successful setup refused. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lscase.h"

static cl_stats chol_stats(const cl_linsol_type *t, const void *st)
{
    cl_stats s = {0};
    t->stats(st, &s);
    return s;
}

Test(linsol_cholmod, spd_solves_with_one_analysis)
{
    ls_case c;
    ls_init(&c, 101);
    const cl_linsol_type *t = ls_find("cholmod");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    const int nset = 20;
    for (int k = 0; k < nset; k++) {
        double h = 1e-3 * (1.0 + k % 9);
        ls_fill(&c, 300 + (unsigned long)k, 1.0);
        double res = ls_setup_solve(t, st, &c, h, h * h, (unsigned long)k,
                                    rhs, x);
        cr_assert_leq(res, 1e-10, "setup %d: residual %g", k, res);
    }
    cl_stats s = chol_stats(t, st);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_setups, nset);
    cr_assert_eq(s.lin_solves, nset);
    cr_assert_eq(s.lin_fallbacks, 0);
    cr_assert_str_eq(s.linsol, "cholmod");
    t->free(st);
    ls_free(&c);
}

/* x may be rhs; several solves per setup. */
Test(linsol_cholmod, in_place_and_repeated_solves)
{
    ls_case c;
    ls_init(&c, 102);
    const cl_linsol_type *t = ls_find("cholmod");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    cl_error err = {0};
    cr_assert_eq(t->setup(st, 0.01, 1e-4, c.dfdx, c.dfdv, &err), CL_OK);
    for (unsigned long k = 0; k < 3; k++) {
        double rhs[LS_N], x[LS_N];
        ls_rhs(k, rhs);
        memcpy(x, rhs, sizeof x);
        cr_assert_eq(t->solve(st, x, x, &err), CL_OK, "%s", err.msg);
        cr_assert_leq(ls_residual(&c, 0.01, 1e-4, rhs, x), 1e-10);
    }
    cr_assert_eq(chol_stats(t, st).lin_solves, 3);
    t->free(st);
    ls_free(&c);
}

/* A = M - L with the Laplacian L >> M: indefinite.  CHOLMOD reports it,
 * klu solves that setup exactly; the next SPD setup is CHOLMOD's again. */
Test(linsol_cholmod, indefinite_goes_to_klu)
{
    ls_case c;
    ls_init(&c, 103);
    const cl_linsol_type *t = ls_find("cholmod");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    ls_fill(&c, 103, -1.0);
    cr_assert_leq(ls_setup_solve(t, st, &c, 0.0, 1.0, 1, rhs, x), 1e-10);
    cl_stats s = chol_stats(t, st);
    cr_assert_eq(s.lin_fallbacks, 1);
    cr_assert_str_eq(s.linsol, "cholmod+klu");
    cr_assert_eq(s.symbolic_facts, 2, "CHOLMOD's analysis and klu's");
    ls_fill(&c, 104, 1.0);
    cr_assert_leq(ls_setup_solve(t, st, &c, 0.01, 1e-4, 2, rhs, x), 1e-10);
    s = chol_stats(t, st);
    cr_assert_eq(s.lin_fallbacks, 1);
    cr_assert_eq(s.lin_setups, 2);
    cr_assert_eq(s.lin_solves, 2);
    t->free(st);
    ls_free(&c);
}

/* CHOLMOD reads one triangle only: a nonsymmetric A must not reach it. */
Test(linsol_cholmod, nonsymmetric_goes_to_klu)
{
    ls_case c;
    ls_init(&c, 105);
    unsigned long seed = 7;
    size_t nval = 9 * c.pat.nnzb;
    for (size_t q = 0; q < nval; q++)
        c.dfdx[q] += 1e-3 * ls_rand(&seed);
    const cl_linsol_type *t = ls_find("cholmod");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    cr_assert_leq(ls_setup_solve(t, st, &c, 0.01, 1e-4, 3, rhs, x), 1e-10);
    cr_assert_eq(chol_stats(t, st).lin_fallbacks, 1);
    t->free(st);
    ls_free(&c);
}

Test(linsol_cholmod, solve_needs_a_setup)
{
    ls_case c;
    ls_init(&c, 106);
    const cl_linsol_type *t = ls_find("cholmod");
    void *st = ls_create(t, &c, &(cl_linsol_opts){0});
    double rhs[LS_N], x[LS_N];
    cl_error err = {0};
    ls_rhs(1, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "cholmod"), "%s", err.msg);
    t->free(st);
    ls_free(&c);
}
