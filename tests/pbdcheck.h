/* Shared helpers of the tearing and position-based tests
 * (tests/test_tearing.c, tests/test_pbd.c, tests/test_verlet_pbd.c): the
 * pulled cloth, a run of an integrator over many outputs with the state
 * checked at each, and the constraint violation of level pairs.  Header
 * only (static inline), included after "fdcheck.h". */
#ifndef CL_TESTS_PBDCHECK_H
#define CL_TESTS_PBDCHECK_H

#include "fdcheck.h"
#include "integrators/integrator.h"

/* hang's cloth at n = 8 whose pins (0,0) and (0,n-1) move apart along z
 * at 2 m/s each (settings to combine with a model's own). */
#define PB_PULL                                                           \
    "cloth.n=8", "pins.at=0,0", "pins.velocity=0,0,-2", "pins2.at=0,-1", \
        "pins2.velocity=0,0,2"

/* The free state of a model and its size. */
typedef struct {
    cl_model *m;
    const cl_system *sys;
    size_t n;     /* sys->n */
    double *x, *v;
    cl_stats st;  /* statistics at the end of pb_integrate */
} pb_case;

static inline pb_case pb_open(cl_model *m)
{
    pb_case c = {.m = m, .sys = cl_model_system(m)};
    c.n = c.sys->n;
    c.x = fd_vec(c.n);
    c.v = fd_vec(c.n);
    cr_assert_eq(cl_model_initial_state(m, c.x, c.v), CL_OK);
    return c;
}

static inline void pb_close(pb_case *c)
{
    free(c->x);
    free(c->v);
    cl_model_free(c->m);
}

/* Called after every output of pb_integrate (state in c->x, c->v). */
typedef void (*pb_check)(pb_case *c, double t, void *ctx);

/* Integrate with `name` from t = 0 to T in nout equal advances; every
 * advance must succeed with a finite state and the step count never
 * decreases (counters survive a solver restart after tearing); then
 * check(c, t, ctx) if check is not NULL. */
static inline void pb_integrate(pb_case *c, const char *name,
                                const cl_integrator_opts *o, double T,
                                int nout, pb_check check, void *ctx)
{
    const cl_integrator_type *it = cl_integrator_find(name);
    cr_assert_not_null(it, "%s not registered", name);
    void *st = NULL;
    cl_error err = {0};
    long steps = 0;
    cr_assert_eq(it->create(c->sys, o, 0.0, c->x, c->v, &st, &err), CL_OK,
                 "%s: %s", name, err.msg);
    for (int k = 1; k <= nout; k++) {
        double t = T * k / nout;
        cr_assert_eq(it->advance(st, t, c->x, c->v, &err), CL_OK,
                     "%s at t = %g: %s", name, t, err.msg);
        for (size_t i = 0; i < c->n; i++)
            cr_assert(isfinite(c->x[i]) && isfinite(c->v[i]),
                      "%s: state not finite at t = %g", name, t);
        it->stats(st, &c->st);
        cr_assert_geq(c->st.steps, steps, "%s: step count went back", name);
        steps = c->st.steps;
        if (check)
            check(c, t, ctx);
    }
    it->free(st);
}

/* Full-particle positions of the free state x at time t into xf. */
static inline void pb_full(const pb_case *c, double t, const double *x,
                           double *xf)
{
    cl_cloth_scatter(cl_model_cloth(c->m), t, x, NULL, xf, NULL);
}

/* max |d - L| / L over the pairs of set at full positions xf, skipping
 * torn connections. */
static inline double pb_violation(const cl_model *m, const cl_pairset *set,
                                  const double *xf)
{
    double worst = 0.0;
    for (size_t k = 0; k < set->n; k++) {
        const cl_pair *p = &set->pair[k];
        if (cl_model_is_broken(m, p->a, p->b))
            continue;
        double e = fabs(cl_dist(xf + 3 * p->a, xf + 3 * p->b) - p->rest) /
                   p->rest;
        worst = e > worst || e != e ? e : worst;
    }
    return worst;
}

#endif
