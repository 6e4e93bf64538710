/* The spring2 problem (problems/spring2.ini) for the integrator accuracy
 * tests: one free particle of mass 1 on a linear spring (ks = 100) to a
 * pinned particle at the origin, starting at (L, 0, 0), L = 1, with
 * velocity (v0, 0, 0), v0 = 1.  The motion stays on the x axis:
 *
 *   x1(t) = L + (v0/w) sin(w t),   v(t) = v0 cos(w t),   w = 10.
 *
 * Loaded through the model (tests run from the repository root); run any
 * integrator to T and measure the max error of the positions and of the
 * velocities against the closed form.  Header only, included by tests
 * after <criterion/criterion.h>. */
#ifndef CL_TESTS_SPRING2_H
#define CL_TESTS_SPRING2_H

#include <criterion/criterion.h>

#include <math.h>

#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"

#define S2_L 1.0
#define S2_V0 1.0
#define S2_W 10.0

typedef struct {
    cl_config *cfg;
    cl_model *m;
    const cl_system *sys;
    double x0[3], v0[3];
} s2_problem;

static inline void s2_load(s2_problem *p)
{
    cl_error err = {0};
    p->cfg = cl_config_alloc();
    cr_assert_not_null(p->cfg);
    cr_assert_eq(cl_config_load(p->cfg, "problems/spring2.ini", &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_model_create(p->cfg, &p->m, &err), CL_OK, "%s",
                 err.msg);
    p->sys = cl_model_system(p->m);
    cr_assert_eq(p->sys->n, 3, "spring2 has one free particle");
    cl_model_initial_state(p->m, p->x0, p->v0);
}

static inline void s2_free(s2_problem *p)
{
    cl_model_free(p->m);
    cl_config_free(p->cfg);
}

typedef struct {
    double ex, ev; /* max error of positions, of velocities */
} s2_error;

/* Errors of a state at time t against the closed form. */
static inline s2_error s2_state_error(const double *x, const double *v,
                                      double t)
{
    const double xe[3] = {S2_L + S2_V0 / S2_W * sin(S2_W * t), 0, 0};
    const double ve[3] = {S2_V0 * cos(S2_W * t), 0, 0};
    s2_error e = {0, 0};
    for (int r = 0; r < 3; r++) {
        e.ex = fmax(e.ex, fabs(x[r] - xe[r]));
        e.ev = fmax(e.ev, fabs(v[r] - ve[r]));
    }
    return e;
}

/* Run integrator `name` with options o from the initial state to T; the
 * statistics go to *s when s is not NULL. */
static inline s2_error s2_run(const s2_problem *p, const char *name,
                              const cl_integrator_opts *o, double T,
                              cl_stats *s)
{
    const cl_integrator_type *it = cl_integrator_find(name);
    cr_assert_not_null(it, "integrator %s not registered", name);
    double x[3], v[3];
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(p->sys, o, 0.0, p->x0, p->v0, &st, &err), CL_OK,
                 "%s: %s", name, err.msg);
    cr_assert_eq(it->advance(st, T, x, v, &err), CL_OK, "%s: %s", name,
                 err.msg);
    if (s)
        it->stats(st, s);
    it->free(st);
    return s2_state_error(x, v, T);
}

/* Least-squares slope of log(e) against log(h), k points. */
static inline double s2_slope(const double *h, const double *e, int k)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i = 0; i < k; i++) {
        double lx = log(h[i]), ly = log(e[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

/* An adaptive method `name` on spring2 to T = 1 with rtol = atol = tol for
 * tol = 1e-6, 1e-8, 1e-10: the error of the state must stay below
 * factor[k] * tol at the k-th tolerance and shrink at least 10-fold per
 * 100-fold tighter tol. */
static inline void s2_check_tolerance(const char *name,
                                      const double factor[3])
{
    s2_problem p;
    s2_load(&p);
    double prev = INFINITY, tol = 1e-6;
    for (int k = 0; k < 3; k++, tol /= 100) {
        cl_integrator_opts o = {.rtol = tol, .atol = tol};
        cl_stats s;
        s2_error e = s2_run(&p, name, &o, 1.0, &s);
        double err = fmax(e.ex, e.ev);
        cr_log_info("%s tol %g: x err %.3e, v err %.3e (%.1f tol), %ld steps, "
                    "%ld rhs, %ld jac, %ld err fails", name, tol, e.ex, e.ev,
                    err / tol, s.steps, s.rhs_evals, s.jac_evals,
                    s.err_fails);
        cr_expect_lt(err, factor[k] * tol, "%s tol %g: error %g", name, tol,
                     err);
        cr_expect_lt(err, prev / 10, "%s tol %g: error %g after %g", name,
                     tol, err, prev);
        cr_expect_gt(s.steps, 0);
        prev = err;
    }
    s2_free(&p);
}

#endif
