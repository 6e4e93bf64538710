/* Shared helpers of the mass-spring tests (tests/test_springs.c,
 * tests/test_spring_damping.c): models built from a base list of settings
 * plus extras, a test case (model, state and work vectors, random stream),
 * and the spring network of a grid under given [springs] settings.
 * Header only (static inline), included after "fdcheck.h". */
#ifndef CL_TESTS_SPRINGCHECK_H
#define CL_TESTS_SPRINGCHECK_H

#include "fdcheck.h"
#include "forces/springs.h"

/* No Choi-Ko terms, no gravity, no pins: the mass-spring terms alone. */
#define SC_BASE                                                            \
    FD_SETS("type1.enabled=false", "type2.enabled=false", "damping.kd=0", \
            "gravity.g=0,0,0", "pins.at=")

/* Model from the settings of `a` followed by those of `b` (either NULL). */
static inline cl_model *sc_model(const char *const *a, const char *const *b)
{
    const char *sets[40];
    size_t n = 0;
    for (const char *const *l = a; l && *l; l++, n++) {
        cr_assert_lt(n, 39u);
        sets[n] = *l;
    }
    for (const char *const *l = b; l && *l; l++, n++) {
        cr_assert_lt(n, 39u);
        sets[n] = *l;
    }
    sets[n] = NULL;
    return fd_model(sets);
}

typedef struct {
    cl_model *m;
    size_t n;             /* 3 * particles */
    double h;             /* smaller positive rest spacing */
    double *x, *v, *f, *g; /* full-particle vectors, zeroed */
    fd_rng r;
} sc_case;

static inline sc_case sc_open(const char *const *extra, uint64_t seed)
{
    sc_case c;
    c.m = sc_model(SC_BASE, extra);
    c.n = fd_n(c.m);
    const cl_cloth *cl = cl_model_cloth(c.m);
    c.h = cl->hu > 0 && (cl->hu < cl->hv || !(cl->hv > 0)) ? cl->hu : cl->hv;
    c.x = fd_vec(c.n);
    c.v = fd_vec(c.n);
    c.f = fd_vec(c.n);
    c.g = fd_vec(c.n);
    c.r.s = seed;
    return c;
}

/* x = diag(sx, 1, sz) X0 + jitter (in-plane jp h, normal jn h), v uniform
 * in [-vs, vs). */
static inline void sc_state(sc_case *c, double sx, double sz, double jp,
                            double jn, double vs)
{
    double A[9];
    fd_scale(sx, sz, A);
    fd_deform(c->m, A, jp, jn, &c->r, c->x);
    fd_random_vec(&c->r, vs, c->v, c->n);
}

static inline void sc_close(sc_case *c)
{
    free(c->x);
    free(c->v);
    free(c->f);
    free(c->g);
    cl_model_free(c->m);
}

/* The spring network of cloth c under the [springs] settings `sets`. */
static inline cl_springnet sc_network(const cl_cloth *c,
                                      const char *const *sets)
{
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    cl_error err = {0};
    for (size_t k = 0; sets && sets[k]; k++)
        cr_assert_eq(cl_config_set(cfg, sets[k], &err), CL_OK, "%s",
                     err.msg);
    cl_springnet net;
    cr_assert_eq(cl_springs_network(cfg, c, &net, &err), CL_OK, "%s",
                 err.msg);
    cl_config_free(cfg);
    return net;
}

#endif
