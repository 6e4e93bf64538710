/* Shared code of the semi-be and semi-bdf2 tests: spring2 (tests/spring2.h)
 * with overridden keys, its closed form with a pin moving at constant
 * velocity, observed convergence orders for a given linear solver, and the
 * reduced `hang` run whose statistics both methods must give, and the
 * checks of error ratios, registry row and refused options they share.
 *
 * spring2 with the pin moving along x at velocity w ([pins] velocity):
 * y = x - w t - L obeys y'' = -W^2 y, y(0) = 0, y'(0) = v0 - w, so
 *   x(t) = L + w t + ((v0 - w)/W) sin(W t),  v(t) = w + (v0 - w) cos(W t).
 * Header only, included after <criterion/criterion.h>. */
#ifndef CL_TESTS_SEMITEST_H
#define CL_TESTS_SEMITEST_H

#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"
#include "runint.h"
#include "spring2.h"

/* spring2 with "section.key=value" overrides (NULL-terminated, or NULL). */
static inline void st_load(s2_problem *p, const char *const *sets)
{
    cl_error err = {0};
    p->cfg = cl_config_alloc();
    cr_assert_not_null(p->cfg);
    cr_assert_eq(cl_config_load(p->cfg, "problems/spring2.ini", &err), CL_OK,
                 "%s", err.msg);
    for (size_t k = 0; sets && sets[k]; k++)
        cr_assert_eq(cl_config_set(p->cfg, sets[k], &err), CL_OK, "%s",
                     err.msg);
    cr_assert_eq(cl_model_create(p->cfg, &p->m, &err), CL_OK, "%s", err.msg);
    p->sys = cl_model_system(p->m);
    cr_assert_eq(p->sys->n, 3, "spring2 has one free particle");
    cl_model_initial_state(p->m, p->x0, p->v0);
}

/* Error at T of `name` with linear solver `linsol` in steps of dt, against
 * the closed form with pin velocity w: max(|x - x_e|, |v - v_e| / W). */
static inline double st_error(const s2_problem *p, const char *name,
                              const char *linsol, double w, double dt,
                              double T)
{
    const cl_integrator_type *it = cl_integrator_find(name);
    cr_assert_not_null(it, "integrator %s not registered", name);
    cl_integrator_opts o = {.dt = dt, .linsol = linsol};
    double x[3], v[3];
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(p->sys, &o, 0.0, p->x0, p->v0, &st, &err), CL_OK,
                 "%s: %s", name, err.msg);
    cr_assert_eq(it->advance(st, T, x, v, &err), CL_OK, "%s: %s", name,
                 err.msg);
    it->free(st);
    double s = sin(S2_W * T), c = cos(S2_W * T);
    double xe = S2_L + w * T + (S2_V0 - w) / S2_W * s;
    double ve = w + (S2_V0 - w) * c;
    double e = fmax(fabs(x[0] - xe), fabs(v[0] - ve) / S2_W);
    return fmax(e, fmax(fmax(fabs(x[1]), fabs(x[2])),
                        fmax(fabs(v[1]), fabs(v[2])) / S2_W));
}

/* Least-squares order over dt0, dt0/2, ... (npts points) on spring2 with
 * overrides `sets` (pin velocity w). */
static inline double st_order(const char *name, const char *linsol,
                              const char *const *sets, double w, double dt0,
                              int npts, double T)
{
    s2_problem p;
    double h[8], e[8];
    cr_assert_leq(npts, 8);
    st_load(&p, sets);
    for (int k = 0; k < npts; k++) {
        h[k] = dt0 / (double)(1 << k);
        e[k] = st_error(&p, name, linsol, w, h[k], T);
        cr_log_info("%s/%s w=%g dt=%g: error %.4e%s", name, linsol, w, h[k],
                    e[k], k ? "" : " (first)");
        if (k)
            cr_log_info("  ratio %.4f", e[k - 1] / e[k]);
    }
    s2_free(&p);
    double q = s2_slope(h, e, npts);
    cr_log_info("%s/%s w=%g: least-squares order %.4f", name, linsol, w, q);
    return q;
}

/* st_order over dt0, dt0/2, ..., dt0/16 to T = 1 must be `want` to
 * within 0.2. */
static inline void st_expect_order(const char *name, const char *linsol,
                                   const char *const *sets, double w,
                                   double dt0, double want)
{
    double q = st_order(name, linsol, sets, w, dt0, 5, 1.0);
    cr_assert(fabs(q - want) < 0.2, "%s/%s: order %g", name, linsol, q);
}

/* problems/hang.ini with `nset` (cloth.n=...) on `threads` threads, to
 * t_end in steps of 1e-3 by `name` with `linsol` (the first half, then
 * the second); the final state into *x, *v (malloc'd, *n entries),
 * statistics to *s. */
static inline void st_hang_run(const char *name, const char *linsol,
                               const char *nset, int threads, double t_end,
                               double **x, double **v, size_t *n,
                               cl_stats *s)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cr_assert_not_null(cfg);
    cr_assert_eq(cl_config_load(cfg, "problems/hang.ini", &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_config_set(cfg, nset, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_model_set_threads(m, threads, &err), CL_OK, "%s",
                 err.msg);
    const cl_system *sys = cl_model_system(m);
    *n = sys->n;
    *x = malloc(sys->n * sizeof **x);
    *v = malloc(sys->n * sizeof **v);
    cr_assert(*x && *v);
    cl_model_initial_state(m, *x, *v);
    const cl_integrator_type *it = cl_integrator_find(name);
    cr_assert_not_null(it);
    cl_integrator_opts o = {.dt = 1e-3, .linsol = linsol};
    void *st = NULL;
    cr_assert_eq(it->create(sys, &o, 0.0, *x, *v, &st, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(it->advance(st, t_end / 2, *x, *v, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(it->advance(st, t_end, *x, *v, &err), CL_OK, "%s",
                 err.msg);
    it->stats(st, s);
    it->free(st);
    cl_model_free(m);
    cl_config_free(cfg);
}

/* problems/hang.ini with n = 8, 0.2 s in steps of 1e-3 by `name` with
 * `linsol`; statistics to *s.  The lowest particle must be where CVODE
 * puts it at rtol 1e-10 (y = -0.196171 m): backward Euler's to 1.2e-3 m,
 * above its first-order lag h g T / 2 = 9.8e-4 m (measured 9.3e-4 m),
 * semi-bdf2's to 1e-4 m (measured 3e-5 m). */
static inline void st_hang(const char *name, const char *linsol, cl_stats *s)
{
    double *x, *v;
    size_t n;
    st_hang_run(name, linsol, "cloth.n=8", 1, 0.2, &x, &v, &n, s);
    double ymin = 0;
    for (size_t i = 0; i < n; i++) {
        cr_assert(isfinite(x[i]) && isfinite(v[i]));
        if (i % 3 == 1)
            ymin = fmin(ymin, x[i]);
    }
    cr_log_info("%s/%s hang n=8: lowest y %.4f m after 0.2 s; %ld steps, "
                "%ld setups, %ld solves, %ld Krylov iterations, %ld symbolic",
                name, linsol, ymin, s->steps, s->lin_setups, s->lin_solves,
                s->lin_iters, s->symbolic_facts);
    double tol = strcmp(name, "semi-be") == 0 ? 1.2e-3 : 1e-4;
    cr_assert_float_eq(ymin, -0.196171, tol, "lowest y %.6g m", ymin);
    free(x);
    free(v);
}

/* The statistics of a 200-step run with one linear solve per step. */
static inline void st_check_hang_stats(const cl_stats *s, const char *linsol)
{
    cr_assert_eq(s->steps, 200);
    cr_assert_eq(s->lin_setups, 200);
    cr_assert_eq(s->lin_solves, 200);
    cr_assert_eq(s->jac_evals, 200);
    cr_assert_eq(s->rhs_evals, 200);
    if (strcmp(linsol, "klu") == 0) {
        cr_assert_eq(s->symbolic_facts, 1);
        cr_assert_eq(s->lin_iters, 0);
    } else {
        cr_assert_eq(s->symbolic_facts, 0);
        cr_assert_geq(s->lin_iters, 200);
    }
}

/* st_hang with `linsol`, then st_check_hang_stats. */
static inline void st_expect_hang_stats(const char *name, const char *linsol)
{
    cl_stats s = {0};
    st_hang(name, linsol, &s);
    st_check_hang_stats(&s, linsol);
}

/* Error ratios e(dt) / e(dt/2) at T = 2 of positions and velocities, both
 * strictly between lo and hi, on the two damped oscillator particles
 * (ts_oscillators(2)) and on the undamped coupled pair (ts_pair(2, 3,
 * 1.5)). */
static inline void st_expect_ratios_osc_pair(const char *name, double dt,
                                             double lo, double hi)
{
    ts_sys ts;
    double rx, rv;
    for (int sys = 0; sys < 2; sys++) {
        cr_assert_eq(sys == 0 ? ts_oscillators(&ts, 2)
                              : ts_pair(&ts, 2.0, 3.0, 1.5), 0);
        ri_ratios(name, &ts, dt, 2.0, &rx, &rv);
        cr_assert(rx > lo && rx < hi && rv > lo && rv < hi, "ratios %g %g",
                  rx, rv);
        ts_free(&ts);
    }
}

/* A fixed-step method that takes --linsol. */
static inline void st_expect_registry_row(const char *name)
{
    const cl_integrator_type *t = ri_find(name);
    cr_assert(t->fixed_step);
    cr_assert(t->takes_linsol);
}

/* create with options o on one oscillator particle fails with CL_EINVAL,
 * leaves no state, and (if given) names `want` in its message. */
static inline void st_expect_refused(const char *name,
                                     const cl_integrator_opts *o,
                                     const char *want, cl_error *err)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3] = {0}, v[3] = {0};
    void *st = (void *)1;
    cr_assert_eq(ri_find(name)->create(&ts.sys, o, 0.0, x, v, &st, err),
                 CL_EINVAL, "dt = %g, linsol %s", o->dt,
                 o->linsol ? o->linsol : "(default)");
    cr_assert_null(st);
    if (want)
        cr_assert_not_null(strstr(err->msg, want), "%s", err->msg);
    ts_free(&ts);
}

/* A step dt that is not finite and > 0 is refused. */
static inline void st_expect_bad_dt(const char *name, double dt)
{
    cl_integrator_opts o = {.dt = dt};
    cl_error err = {0};
    st_expect_refused(name, &o, NULL, &err);
}

/* An unknown linear solver is refused, naming it and the known ones. */
static inline void st_expect_unknown_linsol(const char *name,
                                            const char *linsol)
{
    cl_integrator_opts o = {.dt = 0.01, .linsol = linsol};
    cl_error err = {0};
    st_expect_refused(name, &o, linsol, &err);
    cr_assert_not_null(strstr(err.msg, "klu, pcg"), "%s", err.msg);
}

#endif
