/* Helpers of the integrator tests that run a method by name on the
 * closed-form systems of testsys.h: one run from a given state, the error
 * of a run against the exact solution, observed error ratios, and the
 * undamped unit oscillator used by the energy tests.  Header only,
 * included after <criterion/criterion.h>. */
#ifndef CL_TESTS_RUNINT_H
#define CL_TESTS_RUNINT_H

#include <criterion/criterion.h>

#include <math.h>

#include "integrators/integrator.h"
#include "testsys.h"

#define RI_MAXN 12

static inline const cl_integrator_type *ri_find(const char *name)
{
    const cl_integrator_type *t = cl_integrator_find(name);
    cr_assert_not_null(t, "integrator %s not registered", name);
    return t;
}

/* Run `name` from (x, v) at t0 to T, in place; statistics to *s if s. */
static inline void ri_run(const char *name, const cl_system *sys,
                          const cl_integrator_opts *o, double t0, double T,
                          double *x, double *v, cl_stats *s)
{
    const cl_integrator_type *it = ri_find(name);
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(sys, o, t0, x, v, &st, &err), CL_OK, "%s: %s",
                 name, err.msg);
    cr_assert_eq(it->advance(st, T, x, v, &err), CL_OK, "%s: %s", name,
                 err.msg);
    if (s)
        it->stats(st, s);
    it->free(st);
}

/* The initial state of ts into x0, v0 and into the working copies x, v. */
static inline void ri_start(const ts_sys *ts, double *x0, double *v0,
                            double *x, double *v)
{
    ts_initial(ts, x0, v0);
    memcpy(x, x0, ts->n * sizeof *x);
    memcpy(v, v0, ts->n * sizeof *v);
}

/* k steps of `name` with dt = h from ts_initial at t = 0: the initial
 * state into x0, v0 and the state after k steps into x, v. */
static inline void ri_steps(const char *name, const ts_sys *ts, double h,
                            int k, double *x0, double *v0, double *x,
                            double *v)
{
    cl_integrator_opts o = {.dt = h};
    ri_start(ts, x0, v0, x, v);
    ri_run(name, &ts->sys, &o, 0.0, k * h, x, v, NULL);
}

/* Max error at T from ts_initial of the positions (*ex) and velocities
 * (*ev) against the exact solution, in steps of dt. */
static inline void ri_error(const char *name, ts_sys *ts, double dt,
                            double T, double *ex, double *ev)
{
    double x[RI_MAXN], v[RI_MAXN], x0[RI_MAXN], v0[RI_MAXN];
    double xe[RI_MAXN], ve[RI_MAXN];
    cr_assert_leq(ts->n, RI_MAXN);
    ri_start(ts, x0, v0, x, v);
    cl_integrator_opts o = {.dt = dt};
    ri_run(name, &ts->sys, &o, 0.0, T, x, v, NULL);
    ts_exact(ts, x0, v0, T, xe, ve);
    *ex = ts_maxdiff(x, xe, ts->n);
    *ev = ts_maxdiff(v, ve, ts->n);
}

/* Error ratios e(dt) / e(dt/2) of positions and velocities. */
static inline void ri_ratios(const char *name, ts_sys *ts, double dt,
                             double T, double *rx, double *rv)
{
    double ex1, ev1, ex2, ev2;
    ri_error(name, ts, dt, T, &ex1, &ev1);
    ri_error(name, ts, dt / 2, T, &ex2, &ev2);
    *rx = ex1 / ex2;
    *rv = ev1 / ev2;
    cr_log_info("%s dt=%g: x err %.3e ratio %.3f, v err %.3e ratio %.3f",
                name, dt, ex1, *rx, ev1, *rv);
}

/* Observed orders on ts from dt to dt/2: the error ratios of positions
 * and velocities must be 2^qx and 2^qv to within 0.1 in the exponent. */
static inline void ri_expect_orders(const char *name, ts_sys *ts, double dt,
                                    double T, double qx, double qv)
{
    double rx, rv;
    ri_ratios(name, ts, dt, T, &rx, &rv);
    cr_expect(fabs(log2(rx) - qx) < 0.1, "%s: position ratio %g, expected "
              "%g (order %g)", name, rx, pow(2, qx), qx);
    cr_expect(fabs(log2(rv) - qv) < 0.1, "%s: velocity ratio %g, expected "
              "%g (order %g)", name, rv, pow(2, qv), qv);
}

/* ri_expect_orders on the two damped oscillator particles
 * (ts_oscillators(2): orders ox, ov) and on the undamped coupled pair
 * (ts_pair(2, 3, 1.5): orders px, pv), to T = 2 from dt. */
static inline void ri_expect_orders_osc_pair(const char *name, double dt,
                                             double ox, double ov, double px,
                                             double pv)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    ri_expect_orders(name, &ts, dt, 2.0, ox, ov);
    ts_free(&ts);
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    ri_expect_orders(name, &ts, dt, 2.0, px, pv);
    ts_free(&ts);
}

/* One oscillator particle whose force fails from t_bad on: kind fail
 * (TS_FAIL_*), status st for TS_FAIL_STATUS, 3 failures for
 * TS_FAIL_TRANSIENT; initial state into x, v (3 each). */
static inline void ri_failing_oscillator_at(ts_sys *ts, int fail,
                                            cl_status st, double t_bad,
                                            double *x, double *v)
{
    cr_assert_eq(ts_oscillators(ts, 1), 0);
    ts->fail = fail;
    ts->t_bad = t_bad;
    ts->fail_status = st;
    ts->fail_left = 3;
    ts_initial(ts, x, v);
}

/* The same failing from t = 1 on. */
static inline void ri_failing_oscillator(ts_sys *ts, int fail, cl_status st,
                                         double *x, double *v)
{
    ri_failing_oscillator_at(ts, fail, st, 1.0, x, v);
}

/* One particle, m = 1, stiffness k on all three components, no damping. */
static inline void ri_unit_oscillator(ts_sys *ts, double k)
{
    cr_assert_eq(ts_oscillators(ts, 1), 0);
    for (int r = 0; r < 3; r++) {
        ts->mass[r] = 1.0;
        ts->k[r] = k;
        ts->c[r] = 0.0;
    }
}

/* Energy of ri_unit_oscillator: sum of (k x^2 + v^2) / 2. */
static inline double ri_osc_energy(const ts_sys *ts, const double *x,
                                   const double *v)
{
    double e = 0;
    for (int r = 0; r < 3; r++)
        e += 0.5 * (ts->k[r] * x[r] * x[r] + v[r] * v[r]);
    return e;
}

/* Relative energy error of `name` on ri_unit_oscillator(k = 1) sampled 16
 * times per period: max over the first and over the last 10 of `periods`
 * periods (h must divide the sample times to 1e-9: it is rounded to whole
 * steps). */
static inline void ri_energy_drift(const char *name, double h, int periods,
                                   double *first, double *last)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, 1.0);
    double x[3] = {1, 0, 0.5}, v[3] = {0, 1, -0.5};
    double E0 = ri_osc_energy(&ts, x, v);
    const cl_integrator_type *it = ri_find(name);
    cl_integrator_opts o = {.dt = h};
    void *st = NULL;
    cl_error err = {0};
    *first = *last = 0;
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    for (int p = 0; p < periods; p++) {
        for (int q = 1; q <= 16; q++) {
            long step = lround((p + q / 16.0) * 6.283185307179586 / h);
            cr_assert_eq(it->advance(st, (double)step * h, x, v, &err),
                         CL_OK, "%s", err.msg);
            double rel = fabs(ri_osc_energy(&ts, x, v) - E0) / E0;
            if (p < 10)
                *first = fmax(*first, rel);
            if (p >= periods - 10)
                *last = fmax(*last, rel);
        }
    }
    it->free(st);
    ts_free(&ts);
    cr_log_info("%s energy error h=%g: first 10 periods %.3e, last 10 %.3e",
                name, h, *first, *last);
}

/* ri_energy_drift over 1000 periods: the energy error stays below bound
 * and does not drift (last 10 periods within 1.1 x the first 10). */
static inline void ri_expect_bounded_energy(const char *name, double h,
                                            double bound)
{
    double first, last;
    ri_energy_drift(name, h, 1000, &first, &last);
    cr_expect_lt(first, bound, "%s: energy error %g", name, first);
    cr_expect_lt(last, 1.1 * first, "%s: energy drifts: %g -> %g", name,
                 first, last);
}

/* |a_i - b_i| <= tol for all i < n (what names the array in messages). */
static inline void ri_expect_near(const double *a, const double *b, size_t n,
                                  double tol, const char *what)
{
    for (size_t i = 0; i < n; i++)
        cr_expect(fabs(a[i] - b[i]) <= tol, "%s[%zu] = %.17g, expected "
                  "%.17g", what, i, a[i], b[i]);
}

#endif
