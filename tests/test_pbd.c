/* Position-based distance constraints, the `pbd` term (the Verlet-and-PBD
 * report; Mueller et al. 2007; forces/pbd.h): level pair counts; the
 * Gauss-Seidel projection satisfies one pair exactly at K = 1 with
 * displacements in inverse proportion to the masses, drives the violation of a
 * jittered cloth down over the sweeps, never moves pinned particles and
 * conserves the centre of mass of free particles with unequal masses; the term
 * has no force, Jacobian or potential; constraints tear by the [tear] cut rule;
 * bad options are refused. */
#include <criterion/criterion.h>

#include "forces/pbd.h"
#include "pbdcheck.h"

Test(pbd, level_pair_counts)
{
    cl_model *m = FD_MODEL("cloth.n=7", "pins.at=");
    const cl_cloth *c = cl_model_cloth(m);
    for (long k = 1; k <= 8; k++) {
        cl_pairset s;
        cl_error err = {0};
        cr_assert_eq(cl_pairs_levels(c, k, &s, &err), CL_OK);
        size_t want = 0, n = 7;
        for (size_t l = 1; l <= (size_t)k && l < n; l++)
            want += 2 * (n - l) * (2 * n - l);
        cr_assert_eq(s.n, want, "levels %ld: %zu pairs, expected %zu", k,
                     s.n, want);
        cl_pairs_free(&s);
    }
    cl_model_free(m);
}

/* A term state on cloth c from "pbd.key=value" settings (NULL: none). */
static void *make_term(const cl_cloth *c, double cut,
                       const char *const *sets)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cl_term_opts o = {.tear_cut = cut};
    void *st = NULL;
    cr_assert_not_null(cfg);
    cr_assert_eq(cl_config_set(cfg, "pbd.enabled=true", &err), CL_OK);
    for (size_t k = 0; sets && sets[k]; k++)
        cr_assert_eq(cl_config_set(cfg, sets[k], &err), CL_OK, "%s",
                     err.msg);
    cr_assert_eq(cl_term_pbd.create(cfg, c, &o, &st, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_not_null(st);
    cl_config_free(cfg);
    return st;
}

/* An nu x nv grid, 1 m square, masses m_p = (1 + p mod 3) 0.01 kg, the
 * particles of `pins` (ending with -1) pinned. */
static void unequal_cloth(int nu, int nv, const int *pins, cl_cloth *c)
{
    cl_error err = {0};
    static const double still[3] = {0, 0, 0};
    cr_assert_eq(cl_cloth_grid(nu, nv, 1.0, 1.0, 0.01, c, &err), CL_OK);
    for (size_t p = 0; p < c->np; p++)
        c->mass[p] = 0.01 * (double)(1 + p % 3);
    for (; *pins >= 0; pins++)
        cr_assert_eq(cl_cloth_pin(c, *pins / nv, *pins % nv, still, INFINITY,
                                  &err), CL_OK);
    cr_assert_eq(cl_cloth_finalize(c, &err), CL_OK);
}

/* x = X0 + amp U(-1, 1) in every component of the free particles (the
 * pinned ones at rest, so that the constraints can be met). */
static void jitter(const cl_cloth *c, double amp, uint64_t seed, double *x)
{
    fd_rng r = {seed};
    for (size_t i = 0; i < 3 * c->np; i++)
        x[i] = c->X0[i] + (c->dof[i / 3] >= 0 ? amp * fd_rand(&r) : 0.0);
}

static const int no_pins[] = {-1};

Test(pbd, one_pair_exact_and_mass_weighted)
{
    cl_cloth c;
    unequal_cloth(1, 2, no_pins, &c); /* masses 0.01 and 0.02 */
    void *st = make_term(&c, 0.0, FD_SETS("pbd.iterations=1"));
    double y[6] = {0, 0, 0, 0.2, 0.1, 1.6}, y0[6];
    memcpy(y0, y, sizeof y);
    cl_term_pbd.project(st, y, c.dof);
    cr_assert_float_eq(cl_dist(y, y + 3), 1.0, 1e-14);
    for (int i = 0; i < 3; i++) {
        double da = y[i] - y0[i], db = y[3 + i] - y0[3 + i];
        cr_assert_float_eq(0.01 * da + 0.02 * db, 0.0, 1e-16,
                           "momentum-like sum, component %d", i);
        cr_assert(fabs(da) >= fabs(db), "the lighter particle moves more");
    }
    cl_term_pbd.free(st);
    cl_cloth_free(&c);
}

Test(pbd, stiffness_scales_one_correction)
{
    cl_cloth c;
    unequal_cloth(1, 2, no_pins, &c);
    void *st = make_term(&c, 0.0,
                         FD_SETS("pbd.iterations=1", "pbd.stiffness=0.25"));
    double y[6] = {0, 0, 0, 0, 0, 1.8};
    cl_term_pbd.project(st, y, c.dof);
    /* along the pair: d - L shrinks by the factor 1 - K */
    cr_assert_float_eq(cl_dist(y, y + 3) - 1.0, 0.75 * 0.8, 1e-14);
    cl_term_pbd.free(st);
    cl_cloth_free(&c);
}

/* Violation of the term's level-1..2 pairs after each of `sweeps` single
 * sweeps, into viol[0..sweeps] (viol[0]: before). */
static void sweep_history(const cl_cloth *c, void *st, double *x,
                          int sweeps, double *viol)
{
    cl_pairset set;
    cl_error err = {0};
    cr_assert_eq(cl_pairs_levels(c, 2, &set, &err), CL_OK);
    for (int k = 0; k <= sweeps; k++) {
        if (k)
            cl_term_pbd.project(st, x, c->dof);
        double w = 0.0;
        for (size_t i = 0; i < set.n; i++) {
            const cl_pair *p = &set.pair[i];
            w = fmax(w, fabs(cl_dist(x + 3 * p->a, x + 3 * p->b) - p->rest) /
                            p->rest);
        }
        viol[k] = w;
    }
    cl_pairs_free(&set);
}

Test(pbd, sweeps_reduce_the_violation)
{
    cl_cloth c;
    static const int pins[] = {0, 5, -1};
    unequal_cloth(6, 6, pins, &c);
    void *st = make_term(&c, 0.0, FD_SETS("pbd.iterations=1", "pbd.levels=2"));
    double *x = fd_vec(3 * c.np), viol[201];
    jitter(&c, 0.03, 7, x);
    sweep_history(&c, st, x, 200, viol);
    cr_log_info("pbd violation: %.3e, after 1 sweep %.3e, 10: %.3e, "
                "50: %.3e, 200: %.3e", viol[0], viol[1], viol[10], viol[50],
                viol[200]);
    /* monotone-ish: never above the worst of the last ten sweeps */
    for (int k = 10; k <= 200; k++)
        cr_assert_leq(viol[k], viol[k - 10], "sweep %d: %g after %g", k,
                      viol[k], viol[k - 10]);
    cr_assert_lt(viol[10], 0.1 * viol[0]);
    cr_assert_lt(viol[200], 0.02 * viol[0]);
    free(x);
    cl_term_pbd.free(st);
    cl_cloth_free(&c);
}

Test(pbd, pinned_particles_never_move)
{
    cl_cloth c;
    static const int pins[] = {0, 4, 12, 24, -1};
    unequal_cloth(5, 5, pins, &c);
    void *st = make_term(&c, 0.0, FD_SETS("pbd.levels=3"));
    double *x = fd_vec(3 * c.np), *x0 = fd_vec(3 * c.np);
    jitter(&c, 0.05, 11, x);
    memcpy(x0, x, 3 * c.np * sizeof *x);
    cl_term_pbd.project(st, x, c.dof);
    size_t moved = 0;
    for (size_t p = 0; p < c.np; p++) {
        bool same = !memcmp(x + 3 * p, x0 + 3 * p, 3 * sizeof *x);
        if (c.dof[p] < 0)
            cr_assert(same, "pinned particle %zu moved", p);
        moved += !same;
    }
    cr_assert_eq(moved, c.nfree, "every free particle was corrected");
    free(x);
    free(x0);
    cl_term_pbd.free(st);
    cl_cloth_free(&c);
}

Test(pbd, centre_of_mass_of_free_particles_kept)
{
    cl_cloth c;
    unequal_cloth(6, 5, no_pins, &c);
    void *st = make_term(&c, 0.0, FD_SETS("pbd.levels=2", "pbd.stiffness=0.7",
                                          "pbd.iterations=25"));
    double *x = fd_vec(3 * c.np), before[3] = {0}, after[3] = {0}, mt = 0;
    jitter(&c, 0.08, 3, x);
    for (size_t p = 0; p < c.np; p++)
        for (int i = 0; i < 3; i++)
            before[i] += c.mass[p] * x[3 * p + i];
    cl_term_pbd.project(st, x, c.dof);
    for (size_t p = 0; p < c.np; p++) {
        mt += c.mass[p];
        for (int i = 0; i < 3; i++)
            after[i] += c.mass[p] * x[3 * p + i];
    }
    for (int i = 0; i < 3; i++)
        cr_assert_float_eq(after[i] / mt, before[i] / mt, 1e-14,
                           "centre of mass, component %d", i);
    free(x);
    cl_term_pbd.free(st);
    cl_cloth_free(&c);
}

Test(pbd, no_force_jacobian_or_potential)
{
    cl_model *m = FD_MODEL("cloth.n=4", "pins.at=0,0", "type1.enabled=false",
                           "type2.enabled=false", "gravity.g=0,0,0",
                           "pbd.enabled=true", "pbd.levels=3");
    const cl_system *sys = cl_model_system(m);
    cr_assert_not_null(sys->project);
    cr_assert(fd_has_term(m, "pbd"));
    cr_assert_eq(sys->pattern->nnzb, sys->pattern->nb,
                 "diagonal blocks only: constraints add no coupling");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_rng r = {5};
    fd_deform(m, NULL, 0.2, 0.2, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    cl_energy e = fd_eval(m, x, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0);
    cr_assert_eq(e.nterm, 0, "no potential column");
    cr_assert_eq(e.power_diss, 0.0);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(pbd, constraints_tear)
{
    cl_cloth c;
    unequal_cloth(1, 3, no_pins, &c);
    void *st = make_term(&c, 1.5, FD_SETS("pbd.iterations=1"));
    /* pair 0-1 at 2 L, pair 1-2 at rest */
    double x[9] = {0, 0, 0, 0, 0, 1.0, 0, 0, 1.5}, v[9] = {0};
    cr_assert_eq(cl_term_pbd.step_done(st, x, v), 1);
    cr_assert_eq(cl_term_pbd.step_done(st, x, v), 0, "broken only once");
    const int(*pairs)[2];
    cr_assert_eq(cl_term_pbd.broken(st, &pairs), 1);
    cr_assert(pairs[0][0] == 0 && pairs[0][1] == 1);
    double y[9];
    memcpy(y, x, sizeof x);
    cl_term_pbd.project(st, y, c.dof);
    cr_assert_eq(memcmp(x, y, sizeof x), 0, "a torn constraint is inert");
    cl_term_pbd.free(st);
    cl_cloth_free(&c);
}

Test(pbd, bad_options_refused)
{
    static const char *const bad[] = {"pbd.stiffness=0", "pbd.stiffness=1.5",
                                      "pbd.iterations=0", "pbd.levels=0",
                                      "pbd.stiffness=nan", NULL};
    for (size_t k = 0; bad[k]; k++) {
        cl_model *m = NULL;
        cl_error err = {0};
        cr_assert_eq(fd_model_try(FD_SETS("pbd.enabled=true", bad[k]), &m,
                                  &err),
                     CL_EINVAL, "%s accepted", bad[k]);
        cr_assert(strstr(err.msg, "pbd"), "%s: %s", bad[k], err.msg);
        cr_assert_null(m);
    }
}
