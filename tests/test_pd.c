/* pd (integrators/pd.c; docs/integrators.md, 9): registered with
 * substeps and iterations; refuses hard constraints; one factorisation
 * per run and one solve per iteration; converged (many iterations) it is
 * backward Euler of the same springs (kinsol-be), on a small cloth with a
 * moving pin, the distance falling as the iterations grow; from the
 * static equilibrium of a spring chain it stays there at any K (closed
 * form, tests/cdyncheck.h). */
#include <criterion/criterion.h>

#include "cdyncheck.h"

Test(pd, registry_row)
{
    const cl_integrator_type *it = cl_integrator_find("pd");
    cr_assert_not_null(it);
    cr_assert(it->fixed_step && it->takes_iterations);
}

Test(pd, refuses_hard_constraints)
{
    pb_case c = pb_open(FD_MODEL("cloth.n=4", "type1.enabled=false",
                                 "type2.enabled=false", "pbd.enabled=true"));
    cl_integrator_opts o = {.dt = 1e-3};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(cl_integrator_find("pd")->create(c.sys, &o, 0.0, c.x, c.v,
                                                  &st, &err),
                 CL_EINVAL);
    cr_assert_null(st);
    cr_assert(strstr(err.msg, "pbd.enabled = false"), "%s", err.msg);
    pb_close(&c);
}

/* A 5 x 5 spring cloth (structural, shear, bend; no damping) under
 * gravity, one pin fixed and one moving, 10 steps of 0.01 s. */
#define PD_CLOTH                                                         \
    "cloth.n=5", "type1.enabled=false", "type2.enabled=false",           \
        "damping.kd=0", "springs.enabled=true", "pins.at=0,0",           \
        "pins2.at=0,-1", "pins2.velocity=0,0.3,0"

static void pd_run(const char *name, const cl_integrator_opts *o, double *x,
                   cl_stats *s)
{
    pb_case c = pb_open(FD_MODEL(PD_CLOTH));
    pb_integrate(&c, name, o, 0.1, 1, NULL, NULL);
    memcpy(x, c.x, c.n * sizeof *x);
    *s = c.st;
    pb_close(&c);
}

/* Measured max |x_pd - x_be|: K = 1 2.4e-2, 10 1.1e-2, 100 5.6e-4,
 * 1000 5.0e-12. */
Test(pd, converged_is_backward_euler)
{
    static const long K[] = {1, 10, 100, 1000};
    double xb[3 * 23], xp[3 * 23], prev = INFINITY;
    cl_stats s;
    cl_integrator_opts ob = {.dt = 0.01, .newton_tol = 1e-13};
    pd_run("kinsol-be", &ob, xb, &s);
    for (size_t k = 0; k < sizeof K / sizeof *K; k++) {
        cl_integrator_opts o = {.dt = 0.01, .iterations = K[k]};
        pd_run("pd", &o, xp, &s);
        cr_assert_eq(s.lin_setups, 1);
        cr_assert_eq(s.symbolic_facts, 1); /* CHOLMOD's analysis, once */
        cr_assert_eq(s.lin_solves, 10 * K[k]);
        double d = 0.0;
        for (size_t i = 0; i < 3 * 23; i++)
            d = fmax(d, fabs(xp[i] - xb[i]));
        cr_log_info("pd K = %ld: max |x - x_be| %.3e", K[k], d);
        cr_assert_lt(d, prev, "K = %ld: %.3e not below %.3e", K[k], d, prev);
        prev = d;
    }
    cr_assert_lt(prev, 1e-9);
}

/* Backward Euler keeps the static equilibrium, and so does pd from its
 * first iteration: at the equilibrium the local step projects every
 * spring onto its own direction and the global step returns the same
 * positions (measured drift 5.6e-17, round-off). */
Test(pd, keeps_the_rest_state)
{
    double e = cd_rest_drift("pd", 0.01, 1, 1);
    cr_log_info("pd drift from the equilibrium at K = 1: %.3e", e);
    cr_assert_lt(e, 1e-12);
}
