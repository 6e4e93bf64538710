/* The explicit limit against the penalty stiffness (analysis/
 * contact_limit.c) on problems/particle-floor: a particle of 0.1 kg at rest
 * in a penalty floor, a spring w = sqrt(k/m) along the normal and no other
 * force with a Jacobian, so the spectrum at that state is mu = k/m (and
 * zeros), symplectic Euler's predicted limit 2/w, and the stability search
 * brackets the same value (the particle never leaves the floor). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>

#include "analysis/contact_limit.h"
#include "problem.h"

/* The search and the prediction of symplectic Euler on particle-floor
 * with the assignments set1, set2 (NULL: none), linearised at its initial
 * state. */
static cl_climit_result cl_search(const char *set1, const char *set2,
                                  const cl_stab_opts *o)
{
    pr_problem p;
    cl_error err = {0};
    cl_integrator_opts io = {0};
    cl_climit_result r = {0};
    pr_load(&p, "problems/particle-floor.ini", set1, set2);
    size_t n = cl_model_system(p.m)->n;
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v);
    cr_assert_eq(cl_model_initial_state(p.m, x, v), CL_OK);
    const cl_integrator_type *se = cl_integrator_find("symplectic-euler");
    cr_assert_eq(cl_climit_predict(p.m, se, 0.0, x, v, &r, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_stability(p.m, se, &io, o, &r.stab, &err), CL_OK, "%s",
                 err.msg);
    free(x);
    free(v);
    pr_free(&p);
    return r;
}

Test(contact_limit, contact_spring_predicted_and_measured)
{
    cl_stab_opts o = {.t_end = 2.0, .dt_max = 0.02, .dt_min = 1e-6,
                      .rel = 0.01, .checks = 100000, .max_stretch = 1.05};
    cl_climit_result r = cl_search(NULL, NULL, &o);
    double w = sqrt(1e4 / 0.1);
    cr_assert_float_eq(r.w_max, w, 1e-9 * w);
    cr_assert_float_eq(r.predicted, 2.0 / w, 1e-12);
    cr_assert_lt(r.stab.dt_stable, r.predicted);
    cr_assert_geq(r.stab.dt_unstable, r.predicted);
    cr_assert_lt(r.stab.dt_unstable / r.stab.dt_stable, 1.011);
}

/* Out of contact (the floor moved away) the particle is free: nothing
 * bounds the step, and the prediction says so. */
Test(contact_limit, out_of_contact_predicts_no_limit)
{
    cl_stab_opts o = {.t_end = 0.2, .dt_max = 0.02, .dt_min = 1e-6,
                      .rel = 0.01, .checks = 10, .max_stretch = 1.05};
    cl_climit_result r = cl_search("obstacle.floor.point=0.9,0,0",
                                   "gravity.g=0,0,0", &o);
    cr_assert_eq(r.w_max, 0.0);
    cr_assert(isinf(r.predicted));
    cr_assert(isnan(r.stab.dt_unstable), "%g", r.stab.dt_unstable);
}
