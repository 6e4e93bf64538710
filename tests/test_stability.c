/* Stability limits (analysis/stability.c) on spring2 stiffened to ks = 1e4
 * (one particle of mass 1 on a spring to a pinned one: w = 100 rad/s,
 * amplitude 0.01 m).  Linear stability theory for x'' = -w^2 x: symplectic
 * Euler and velocity Verlet are stable for dt w < 2, RK4 for
 * dt w < 2 sqrt(2).  The stretch is tested after every step against
 * max_stretch = 1.5: an unstable run grows from 0.01 m to 0.5 m within the
 * horizon T = 4 s unless its step is within about 1% of the limit.  (A
 * looser test would miss it: beyond |x - L| = L the particle swings through
 * the pin into the mirror well of the spring's potential k (|x| - L)^2 / 2,
 * where the energy saturates with d/L around 3.)  Backward Euler is stable
 * at every step. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/stability.h"
#include "io/config.h"
#include "problem.h"

#define ST_W 100.0

typedef pr_problem st_case;

static void st_open(st_case *c, const char *problem, const char *set)
{
    pr_load(c, problem, set, NULL);
}

static void st_close(st_case *c)
{
    pr_free(c);
}

static const cl_stab_opts st_opts = {.t_end = 4.0, .dt_max = 0.1,
                                     .dt_min = 1e-5, .rel = 0.01,
                                     .checks = 1000000, .max_stretch = 1.5};

static cl_stab_result st_search(st_case *c, const char *name,
                                const cl_stab_opts *o)
{
    cl_stab_result r;
    cl_error err = {0};
    cl_integrator_opts io = {0};
    cr_assert_eq(cl_stability(c->m, cl_integrator_find(name), &io, o, &r,
                              &err),
                 CL_OK, "%s: %s", name, err.msg);
    cr_log_info("%s: stable %.6g, unstable %.6g, %d runs: %s", name,
                r.dt_stable, r.dt_unstable, r.ntrial,
                r.failed >= 0 ? r.trial[r.failed].why.msg : "-");
    return r;
}

/* The bracket holds the theoretical limit to within the horizon's
 * resolution, and every run of the search is on record. */
static void expect_limit(const char *name, double limit)
{
    st_case c;
    st_open(&c, "problems/spring2.ini", "type1.ks=1e4");
    cl_stab_result r = st_search(&c, name, &st_opts);
    cr_assert_geq(r.failed, 0);
    cr_assert_eq(r.trial[r.failed].rc, CL_EBLOWUP, "%s",
                 r.trial[r.failed].why.msg);
    /* a step just beyond the limit grows too slowly to show in 4 s */
    cr_assert_leq(r.dt_stable, limit * 1.01, "%s: %g", name, r.dt_stable);
    cr_assert_gt(r.dt_stable, limit * 0.97, "%s: %g", name, r.dt_stable);
    cr_assert_geq(r.dt_unstable, limit, "%s: %g", name, r.dt_unstable);
    cr_assert_gt(r.dt_unstable, r.dt_stable);
    cr_assert_lt(r.dt_unstable / r.dt_stable, 1.03, "%s", name);
    for (int k = 0; k < r.ntrial; k++) {
        const cl_stab_trial *t = &r.trial[k];
        cr_assert_float_eq(t->dt * (double)t->nsteps, 4.0, 1e-12);
        if (t->rc == CL_OK) /* a stable run took all its steps */
            cr_assert_eq(t->stats.steps, t->nsteps);
        else
            cr_assert_lt(t->stats.steps, t->nsteps);
    }
    st_close(&c);
}

Test(stability, symplectic_euler_limit_is_two_over_w)
{
    expect_limit("symplectic-euler", 2 / ST_W);
}

Test(stability, velocity_verlet_limit_is_two_over_w)
{
    expect_limit("velocity-verlet", 2 / ST_W);
}

Test(stability, rk4_limit_is_two_sqrt2_over_w)
{
    expect_limit("rk4", 2 * sqrt(2.0) / ST_W);
}

Test(stability, backward_euler_stable_at_dt_max)
{
    st_case c;
    st_open(&c, "problems/spring2.ini", "type1.ks=1e4");
    cl_stab_result r = st_search(&c, "semi-be", &st_opts);
    cr_assert_eq(r.ntrial, 2); /* dt_max, confirmed by dt_max/2 */
    cr_assert_float_eq(r.trial[1].dt, 0.05, 1e-15);
    cr_assert_float_eq(r.dt_stable, 0.1, 1e-15);
    cr_assert(isnan(r.dt_unstable));
    cr_assert_eq(r.failed, -1);
    st_close(&c);
}

/* Stopped at dt_min: no stable step, the smallest unstable one reported. */
Test(stability, no_stable_step_above_dt_min)
{
    st_case c;
    st_open(&c, "problems/spring2.ini", "type1.ks=1e4");
    cl_stab_opts o = st_opts;
    o.dt_min = 0.03;
    cl_stab_result r = st_search(&c, "symplectic-euler", &o);
    cr_assert(isnan(r.dt_stable));
    /* halving from dt_max = 0.1: 0.1 and 0.05 unstable, 0.025 < dt_min */
    cr_assert_eq(r.ntrial, 2);
    cr_assert_eq(r.dt_unstable, 0.05);
    cr_assert_eq(r.failed, r.ntrial - 1);
    st_close(&c);
}

Test(stability, refused_requests)
{
    st_case c;
    st_open(&c, "problems/spring2.ini", NULL);
    cl_stab_result r;
    cl_error err = {0};
    cl_integrator_opts io = {0};
    cr_assert_eq(cl_stability(c.m, cl_integrator_find("cvode-bdf"), &io,
                              &st_opts, &r, &err),
                 CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "error control"), "%s", err.msg);
    cl_stab_opts o = st_opts;
    o.dt_max = 1.0; /* T/4: too few steps */
    cr_assert_eq(cl_stability(c.m, cl_integrator_find("rk4"), &io, &o, &r,
                              &err),
                 CL_EINVAL);
    cr_assert_not_null(strstr(err.msg, "t_end/10"), "%s", err.msg);
    st_close(&c);
    st_open(&c, "problems/verlet-scene3.ini", NULL);
    o = st_opts;
    cr_assert_eq(cl_stability(c.m, cl_integrator_find("verlet"), &io, &o, &r,
                              &err),
                 CL_EUNSUPPORTED);
    st_close(&c);
}
