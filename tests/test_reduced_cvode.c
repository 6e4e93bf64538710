/* The half-size Newton solvers of cvode-bdf and ida (sun_reduced.h) against
 * the baseline klu-full on hang, n = 16, from rest to T = 0.1 s at rtol
 * 1e-5, atol 1e-7: every --linsol (klu, pcg, pcg-jacobi, cholmod, auto)
 * gives final positions within 10 (rtol max |x| + atol) of klu-full's and
 * velocities within 10 (rtol max |v| + atol), the bound of
 * test_agreement.c (the problem's sensitivity takes over near 0.3 s; at
 * 0.2 s the measured differences were 5e-9 .. 2e-7 m against a bound of
 * 1e-4; 0.1 s keeps the test to seconds).  The statistics name the
 * solver; the direct ones report their one symbolic analysis, the
 * iterative ones their iterations; the default is CL_SUNRED_DEFAULT; an
 * unknown name is refused with the list of the known ones. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/sun_reduced.h"
#include "runsun.h"
#include "timelimit.h"

#define RC_N 16
#define RC_T 0.1
#define RC_RTOL 1e-5
#define RC_ATOL 1e-7

static const char *const rc_linsols[] = {"klu", "pcg", "pcg-jacobi",
                                         "cholmod", "auto"};
#define RC_COUNT (sizeof rc_linsols / sizeof rc_linsols[0])

/* max_i |a_i - b_i| and max_i |b_i| */
static void rc_diff(const double *a, const double *b, size_t n, double *d,
                    double *amp)
{
    *d = *amp = 0.0;
    for (size_t i = 0; i < n; i++) {
        *d = fmax(*d, fabs(a[i] - b[i]));
        *amp = fmax(*amp, fabs(b[i]));
    }
}

/* `integ` with --linsol `ls` from rest to RC_T into x, v (h->sys->n). */
static void rc_run(const rs_hang *h, const char *integ, const char *ls,
                   double *x, double *v, cl_stats *s)
{
    size_t n = h->sys->n;
    memcpy(x, h->x0, n * sizeof *x);
    memcpy(v, h->v0, n * sizeof *v);
    cl_integrator_opts o = {.rtol = RC_RTOL, .atol = RC_ATOL, .linsol = ls};
    ri_run(integ, h->sys, &o, 0.0, RC_T, x, v, s);
    cr_log_info("%s --linsol %-10s: %-16s steps %ld setups %ld solves %ld "
                "lin_iters %ld jac %ld fallbacks %ld", integ, ls, s->linsol,
                s->steps, s->lin_setups, s->lin_solves, s->lin_iters,
                s->jac_evals, s->lin_fallbacks);
}

/* Per-solver expectations on the statistics. */
static void rc_check_stats(const char *ls, const cl_stats *s)
{
    cr_assert(strncmp(s->linsol, ls, strlen(ls)) == 0, "%s: %s", ls,
              s->linsol);
    cr_assert_gt(s->lin_solves, s->steps / 2, "%s", ls);
    cr_assert_gt(s->jac_evals, 0, "%s", ls);
    if (!strcmp(ls, "klu") || !strcmp(ls, "cholmod")) {
        cr_assert_eq(s->symbolic_facts, 1, "%s", ls);
        cr_assert_eq(s->lin_iters, 0, "%s", ls);
    } else if (strcmp(ls, "auto") != 0) {
        cr_assert_geq(s->lin_iters, s->lin_solves / 2, "%s", ls);
        cr_assert_eq(s->symbolic_facts, 0, "%s", ls);
    }
}

static void rc_compare(const char *integ)
{
    rs_hang h;
    rs_hang_load(&h, RC_N);
    size_t n = h.sys->n;
    double *xr = malloc(n * sizeof *xr), *vr = malloc(n * sizeof *vr);
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v);
    cr_assert(xr && vr && x && v);
    cl_stats s;
    rc_run(&h, integ, "klu-full", xr, vr, &s);
    cr_assert_str_eq(s.linsol, "klu-full");
    for (size_t k = 0; k < RC_COUNT; k++) {
        rc_run(&h, integ, rc_linsols[k], x, v, &s);
        rc_check_stats(rc_linsols[k], &s);
        double dx, xmax, dv, vmax;
        rc_diff(x, xr, n, &dx, &xmax);
        rc_diff(v, vr, n, &dv, &vmax);
        double bx = 10 * (RC_RTOL * xmax + RC_ATOL);
        double bv = 10 * (RC_RTOL * vmax + RC_ATOL);
        cr_log_info("%s --linsol %s vs klu-full: |dx| %.3e (bound %.3e), "
                    "|dv| %.3e (bound %.3e)", integ, rc_linsols[k], dx, bx,
                    dv, bv);
        cr_expect_leq(dx, bx, "%s %s: |dx| %.3e", integ, rc_linsols[k], dx);
        cr_expect_leq(dv, bv, "%s %s: |dv| %.3e", integ, rc_linsols[k], dv);
    }
    free(xr);
    free(vr);
    free(x);
    free(v);
    rs_hang_free(&h);
}

Test(reduced_cvode, every_linsol_agrees_with_klu_full)
{
    time_limit(300);
    rc_compare("cvode-bdf");
}

Test(reduced_ida, every_linsol_agrees_with_klu_full)
{
    time_limit(300);
    rc_compare("ida");
}

/* The default is CL_SUNRED_DEFAULT; unknown names are refused. */
Test(reduced_cvode, default_and_unknown_names)
{
    rs_hang h;
    rs_hang_load(&h, 4);
    const char *const integ[] = {"cvode-bdf", "ida"};
    for (size_t k = 0; k < 2; k++) {
        const cl_integrator_type *it = ri_find(integ[k]);
        cr_assert(it->takes_linsol, "%s", integ[k]);
        double *x = malloc(h.sys->n * sizeof *x);
        double *v = malloc(h.sys->n * sizeof *v);
        cr_assert(x && v);
        cl_stats s;
        cl_integrator_opts o = {.rtol = 1e-4, .atol = 1e-6};
        memcpy(x, h.x0, h.sys->n * sizeof *x);
        memcpy(v, h.v0, h.sys->n * sizeof *v);
        ri_run(integ[k], h.sys, &o, 0.0, 0.01, x, v, &s);
        cr_assert(strncmp(s.linsol, CL_SUNRED_DEFAULT,
                          strlen(CL_SUNRED_DEFAULT)) == 0, "%s", s.linsol);
        void *st = (void *)1;
        cl_error err = {0};
        o.linsol = "lu";
        cr_assert_eq(it->create(h.sys, &o, 0.0, x, v, &st, &err), CL_EINVAL);
        cr_assert_null(st);
        cr_assert_not_null(strstr(err.msg, "klu-full, klu, pcg"), "%s",
                           err.msg);
        free(x);
        free(v);
    }
    rs_hang_free(&h);
}
