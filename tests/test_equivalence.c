/* The hand-written linearly implicit methods are the first Newton iterate of
 * the fully implicit ones (docs/integrators.md 3, 4):
 *   semi-be   == kinsol-be   with one Newton iteration,
 *   semi-bdf2 == kinsol-bdf2 with one Newton iteration (Jiao, eq. 15),
 * from the predictor that evaluates the force at x_n.  Exact on a linear
 * model (damped coupled oscillators), and on the Choi-Ko hang cloth too,
 * whose force is affine in v with df/dx independent of v. */
#include <criterion/criterion.h>

#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"
#include "testsys.h"

/* Run `name` for nsteps steps of dt with one Newton iteration (where it
 * applies) and the given linear solver; final state into x, v. */
static void run(const char *name, const cl_system *sys, const char *linsol,
                const double *x0, const double *v0, double dt, long nsteps,
                double *x, double *v)
{
    const cl_integrator_type *it = cl_integrator_find(name);
    cr_assert_not_null(it, "%s is not registered", name);
    cl_integrator_opts o = {.dt = dt, .linsol = linsol, .newton_maxit = 1};
    cl_error err = {0};
    void *st = NULL;
    cr_assert_eq(it->create(sys, &o, 0.0, x0, v0, &st, &err), CL_OK, "%s: %s",
                 name, err.msg);
    cr_assert_eq(it->advance(st, (double)nsteps * dt, x, v, &err), CL_OK,
                 "%s: %s", name, err.msg);
    it->free(st);
}

/* Max difference of the final states of two methods, relative to the
 * size of the state. */
static double compare(const char *a, const char *b, const cl_system *sys,
                      const char *linsol, const double *x0, const double *v0,
                      double dt, long nsteps)
{
    size_t n = sys->n;
    double *xa = malloc(n * sizeof *xa), *va = malloc(n * sizeof *va);
    double *xb = malloc(n * sizeof *xb), *vb = malloc(n * sizeof *vb);
    cr_assert(xa && va && xb && vb);
    run(a, sys, linsol, x0, v0, dt, nsteps, xa, va);
    run(b, sys, linsol, x0, v0, dt, nsteps, xb, vb);
    double scale = 1.0;
    for (size_t i = 0; i < n; i++)
        scale = fmax(scale, fmax(fabs(xa[i]), fabs(va[i])));
    double d = fmax(ts_maxdiff(xa, xb, n), ts_maxdiff(va, vb, n)) / scale;
    cr_log_info("%s vs %s (%s, dt %g, %ld steps): %.3e", a, b,
                linsol ? linsol : "klu", dt, nsteps, d);
    free(xa);
    free(va);
    free(xb);
    free(vb);
    return d;
}

Test(equivalence, linear_model_one_newton_iteration)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 1.5, 4.0, 30.0), 0);
    for (size_t i = 0; i < ts.n; i++)
        ts.c[i] = 0.2 + 0.1 * (double)i; /* damping: df/dv != 0 */
    double x0[6], v0[6];
    ts_initial(&ts, x0, v0);
    /* Round-off for the direct solver; PCG stops at its tolerance (1e-10
     * relative residual), which bounds the difference instead. */
    static const char *const linsols[] = {"klu", "pcg"};
    static const double tol[] = {1e-12, 1e-8};
    for (int k = 0; k < 2; k++) {
        cr_assert_lt(compare("semi-be", "kinsol-be", &ts.sys, linsols[k], x0,
                             v0, 0.01, 200),
                     tol[k]);
        cr_assert_lt(compare("semi-bdf2", "kinsol-bdf2", &ts.sys, linsols[k],
                             x0, v0, 0.01, 200),
                     tol[k]);
    }
    ts_free(&ts);
}

Test(equivalence, choiko_hang_one_newton_iteration)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cr_assert_eq(cl_config_load(cfg, "problems/hang.ini", &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_config_set(cfg, "cloth.n=8", &err), CL_OK);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    const cl_system *sys = cl_model_system(m);
    double *x0 = malloc(sys->n * sizeof *x0), *v0 = malloc(sys->n * sizeof *v0);
    cl_model_initial_state(m, x0, v0);
    /* the same linear system solved twice: round-off apart (8.5e-15 and
     * 6.3e-14 measured over 30 steps) */
    cr_assert_lt(compare("semi-be", "kinsol-be", sys, NULL, x0, v0, 0.01, 30),
                 1e-12);
    cr_assert_lt(compare("semi-bdf2", "kinsol-bdf2", sys, NULL, x0, v0, 0.01,
                         30),
                 1e-12);
    free(x0);
    free(v0);
    cl_model_free(m);
    cl_config_free(cfg);
}
