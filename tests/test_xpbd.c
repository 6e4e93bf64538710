/* xpbd (integrators/xpbd.c; docs/integrators.md, 9): registered with
 * substeps and iterations; refused without distance constraints and with
 * tearing; from the static equilibrium of a spring chain it drifts less
 * the more iterations it makes, toward the force model's equilibrium
 * (closed form, tests/cdyncheck.h); on a chain of hard constraints the
 * same budget S K = 20 spent on substeps leaves less constraint error
 * than spent on iterations (Macklin et al., "Small steps in physics
 * simulation"); S substeps of dt equal S steps of dt / S. */
#include <criterion/criterion.h>

#include "cdyncheck.h"

Test(xpbd, registry_row)
{
    const cl_integrator_type *it = cl_integrator_find("xpbd");
    cr_assert_not_null(it);
    cr_assert(it->fixed_step && it->takes_iterations);
    cr_assert(!it->takes_linsol && !it->takes_max_order);
}

static cl_status xpbd_try(cl_model *m, cl_error *err)
{
    pb_case c = pb_open(m);
    const cl_integrator_type *it = cl_integrator_find("xpbd");
    cl_integrator_opts o = {.dt = 1e-3};
    void *st = NULL;
    cl_status rc = it->create(c.sys, &o, 0.0, c.x, c.v, &st, err);
    cr_assert_null(st);
    pb_close(&c);
    return rc;
}

Test(xpbd, refused_without_distance_constraints)
{
    cl_error err = {0};
    cr_assert_eq(xpbd_try(FD_MODEL("cloth.n=4"), &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "xpbd needs distance constraints") &&
              strstr(err.msg, "springs.enabled"), "%s", err.msg);
    cr_assert_eq(xpbd_try(FD_MODEL(CD_CHAIN, "tear.cut=2"), &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "tear.cut"), "%s", err.msg);
}

/* Measured drift from the equilibrium (dt = 0.01, S = 1): K = 1 1.7e-2,
 * 2 3.5e-3, 4 1.8e-4, 8 2.9e-7, 16 7.1e-13 (round-off beyond). */
Test(xpbd, converges_to_the_force_models_rest_state)
{
    static const long K[] = {1, 2, 4, 8, 16};
    double prev = INFINITY;
    for (size_t k = 0; k < sizeof K / sizeof *K; k++) {
        double e = cd_rest_drift("xpbd", 0.01, 1, K[k]);
        cr_log_info("xpbd K = %ld: drift from the equilibrium %.3e", K[k],
                    e);
        cr_assert_lt(e, prev, "K = %ld: %.3e, not below %.3e", K[k], e,
                     prev);
        prev = e;
    }
    cr_assert_lt(prev, 1e-11, "K = 16: %.3e", prev);
}

/* The largest link violation |d - L| / L of a 20-link chain of hard
 * constraints (the pbd term) released horizontally, over 1 s of steps
 * dt = 0.01 with S substeps and K iterations. */
static void watch_links(pb_case *c, double t, void *ctx)
{
    double *w = ctx, xf[3 * 21];
    cl_pairset set = {0};
    cl_error err = {0};
    cr_assert_eq(cl_pairs_levels(cl_model_cloth(c->m), 1, &set, &err),
                 CL_OK);
    pb_full(c, t, c->x, xf);
    *w = fmax(*w, pb_violation(c->m, &set, xf));
    cl_pairs_free(&set);
}

static double hard_chain_error(long S, long K)
{
    pb_case c = pb_open(FD_MODEL("cloth.nu=21", "cloth.nv=1", "cloth.size=1",
                                 "cloth.particle_mass=0.01", "pins.at=0,0",
                                 "type1.enabled=false",
                                 "type2.enabled=false", "damping.kd=0",
                                 "pbd.enabled=true"));
    cl_integrator_opts o = {.dt = 0.01, .substeps = S, .iterations = K};
    double worst = 0.0;
    pb_integrate(&c, "xpbd", &o, 1.0, 20, watch_links, &worst);
    cr_assert_eq(c.st.nonlin_iters, 100 * S * K);
    pb_close(&c);
    return worst;
}

/* Measured: (S, K) = (1, 20) 4.9e-2, (2, 10) 2.6e-2, (4, 5) 1.3e-2,
 * (10, 2) 5.5e-3, (20, 1) 3.1e-3. */
Test(xpbd, substeps_beat_iterations_at_equal_cost)
{
    static const long S[] = {1, 2, 4, 10, 20};
    double prev = INFINITY;
    for (size_t k = 0; k < sizeof S / sizeof *S; k++) {
        double e = hard_chain_error(S[k], 20 / S[k]);
        cr_log_info("xpbd S = %ld, K = %ld: link error %.3e", S[k],
                    20 / S[k], e);
        cr_assert_lt(e, prev, "S = %ld: %.3e, not below %.3e", S[k], e,
                     prev);
        prev = e;
    }
    cr_assert_lt(prev, 4e-3);
}

/* S substeps of a step dt are S steps of dt / S (a moving pin checks
 * that the anchors follow the substeps). */
Test(xpbd, substeps_are_smaller_steps)
{
    const char *const sets[] = {CD_CHAIN, "pins.velocity=0,0.5,0", NULL};
    pb_case a = pb_open(fd_model(sets)), b = pb_open(fd_model(sets));
    cl_integrator_opts oa = {.dt = 0.02, .substeps = 4, .iterations = 3};
    cl_integrator_opts ob = {.dt = 0.005, .iterations = 3};
    pb_integrate(&a, "xpbd", &oa, 0.2, 2, NULL, NULL);
    pb_integrate(&b, "xpbd", &ob, 0.2, 2, NULL, NULL);
    double d = 0.0;
    for (size_t i = 0; i < a.n; i++)
        d = fmax(d, fabs(a.x[i] - b.x[i]) + fabs(a.v[i] - b.v[i]));
    cr_assert_lt(d, 1e-12, "%g", d);
    cr_assert_eq(a.st.steps, 10);
    cr_assert_eq(a.st.rhs_evals, 40);
    cr_assert_gt(a.x[1], 0.05, "the pin pulled the chain up");
    pb_close(&a);
    pb_close(&b);
}
