/* Helpers of the tests of the adaptive SUNDIALS integrators (cvode-bdf-dense,
 * cvode-bdf-gmres, cvode-adams, ida) and of the cross-integrator
 * agreement test: error against the closed-form systems of testsys.h over
 * several outputs, a failure-injection run, and the hang problem loaded
 * through the model with n particles per side (tests run from the
 * repository root).  Header only, included after <criterion/criterion.h>. */
#ifndef CL_TESTS_RUNSUN_H
#define CL_TESTS_RUNSUN_H

#include <criterion/criterion.h>

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"
#include "runint.h"
#include "testsys.h"

/* Integrate `name` on ts from ts_initial at 0 to T with nout equally spaced
 * outputs; returns the max error in x and v over the outputs relative to
 * the solution's size (max |x_i|, |v_i| over the outputs, at least 1);
 * statistics at the end to *s if s. */
static inline double rs_exact_error(const char *name, ts_sys *ts,
                                    const cl_integrator_opts *o, double T,
                                    int nout, cl_stats *s)
{
    const cl_integrator_type *it = ri_find(name);
    double x0[RI_MAXN], v0[RI_MAXN], x[RI_MAXN], v[RI_MAXN];
    double xe[RI_MAXN], ve[RI_MAXN], e = 0, amp = 1;
    cr_assert_leq(ts->n, RI_MAXN);
    ts_initial(ts, x0, v0);
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(&ts->sys, o, 0.0, x0, v0, &st, &err), CL_OK,
                 "%s: %s", name, err.msg);
    for (int i = 1; i <= nout; i++) {
        double t = T * i / nout;
        cr_assert_eq(it->advance(st, t, x, v, &err), CL_OK, "%s: %s", name,
                     err.msg);
        ts_exact(ts, x0, v0, t, xe, ve);
        e = fmax(e, fmax(ts_maxdiff(x, xe, ts->n), ts_maxdiff(v, ve, ts->n)));
        for (size_t j = 0; j < ts->n; j++)
            amp = fmax(amp, fmax(fabs(xe[j]), fabs(ve[j])));
    }
    if (s)
        it->stats(st, s);
    it->free(st);
    cr_log_info("%s rtol %g: max rel. error %.3e over %d outputs", name,
                o->rtol, e / amp, nout);
    return e / amp;
}

/* Log the statistics of a run of ts and check the counters the system can
 * see: the force evaluations the method reports are the calls ts saw, and
 * so are its Jacobian evaluations when `own_jacobian` (the method's
 * Jacobian is the system's, not a difference quotient). */
static inline void rs_check_stats(const char *name, const cl_stats *s,
                                  const ts_sys *ts, bool own_jacobian)
{
    cr_log_info("%s stats: steps %ld rhs %ld jac %ld setups %ld solves %ld "
                "lin_iters %ld nonlin %ld ncf %ld etf %ld symbolic %ld", name,
                s->steps, s->rhs_evals, s->jac_evals, s->lin_setups,
                s->lin_solves, s->lin_iters, s->nonlin_iters, s->nonlin_fails,
                s->err_fails, s->symbolic_facts);
    cr_assert_eq(s->rhs_evals, ts->nforce, "%s: %ld force evaluations "
                 "reported, %ld made", name, s->rhs_evals, ts->nforce);
    if (own_jacobian)
        cr_assert_eq(s->jac_evals, ts->njac, "%s: %ld Jacobian evaluations "
                     "reported, %ld made", name, s->jac_evals, ts->njac);
}

/* The coupled pair (m, k, a) to T = 10 within 100 rtol (atol = rtol /
 * 100); statistics to *s (checked by rs_check_stats, with own_jacobian)
 * if s. */
static inline void rs_check_pair(const char *name, double m, double k,
                                 double a, double rtol, cl_stats *s,
                                 bool own_jacobian)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, m, k, a), 0);
    cl_integrator_opts o = {.rtol = rtol, .atol = rtol / 100};
    double e = rs_exact_error(name, &ts, &o, 10.0, 25, s);
    cr_assert_lt(e, 100 * rtol, "%s: %.3e", name, e);
    if (s)
        rs_check_stats(name, s, &ts, own_jacobian);
    ts_free(&ts);
}

/* Two particles with fast modes at -1e6 and -1e4 and slow ones near -1
 * (an explicit method would need h < 2e-6): within 100 rtol at rtol 1e-6
 * to T = 10 in fewer than 5000 steps. */
static inline void rs_check_stiff(const char *name)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    for (int r = 0; r < 3; r++) {
        ts.mass[r] = ts.mass[3 + r] = 1.0;
        ts.k[r] = 1e6;
        ts.c[r] = 1e6 + 1.0;
        ts.k[3 + r] = 1e4 * (r + 1);
        ts.c[3 + r] = 1e4 * (r + 1) + 3.0;
    }
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    cl_stats s;
    cr_assert_lt(rs_exact_error(name, &ts, &o, 10.0, 10, &s), 100 * o.rtol);
    cr_log_info("%s stiff: %ld steps", name, s.steps);
    cr_assert_lt(s.steps, 5000, "%s: %ld steps", name, s.steps);
    ts_free(&ts);
}

/* The closed-form checks: three oscillator particles (undamped, light,
 * moderate damping) to T = 10 within 100 rtol at rtol 1e-6 and 1e-9, the
 * tighter run more accurate; the coupled pair (2, 3, 1.5) at rtol 1e-6;
 * the stiff set if `stiff`. */
static inline void rs_check_closed_forms(const char *name, bool stiff)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8};
    double e = rs_exact_error(name, &ts, &o, 10.0, 20, NULL);
    cr_assert_lt(e, 100 * o.rtol, "%s: %.3e", name, e);
    o.rtol = 1e-9;
    o.atol = 1e-11;
    double e2 = rs_exact_error(name, &ts, &o, 10.0, 20, NULL);
    cr_assert_lt(e2, 100 * o.rtol, "%s: %.3e", name, e2);
    cr_assert_lt(e2, e, "%s", name);
    ts_free(&ts);
    rs_check_pair(name, 2.0, 3.0, 1.5, 1e-6, NULL, false);
    if (stiff)
        rs_check_stiff(name);
}

/* One oscillator particle whose force fails from t_bad on (TS_FAIL_*):
 * create must give want_create; if it succeeded, the advance to 0.5
 * (t_bad > 0.5) succeeds and the advance to 3 reports want, naming a
 * time. */
static inline void rs_expect_failure(const char *name, int fail, double t_bad,
                                     cl_status sys_status,
                                     cl_status want_create, cl_status want)
{
    const cl_integrator_type *it = ri_find(name);
    ts_sys ts;
    double x[3], v[3];
    ri_failing_oscillator_at(&ts, fail, sys_status, t_bad, x, v);
    cl_integrator_opts o = {0};
    void *st = NULL;
    cl_error err = {0};
    cl_status got = it->create(&ts.sys, &o, 0.0, x, v, &st, &err);
    cr_assert_eq(got, want_create, "%s create: %s: %s", name,
                 cl_status_name(got), err.msg);
    if (got == CL_OK) {
        if (t_bad > 0.5)
            cr_assert_eq(it->advance(st, 0.5, x, v, &err), CL_OK, "%s: %s",
                         name, err.msg);
        got = it->advance(st, 3.0, x, v, &err);
        cl_stats s;
        it->stats(st, &s);
        cr_log_info("%s failure after %ld steps: %s", name, s.steps,
                    err.msg);
        cr_assert_eq(got, want, "%s: %s: %s", name, cl_status_name(got),
                     err.msg);
        it->free(st);
    } else {
        cr_log_info("%s failure: %s", name, err.msg);
    }
    cr_assert_not_null(strstr(err.msg, "t = "), "%s", err.msg);
    ts_free(&ts);
}

/* The failure checks: NaN forces from the start and from t = 1 on give
 * CL_EBLOWUP, a system error from t = 1 on (CL_EINVAL) is passed on.  A
 * method that evaluates the force in create (create_evaluates) fails
 * create when the force fails from the start, otherwise the advance. */
static inline void rs_check_failures(const char *name, bool create_evaluates)
{
    cl_status at0 = create_evaluates ? CL_EBLOWUP : CL_OK;
    rs_expect_failure(name, TS_FAIL_NAN, -1.0, CL_OK, at0, CL_EBLOWUP);
    rs_expect_failure(name, TS_FAIL_NAN, 1.0, CL_OK, CL_OK, CL_EBLOWUP);
    rs_expect_failure(name, TS_FAIL_STATUS, 1.0, CL_EINVAL, CL_OK, CL_EINVAL);
    at0 = create_evaluates ? CL_EINVAL : CL_OK;
    rs_expect_failure(name, TS_FAIL_STATUS, -1.0, CL_EINVAL, at0, CL_EINVAL);
}

/* The hang problem with n particles per side. */
typedef struct {
    cl_config *cfg;
    cl_model *m;
    const cl_system *sys;
    double *x0, *v0; /* initial state, sys->n each */
} rs_hang;

static inline void rs_hang_load(rs_hang *h, int n)
{
    cl_error err = {0};
    char set[64];
    snprintf(set, sizeof set, "cloth.n=%d", n);
    h->cfg = cl_config_alloc();
    cr_assert_not_null(h->cfg);
    cr_assert_eq(cl_config_load(h->cfg, "problems/hang.ini", &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_config_set(h->cfg, set, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_model_create(h->cfg, &h->m, &err), CL_OK, "%s",
                 err.msg);
    h->sys = cl_model_system(h->m);
    h->x0 = malloc(h->sys->n * sizeof *h->x0);
    h->v0 = malloc(h->sys->n * sizeof *h->v0);
    cr_assert(h->x0 && h->v0);
    cl_model_initial_state(h->m, h->x0, h->v0);
}

static inline void rs_hang_free(rs_hang *h)
{
    free(h->x0);
    free(h->v0);
    cl_model_free(h->m);
    cl_config_free(h->cfg);
}

#endif
