/* Spectra (analysis/spectrum.c) on spring2 stiffened to ks = 1e4: one free
 * particle of mass 1 on a spring to a pinned one along x, w = 100 rad/s.
 * At rest the spring has no tension, so only x is stiff: mu = {0, 0, w^2},
 * lambda = {+-i w, 0 x 4}.  Predicted limits: 2/w for the symplectic
 * methods, 2 sqrt(2)/w for rk4, 0 for fe (undamped).  With pair damping
 * kd = 20 (c = 20/s): lambda = -10 +- i sqrt(w^2 - 100), fe's limit
 * -2 Re/|lambda|^2 = 2e-3, which the stability search finds too (over
 * T = 40 s: near the limit the growth per step is small, and over a short
 * horizon a slightly unstable step passes for a stable one).
 * Compressed to d = L/2 the spring pushes (s = -5e3 N), a transverse
 * stiffness s/d = -1e4: two growing modes at rate 100/s. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/spectrum.h"
#include "analysis/stability.h"
#include "io/config.h"
#include "problem.h"

typedef struct {
    pr_problem p;
    cl_model *m;
    cl_spectrum s;
} sp_case;

/* spring2 with ks = 1e4 and `set` (or none), spectrum at x = (x1, 0, 0),
 * v = 0. */
static void sp_open(sp_case *c, const char *set, double x1)
{
    cl_error err = {0};
    pr_load(&c->p, "problems/spring2.ini", "type1.ks=1e4", set);
    c->m = c->p.m;
    double x[3] = {x1, 0, 0}, v[3] = {0, 0, 0};
    cr_assert_eq(cl_spectrum_compute(c->m, 0.0, x, v, &c->s, &err), CL_OK,
                 "%s", err.msg);
}

static void sp_close(sp_case *c)
{
    cl_spectrum_free(&c->s);
    pr_free(&c->p);
}

static double sp_limit(const cl_spectrum *s, const char *name)
{
    cl_spectrum_limit lim[64];
    size_t n = cl_spectrum_limits(s, lim, 64);
    cr_assert_leq(n, 64);
    for (size_t k = 0; k < n; k++)
        if (!strcmp(lim[k].integrator, name))
            return lim[k].h;
    cr_assert_fail("no limit for %s", name);
    return NAN;
}

Test(spectrum, undamped_spring_at_rest)
{
    sp_case c;
    sp_open(&c, NULL, 1.0);
    cr_assert_eq(c.s.n, 3);
    cr_assert(fabs(c.s.mu[0]) < 1e-9 && fabs(c.s.mu[1]) < 1e-9);
    cr_assert_float_eq(c.s.mu[2], 1e4, 1e-8);
    cr_assert_float_eq(c.s.w_max, 100.0, 1e-10);
    cr_assert_float_eq(hypot(c.s.re[0], c.s.im[0]), 100.0, 1e-9);
    cr_assert_float_eq(fabs(c.s.im[0]), 100.0, 1e-9);
    cr_assert_eq(c.s.n_growing, 0);
    cr_assert_eq(c.s.n_negative, 0);
    cr_assert_eq(c.s.n_zero, 2);
    cr_assert_float_eq(sp_limit(&c.s, "symplectic-euler"), 0.02, 1e-15);
    cr_assert_float_eq(sp_limit(&c.s, "velocity-verlet"), 0.02, 1e-15);
    cr_assert_float_eq(sp_limit(&c.s, "rk4"), 2 * sqrt(2.0) / 100, 1e-9);
    cr_assert_eq(sp_limit(&c.s, "fe"), 0.0);
    sp_close(&c);
}

/* The fe prediction on the damped spring, and the stability search on the
 * same system (tight stretch test, every step) agreeing with it. */
Test(spectrum, damped_spring_fe_limit_matches_the_search)
{
    sp_case c;
    sp_open(&c, "damping.kd=20", 1.0);
    double h = sp_limit(&c.s, "fe");
    cr_log_info("fe predicted %.6g", h);
    cr_assert_float_eq(h, 2e-3, 1e-12);
    cr_assert_float_eq(c.s.re[0], -10.0, 1e-9);
    /* T long enough for a growth of 1 + 1e-4 per step to show */
    cl_stab_opts o = {.t_end = 40.0, .dt_max = 0.01, .dt_min = 1e-5,
                      .rel = 0.005, .checks = 1000000, .max_stretch = 1.5};
    cl_stab_result r;
    cl_integrator_opts io = {0};
    cl_error err = {0};
    cr_assert_eq(cl_stability(c.m, cl_integrator_find("fe"), &io, &o, &r,
                              &err),
                 CL_OK, "%s", err.msg);
    cr_log_info("fe measured (%.6g, %.6g)", r.dt_stable, r.dt_unstable);
    cr_assert(r.dt_stable > 0.97 * h && r.dt_stable < 1.03 * h, "%g",
              r.dt_stable);
    sp_close(&c);
}

/* The symplectic methods' predictions on c.m found by the stability
 * search to 3 %. */
static void symplectic_limits_searched(const sp_case *c)
{
    static const char *const name[] = {"symplectic-euler", "verlet",
                                       "velocity-verlet"};
    cl_stab_opts o = {.t_end = 40.0, .dt_max = 0.1, .dt_min = 1e-5,
                      .rel = 0.005, .checks = 1000000, .max_stretch = 1.5};
    for (int k = 0; k < 3; k++) {
        double h = sp_limit(&c->s, name[k]);
        cl_stab_result r;
        cl_integrator_opts io = {0};
        cl_error err = {0};
        cr_assert_eq(cl_stability(c->m, cl_integrator_find(name[k]), &io, &o,
                                  &r, &err),
                     CL_OK, "%s", err.msg);
        cr_log_info("%s predicted %.6g, measured (%.6g, %.6g)", name[k], h,
                    r.dt_stable, r.dt_unstable);
        cr_assert(r.dt_stable > 0.97 * h && r.dt_stable < 1.03 * h,
                  "%s: %g against %g", name[k], r.dt_stable, h);
    }
}

/* With damping the symplectic limits fall below 2/w: symplectic Euler and
 * Verlet at (sqrt(c^2 + 4 w^2) - c) / w^2 (trace 2 - h^2 w^2 - h c,
 * determinant 1 - h c), velocity Verlet lower still (its damping sees
 * the predictor, its kept acceleration the last one's: three states); the
 * stability search finds each prediction, lightly damped (c = 20/s) and
 * overdamped (c = 210/s > 2 w: the first-order eigenvalues are real). */
Test(spectrum, damped_spring_symplectic_limits_match_the_search)
{
    sp_case c;
    sp_open(&c, "damping.kd=20", 1.0);
    double closed = (sqrt(20.0 * 20.0 + 4e4) - 20.0) / 1e4;
    cr_assert_float_eq(sp_limit(&c.s, "symplectic-euler"), closed, 1e-12);
    cr_assert_float_eq(sp_limit(&c.s, "verlet"), closed, 1e-12);
    cr_assert_lt(sp_limit(&c.s, "velocity-verlet"), 0.95 * closed);
    symplectic_limits_searched(&c);
    sp_close(&c);
    sp_open(&c, "damping.kd=210", 1.0);
    closed = (sqrt(210.0 * 210.0 + 4e4) - 210.0) / 1e4;
    cr_assert_eq(c.s.im[0], 0.0, "overdamped: real eigenvalues");
    cr_assert_float_eq(sp_limit(&c.s, "symplectic-euler"), closed, 1e-12);
    symplectic_limits_searched(&c);
    sp_close(&c);
}

/* The search's first step dt_max counts as stable only when dt_max/2 is
 * too: symplectic Euler at h c = 1 on the damped spring (c = 20/s, h =
 * 0.05) lands on the equilibrium and stays there, yet 0.025 blows up; the
 * limit is the prediction below it, not "stable at dt_max". */
Test(spectrum, stable_dt_max_is_confirmed_by_its_half)
{
    sp_case c;
    sp_open(&c, "damping.kd=20", 1.0);
    cl_stab_opts o = {.t_end = 40.0, .dt_max = 0.05, .dt_min = 1e-5,
                      .rel = 0.005, .checks = 1000000, .max_stretch = 1.5};
    cl_stab_result r;
    cl_integrator_opts io = {0};
    cl_error err = {0};
    cr_assert_eq(cl_stability(c.m, cl_integrator_find("symplectic-euler"),
                              &io, &o, &r, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_eq(r.trial[0].rc, CL_OK, "h c = 1 stable");
    cr_assert_neq(r.trial[1].rc, CL_OK, "h c = 1/2 unstable");
    double h = sp_limit(&c.s, "symplectic-euler");
    cr_assert(r.dt_stable > 0.97 * h && r.dt_stable < 1.03 * h,
              "%g against %g", r.dt_stable, h);
    sp_close(&c);
}

/* The explicit limits come from the registry's regions, Taylor ones first:
 * exactly the rows `clothode spectrum` prints, one for every explicit
 * integrator of the registry (one added there included), the six known
 * ones in this order. */
Test(spectrum, limits_listed_from_the_regions)
{
    static const char *const known[] = {
        "fe", "rk4", "symplectic-euler", "symplectic-euler-x", "verlet",
        "velocity-verlet"};
    size_t explicit = 0;
    for (size_t i = 0; cl_integrator_registry[i]; i++) {
        cl_region_kind k = cl_integrator_registry[i]->region->kind;
        explicit += k == CL_REGION_TAYLOR || k == CL_REGION_SYMPLECTIC;
    }
    sp_case c;
    sp_open(&c, NULL, 1.0);
    cl_spectrum_limit lim[64];
    size_t n = cl_spectrum_limits(&c.s, lim, 64);
    cr_assert_eq(n, explicit);
    cr_assert_eq(cl_spectrum_limits(&c.s, NULL, 0), explicit);
    size_t next = 0;
    bool symplectic = false;
    for (size_t k = 0; k < n; k++) {
        const cl_integrator_type *t = cl_integrator_find(lim[k].integrator);
        cr_assert_eq(lim[k].h, cl_spectrum_step_limit(&c.s, t->region));
        /* the Taylor regions first */
        cr_assert(!symplectic || t->region->kind == CL_REGION_SYMPLECTIC,
                  "%s after a symplectic one", lim[k].integrator);
        symplectic = t->region->kind == CL_REGION_SYMPLECTIC;
        if (next < 6 && !strcmp(lim[k].integrator, known[next]))
            next++;
    }
    cr_assert_eq(next, 6, "the known six not all there, in order");
    sp_close(&c);
}

/* Implicit methods: the undamped pair +-100i lies on the imaginary axis,
 * inside an A-stable region (every step stable) but outside BDF5's sector
 * of 51.84 degrees.  With kd = 140 the pair is -70 +- 71.41i, at
 * atan(71.41/70) = 45.6 degrees from the negative real axis, and the
 * transverse modes -140 lie on that axis: all inside. */
Test(spectrum, implicit_sectors)
{
    sp_case c;
    sp_open(&c, NULL, 1.0);
    cr_assert_eq(cl_spectrum_step_limit(&c.s, &cl_region_a_stable),
                 INFINITY);
    cr_assert(isnan(cl_spectrum_step_limit(&c.s, &cl_region_bdf5)));
    cr_assert(isnan(cl_spectrum_step_limit(&c.s, &cl_region_adaptive)));
    cr_assert(isnan(cl_spectrum_step_limit(&c.s, &cl_region_projected)));
    sp_close(&c);
    sp_open(&c, "damping.kd=140", 1.0);
    cr_assert_float_eq(c.s.re[2], -70.0, 1e-9);
    cr_assert_float_eq(fabs(c.s.im[2]), sqrt(1e4 - 70 * 70), 1e-9);
    cr_assert_eq(cl_spectrum_step_limit(&c.s, &cl_region_bdf5), INFINITY);
    sp_close(&c);
}

Test(spectrum, compressed_spring_has_growing_modes)
{
    sp_case c;
    sp_open(&c, NULL, 0.5);
    cr_assert_float_eq(c.s.mu[0], -1e4, 1e-8);
    cr_assert_float_eq(c.s.mu[1], -1e4, 1e-8);
    cr_assert_eq(c.s.n_growing, 2);
    cr_assert_float_eq(c.s.growth_max, 100.0, 1e-9);
    cr_assert_eq(c.s.n_negative, 2);
    cr_assert_eq(c.s.n_zero, 0);
    sp_close(&c);
}

/* A flat 8 x 8 cloth at rest: each free particle's out-of-plane direction
 * is a zero mode, which round-off puts on either side of 0 (about half of
 * the 62 came out below it, |mu| <= 7e-10 against mu_max 9.7e5): counted
 * as zero, none as negative. */
/* The spectrum of the problem at `path` (with sets set1, set2) at its
 * initial state, into s (the caller frees it). */
static void initial_spectrum(const char *path, const char *set1,
                             const char *set2, cl_spectrum *s)
{
    pr_problem p;
    pr_load(&p, path, set1, set2);
    const cl_system *sys = cl_model_system(p.m);
    double *x = malloc(sys->n * sizeof *x), *v = calloc(sys->n, sizeof *v);
    cr_assert(x && v);
    cr_assert_eq(cl_model_initial_state(p.m, x, v), CL_OK);
    cl_error err = {0};
    cr_assert_eq(cl_spectrum_compute(p.m, 0.0, x, v, s, &err), CL_OK, "%s",
                 err.msg);
    free(x);
    free(v);
    pr_free(&p);
}

Test(spectrum, flat_cloth_zero_modes_are_not_negative)
{
    cl_spectrum s;
    initial_spectrum("problems/hang-smooth.ini", "cloth.n=8", NULL, &s);
    cr_assert_eq(s.n, 186);
    cr_assert_eq(s.n_negative, 0, "%zu", s.n_negative);
    cr_assert_eq(s.n_zero, 62, "%zu", s.n_zero);
    cl_spectrum_free(&s);
}

/* hang (3 x 3) at its initial state with stiffness `ks`: w_max and
 * |lambda|_max. */
static void hang_spectrum(const char *ks, double *w_max, double *lam_max)
{
    cl_spectrum s;
    initial_spectrum("problems/hang.ini", "cloth.n=3", ks, &s);
    *w_max = s.w_max;
    *lam_max = s.lambda_max;
    cl_spectrum_free(&s);
}

/* A stiffness of 1e-300 beside bending stiffness of order one put GSL's
 * symmetric QR iteration into subnormal numbers, where it never ended;
 * the matrices are scaled and cleared below round-off first, and the
 * spectrum is the one of any other negligible stiffness. */
Test(spectrum, negligible_stiffness_ends, .timeout = 60)
{
    double w0, l0, w1, l1;
    hang_spectrum("type1.ks=1e-30", &w0, &l0);
    hang_spectrum("type1.ks=1e-300", &w1, &l1);
    /* flat at rest: no stiffness beyond round-off; the damped first-order
     * spectrum (|lambda| 0.806/s) alike */
    cr_assert(w0 < 1e-10 && w1 < 1e-10, "%g %g", w0, w1);
    cr_assert_float_eq(l0, 0.805994, 1e-6 * 0.806, "%.9g", l0);
    cr_assert_float_eq(l1, l0, 1e-12 * l0);
}

Test(spectrum, large_cloth_refused)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cr_assert_eq(cl_config_load(cfg, "problems/hang.ini", &err), CL_OK);
    cr_assert_eq(cl_config_set(cfg, "cloth.n=26", &err), CL_OK);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    size_t n = cl_model_system(m)->n;
    double *x = calloc(n, sizeof *x), *v = calloc(n, sizeof *v);
    cl_spectrum s;
    cr_assert_eq(cl_spectrum_compute(m, 0.0, x, v, &s, &err),
                 CL_EUNSUPPORTED);
    cr_assert_not_null(strstr(err.msg, "24 x 24"), "%s", err.msg);
    free(x);
    free(v);
    cl_model_free(m);
    cl_config_free(cfg);
}

/* The contact term is part of the model's Jacobian: on particle-floor (a
 * particle of 0.1 kg in a penalty floor of normal x, k = 1e4 N/m, no other
 * stiffness) linearised in contact, mu = {0, 0, k/m}; with the floor moved
 * out of reach, all zero. */
static double sp_mu_max_floor(const char *set)
{
    pr_problem p;
    cl_spectrum s = {0};
    cl_error err = {0};
    double x[3], v[3];
    pr_load(&p, "problems/particle-floor.ini", set, NULL);
    cr_assert_eq(cl_model_initial_state(p.m, x, v), CL_OK);
    cr_assert_eq(cl_spectrum_compute(p.m, 0.0, x, v, &s, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(s.n, 3);
    cr_assert_float_eq(s.mu[0], 0.0, 1e-9);
    cr_assert_float_eq(s.mu[1], 0.0, 1e-9);
    double mu = s.mu[2];
    cl_spectrum_free(&s);
    pr_free(&p);
    return mu;
}

Test(spectrum, contact_spring_in_contact_only)
{
    cr_assert_float_eq(sp_mu_max_floor(NULL), 1e4 / 0.1, 1e-6);
    cr_assert_float_eq(sp_mu_max_floor("obstacle.floor.point=0.9,0,0"), 0.0,
                       1e-9);
}
