/* ida against closed-form solutions (oscillators, coupled pair, a stiff
 * overdamped set); the iteration matrix c_j diag(I, M) - [[0, I], [df/dx,
 * df/dv]] entry by entry against a dense reference; statistics with one
 * KLU symbolic analysis (klu-full); consistent initial conditions (a
 * failing initial force fails create); blow-up reporting. */
#include <criterion/criterion.h>

#include <stdlib.h>

#include "linalg/firstorder.h"
#include "runsun.h"

#define IN "ida"

Test(ida, closed_form_solutions)
{
    rs_check_closed_forms(IN, true);
}

/* The baseline klu-full: the force and Jacobian evaluations reported are
 * those the system saw (residual evaluations plus the one force evaluation
 * for y'(0)); one KLU solve per Newton iteration; one symbolic analysis
 * for the whole run. */
Test(ida, statistics_and_one_symbolic_analysis)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 1.0, 2.0, 4.0), 0);
    cl_integrator_opts o = {.rtol = 1e-7, .atol = 1e-9,
                            .linsol = "klu-full"};
    cl_stats s;
    cr_assert_lt(rs_exact_error(IN, &ts, &o, 10.0, 25, &s), 100 * o.rtol);
    rs_check_stats(IN, &s, &ts, true);
    ts_free(&ts);
    cr_assert_str_eq(s.linsol, "klu-full");
    cr_assert_eq(s.lin_solves, s.nonlin_iters);
    cr_assert_eq(s.lin_iters, 0);
    cr_assert_eq(s.symbolic_facts, 1);
}

/* Random blocks (mass differing per component) against the dense matrix
 * G = c_j diag(I, M) - [[0, I], [df/dx, df/dv]]. */
Test(ida, iteration_matrix_matches_dense_reference)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 1.0, 2.0, 4.0), 0);
    enum { N = 6, NN = 12 };
    for (int i = 0; i < N; i++)
        ts.mass[i] = 0.5 + 0.25 * i;
    size_t nval = 9 * ts.pat.nnzb;
    double *dx = malloc(nval * sizeof *dx), *dv = malloc(nval * sizeof *dv);
    cr_assert(dx && dv);
    for (size_t k = 0; k < nval; k++) {
        dx[k] = sin(1.0 + 3.1 * (double)k);
        dv[k] = cos(0.5 + 1.9 * (double)k);
    }
    cl_firstorder fo;
    cl_error err;
    cr_assert_eq(cl_firstorder_create(&ts.pat, ts.mass, &fo, &err), CL_OK);
    sunindextype cp[NN + 1], *rv = malloc((size_t)fo.nnz * sizeof *rv);
    double *val = malloc((size_t)fo.nnz * sizeof *val), G[NN][NN] = {{0}};
    cr_assert(rv && val);
    const double cj = 7.5;
    cl_firstorder_fill_implicit_arrays(&fo, dx, dv, cj, cp, rv, val);
    for (int j = 0; j < NN; j++)
        for (sunindextype k = cp[j]; k < cp[j + 1]; k++)
            G[rv[k]][j] += val[k];
    double R[NN][NN] = {{0}};
    for (int i = 0; i < N; i++) {
        R[i][i] = cj;
        R[i][N + i] = -1.0;
        R[N + i][N + i] = cj * ts.mass[i];
    }
    for (size_t bi = 0; bi < 2; bi++)
        for (size_t k = ts.pat.rowptr[bi]; k < ts.pat.rowptr[bi + 1]; k++)
            for (size_t r = 0; r < 3; r++)
                for (size_t q = 0; q < 3; q++) {
                    size_t row = N + 3 * bi + r, col = 3 * ts.pat.col[k] + q;
                    R[row][col] -= dx[9 * k + 3 * r + q];
                    R[row][N + col] -= dv[9 * k + 3 * r + q];
                }
    for (int r = 0; r < NN; r++)
        for (int q = 0; q < NN; q++)
            cr_assert_float_eq(G[r][q], R[r][q], 1e-14, "G(%d,%d)", r, q);
    free(rv);
    free(val);
    free(dx);
    free(dv);
    cl_firstorder_free(&fo);
    ts_free(&ts);
}

/* NaN forces are blow-ups, system errors are passed on (a failure at t0
 * fails create: y'(0) needs the force). */
Test(ida, failures_reported)
{
    rs_check_failures(IN, true);
}

Test(ida, output_times_and_options)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x0[3], v0[3], x[3], v[3];
    ts_initial(&ts, x0, v0);
    cl_integrator_opts o = {0};
    void *st;
    cl_error err;
    const cl_integrator_type *it = ri_find(IN);
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x0, v0, &st, &err), CL_OK);
    cr_assert_eq(it->advance(st, 0.0, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(ts_maxdiff(x, x0, 3) + ts_maxdiff(v, v0, 3), 0.0);
    cr_assert_eq(it->advance(st, 1.0, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(it->advance(st, 0.5, x, v, &err), CL_EINVAL);
    it->free(st);
    o.max_steps = 5;
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x0, v0, &st, &err), CL_OK);
    cr_assert_eq(it->advance(st, 100.0, x, v, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "IDA_TOO_MUCH_WORK"), "%s", err.msg);
    it->free(st);
    o = (cl_integrator_opts){.rtol = -1.0};
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x0, v0, &st, &err), CL_EINVAL);
    ts_free(&ts);
}
