/* The contact study (analysis/contact_study.c) on problems/particle-floor:
 * a particle of m = 0.1 kg under g = 9.81 m/s^2, starting at rest
 * D = 1e-4 m deep in a floor.
 *  - penalty k = 1e4 N/m: the rest depth is m g / k = 9.81e-5 m, which
 *    backward Euler (semi-be) settles to; in contact the particle is a
 *    spring w = sqrt(k/m) = 316.2 rad/s, so symplectic Euler is stable
 *    for dt < 2/w = 6.325e-3 s (it never leaves the floor: it starts
 *    1.9 um from rest);
 *  - projection with the inward velocity removed: every step starts at
 *    rest on the surface and sinks g dt^2 before it is projected back (the
 *    first from D), so the worst penetration is D + g dt^2 and the end
 *    state lies on the surface. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "analysis/contact_study.h"
#include "problem.h"

#define CS_M 0.1
#define CS_G 9.81
#define CS_K 1e4
#define CS_D 1e-4

static cl_stab_opts cs_opts(double t_end, long checks)
{
    return (cl_stab_opts){.t_end = t_end, .checks = checks,
                          .max_stretch = 1.05};
}

static cl_cstudy_result cs_study(const char *set, const char *name,
                                 const cl_stab_opts *o, const double *dt,
                                 int ndt)
{
    pr_problem p;
    cl_cstudy_result r;
    cl_error err = {0};
    cl_integrator_opts io = {0};
    pr_load(&p, "problems/particle-floor.ini", set, NULL);
    cr_assert_eq(cl_cstudy_run(p.m, cl_integrator_find(name), &io, o, dt,
                               ndt, &r, &err),
                 CL_OK, "%s: %s", name, err.msg);
    pr_free(&p);
    return r;
}

Test(contact_study, penalty_rest_depth_is_m_g_over_k)
{
    const double dt[] = {1e-2, 1e-3};
    cl_stab_opts o = cs_opts(2.0, 20);
    cl_cstudy_result r = cs_study(NULL, "semi-be", &o, dt, 2);
    cr_assert_eq(r.n, 2);
    for (int k = 0; k < 2; k++) {
        const cl_cstudy_row *w = &r.row[k];
        cr_assert_eq(w->run.rc, CL_OK, "%s", w->run.why.msg);
        cr_assert_eq(w->run.nsteps, lround(2.0 / dt[k]));
        cr_assert_eq(w->run.stats.steps, w->run.nsteps);
        cr_assert_float_eq(w->rest_pen, CS_M * CS_G / CS_K, 1e-12,
                           "dt %g: %.12g", dt[k], w->rest_pen);
        cr_assert_eq(w->rest_contacts, 1);
        /* it starts deeper than it rests, and never deeper than it starts
         * by more than the rest depth's overshoot */
        cr_assert_geq(w->worst_pen, w->rest_pen);
        cr_assert_lt(w->worst_pen, CS_D + 1e-6);
    }
    cr_assert(isnan(r.dt_unstable));
    cr_assert_eq(r.dt_stable, 1e-2);
}

/* Either side of 2/w = 6.325e-3 s, on T = 1.98 s (330 and 300 steps),
 * the stretch tested after every step. */
Test(contact_study, explicit_limit_of_the_contact_spring)
{
    const double dt[] = {6.6e-3, 6e-3};
    cl_stab_opts o = cs_opts(1.98, 100000);
    cl_cstudy_result r = cs_study(NULL, "symplectic-euler", &o, dt, 2);
    cr_assert_eq(r.row[0].run.rc, CL_EBLOWUP, "%s", r.row[0].run.why.msg);
    cr_assert(isnan(r.row[0].rest_pen) && r.row[0].rest_contacts == -1);
    cr_assert_gt(r.row[0].stretch_max, 1.05);
    cr_assert_eq(r.row[1].run.rc, CL_OK, "%s", r.row[1].run.why.msg);
    cr_assert_lt(r.row[1].stretch_max, 1.0 + CS_D);
    cr_assert_float_eq(r.dt_unstable, 6.6e-3, 1e-15);
    cr_assert_float_eq(r.dt_stable, 6e-3, 1e-15);
    cr_assert_lt(r.dt_stable, 2.0 * sqrt(CS_M / CS_K));
    cr_assert_gt(r.dt_unstable, 2.0 * sqrt(CS_M / CS_K));
}

Test(contact_study, projection_sinks_g_dt_squared_per_step)
{
    const double dt[] = {1e-2, 1e-3};
    cl_stab_opts o = cs_opts(2.0, 20);
    cl_cstudy_result r = cs_study("obstacle.floor.response=project",
                                  "symplectic-euler", &o, dt, 2);
    for (int k = 0; k < 2; k++) {
        const cl_cstudy_row *w = &r.row[k];
        cr_assert_eq(w->run.rc, CL_OK, "%s", w->run.why.msg);
        cr_assert_float_eq(w->worst_pen, CS_D + CS_G * dt[k] * dt[k], 1e-12,
                           "dt %g: %.12g", dt[k], w->worst_pen);
        cr_assert_float_eq(w->worst_t, dt[k], 1e-15);
        cr_assert_leq(w->rest_pen, 1e-15);
        cr_assert_eq(w->rest_contacts, 1);
    }
}

static void cs_refused(const char *problem, const char *name, double dt,
                       const char *want)
{
    pr_problem p;
    cl_error err = {0};
    cl_stab_opts o = cs_opts(2.0, 20);
    pr_load(&p, problem, NULL, NULL);
    cr_assert_eq(cl_cstudy_check(p.m, cl_integrator_find(name), &o, &dt, 1,
                                 &err),
                 CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, want), "%s", err.msg);
    pr_free(&p);
}

Test(contact_study, refusals)
{
    cs_refused("problems/particle-floor.ini", "cvode-bdf", 1e-2,
               "error control");
    cs_refused("problems/particle-floor.ini", "semi-be", 3e-2,
               "whole number");
    cs_refused("problems/spring2.ini", "semi-be", 1e-2, "no obstacle");
}
