/* Helpers of the kinsol-be, kinsol-bdf2, kinsol-midpoint tests, on spring2
 * loaded with overrides (semitest.h: st_load; an off-axis initial velocity
 * makes it nonlinear, Choi-Ko damping makes f depend on v): the force and
 * 3x3 Jacobian blocks of its one free particle, the Newton matrix
 * M - a D - b K, a 3x3 solve, runs from the initial state, and the
 * comparison of one Newton iteration per step with a hand-written
 * linearised step.  Header only, included after <criterion/criterion.h>. */
#ifndef CL_TESTS_KINSOL_TEST_H
#define CL_TESTS_KINSOL_TEST_H

#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"
#include "semitest.h"

/* f, df/dx (K) and df/dv (D) of the one free particle at (t, x, v). */
static inline void kt_linearise(const s2_problem *p, double t,
                                const double *x, const double *v,
                                double f[3], double K[9], double D[9])
{
    const cl_system *sys = p->sys;
    size_t nval = 9 * sys->pattern->nnzb, d = sys->pattern->diag[0];
    double *dfdx = calloc(nval, sizeof *dfdx);
    double *dfdv = calloc(nval, sizeof *dfdv);
    cr_assert(dfdx && dfdv && sys->pattern->nb == 1);
    cr_assert_eq(sys->jacobian(sys->data, t, x, v, NULL, dfdx, dfdv), CL_OK);
    cr_assert_eq(sys->force(sys->data, t, x, v, f), CL_OK);
    memcpy(K, dfdx + 9 * d, 9 * sizeof *K);
    memcpy(D, dfdv + 9 * d, 9 * sizeof *D);
    free(dfdx);
    free(dfdv);
}

/* A = M - a D - b K for the one free particle (3x3, row-major). */
static inline void kt_newton_matrix(const s2_problem *p, double a, double b,
                                    const double K[9], const double D[9],
                                    double A[9])
{
    for (int r = 0; r < 9; r++)
        A[r] = -a * D[r] - b * K[r];
    for (int r = 0; r < 3; r++)
        A[4 * r] += p->sys->mass[r];
}

static inline double kt_det3(const double A[9])
{
    return A[0] * (A[4] * A[8] - A[5] * A[7]) -
           A[1] * (A[3] * A[8] - A[5] * A[6]) +
           A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* Solve A y = b (3x3, row-major) by Cramer's rule. */
static inline void kt_solve3(const double A[9], const double b[3],
                             double y[3])
{
    double det = kt_det3(A);
    cr_assert(fabs(det) > 0);
    for (int c = 0; c < 3; c++) {
        double B[9];
        memcpy(B, A, sizeof B);
        for (int r = 0; r < 3; r++)
            B[3 * r + c] = b[r];
        y[c] = kt_det3(B) / det;
    }
}

/* Max |a_i - b_i| over 3 entries. */
static inline double kt_diff3(const double *a, const double *b)
{
    double d = 0;
    for (int r = 0; r < 3; r++)
        d = fmax(d, fabs(a[r] - b[r]));
    return d;
}

/* Create `name` on p's system from its initial state. */
static inline void *kt_create(const char *name, const s2_problem *p,
                              const cl_integrator_opts *o)
{
    const cl_integrator_type *it = cl_integrator_find(name);
    cr_assert_not_null(it, "%s not registered", name);
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(p->sys, o, 0.0, p->x0, p->v0, &st, &err), CL_OK,
                 "%s: %s", name, err.msg);
    return st;
}

/* Run `name` from p's initial state to T into x, v; statistics to *s. */
static inline void kt_run(const char *name, const s2_problem *p,
                          const cl_integrator_opts *o, double T, double *x,
                          double *v, cl_stats *s)
{
    const cl_integrator_type *it = cl_integrator_find(name);
    void *st = kt_create(name, p, o);
    cl_error err = {0};
    cr_assert_eq(it->advance(st, T, x, v, &err), CL_OK, "%s: %s", name,
                 err.msg);
    it->stats(st, s);
    it->free(st);
}

/* Observed order of `name` on spring2 at T = 1, dt0 halved 4 times, with
 * the pin at rest and moving at 0.5 m/s (then f depends on t, which tests
 * the evaluation time te): both within 0.2 of `order`. */
static inline void kt_check_order(const char *name, double order, double dt0)
{
    const char *const moving[] = {"pins.velocity=0.5,0,0", NULL};
    double q0 = st_order(name, "klu", NULL, 0.0, dt0, 5, 1.0);
    double q1 = st_order(name, "klu", moving, 0.5, dt0, 5, 1.0);
    cr_assert(fabs(q0 - order) < 0.2 && fabs(q1 - order) < 0.2,
              "%s: observed orders %g, %g (moving pin), expected %g", name,
              q0, q1, order);
}

/* A hand-written linearised step: updates x, v and the previous state xp,
 * vp in place; k is the step index from 0, t its start. */
typedef void (*kt_step_fn)(const s2_problem *p, double t, double h,
                           double *x, double *v, double *xp, double *vp,
                           int k);

/* On spring2 made nonlinear (off-axis velocity) and damped (Choi-Ko pair
 * damping: f affine in v, df/dx independent of v), take 6 steps of 0.05
 * with `name` at newton_maxit = 1 and, alongside, with `ref`: the states
 * must agree to round-off, and differ from the converged method's. */
static inline void kt_check_one_iteration(const char *name, kt_step_fn ref)
{
    const char *const sets[] = {"init.velocity=1,0.8,0", "damping.kd=0.3",
                                NULL};
    s2_problem p;
    st_load(&p, sets);
    const cl_integrator_type *it = cl_integrator_find(name);
    const double h = 0.05;
    cl_integrator_opts one = {.dt = h, .newton_maxit = 1};
    cl_integrator_opts conv = {.dt = h, .newton_tol = 1e-13};
    void *s1 = kt_create(name, &p, &one), *sc = kt_create(name, &p, &conv);
    double x[3], v[3], xp[3], vp[3], x1[3], v1[3], xc[3], vc[3];
    double d = 0, dconv = 0, f[3], K[9], D[9];
    kt_linearise(&p, 0.0, p.x0, p.v0, f, K, D);
    cr_assert(D[0] != 0.0, "damping acts on the free particle");
    memcpy(x, p.x0, sizeof x);
    memcpy(v, p.v0, sizeof v);
    for (int k = 0; k < 6; k++) {
        cl_error err = {0};
        ref(&p, k * h, h, x, v, xp, vp, k);
        cr_assert_eq(it->advance(s1, (k + 1) * h, x1, v1, &err), CL_OK,
                     "%s", err.msg);
        cr_assert_eq(it->advance(sc, (k + 1) * h, xc, vc, &err), CL_OK,
                     "%s", err.msg);
        d = fmax(d, fmax(kt_diff3(x, x1), kt_diff3(v, v1)));
        dconv = fmax(dconv, fmax(kt_diff3(xc, x1), kt_diff3(vc, v1)));
    }
    cl_stats s;
    it->stats(s1, &s);
    cr_assert_eq(s.nonlin_iters, 6);
    it->free(s1);
    it->free(sc);
    s2_free(&p);
    cr_log_info("%s, 1 Newton iteration vs hand-written linearised step: "
                "max diff %.3e; vs converged: %.3e", name, d, dconv);
    cr_assert_lt(d, 1e-13);
    cr_assert_gt(dconv, 1e-5, "the problem is nonlinear");
}

#endif
