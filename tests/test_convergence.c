/* Convergence study (analysis/convergence.c) on spring2 (one particle on a
 * linear spring, problems/spring2.ini): the fitted orders of fixed-step
 * methods, the tolerance levels of an adaptive one, a level that blows up
 * (recorded, left out of the fit, later levels still measured), the
 * reference's floor and the refused requests. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/convergence.h"
#include "io/config.h"
#include "problem.h"

typedef struct {
    pr_problem p;
    cl_model *m;
    cl_conv_opts o;
    cl_conv_ref ref;
} cv_case;

/* spring2 with the assignment `set` (or none), reference to T. */
static void cv_open(cv_case *c, const char *set, double T)
{
    cl_error err = {0};
    pr_load(&c->p, "problems/spring2.ini", set, NULL);
    c->m = c->p.m;
    c->o = (cl_conv_opts){.t_end = T, .max_stretch = 10, .ref_rtol = 1e-11,
                          .ref_linsol = ""};
    cr_assert_eq(cl_conv_reference(c->m, &c->o, &c->ref, &err), CL_OK, "%s",
                 err.msg);
}

static void cv_close(cv_case *c)
{
    cl_conv_ref_free(&c->ref);
    pr_free(&c->p);
}

/* The levels of `name` from dt (fixed) or rtol, atol = rtol / 100. */
static cl_conv_result cv_levels(cv_case *c, const char *name, double first,
                                int levels)
{
    const cl_integrator_type *type = cl_integrator_find(name);
    cr_assert_not_null(type, "%s", name);
    cl_integrator_opts io = {.dt = type->fixed_step ? first : 0.0,
                             .rtol = first, .atol = first / 100};
    cl_conv_result r;
    cl_error err = {0};
    cr_assert_eq(cl_convergence(c->m, type, &io, levels, &c->o, &c->ref, &r,
                                &err),
                 CL_OK, "%s: %s", name, err.msg);
    cr_assert_eq(r.nlev, levels);
    for (int k = 0; k < r.nlev; k++)
        cr_log_info("%s %g: err_x %.3e err_v %.3e order %.3f fitted %d",
                    name, r.lev[k].param, r.lev[k].err_x, r.lev[k].err_v,
                    r.lev[k].order, r.lev[k].fitted);
    cr_log_info("%s: slope %.3f (x), %.3f (v) over %d", name, r.slope_x,
                r.slope_v, r.nfit);
    return r;
}

/* The reference is far closer to the closed form x = L + (v0/w) sin(w t)
 * (L = 1, v0 = 1, w = 10) than its floor says. */
Test(convergence, reference_and_floor)
{
    cv_case c;
    cv_open(&c, NULL, 1.0);
    double xe = 1.0 + 0.1 * sin(10.0);
    cr_log_info("reference error %.3e, floor %.3e", fabs(c.ref.x[0] - xe),
                c.ref.err_x);
    cr_assert_lt(fabs(c.ref.x[0] - xe), 1e-9);
    cr_assert_gt(c.ref.err_x, 0.0);
    cr_assert_lt(c.ref.err_x, 1e-8);
    /* v = v0 cos(w t): the velocities are less accurate (measured 5.4e-9
     * m/s against a floor of 3.5e-8) */
    double ve = cos(10.0);
    cr_log_info("velocity error %.3e, floor %.3e", fabs(c.ref.v[0] - ve),
                c.ref.err_v);
    cr_assert_lt(fabs(c.ref.v[0] - ve), c.ref.err_v);
    cr_assert_gt(fabs(c.ref.v[0] - ve), 1e-9);
    cv_close(&c);
}

/* rk4 from dt = 1/75 s: at dt = 1/300 its position error (8.5e-9 m, 4.8
 * floors) enters the position fit, its velocity error (5.9e-8 m/s, 1.7
 * velocity floors, of which 5.4e-9 the reference's) not the velocity one;
 * at 1/600 (2.2e-10 m) neither.  Both orders are rk4's 4. */
Test(convergence, velocity_floor_of_its_own)
{
    cv_case c;
    cv_open(&c, NULL, 1.0);
    cl_conv_result r = cv_levels(&c, "rk4", 1.0 / 75, 4);
    cr_assert(r.lev[2].fitted && !r.lev[2].fitted_v);
    cr_assert(!r.lev[3].fitted && !r.lev[3].fitted_v);
    cr_assert_eq(r.nfit, 3);
    cr_assert_eq(r.nfit_v, 2);
    cr_assert(fabs(r.slope_v - 4.0) < 0.2, "%.3f", r.slope_v);
    cr_assert(fabs(r.slope_x - 4.0) < 0.1, "%.3f", r.slope_x);
    cv_close(&c);
}

/* rk4 from dt = 1e-2: at dt = 2.5e-3 its position error, 2.446e-9 m, is
 * 1.4 floors and 12 % off the closed form's 2.768e-9 (the reference's own
 * error, 3.2e-10 m, is a fifth of the floor): it enters no fit, and the
 * order is 4.04 over the first two levels (4.11 with it; 4.03 from the
 * exact errors of all three). */
Test(convergence, levels_near_the_floor_are_left_out)
{
    cv_case c;
    cv_open(&c, NULL, 1.0);
    cl_conv_result r = cv_levels(&c, "rk4", 1e-2, 4);
    cr_assert(r.lev[2].err_x > c.ref.err_x, "%g", r.lev[2].err_x);
    cr_assert(!r.lev[2].fitted && !r.lev[2].fitted_v);
    cr_assert_eq(r.nfit, 2);
    cr_assert(fabs(r.slope_x - 4.03) < 0.03, "%.3f", r.slope_x);
    cv_close(&c);
}

/* Observed orders of three fixed-step methods (theory: 1, 2, 4;
 * docs/integrators.md 2, 3). */
Test(convergence, fixed_step_orders)
{
    static const struct { const char *name; double order; } m[] = {
        {"fe", 1.0}, {"semi-bdf2", 2.0}, {"rk4", 4.0},
        {"kinsol-midpoint", 2.0}, {"kinsol-galpha", 2.0}};
    cv_case c;
    cv_open(&c, NULL, 1.0);
    for (size_t i = 0; i < sizeof m / sizeof m[0]; i++) {
        cl_conv_result r = cv_levels(&c, m[i].name, 1e-2, 4);
        cr_assert(r.fixed);
        for (int k = 0; k < r.nlev; k++) {
            cr_assert_eq(r.lev[k].param, ldexp(1e-2, -k));
            cr_assert_eq(r.lev[k].stats.steps, 100L << k);
        }
        cr_assert(isnan(r.lev[0].order));
        cr_assert_geq(r.nfit, 2, "%s", m[i].name);
        cr_expect(fabs(r.slope_x - m[i].order) < 0.2, "%s: %.3f", m[i].name,
                  r.slope_x);
    }
    cv_close(&c);
}

/* rtol levels of cvode-bdf: decades, each exactly the double of the
 * decimal printed (1e-4 * 10^-2 is 1.0000000000000002e-06, not the
 * 1e-06 the table shows and a run given it would use), errors falling
 * from the first to the last level. */
Test(convergence, adaptive_levels_are_tolerances)
{
    static const double printed[] = {1e-4, 1e-5, 1e-6, 1e-7};
    cv_case c;
    cv_open(&c, NULL, 1.0);
    cl_conv_result r = cv_levels(&c, "cvode-bdf", 1e-4, 4);
    cr_assert(!r.fixed);
    cr_assert_neq(1e-4 * pow(10.0, -2), 1e-6);
    for (int k = 0; k < r.nlev; k++)
        cr_assert_eq(r.lev[k].param, printed[k], "level %d: %.17g", k,
                     r.lev[k].param);
    /* tolerance proportionality: the error falls about as the tolerance
     * (measured: 478 times over three decades, slope 0.84) */
    cr_assert_lt(r.lev[3].err_x, r.lev[0].err_x / 100);
    cr_assert(r.slope_x > 0.6 && r.slope_x < 1.1, "slope %g", r.slope_x);
    cv_close(&c);
}

/* ks = 1e4 (w = 100): symplectic Euler is unstable for dt w > 2.  At
 * dt = 0.04 it overflows over 1000 steps; at dt = 0.02 (dt w = 2, a double
 * eigenvalue -1) it grows linearly and ends finite but stretched far
 * beyond max_stretch; dt = 0.01 is stable. */
Test(convergence, blown_up_level_is_recorded_and_skipped)
{
    cv_case c;
    cv_open(&c, "type1.ks=1e4", 40.0);
    cl_conv_result r = cv_levels(&c, "symplectic-euler", 0.04, 3);
    cr_assert_eq(r.lev[0].rc, CL_EBLOWUP, "%s", r.lev[0].why.msg);
    cr_assert(isnan(r.lev[0].err_x) && !r.lev[0].fitted);
    cr_assert_eq(r.lev[1].rc, CL_EBLOWUP, "%s", r.lev[1].why.msg);
    cr_assert_not_null(strstr(r.lev[1].why.msg, "max stretch"), "%s",
                       r.lev[1].why.msg);
    cr_assert(isnan(r.lev[1].order) && isnan(r.lev[2].order));
    cr_assert_eq(r.lev[2].rc, CL_OK, "%s", r.lev[2].why.msg);
    /* the surviving level's error, deterministic (3.165e-3 measured) */
    cr_assert_float_eq(r.lev[2].err_x, 3.165e-3, 0.02 * 3.165e-3, "%g",
                       r.lev[2].err_x);
    cv_close(&c);
}

static cl_status cv_request(cv_case *c, const char *name, double dt,
                            int levels, cl_error *err)
{
    cl_integrator_opts io = {.dt = dt, .rtol = 1e-6, .atol = 1e-8};
    cl_conv_result r;
    return cl_convergence(c->m, cl_integrator_find(name), &io, levels, &c->o,
                          &c->ref, &r, err);
}

Test(convergence, refused_requests)
{
    cv_case c;
    cv_open(&c, NULL, 1.0);
    cl_error err = {0};
    cr_assert_eq(cv_request(&c, "rk4", 1e-2, 1, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "levels"), "%s", err.msg);
    cr_assert_eq(cv_request(&c, "rk4", 0.3, 3, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "whole number"), "%s", err.msg);
    cr_assert_eq(cv_request(&c, "cvode-bdf", 0, 12, &err), CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "1e-15"), "%s", err.msg);
    cl_conv_ref bad;
    c.o.ref_rtol = 1e-3;
    cr_assert_eq(cl_conv_reference(c.m, &c.o, &bad, &err), CL_EINVAL);
    cv_close(&c);
}

/* Tearing changes the model for good: no repeated runs. */
Test(convergence, tearing_model_refused)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cr_assert_eq(cl_config_load(cfg, "problems/verlet-scene3.ini", &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    cl_conv_opts o = {.t_end = 0.1, .max_stretch = 10, .ref_rtol = 1e-8,
                      .ref_linsol = ""};
    cl_conv_ref ref;
    cr_assert_eq(cl_conv_reference(m, &o, &ref, &err), CL_EUNSUPPORTED);
    cr_assert_not_null(strstr(err.msg, "tear"), "%s", err.msg);
    cl_model_free(m);
    cl_config_free(cfg);
}

/* Work-precision: the cheapest level that reaches a target error. */
Test(convergence, cheapest_level_for_a_target)
{
    cv_case c;
    cv_open(&c, NULL, 1.0);
    cl_conv_result r = cv_levels(&c, "rk4", 1e-2, 3);
    double e1 = r.lev[1].err_x;
    cr_assert_eq(cl_conv_cheapest(&r, e1), fmin(r.lev[1].stats.cpu,
                                                r.lev[2].stats.cpu));
    cr_assert(isnan(cl_conv_cheapest(&r, r.lev[2].err_x / 2)));
    cr_assert_eq(cl_conv_cheapest(&r, 1.0),
                 fmin(r.lev[0].stats.cpu,
                      fmin(r.lev[1].stats.cpu, r.lev[2].stats.cpu)));
    cv_close(&c);
}
