/* cvode-bdf-gmres against closed-form solutions (oscillators, coupled
 * pair, a stiff overdamped set); statistics of the Krylov solver; the
 * block-Jacobi preconditioner is exact for uncoupled particles (one Krylov
 * iteration per solve) and only approximate for coupled ones; options;
 * blow-up reporting. */
#include <criterion/criterion.h>

#include "runsun.h"

#define GN "cvode-bdf-gmres"

Test(cvode_bdf_gmres, closed_form_solutions)
{
    rs_check_closed_forms(GN, true);
}

/* The preconditioner drops the coupling blocks: GMRES has to iterate. */
Test(cvode_bdf_gmres, coupling_needs_krylov_iterations)
{
    cl_stats s;
    rs_check_pair(GN, 1.0, 2.0, 4.0, 1e-7, &s, true);
    cr_log_info("pair: lin_iters %ld, lin_solves %ld", s.lin_iters,
                s.lin_solves);
    cr_assert_gt(s.lin_iters, s.lin_solves);
}

/* Uncoupled particles: P_i is exactly the diagonal block of I - gamma J
 * (with the Jacobian constant, at every gamma), so every Krylov solve
 * converges in one iteration. */
Test(cvode_bdf_gmres, statistics_and_exact_block_preconditioner)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    cl_integrator_opts o = {.rtol = 1e-7, .atol = 1e-9};
    cl_stats s;
    rs_exact_error(GN, &ts, &o, 10.0, 10, &s);
    rs_check_stats(GN, &s, &ts, true);
    cr_assert_gt(s.lin_solves, 0);
    cr_assert_eq(s.lin_iters, s.lin_solves);
    cr_assert_eq(s.symbolic_facts, 0);
    ts_free(&ts);
}

Test(cvode_bdf_gmres, krylov_options)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 1.0, 2.0, 4.0), 0);
    cl_integrator_opts o = {.rtol = 1e-7, .atol = 1e-9, .lin_maxit = 2,
                            .lin_tol = 0.01};
    cr_assert_lt(rs_exact_error(GN, &ts, &o, 5.0, 5, NULL), 100 * o.rtol);
    const cl_integrator_opts bad[] = {{.lin_maxit = -1}, {.lin_tol = -0.1},
                                      {.lin_tol = NAN}};
    double x[6] = {0}, v[6] = {0};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        void *st = (void *)1;
        cl_error err;
        cr_assert_eq(ri_find(GN)->create(&ts.sys, &bad[i], 0.0, x, v, &st,
                                         &err), CL_EINVAL, "case %zu", i);
        cr_assert_null(st);
    }
    ts_free(&ts);
}

/* NaN forces are blow-ups, system errors are passed on. */
Test(cvode_bdf_gmres, failures_reported)
{
    rs_check_failures(GN, false);
}
