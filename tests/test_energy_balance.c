/* Energy balance (analysis/energy_balance.c) on spring2 (one particle of
 * mass 1 on a spring ks = 100 to a pinned one, w = 10, E(0) = 1/2 J of
 * kinetic energy).  Undamped: backward Euler loses energy (a factor
 * 1/(1 + h^2 w^2) per step), forward Euler gains it (1 + h^2 w^2), velocity
 * Verlet keeps it to O(h^2).  Damped (pair damping kd = 2): a tight
 * cvode-bdf run closes the balance E(T) - E(0) - W(T) while W takes most
 * of the energy, which checks the dissipated power and its quadrature. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "analysis/energy_balance.h"
#include "io/config.h"
#include "problem.h"

typedef struct {
    pr_problem p;
    cl_ebal_result r;
} eb_case;

static void eb_open(eb_case *c, const char *problem, const char *set)
{
    memset(c, 0, sizeof *c);
    pr_load(&c->p, problem, set, NULL);
}

static void eb_close(eb_case *c)
{
    cl_ebal_free(&c->r);
    pr_free(&c->p);
}

/* Run `name` (dt = h, or rtol = h, atol = h / 100) to T with `samples`. */
static const cl_ebal_result *eb_run(eb_case *c, const char *name, double h,
                                    double T, long samples)
{
    const cl_integrator_type *type = cl_integrator_find(name);
    cl_integrator_opts io = {.dt = type->fixed_step ? h : 0.0, .rtol = h,
                             .atol = h / 100};
    cl_error err = {0};
    cl_ebal_free(&c->r);
    cr_assert_eq(cl_ebal_run(c->p.m, type, &io, T, samples, 10.0, &c->r, &err),
                 CL_OK, "%s: %s", name, err.msg);
    cr_assert_eq(c->r.rc, CL_OK, "%s: %s", name, c->r.why.msg);
    const cl_ebal_sample *e = &c->r.s[c->r.n - 1];
    cr_log_info("%s: E(0) %.6g E(T) %.6g W %.6g B %.3e max|B| %.3e S %.3g",
                name, c->r.s[0].total, e->total, e->dissipated, e->balance,
                c->r.balance_max, c->r.scale);
    return &c->r;
}

Test(energy_balance, undamped_spring_gain_and_loss)
{
    eb_case c;
    eb_open(&c, "problems/spring2.ini", NULL);
    const double E0 = 0.5, q = 1 + 0.01 * 0.01 * 100; /* 1 + h^2 w^2 */
    const cl_ebal_result *r = eb_run(&c, "semi-be", 0.01, 1.0, 100);
    const cl_ebal_sample *e = &r->s[r->n - 1];
    cr_assert_eq(r->n, 101);
    cr_assert_float_eq(r->s[0].total, E0, 1e-15);
    cr_assert_eq(e->dissipated, 0.0);
    /* BE on x'' = -w^2 x: the energy norm shrinks by 1/q each step */
    cr_assert_float_eq(e->total, E0 * pow(q, -100), 1e-9);
    cr_assert_float_eq(e->balance, e->total - E0, 1e-15);
    r = eb_run(&c, "fe", 0.01, 1.0, 100);
    cr_assert_float_eq(r->s[r->n - 1].total, E0 * pow(q, 100), 1e-9);
    /* velocity Verlet keeps v^2/2 + w^2 x^2 (1 - h^2 w^2 / 4) / 2 (its
     * modified energy on x'' = -w^2 x), E0 at the start from x = 0: at the
     * turning points E exceeds it by h^2 w^2 / 4 of the potential, about
     * E0 h^2 w^2 / 4; the samples (63 a period) catch it within 1 % */
    r = eb_run(&c, "velocity-verlet", 0.01, 1.0, 100);
    cr_assert_float_eq(r->balance_max, E0 * (q - 1) / 4,
                       0.01 * E0 * (q - 1) / 4, "%g", r->balance_max);
    eb_close(&c);
}

Test(energy_balance, damped_spring_balance_closes)
{
    eb_case c;
    eb_open(&c, "problems/spring2.ini", "damping.kd=2");
    const cl_ebal_result *r = eb_run(&c, "cvode-bdf", 1e-10, 1.0, 2000);
    const cl_ebal_sample *e = &r->s[r->n - 1];
    cr_assert_eq(r->n, 2001);
    cr_assert_lt(e->dissipated, -0.5 * 0.5, "W = %g", e->dissipated);
    /* measured 4.1e-7 J: the trapezoidal W over 2000 samples */
    cr_assert_lt(r->balance_max, 2e-6 * r->scale, "%g", r->balance_max);
    eb_close(&c);
}

/* The scale S is the energy that moved (kinetic, potential change, W):
 * one motion with the potential's zero 1000 J lower gives the same S and
 * B, where |E(0)| in S would have divided max |B| by 1000. */
static double scale_of(double offset, double *bmax)
{
    const double kin[] = {0.0, 0.3, 0.1}, pot[] = {0.0, -0.4, -0.2},
                 pw[] = {0.0, -0.2, -0.6};
    cl_ebal_sample s[3];
    cl_ebal_result r = {.s = s};
    double trapz = 0.0;
    for (int k = 0; k < 3; k++) {
        cl_energy e = {.kinetic = kin[k], .potential = pot[k] + offset,
                       .total = kin[k] + pot[k] + offset,
                       .power_diss = pw[k]};
        cr_assert_eq(cl_ebal_add(&r, 3, &trapz, 0.5 * k, &e), CL_OK);
    }
    *bmax = r.balance_max;
    return r.scale;
}

Test(energy_balance, scale_is_the_energy_that_moved)
{
    double b0, b1;
    double s0 = scale_of(0.0, &b0), s1 = scale_of(1000.0, &b1);
    /* W(1) = -0.05, W(2) = -0.25: S = max(0.3, 0.4, 0.25) */
    cr_assert_float_eq(s0, 0.4, 1e-15);
    cr_assert_float_eq(s1, s0, 1e-12);
    cr_assert_float_eq(b1, b0, 1e-12);
    cr_assert_float_eq(b0, 0.15, 1e-15); /* B(2) = -0.1 + 0.25 */
}

/* A fixed-step method is sampled at most once per step: 10^8 samples
 * asked of 10 steps are 11 (and the storage is sized for 11). */
Test(energy_balance, samples_at_most_every_step)
{
    eb_case c;
    eb_open(&c, "problems/spring2.ini", NULL);
    const cl_ebal_result *r = eb_run(&c, "rk4", 0.1, 1.0, 1000);
    cr_assert_eq(r->n, 11);
    for (size_t k = 0; k < r->n; k++)
        cr_assert_float_eq(r->s[k].t, 0.1 * (double)k, 1e-12);
    r = eb_run(&c, "rk4", 0.1, 1.0, 100000000);
    cr_assert_eq(r->n, 11);
    eb_close(&c);
}

Test(energy_balance, refused_requests)
{
    eb_case c;
    eb_open(&c, "problems/spring2.ini", NULL);
    cl_integrator_opts io = {.dt = 0.3};
    cl_error err = {0};
    cr_assert_eq(cl_ebal_run(c.p.m, cl_integrator_find("rk4"), &io, 1.0, 10,
                             10.0, &c.r, &err),
                 CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "whole number"), "%s", err.msg);
    eb_close(&c);
    eb_open(&c, "problems/verlet-scene3.ini", NULL);
    io.dt = 1e-3;
    cr_assert_eq(cl_ebal_run(c.p.m, cl_integrator_find("verlet"), &io, 0.1,
                             10, 10.0, &c.r, &err),
                 CL_EUNSUPPORTED);
    eb_close(&c);
}
