/* cvode-bdf-dense against closed-form solutions (oscillators, coupled
 * pair); statistics of the difference-quotient Jacobian; the size limit
 * (24 x 24 particles: the hang problem with n = 25 is refused clearly, a
 * system at the limit is accepted); blow-up reporting. */
#include <criterion/criterion.h>

#include <string.h>

#include "runsun.h"

#define DN "cvode-bdf-dense"

Test(cvode_bdf_dense, closed_form_solutions)
{
    rs_check_closed_forms(DN, true);
}

/* The force evaluations reported are those the system saw, the 2n of
 * every difference-quotient Jacobian included (the system's Jacobian is
 * never called); the LU solves counted by the solver are CVODE's Newton
 * iterations, one each. */
Test(cvode_bdf_dense, statistics)
{
    cl_stats s;
    rs_check_pair(DN, 1.0, 2.0, 4.0, 1e-7, &s, false);
    cr_assert_eq(s.lin_solves, s.nonlin_iters);
    cr_assert_eq(s.lin_iters, 0);
    cr_assert_eq(s.symbolic_facts, 0);
}

Test(cvode_bdf_dense, refuses_hang_n25)
{
    rs_hang h;
    rs_hang_load(&h, 25);
    cl_integrator_opts o = {0};
    void *st = (void *)1;
    cl_error err = {0};
    cr_assert_eq(ri_find(DN)->create(h.sys, &o, 0.0, h.x0, h.v0, &st, &err),
                 CL_EUNSUPPORTED, "%s", err.msg);
    cr_assert_null(st);
    cr_log_info("%s", err.msg);
    char size[32];
    snprintf(size, sizeof size, "%zu unknowns", h.sys->n);
    cr_assert_not_null(strstr(err.msg, size), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "24 x 24"), "%s", err.msg);
    cr_assert_not_null(strstr(err.msg, "1728"), "%s", err.msg);
    rs_hang_free(&h);
}

/* 576 particles (n = 1728) is the largest system accepted. */
Test(cvode_bdf_dense, accepts_the_limit)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 576), 0);
    double *x = calloc(ts.n, sizeof *x), *v = calloc(ts.n, sizeof *v);
    cr_assert(x && v);
    cl_integrator_opts o = {0};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(ri_find(DN)->create(&ts.sys, &o, 0.0, x, v, &st, &err),
                 CL_OK, "%s", err.msg);
    ri_find(DN)->free(st);
    free(x);
    free(v);
    ts_free(&ts);
}

/* NaN forces are blow-ups, system errors are passed on. */
Test(cvode_bdf_dense, failures_reported)
{
    rs_check_failures(DN, false);
}
