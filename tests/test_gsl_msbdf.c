/* gsl-msbdf: reaches its tolerance on spring2 in the sense of a BDF code
 * (global error at T = 1 below 80, 600 and 2500 tol for tol = 1e-6, 1e-8
 * and 1e-10, shrinking at least 10-fold per 100-fold tighter tol; measured
 * 40, 300, 1300 tol, cvode-bdf 160 to 700 tol: the local error control
 * does not bound the global error, which accumulates over the 100-300
 * steps), the dense
 * first-order Jacobian against central differences of the RHS (coupled
 * pair with damping and distinct masses), dfdt = 0 for an autonomous
 * system, the size limit (CL_EUNSUPPORTED above 1728 unknowns), its
 * advantage on a stiff problem (far fewer steps than gsl-rk8pd), and
 * agreement with a tight cvode-bdf run on the hang cloth.  Options and
 * failures: test_gslode.c. */
#include <criterion/criterion.h>

#include "integrators/gslode.h"
#include "runint.h"
#include "runsun.h"
#include "spring2.h"
#include "timelimit.h"

Test(gsl_msbdf, reaches_tolerance_on_spring2)
{
    s2_check_tolerance("gsl-msbdf", (const double[3]){80, 600, 2500});
}

Test(gsl_msbdf, refuses_large_systems)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 577), 0); /* n = 1731 > 1728 */
    double *x = calloc(ts.n, sizeof *x), *v = calloc(ts.n, sizeof *v);
    cr_assert(x && v);
    cl_integrator_opts o = {0};
    void *st = (void *)1;
    cl_error err;
    cr_expect_eq(ri_find("gsl-msbdf")->create(&ts.sys, &o, 0.0, x, v, &st,
                                              &err),
                 CL_EUNSUPPORTED);
    cr_expect_null(st);
    cr_expect_not_null(strstr(err.msg, "1728"), "%s", err.msg);
    cr_expect_not_null(strstr(err.msg, "1731"), "%s", err.msg);
    free(x);
    free(v);
    ts_free(&ts);
}

/* dfdy[r][c] against (F(y + d e_c) - F(y - d e_c)) / 2d, F the RHS. */
static void check_jacobian(cl_gslode *s, const double *y)
{
    enum { D = 12 };
    double J[D * D], dfdt[D], yp[D], fp[D], fm[D], d = 1e-6;
    cr_assert_eq(s->gsys.dimension, D);
    cr_assert_eq(s->gsys.jacobian(0.5, y, J, dfdt, s), 0);
    for (int c = 0; c < D; c++) {
        memcpy(yp, y, sizeof yp);
        yp[c] = y[c] + d;
        cr_assert_eq(s->gsys.function(0.5, yp, fp, s), 0);
        yp[c] = y[c] - d;
        cr_assert_eq(s->gsys.function(0.5, yp, fm, s), 0);
        for (int r = 0; r < D; r++)
            cr_expect_float_eq(J[r * D + c], (fp[r] - fm[r]) / (2 * d), 1e-7,
                               "dfdy[%d][%d]", r, c);
    }
    for (int r = 0; r < D; r++)
        cr_expect_eq(dfdt[r], 0.0, "dfdt[%d] = %g", r, dfdt[r]);
}

Test(gsl_msbdf, dense_jacobian_matches_differences)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    for (int i = 0; i < 6; i++) {
        ts.mass[i] = 1.0 + 0.25 * i;
        ts.c[i] = 0.1 * (i + 1);
    }
    double x[6], v[6], y[12];
    ts_initial(&ts, x, v);
    memcpy(y, x, sizeof x);
    memcpy(y + 6, v, sizeof v);
    cl_integrator_opts o = {0};
    void *st;
    cl_error err;
    cr_assert_eq(ri_find("gsl-msbdf")->create(&ts.sys, &o, 0.0, x, v, &st,
                                              &err),
                 CL_OK, "%s", err.msg);
    check_jacobian(st, y);
    cl_stats s;
    ri_find("gsl-msbdf")->stats(st, &s);
    cr_expect_eq(s.jac_evals, 1);
    ri_find("gsl-msbdf")->free(st);
    ts_free(&ts);
}

/* m = 1; component 0 a slow undamped oscillator (k = 1), components 1, 2
 * stiff and overdamped (k = 1e6, c = 1e4: eigenvalues about -1e4 and
 * -100).  To T = 2 both methods are accurate, but rk8pd's step is held at
 * its stability limit (~5e-4) while msbdf's follows the slow motion. */
Test(gsl_msbdf, stiff_problem_few_steps)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, 1e6);
    ts.k[0] = 1.0;
    ts.c[1] = ts.c[2] = 1e4;
    const char *names[2] = {"gsl-msbdf", "gsl-rk8pd"};
    const double tol[2] = {2e-5, 1e-10}; /* measured 4.4e-6, 1.4e-13 */
    long steps[2];
    for (int i = 0; i < 2; i++) {
        double x0[6], v0[6], x[6], v[6], xe[6], ve[6]; /* 6: see ts_exact */
        ts_initial(&ts, x0, v0);
        memcpy(x, x0, 3 * sizeof *x);
        memcpy(v, v0, 3 * sizeof *v);
        cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
        cl_stats s;
        ri_run(names[i], &ts.sys, &o, 0.0, 2.0, x, v, &s);
        ts_exact(&ts, x0, v0, 2.0, xe, ve);
        steps[i] = s.steps;
        cr_log_info("%s stiff: %ld steps, %ld rhs, %ld jac, x err %.2e",
                    names[i], s.steps, s.rhs_evals, s.jac_evals,
                    ts_maxdiff(x, xe, 3));
        cr_expect_lt(ts_maxdiff(x, xe, 3), tol[i], "%s", names[i]);
    }
    cr_expect_lt(5 * steps[0], steps[1], "msbdf %ld steps, rk8pd %ld",
                 steps[0], steps[1]);
    ts_free(&ts);
}

/* The cloth: hang with n = 5 (69 unknowns; n = 5 stays well conditioned to
 * T = 0.5, n = 6 to 12 do not: test_agreement.c) to T = 0.5; gsl-msbdf at
 * rtol 1e-6, atol 1e-8 against cvode-bdf at rtol 1e-10, atol 1e-12: final
 * positions within 10 (rtol max|x| + atol). */
Test(gsl_msbdf, agrees_with_tight_cvode_on_hang)
{
    time_limit(120);
    rs_hang h;
    rs_hang_load(&h, 5);
    size_t n = h.sys->n;
    double *x[2], *v = malloc(n * sizeof *v), xmax = 0, d = 0;
    const char *names[2] = {"gsl-msbdf", "cvode-bdf"};
    const double tol[2] = {1e-6, 1e-10};
    cr_assert_not_null(v);
    for (int k = 0; k < 2; k++) {
        cl_integrator_opts o = {.rtol = tol[k], .atol = tol[k] / 100};
        x[k] = malloc(n * sizeof *x[k]);
        cr_assert_not_null(x[k]);
        memcpy(x[k], h.x0, n * sizeof *x[k]);
        memcpy(v, h.v0, n * sizeof *v);
        ri_run(names[k], h.sys, &o, 0.0, 0.5, x[k], v, NULL);
    }
    for (size_t i = 0; i < n; i++) {
        xmax = fmax(xmax, fabs(x[1][i]));
        d = fmax(d, fabs(x[0][i] - x[1][i]));
    }
    cr_log_info("gsl-msbdf vs tight cvode-bdf on hang n = 5: %.3e", d);
    cr_expect_leq(d, 10 * (1e-6 * xmax + 1e-8), "%.3e", d);
    free(x[0]);
    free(x[1]);
    free(v);
    rs_hang_free(&h);
}
