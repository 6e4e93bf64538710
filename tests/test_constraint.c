/* Baraff-Witkin constraints (contact/constraint.h; docs/model.md, eqs.
 * C10-C13; docs/integrators.md, 3.4): one particle's filter, velocity
 * change, position correction, release and demotion; after every semi-be
 * and semi-bdf2 step a constrained particle's velocity relative to a
 * moving, turning sphere has no normal part (none at all when it sticks)
 * to round-off; pins expressed as full constraints give the trajectory of
 * pins removed from the system to 1e-12 m; every other integrator refuses
 * a constraint obstacle. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/constraint.h"
#include "integrators/integrator.h"
#include "problem.h"
#include "tmpdir.h"

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* ---- one particle ------------------------------------------------------- */

static const double n_up[3] = {0.0, 0.6, 0.8};

static cl_contact_point contact_at(double d)
{
    cl_contact_point q = {.d = d};
    memcpy(q.n, n_up, sizeof q.n);
    q.u[0] = 0.5; /* the obstacle moves along x */
    return q;
}

Test(constraint, normal_constraint_filters_the_normal_and_corrects_depth)
{
    cl_response_params r = {.kind = CL_RESPONSE_CONSTRAINT, .offset = 0.01};
    cl_contact_point q = contact_at(-0.02);
    const double v[3] = {1.0, -2.0, 0.5};
    cl_constraint c;
    double S[9], z[3], y[3], g[3];
    cl_constraint_start(&r, &q, v, &c, S, z, y, g);
    cr_assert_eq(c.mode, CL_CONSTRAINT_NORMAL);
    double w[3] = {v[0] - 0.5, v[1], v[2]}, wn = dot3(w, n_up);
    for (int i = 0; i < 3; i++) {
        double Sn = dot3(S + 3 * i, n_up);
        cr_assert_float_eq(Sn, 0.0, 1e-15, "S n [%d]", i);
        cr_assert_float_eq(z[i], -wn * n_up[i], 1e-15, "z[%d]", i);
        cr_assert_float_eq(y[i], 0.03 * n_up[i], 1e-15, "y[%d]", i);
        cr_assert_eq(g[i], 0.0);
        /* the new relative velocity (w + z) has no normal part */
    }
    double wz[3] = {w[0] + z[0], w[1] + z[1], w[2] + z[2]};
    cr_assert_float_eq(dot3(wz, n_up), 0.0, 1e-15);
    /* S is the projector onto the tangent plane: S t = t */
    const double t[3] = {0.0, 0.8, -0.6};
    for (int i = 0; i < 3; i++)
        cr_assert_float_eq(dot3(S + 3 * i, t), t[i], 1e-15);
}

Test(constraint, friction_starts_fully_constrained)
{
    cl_response_params r = {.kind = CL_RESPONSE_CONSTRAINT, .mu = 0.4};
    cl_contact_point q = contact_at(0.0);
    const double v[3] = {1.0, -2.0, 0.5};
    cl_constraint c;
    double S[9], z[3], y[3], g[3];
    cl_constraint_start(&r, &q, v, &c, S, z, y, g);
    cr_assert_eq(c.mode, CL_CONSTRAINT_FULL);
    for (int i = 0; i < 9; i++)
        cr_assert_eq(S[i], 0.0);
    cr_assert_float_eq(z[0], -0.5, 1e-15);
    cr_assert_float_eq(z[1], 2.0, 1e-15);
    cr_assert_float_eq(z[2], -0.5, 1e-15);
}

/* A pulling impulse (r . n < 0) frees; a pushing one keeps a normal
 * constraint; a sticking one slides when |r_t| > mu r.n, with the kinetic
 * impulse mu (r . n) r_t / |r_t|. */
Test(constraint, release_and_demotion_follow_the_impulse)
{
    cl_response_params r = {.kind = CL_RESPONSE_CONSTRAINT, .mu = 0.5};
    cl_contact_point q = contact_at(0.0);
    const double v[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.8, -0.6};
    cl_constraint c;
    double S[9], z[3], y[3], g[3], imp[3];
    cl_constraint_start(&r, &q, v, &c, S, z, y, g);
    for (int i = 0; i < 3; i++) /* r.n = 2, |r_t| = 0.9 < mu r.n = 1 */
        imp[i] = 2.0 * n_up[i] + 0.9 * t[i];
    cr_assert_not(cl_constraint_release(0.5, imp, &c, S, z, y, g));
    cr_assert_eq(c.mode, CL_CONSTRAINT_FULL);
    for (int i = 0; i < 3; i++) /* |r_t| = 1.5 > 1: slides */
        imp[i] = 2.0 * n_up[i] + 1.5 * t[i];
    cr_assert(cl_constraint_release(0.5, imp, &c, S, z, y, g));
    cr_assert_eq(c.mode, CL_CONSTRAINT_NORMAL);
    for (int i = 0; i < 3; i++) {
        cr_assert_float_eq(g[i], 1.0 * t[i], 1e-15, "g[%d]", i);
        cr_assert_float_eq(dot3(S + 3 * i, t), t[i], 1e-15);
    }
    cr_assert_not(cl_constraint_release(0.5, imp, &c, S, z, y, g));
    for (int i = 0; i < 3; i++)
        imp[i] = -1e-9 * n_up[i];
    cr_assert(cl_constraint_release(0.5, imp, &c, S, z, y, g));
    cr_assert_eq(c.mode, CL_CONSTRAINT_FREE);
    for (int i = 0; i < 9; i++)
        cr_assert_eq(S[i], (double)(i % 4 == 0));
    for (int i = 0; i < 3; i++)
        cr_assert(z[i] == 0.0 && y[i] == 0.0 && g[i] == 0.0);
}

/* ---- through the integrators -------------------------------------------- */

#define NP 9

/* Nine unconnected particles of 0.1 kg under gravity and a sphere of
 * radius 0.5 at the origin moving at (0.1, 0.2, 0.05) m/s and turning at
 * 2 rad/s about z, response = constraint with friction mu. */
static void sphere_problem(pr_problem *p, char *dir, double mu)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[cloth]\nnu = 3\nnv = 3\nsize = 0.1\nparticle_mass = 0.1\n"
             "[pins]\nat =\n[type1]\nenabled = false\n[type2]\n"
             "enabled = false\n[damping]\nkd = 0\n"
             "[gravity]\ng = 0, -9.81, 0\n"
             "[obstacle.ball]\nshape = sphere\ncenter = 0, 0, 0\n"
             "radius = 0.5\npath = 0: 0, 0, 0; 10: 1, 2, 0.5\n"
             "omega = 0, 0, 2\nresponse = constraint\nmu = %g\n", mu);
    pr_load_text(p, dir, "constraint", text);
}

/* On the sphere within 0.35 rad of its top, sliding across it at 0.3 m/s
 * relative to the obstacle's velocity at the centre, one particle
 * approaching at 1 m/s. */
static void on_sphere(double *x, double *v)
{
    for (int k = 0; k < NP; k++) {
        double th = 0.35 * k / (NP - 1), ph = 0.7 * k;
        double n[3] = {sin(th) * cos(ph), cos(th), sin(th) * sin(ph)};
        double t[3] = {-sin(ph), 0.0, cos(ph)}; /* tangent: n . t = 0 */
        for (int i = 0; i < 3; i++) {
            x[3 * k + i] = 0.5 * n[i];
            v[3 * k + i] = 0.3 * t[i] - (k == 4 ? n[i] : 0.0);
        }
        v[3 * k] += 0.1, v[3 * k + 1] += 0.2, v[3 * k + 2] += 0.05;
    }
}

/* Run `name` in steps of h and check after every step the velocity
 * relative to the sphere of every particle, with n and u of its contact
 * point at the step's start: its normal part is zero (the whole of it
 * when `stuck`). */
static void expect_held(const char *name, double mu, bool stuck)
{
    pr_problem p;
    char dir[512];
    sphere_problem(&p, dir, mu);
    const cl_system *sys = cl_model_system(p.m);
    const cl_obstacle *o = cl_contact_obstacle(cl_model_contact(p.m), 0);
    const double h = 0.01;
    double x[3 * NP], v[3 * NP], worst = 0.0;
    on_sphere(x, v);
    cl_integrator_opts io = {.dt = h};
    void *st = NULL;
    cl_error err = {0};
    const cl_integrator_type *type = cl_integrator_find(name);
    cr_assert_eq(type->create(sys, &io, 0.0, x, v, &st, &err), CL_OK, "%s",
                 err.msg);
    for (int k = 0; k < 20; k++) {
        cl_pose P;
        cl_contact_point q[NP];
        cl_obstacle_pose(o, k * h, &P);
        for (int i = 0; i < NP; i++) {
            cl_obstacle_near(o, &P, x + 3 * i, INFINITY, NULL, &q[i]);
            double w2 = 0.0; /* held within h |w| (contact.c) */
            for (int j = 0; j < 3; j++)
                w2 += pow(v[3 * i + j] - q[i].u[j], 2);
            cr_assert_leq(q[i].d, 1e-9 + (k ? h * sqrt(w2) : 0.0),
                          "%s step %d: particle %d left the sphere (d = %g)",
                          name, k, i, q[i].d);
        }
        cr_assert_eq(type->advance(st, (k + 1) * h, x, v, &err), CL_OK,
                     "%s", err.msg);
        for (int i = 0; i < NP; i++) {
            double w[3];
            for (int j = 0; j < 3; j++)
                w[j] = v[3 * i + j] - q[i].u[j];
            double wn = fabs(dot3(w, q[i].n));
            double wt = sqrt(fmax(0.0, dot3(w, w) - wn * wn));
            worst = fmax(worst, wn);
            cr_assert_leq(wn, 1e-13, "%s step %d particle %d: normal "
                          "relative velocity %g m/s", name, k + 1, i, wn);
            if (stuck)
                cr_assert_leq(wt, 1e-13, "%s step %d particle %d: "
                              "tangential %g m/s", name, k + 1, i, wt);
        }
    }
    type->free(st);
    pr_free(&p);
    tmp_rm_rf(dir);
}

Test(constraint, semi_be_normal_velocity_zero_after_every_step)
{
    expect_held("semi-be", 0.0, false);
}

Test(constraint, semi_be_sliding_with_friction_keeps_the_normal)
{
    expect_held("semi-be", 0.5, false);
}

Test(constraint, semi_be_sticking_removes_all_relative_velocity)
{
    expect_held("semi-be", 1e3, true);
}

Test(constraint, semi_bdf2_normal_velocity_zero_after_every_step)
{
    expect_held("semi-bdf2", 0.0, false);
}

/* ---- pins as constraints ------------------------------------------------ */

#define MAXPIN 8
static int pin_dof[MAXPIN]; /* free index of each pin in the unpinned run */
static size_t npin, nfree;

/* Every particle free but the pins, fully constrained with z = y = g = 0
 * (pins at rest stay so), never released. */
static cl_status pins_as_constraints(void *data, double t, double h,
                                     const double *x, const double *v,
                                     const double *impulse,
                                     cl_constraint_set *cs, bool *changed)
{
    (void)data, (void)t, (void)h, (void)x, (void)v;
    *changed = false;
    if (impulse)
        return CL_OK;
    for (size_t i = 0; i < nfree; i++)
        cl_constraint_none(cs->S + 9 * i, cs->z + 3 * i, cs->y + 3 * i,
                           cs->g + 3 * i);
    for (size_t k = 0; k < npin; k++)
        for (int j = 0; j < 9; j++)
            cs->S[9 * pin_dof[k] + j] = 0.0;
    return CL_OK;
}

/* x at T of `name` (linear solver ls) from the initial state. */
static void run_to(const char *name, const char *ls, const cl_system *sys,
                   const cl_model *m, double T, double *x)
{
    double v[3 * 64];
    cl_integrator_opts io = {.dt = 0.01, .linsol = ls};
    void *st = NULL;
    cl_error err = {0};
    const cl_integrator_type *type = cl_integrator_find(name);
    cl_model_initial_state(m, x, v);
    cr_assert_eq(type->create(sys, &io, 0.0, x, v, &st, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(type->advance(st, T, x, v, &err), CL_OK, "%s", err.msg);
    type->free(st);
}

/* hang on 6 x 6 particles with its two pinned corners, once pinned
 * (removed from the system), once free and fully constrained. */
static void expect_pins_equal(const char *name, const char *ls)
{
    pr_problem pinned, freed;
    pr_load(&pinned, "problems/hang.ini", "cloth.n=6", NULL);
    pr_load(&freed, "problems/hang.ini", "cloth.n=6", "pins.at=");
    const cl_cloth *cp = cl_model_cloth(pinned.m),
                   *cf = cl_model_cloth(freed.m);
    cr_assert_eq(cf->nfree, cp->np);
    npin = 0;
    nfree = cf->nfree;
    for (size_t p = 0; p < cp->np; p++)
        if (cp->dof[p] < 0 && npin < MAXPIN)
            pin_dof[npin++] = cf->dof[p];
    cr_assert_eq(npin, 2);
    cl_system sys = *cl_model_system(freed.m);
    sys.constrain = pins_as_constraints;
    double xp[3 * 64], xf[3 * 64], worst = 0.0;
    run_to(name, ls, cl_model_system(pinned.m), pinned.m, 0.5, xp);
    run_to(name, ls, &sys, freed.m, 0.5, xf);
    for (size_t p = 0; p < cp->np; p++) {
        int ip = cp->dof[p], jf = cf->dof[p];
        for (int i = 0; i < 3; i++) {
            double want = ip >= 0 ? xp[3 * ip + i] : cp->X0[3 * p + i];
            worst = fmax(worst, fabs(xf[3 * jf + i] - want));
        }
    }
    cr_assert_leq(worst, 1e-12, "%s/%s: constrained pins differ from "
                  "removed ones by %g m", name, ls, worst);
    pr_free(&pinned);
    pr_free(&freed);
}

Test(constraint, pins_as_full_constraints_equal_removed_pins_klu)
{
    expect_pins_equal("semi-be", "klu");
    expect_pins_equal("semi-bdf2", "klu");
}

Test(constraint, pins_as_full_constraints_equal_removed_pins_pcg)
{
    expect_pins_equal("semi-be", "pcg");
    expect_pins_equal("semi-bdf2", "pcg");
}

/* ---- the rule ----------------------------------------------------------- */

Test(constraint, every_other_integrator_refuses_constraints)
{
    pr_problem p;
    char dir[512];
    sphere_problem(&p, dir, 0.0);
    const cl_system *sys = cl_model_system(p.m);
    double x[3 * NP], v[3 * NP];
    on_sphere(x, v);
    cl_integrator_opts io = {.dt = 1e-3, .rtol = 1e-6, .atol = 1e-8};
    size_t refused = 0, k = 0;
    for (; cl_integrator_registry[k]; k++) {
        const cl_integrator_type *t = cl_integrator_registry[k];
        void *st = NULL;
        cl_error err = {0};
        cl_status rc = t->create(sys, &io, 0.0, x, v, &st, &err);
        if (!strcmp(t->name, "semi-be") || !strcmp(t->name, "semi-bdf2")) {
            cr_expect_eq(rc, CL_OK, "%s: %s", t->name, err.msg);
            t->free(st);
            continue;
        }
        cr_expect_eq(rc, CL_EUNSUPPORTED, "%s accepted constraints",
                     t->name);
        cr_expect(strstr(err.msg, "response = constraint") &&
                      strstr(err.msg, t->name),
                  "%s: %s", t->name, err.msg);
        cr_expect_null(st);
        refused++;
    }
    cr_expect_eq(refused, k - 2, "%zu of %zu refused", refused, k);
    pr_free(&p);
    tmp_rm_rf(dir);
}
