/* Every registered integrator runs the hang cloth (reduced to 6 x 6) for a
 * short time at a step it can take, and reports the common statistics.
 * The cloth carries position-based constraints (pbd.enabled) for
 * verlet-pbd; every other method ignores them. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"

static bool is_explicit(const char *name)
{
    static const char *const names[] = {"fe", "symplectic-euler",
                                        "symplectic-euler-x", "verlet",
                                        "velocity-verlet", "rk4",
                                        "verlet-pbd", NULL};
    for (size_t k = 0; names[k]; k++)
        if (!strcmp(name, names[k]))
            return true;
    return false;
}

static void run_one(const cl_integrator_type *it, const cl_system *sys,
                    const double *x0, const double *v0)
{
    /* Explicit methods at 1e-5, fixed-step implicit at 1e-3, adaptive ones
     * with the problem's tolerances. */
    cl_integrator_opts o = {.dt = it->fixed_step
                                      ? (is_explicit(it->name) ? 1e-5 : 1e-3)
                                      : 0.0,
                            .rtol = 1e-4, .atol = 1e-6};
    double T = 0.02;
    size_t n = sys->n;
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v);
    void *st = NULL;
    cl_error err = {0};
    cl_stats s = {0};
    cr_assert_eq(it->create(sys, &o, 0.0, x0, v0, &st, &err), CL_OK, "%s: %s",
                 it->name, err.msg);
    cr_assert_eq(it->advance(st, T, x, v, &err), CL_OK, "%s: %s", it->name,
                 err.msg);
    it->stats(st, &s);
    it->free(st);
    cr_assert_gt(s.steps, 0, "%s: no steps", it->name);
    cr_assert_geq(s.rhs_evals, s.steps, "%s: %ld force evaluations for %ld "
                  "steps", it->name, s.rhs_evals, s.steps);
    if (it->fixed_step)
        cr_assert_eq(s.steps, lround(T / o.dt), "%s", it->name);
    /* The cloth has started to fall: free particles below the rest plane. */
    double ymin = 0.0;
    for (size_t k = 1; k < n; k += 3)
        ymin = fmin(ymin, x[k]);
    cr_assert_lt(ymin, -1e-4, "%s: the cloth did not move", it->name);
    for (size_t k = 0; k < n; k++)
        cr_assert(isfinite(x[k]) && isfinite(v[k]), "%s", it->name);
    free(x);
    free(v);
}

Test(every_integrator, runs_hang_and_counts)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cr_assert_eq(cl_config_load(cfg, "problems/hang.ini", &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_config_set(cfg, "cloth.n=6", &err), CL_OK);
    cr_assert_eq(cl_config_set(cfg, "pbd.enabled=true", &err), CL_OK);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    const cl_system *sys = cl_model_system(m);
    double *x0 = malloc(sys->n * sizeof *x0), *v0 = malloc(sys->n * sizeof *v0);
    cl_model_initial_state(m, x0, v0);
    size_t count = 0;
    for (size_t k = 0; cl_integrator_registry[k]; k++, count++)
        run_one(cl_integrator_registry[k], sys, x0, v0);
    cr_assert_geq(count, 18,
                  "fewer integrators than docs/integrators.md lists");
    free(x0);
    free(v0);
    cl_model_free(m);
    cl_config_free(cfg);
}
