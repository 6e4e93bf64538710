/* Tests for integrators/memguard: the estimate of the factors' entries
 * bounds what CHOLMOD's symbolic analysis (AMD ordering) finds on the hang
 * grid from above, by no more than a factor 3; the dense estimate is the
 * matrix and its copy; an estimate beyond the available memory is refused
 * with it. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "integrators/memguard.h"
#include "problem.h"

static const cl_integrator_type *by_name(const char *name)
{
    const cl_integrator_type *t = cl_integrator_find(name);
    cr_assert_not_null(t, "%s", name);
    return t;
}

/* Entries of L from CHOLMOD's analysis of the Newton matrix's pattern. */
static double cholmod_lnz(const cl_system *sys)
{
    const cl_linsol_type *lt = cl_linsol_find("cholmod");
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(lt->create(sys->pattern, sys->mass, &(cl_linsol_opts){0},
                            &st, &err), CL_OK, "%s", err.msg);
    double setup, solve;
    lt->cost(st, &setup, &solve); /* solve = 4 nnz(L) */
    lt->free(st);
    return solve / 4.0;
}

Test(memguard, factor_estimate_bounds_cholmod_from_above)
{
    static const char *const sizes[] = {"cloth.n=16", "cloth.n=32"};
    const cl_integrator_type *cv = by_name("cvode-bdf");
    for (int k = 0; k < 2; k++) {
        pr_problem p;
        pr_load(&p, "problems/hang.ini", sizes[k], NULL);
        const cl_system *sys = cl_model_system(p.m);
        double lnz = cholmod_lnz(sys);
        /* bytes per factor entry: 16 (value and index) */
        double lu = (cl_memguard_estimate(cv, sys, "klu") -
                     cl_memguard_estimate(cv, sys, "pcg")) / 16.0;
        double chol = (cl_memguard_estimate(cv, sys, "cholmod") -
                       cl_memguard_estimate(cv, sys, "pcg")) / 16.0;
        cr_assert(lu >= 2.0 * lnz && lu <= 3.0 * 2.0 * lnz,
                  "%s: LU estimate %g entries, CHOLMOD's 2 nnz(L) = %g",
                  sizes[k], lu, 2.0 * lnz);
        cr_assert(chol >= lnz && chol <= 3.0 * lnz,
                  "%s: Cholesky estimate %g entries, CHOLMOD's nnz(L) = %g",
                  sizes[k], chol, lnz);
        cr_assert_eq(cl_memguard_estimate(cv, sys, "auto"),
                     cl_memguard_estimate(cv, sys, "klu"));
        pr_free(&p);
    }
}

Test(memguard, dense_and_explicit_estimates)
{
    pr_problem p;
    pr_load(&p, "problems/hang.ini", "cloth.n=8", NULL);
    const cl_system *sys = cl_model_system(p.m);
    double jac = 2.0 * 9.0 * (double)sys->pattern->nnzb * 8.0;
    double m = 2.0 * (double)sys->n;
    cr_assert_eq(cl_memguard_estimate(by_name("cvode-bdf-dense"), sys, NULL),
                 jac + 2.0 * m * m * 8.0);
    cr_assert_eq(cl_memguard_estimate(by_name("gsl-msbdf"), sys, NULL),
                 jac + 2.0 * m * m * 8.0);
    cr_assert_eq(cl_memguard_estimate(by_name("rk4"), sys, NULL), jac);
    pr_free(&p);
}

Test(memguard, beyond_the_available_memory_is_refused)
{
    pr_problem p;
    pr_load(&p, "problems/hang.ini", "cloth.n=200", NULL);
    const cl_system *sys = cl_model_system(p.m);
    cl_error err = {0};
    const cl_integrator_type *dense = by_name("cvode-bdf-dense");
    cr_assert_eq(cl_memguard_check(dense, sys, NULL, &err), CL_ENOMEM);
    cr_assert_not_null(strstr(err.msg, "need about 922 GB"), "%s", err.msg);
    cr_assert_eq(cl_memguard_check(by_name("rk4"), sys, NULL, &err), CL_OK,
                 "%s", err.msg);
    pr_free(&p);
}
