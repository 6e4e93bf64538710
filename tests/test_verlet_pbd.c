/* verlet-pbd (the Verlet-and-PBD report's loop: damped Verlet, projection,
 * velocity from the projected positions; integrators/verlet_pbd.c): refused
 * without position-based constraints; identical to verlet where no constraint
 * is violated (a rigid fall); a single constraint's residual after the
 * sweeps is (1 - K)^n times the predictor's; a hanging PBD cloth keeps its
 * rest lengths to within 1 % at K = 1; a PBD cloth with [tear] cut tears
 * when its pins are pulled apart; the command line runs ms-hang with pbd
 * switched on to the library's final state. */
#include <criterion/criterion.h>

#include "io/state.h"
#include "pbdcheck.h"
#include "runcli.h"

Test(verlet_pbd, refused_without_constraints)
{
    pb_case c = pb_open(FD_MODEL("cloth.n=4"));
    const cl_integrator_type *it = cl_integrator_find("verlet-pbd");
    cr_assert_not_null(it);
    cr_assert(it->fixed_step);
    cl_integrator_opts o = {.dt = 1e-3};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(c.sys, &o, 0.0, c.x, c.v, &st, &err), CL_EINVAL);
    cr_assert_null(st);
    cr_assert(strstr(err.msg, "pbd.enabled = true"), "%s", err.msg);
    pb_close(&c);
}

Test(verlet_pbd, bad_velocity_damping_refused)
{
    pb_case c = pb_open(FD_MODEL("cloth.n=4", "pbd.enabled=true"));
    const cl_integrator_type *it = cl_integrator_find("verlet-pbd");
    cl_integrator_opts o = {.dt = 1e-3, .vdamp = 1.0};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(c.sys, &o, 0.0, c.x, c.v, &st, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "verlet-pbd") && strstr(err.msg, "vdamp"),
              "%s", err.msg);
    pb_close(&c);
}

/* A free cloth falling under gravity stays at its rest shape: the
 * projection has nothing to correct (beyond round-off) and verlet-pbd
 * follows verlet. */
Test(verlet_pbd, rigid_fall_equals_verlet)
{
    const char *const sets[] = {"cloth.n=5", "pins.at=", "type1.ks=50",
                                "type2.enabled=false", "pbd.enabled=true",
                                "init.velocity=0.3,0.1,-0.2", NULL};
    pb_case a = pb_open(fd_model(sets)), b = pb_open(fd_model(sets));
    cl_integrator_opts o = {.dt = 1e-3, .vdamp = 0.01};
    pb_integrate(&a, "verlet-pbd", &o, 0.2, 4, NULL, NULL);
    pb_integrate(&b, "verlet", &o, 0.2, 4, NULL, NULL);
    double dx = 0.0;
    for (size_t i = 0; i < a.n; i++)
        dx = fmax(dx, fabs(a.x[i] - b.x[i]));
    cr_assert_lt(dx, 1e-12, "verlet-pbd - verlet: %g", dx);
    cr_assert_lt(a.x[1], -0.1, "the cloth fell");
    pb_close(&a);
    pb_close(&b);
}

/* The largest violation of the level-1 pairs seen at the outputs. */
typedef struct {
    cl_pairset set;
    double *xf;
    double worst;
} watch;

static void watch_violation(pb_case *c, double t, void *ctx)
{
    watch *w = ctx;
    pb_full(c, t, c->x, w->xf);
    w->worst = fmax(w->worst, pb_violation(c->m, &w->set, w->xf));
}

Test(verlet_pbd, hanging_cloth_keeps_rest_lengths)
{
    pb_case c = pb_open(FD_MODEL("cloth.n=8", "type1.enabled=false",
                                 "type2.enabled=false", "pbd.enabled=true",
                                 "pbd.iterations=100"));
    watch w = {.xf = fd_vec(3 * cl_model_cloth(c.m)->np)};
    cl_error err = {0};
    cr_assert_eq(cl_pairs_levels(cl_model_cloth(c.m), 1, &w.set, &err),
                 CL_OK);
    cl_integrator_opts o = {.dt = 1e-3, .vdamp = 0.01};
    pb_integrate(&c, "verlet-pbd", &o, 0.5, 50, watch_violation, &w);
    cr_log_info("verlet-pbd: max |d/L - 1| = %.3e over 0.5 s", w.worst);
    cr_assert_lt(w.worst, 5e-4); /* 2.2e-4 measured */
    double ymin = 0.0;
    for (size_t i = 1; i < c.n; i += 3)
        ymin = fmin(ymin, c.x[i]);
    cr_log_info("verlet-pbd: lowest y %.6f m", ymin);
    /* the cloth hangs down, its far corners swinging (deterministic:
     * -0.39351 m measured) */
    cr_assert_float_eq(ymin, -0.39351, 4e-3, "lowest y %g", ymin);
    free(w.xf);
    cl_pairs_free(&w.set);
    pb_close(&c);
}

Test(verlet_pbd, pulled_pbd_cloth_tears)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "type1.enabled=false",
                                 "type2.enabled=false", "pbd.enabled=true",
                                 "pbd.levels=2", "tear.cut=1.5"));
    cl_integrator_opts o = {.dt = 1e-3, .vdamp = 0.01};
    pb_integrate(&c, "verlet-pbd", &o, 0.5, 10, NULL, NULL);
    cr_log_info("verlet-pbd: %zu constraints torn", cl_model_broken(c.m));
    cr_assert_eq(cl_model_broken(c.m), 7);
    pb_close(&c);
}

/* One step of `name` from the initial state of a two-particle cloth (the
 * first pinned) whose single constraint joins them; the pair's length
 * minus its rest length afterwards. */
static double pair_residual(const char *stiffness, const char *iterations,
                            const char *name)
{
    pb_case c = pb_open(FD_MODEL("cloth.nu=2", "cloth.nv=1", "pins.at=0,0",
                                 "type2.enabled=false", "pbd.enabled=true",
                                 stiffness, iterations,
                                 "init.velocity=1,0.5,0"));
    const double *X0 = cl_model_cloth(c.m)->X0;
    cl_integrator_opts o = {.dt = 0.01};
    pb_integrate(&c, name, &o, 0.01, 1, NULL, NULL);
    double d = sqrt(pow(c.x[0] - X0[0], 2) + pow(c.x[1] - X0[1], 2) +
                    pow(c.x[2] - X0[2], 2));
    double rest = cl_dist(X0, X0 + 3);
    pb_close(&c);
    return d - rest;
}

/* A single constraint with a pinned end: each sweep moves the free end
 * along the pair by K times the violation, so after n sweeps the residual
 * is (1 - K)^n times the violation of the Verlet predictor (verlet's own
 * step from the same state; 0.01 m of stretch from the initial velocity):
 * the projection runs with the configured stiffness and sweeps, after the
 * predictor, once per step. */
Test(verlet_pbd, residual_after_the_sweeps)
{
    static const struct {
        const char *k, *n;
        double factor;
    } cases[] = {{"pbd.stiffness=0.5", "pbd.iterations=1", 0.5},
                 {"pbd.stiffness=0.5", "pbd.iterations=3", 0.125},
                 {"pbd.stiffness=0.25", "pbd.iterations=2", 0.5625},
                 {"pbd.stiffness=1", "pbd.iterations=1", 0.0}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        double pred = pair_residual(cases[k].k, cases[k].n, "verlet");
        double r = pair_residual(cases[k].k, cases[k].n, "verlet-pbd");
        cr_log_info("%s %s: predictor %.6e, after the sweeps %.6e",
                    cases[k].k, cases[k].n, pred, r);
        cr_assert_gt(pred, 5e-3, "the predictor stretches the pair");
        cr_assert(fabs(r - cases[k].factor * pred) <= 1e-14,
                  "%s %s: residual %.17g, expected %.17g", cases[k].k,
                  cases[k].n, r, cases[k].factor * pred);
    }
}

/* The command line runs ms-hang with verlet-pbd: its final state is the
 * library's (the [run] step 5e-4 and no velocity damping), whose level-1
 * residual the projection has held below 1e-3 of the rest lengths (its 10
 * sweeps leave 7.6e-4 after 0.1 s); without pbd it is refused. */
Test(verlet_pbd, command_line_on_ms_hang)
{
    char dir[256], path[300];
    tmp_mkdtemp(dir, sizeof dir, "vpbd");
    cli_result r;
    cli_run(&r, "run", "ms-hang", "--integrator", "verlet-pbd", "--t-end",
            "0.1", "--frames", "0", "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_load(cfg, "problems/ms-hang.ini", &err), CL_OK,
                 "%s", err.msg);
    cl_model *m = NULL;
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    pb_case c = pb_open(m);
    cl_integrator_opts o = {.dt = 5e-4};
    pb_integrate(&c, "verlet-pbd", &o, 0.1, 1, NULL, NULL);
    size_t np = cl_model_cloth(m)->np;
    double *xf = fd_vec(3 * np), *xc = fd_vec(3 * np), *vc = fd_vec(3 * np);
    pb_full(&c, 0.1, c.x, xf);
    snprintf(path, sizeof path, "%s/final.csv", dir);
    cr_assert_eq(cl_state_read(path, np, xc, vc, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(memcmp(xf, xc, 3 * np * sizeof *xf), 0,
                 "final.csv holds the library's state");
    cl_pairset set;
    cr_assert_eq(cl_pairs_levels(cl_model_cloth(m), 1, &set, &err), CL_OK);
    double worst = pb_violation(m, &set, xc);
    cr_log_info("ms-hang verlet-pbd: max |d/L - 1| = %.3e at 0.1 s", worst);
    cr_assert_lt(worst, 1e-3);
    cl_pairs_free(&set);
    free(xf);
    free(xc);
    free(vc);
    pb_close(&c);
    cl_config_free(cfg);
    cli_run(&r, "run", "ms-hang", "--integrator", "verlet-pbd", "--set",
            "pbd.enabled=false", "--t-end", "0.1", "--frames", "0", "--out",
            dir, "--quiet", NULL);
    cli_assert_error(&r, 0, "verlet-pbd", "pbd.enabled = true", NULL);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}
