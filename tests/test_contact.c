/* Contact on whole problems (contact/contact.h through the model): a
 * particle dropped on a plane (projection: never below the offset;
 * penalty: at rest m g / k inside the band), a block on an inclined plane
 * (slides with a = g (sin theta - mu cos theta), sticks when
 * mu > tan theta) with either response, the energy balance with contact
 * and friction, the refusal of projection by the methods that cannot
 * apply it, the contact hook's worst penetration, cvode-bdf's outputs,
 * worst penetration and step limit with projection, and continuous
 * detection (ccd) stopping a fast particle at a thin box and a small fast
 * sphere catching a particle, which pass through with it off; the
 * barrier: the filter of a straight move, a start inside it refused, a
 * particle dropped on a barrier plane kept outside by kinsol-be and by
 * cvode-bdf, and the energy balance with the barrier and its friction. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/energy_balance.h"
#include "contact/barrier.h"
#include "integrators/integrator.h"
#include "problem.h"
#include "tmpdir.h"

/* Two free, unconnected particles of 0.1 kg (a 1 x 2 grid without force
 * terms) that move alike, gravity 9.81 and the obstacle lines `obstacle`
 * (an [obstacle.floor] section body). */
static void particle(pr_problem *p, char *dir, const char *obstacle)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[cloth]\nnu = 1\nnv = 2\nsize = 0.1\nparticle_mass = 0.1\n"
             "[pins]\nat =\n[type1]\nenabled = false\n[type2]\n"
             "enabled = false\n[damping]\nkd = 0\n"
             "[gravity]\ng = 0, -9.81, 0\n"
             "[obstacle.floor]\n%s\n", obstacle);
    pr_load_text(p, dir, "contact", text);
}

/* Run `name` from x0 (at rest) to T in `steps` output steps; the lowest
 * signed height above the plane through 0 with normal nrm at any output
 * and the final position; the heights at the outputs in height[1..steps]
 * if not NULL. */
static double run_particle_heights(pr_problem *p, const char *name,
                                   const cl_integrator_opts *io,
                                   const double x0[3], double T, long steps,
                                   const double nrm[3], double x[3],
                                   double *height)
{
    const cl_system *sys = cl_model_system(p->m);
    const cl_integrator_type *type = cl_integrator_find(name);
    double xs[6], v[6] = {0.0}, low = INFINITY;
    void *st = NULL;
    cl_error err = {0};
    cl_model_initial_state(p->m, xs, v);
    for (int i = 0; i < 3; i++) /* both particles start at x0 + offset */
        xs[3 + i] = x0[i] + xs[3 + i] - xs[i], xs[i] = x0[i];
    cr_assert_eq(type->create(sys, io, 0.0, xs, v, &st, &err), CL_OK, "%s: %s",
                 name, err.msg);
    for (long k = 1; k <= steps; k++) {
        cr_assert_eq(type->advance(st, T * (double)k / (double)steps, xs, v,
                                   &err), CL_OK, "%s: %s", name, err.msg);
        double h = xs[0] * nrm[0] + xs[1] * nrm[1] + xs[2] * nrm[2];
        low = fmin(low, h);
        if (height)
            height[k] = h;
    }
    memcpy(x, xs, 3 * sizeof *x);
    type->free(st);
    return low;
}

static double run_particle(pr_problem *p, const char *name,
                           const cl_integrator_opts *io, const double x0[3],
                           double T, long steps, const double nrm[3],
                           double x[3])
{
    return run_particle_heights(p, name, io, x0, T, steps, nrm, x, NULL);
}

static const double up[3] = {0.0, 1.0, 0.0};

Test(contact, dropped_on_a_plane_with_projection_stays_above_the_offset)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, "shape = plane\nnormal = 0, 1, 0\n"
                            "response = project\noffset = 0.01");
    const double x0[3] = {0.0, 0.5, 0.0};
    double x[3];
    cl_integrator_opts io = {.dt = 1e-3};
    const char *names[] = {"symplectic-euler", "semi-be", "kinsol-bdf2",
                           "verlet"};
    for (size_t k = 0; k < 4; k++) {
        double low = run_particle(&p, names[k], &io, x0, 1.0, 1000, up, x);
        cr_expect_geq(low, 0.01 - 1e-12, "%s: lowest %.17g", names[k], low);
        cr_expect_lt(fabs(x[1] - 0.01), 1e-9, "%s: rests at %.17g",
                     names[k], x[1]);
    }
    cl_integrator_opts cv = {.rtol = 1e-6, .atol = 1e-8};
    double low = run_particle(&p, "cvode-bdf", &cv, x0, 1.0, 200, up, x);
    cr_expect_geq(low, 0.01 - 1e-12, "cvode-bdf: lowest %.17g", low);
    cr_expect_lt(fabs(x[1] - 0.01), 1e-9, "cvode-bdf: rests at %.17g", x[1]);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* cvode-bdf projecting a particle dropped from 0.5 m onto the plane
 * (impact at t = sqrt(2 0.5 / g) = 0.31928 s), outputs every millisecond:
 * they are ends of steps (CVODE's stop time), so until the impact they
 * follow the free fall (outputs interpolated across the projected step of
 * the impact had the particle slow down in mid-air), and the worst
 * penetration is that of the accepted step before its projection: the
 * step to 0.320 s, whose end falls 0.5 - g 0.32^2 / 2 = -2.272e-3 m (it
 * was not recorded at all). */
Test(contact, cvode_bdf_projection_outputs_are_steps_ends)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, "shape = plane\nnormal = 0, 1, 0\nresponse = project");
    const double x0[3] = {0.0, 0.5, 0.0}, g = 9.81;
    double x[3], height[1001], pen, t_pen;
    cl_integrator_opts cv = {.rtol = 1e-8, .atol = 1e-10};
    cl_model_contact_start(p.m, 0.0, false);
    run_particle_heights(&p, "cvode-bdf", &cv, x0, 1.0, 1000, up, x, height);
    for (long k = 1; k <= 319; k++) {
        double t = 1e-3 * (double)k, fall = 0.5 - 0.5 * g * t * t;
        cr_assert_float_eq(height[k], fall, 1e-6, "t = %g: %.9g, free fall "
                           "%.9g", t, height[k], fall);
    }
    cl_model_contact_worst(p.m, &pen, &t_pen);
    cr_expect_float_eq(pen, 0.5 * g * 0.32 * 0.32 - 0.5, 1e-6,
                       "worst penetration %.9g", pen);
    cr_expect_float_eq(t_pen, 0.32, 1e-12, "at t = %.17g", t_pen);
    cr_expect_lt(fabs(x[1]), 1e-9, "rests at %.17g", x[1]);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* Stepping one step at a time, cvode-bdf with projection still stops at
 * max_steps steps an advance (CVODE counts its limit per call): the drop
 * to 1 s in one output takes 21 steps. */
Test(contact, cvode_bdf_projection_keeps_the_step_limit)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, "shape = plane\nnormal = 0, 1, 0\nresponse = project");
    const cl_system *sys = cl_model_system(p.m);
    const cl_integrator_type *type = cl_integrator_find("cvode-bdf");
    double xs[6], v[6] = {0.0};
    cl_model_initial_state(p.m, xs, v);
    xs[1] = xs[4] = 0.5;
    for (long limit = 5; limit <= 500; limit *= 100) {
        cl_integrator_opts io = {.rtol = 1e-8, .atol = 1e-10,
                                 .max_steps = limit};
        void *st = NULL;
        cl_error err = {0};
        double x[6], w[6];
        memcpy(x, xs, sizeof x);
        memcpy(w, v, sizeof w);
        cr_assert_eq(type->create(sys, &io, 0.0, x, w, &st, &err), CL_OK,
                     "%s", err.msg);
        cl_status rc = type->advance(st, 1.0, x, w, &err);
        if (limit == 5) {
            cr_expect_eq(rc, CL_ESOLVER, "%ld steps: %s", limit, err.msg);
            cr_expect_not_null(strstr(err.msg, "CV_TOO_MUCH_WORK"), "%s",
                               err.msg);
        } else {
            cr_expect_eq(rc, CL_OK, "%ld steps: %s", limit, err.msg);
        }
        type->free(st);
    }
    pr_free(&p);
    tmp_rm_rf(dir);
}

Test(contact, penalty_rest_depth_is_m_g_over_k)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, "shape = plane\nnormal = 0, 1, 0\n"
                            "response = penalty\nk = 2000\neps = 0.01\n"
                            "damping = 20");
    const double x0[3] = {0.0, 0.2, 0.0}, depth = 0.1 * 9.81 / 2000;
    double x[3];
    cl_integrator_opts cv = {.rtol = 1e-8, .atol = 1e-10};
    run_particle(&p, "cvode-bdf", &cv, x0, 3.0, 10, up, x);
    /* at rest the damping is idle: the depth is CVODE's to its tolerance
     * (4e-11 relative measured), backward Euler's to round-off (1e-14) */
    cr_expect_lt(fabs((0.01 - x[1]) - depth), 1e-8 * depth,
                 "rest at %.9g below the band's edge, m g / k = %.9g",
                 0.01 - x[1], depth);
    cl_integrator_opts se = {.dt = 1e-3};
    run_particle(&p, "semi-be", &se, x0, 3.0, 10, up, x);
    cr_expect_lt(fabs((0.01 - x[1]) - depth), 1e-11 * depth, "semi-be: %.9g",
                 0.01 - x[1]);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* A block on a 30 degree slope (the plane through 0 tilted about z):
 * the distance it slides along the slope in T = 1 s from rest. */
static double slide(const char *response, double mu, const char *name,
                    const cl_integrator_opts *io, double x0_depth)
{
    pr_problem p;
    char dir[512], body[512];
    double th = M_PI / 6, n[3] = {-sin(th), cos(th), 0.0};
    snprintf(body, sizeof body,
             "shape = plane\nnormal = %.17g, %.17g, 0\nresponse = %s\n"
             "mu = %g\n%s", n[0], n[1], response, mu,
             !strcmp(response, "penalty")
                 ? "k = 10000\neps = 0.01\ndamping = 50\nv_smooth = 1e-4"
                 : "");
    particle(&p, dir, body);
    double x0[3] = {x0_depth * n[0], x0_depth * n[1], 0.0}, x[3];
    run_particle(&p, name, io, x0, 1.0, 100, n, x);
    pr_free(&p);
    tmp_rm_rf(dir);
    double down[3] = {-cos(th), -sin(th), 0.0};
    return (x[0] - x0[0]) * down[0] + (x[1] - x0[1]) * down[1];
}

Test(contact, block_on_a_slope_slides_with_coulomb_friction)
{
    double th = M_PI / 6, mu = 0.3;
    double s = 0.5 * 9.81 * (sin(th) - mu * cos(th)); /* 1/2 a T^2 */
    cl_integrator_opts se = {.dt = 1e-4};
    double got = slide("project", mu, "symplectic-euler", &se, 0.0);
    /* first order in h: 3.2e-4 relative at h = 1e-4 */
    cr_expect_lt(fabs(got - s), 1e-3 * s, "project: %.6g m, expected %.6g",
                 got, s);
    cl_integrator_opts cv = {.rtol = 1e-8, .atol = 1e-10};
    double eq = 0.01 - 0.1 * 9.81 * cos(th) / 10000; /* at rest depth */
    got = slide("penalty", mu, "cvode-bdf", &cv, eq);
    /* the band's smoothing and damping: 6.6e-5 relative */
    cr_expect_lt(fabs(got - s), 2e-4 * s, "penalty: %.6g m, expected %.6g",
                 got, s);
}

/* Projection keeps a sticking particle's velocity at 0; what remains is
 * the position step's own tangential part, h^2 g sin theta a step, which
 * a projection along the normal does not undo: a creep at h g sin theta,
 * first order in h (docs/model.md 4.5, after the fixed-step rule). */
Test(contact, block_on_a_slope_sticks_when_mu_exceeds_tan_theta)
{
    double th = M_PI / 6, mu = 1.2 * tan(th), h = 1e-4;
    double creep_h = 1.0 * h * 9.81 * sin(th); /* T h g sin theta */
    cl_integrator_opts se = {.dt = h};
    double got = slide("project", mu, "symplectic-euler", &se, 0.0);
    cr_expect_lt(fabs(got - creep_h), 1e-6 * creep_h,
                 "project: slid %.9g m, the step's creep %.9g m", got,
                 creep_h);
    got = slide("project", tan(th) * (1 + 1e-9), "symplectic-euler", &se,
                0.0);
    cr_expect_lt(fabs(got - creep_h), 1e-2 * creep_h,
                 "project at mu = tan theta: slid %.9g m", got);
    cl_integrator_opts cv = {.rtol = 1e-8, .atol = 1e-10};
    double eq = 0.01 - 0.1 * 9.81 * cos(th) / 10000;
    got = slide("penalty", mu, "cvode-bdf", &cv, eq);
    /* smoothed Coulomb: creeps at about v_s tan / sqrt(mu^2 - tan^2) */
    double creep = 1e-4 * tan(th) / sqrt(mu * mu - tan(th) * tan(th));
    cr_expect_lt(fabs(got - creep), 1e-2 * creep, "penalty: slid %.4g m "
                 "(creep %.4g m/s)", got, creep);
}

/* The projections' energy change enters W: velocity Verlet is exact for a
 * particle under gravity alone, so the balance of a particle thrown onto
 * a slope with friction closes to round-off. */
Test(contact, energy_balance_closes_with_projection_and_friction)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, "shape = plane\nnormal = -0.3, 1, 0\n"
                      "point = 0, -0.5, 0\nresponse = project\nmu = 0.4");
    cl_ebal_result r;
    cl_error err = {0};
    cl_integrator_opts io = {.dt = 1e-3};
    cr_assert_eq(cl_ebal_run(p.m, cl_integrator_find("velocity-verlet"), &io,
                             1.0, 1000, 10.0, &r, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(r.rc, CL_OK, "%s", r.why.msg);
    const cl_ebal_sample *e = &r.s[r.n - 1];
    cr_log_info("E(0) %.9g E(T) %.9g W %.9g max|B| %.3e", r.s[0].total,
                e->total, e->dissipated, r.balance_max);
    cr_expect_lt(e->dissipated, -0.1 * r.scale, "the slope took energy");
    cr_expect_lt(r.balance_max, 1e-12 * r.scale, "max |B| = %.3g",
                 r.balance_max);
    cl_ebal_free(&r);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* Penalty, damping and friction on a cloth falling onto a sphere: a tight
 * cvode-bdf run closes the balance.  The normal damping's power jumps
 * where a particle enters the band, so the trapezoidal W converges at
 * about first order in the sample spacing: measured max |B| / S = 7.3e-3,
 * 8.3e-4, 7.6e-5 with 1000, 6000, 24000 samples; without damping and
 * friction 6e-8. */
/* A 5 x 5 cloth falling onto a sphere with the response `keys`, a tight
 * cvode-bdf run with `samples` samples to 0.6 s: max |B| < bound S, and
 * W < dissipated S when dissipated < 0. */
static void sphere_drop_balance(const char *keys, long samples, double bound,
                                double dissipated)
{
    char dir[512], path[600], text[1024];
    tmp_mkdtemp(dir, sizeof dir, "contact");
    snprintf(path, sizeof path, "%s/drop.ini", dir);
    snprintf(text, sizeof text,
             "[cloth]\nn = 5\nsize = 1\nmass = 0.1\n[pins]\nat =\n"
             "[type2]\nenabled = false\n[damping]\nkd = 0\n"
             "[obstacle.ball]\nshape = sphere\ncenter = 0.5, -0.3, 0.5\n"
             "radius = 0.25\n%s", keys);
    tmp_put(path, text);
    pr_problem p;
    pr_load(&p, path, NULL, NULL);
    cl_ebal_result r;
    cl_error err = {0};
    cl_integrator_opts io = {.rtol = 1e-9, .atol = 1e-11};
    cr_assert_eq(cl_ebal_run(p.m, cl_integrator_find("cvode-bdf"), &io, 0.6,
                             samples, 10.0, &r, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(r.rc, CL_OK, "%s", r.why.msg);
    const cl_ebal_sample *e = &r.s[r.n - 1];
    cr_log_info("E(0) %.9g E(T) %.9g W %.9g max|B| %.3e S %.3g",
                r.s[0].total, e->total, e->dissipated, r.balance_max,
                r.scale);
    if (dissipated < 0.0)
        cr_expect_lt(e->dissipated, dissipated * r.scale,
                     "contact dissipated");
    cr_expect_lt(r.balance_max, bound * r.scale, "max |B| = %.3g",
                 r.balance_max);
    cl_ebal_free(&r);
    pr_free(&p);
    tmp_rm_rf(dir);
}

Test(contact, energy_balance_closes_with_penalty_and_friction)
{
    sphere_drop_balance("response = penalty\nk = 200\neps = 0.01\n"
                        "damping = 0.2\nmu = 0.3\nv_smooth = 0.05\n",
                        24000, 2e-4, -1e-3);
}

Test(contact, projection_refused_by_methods_that_cannot_apply_it)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, "shape = plane\nnormal = 0, 1, 0\nresponse = project");
    const cl_system *sys = cl_model_system(p.m);
    double x[6] = {0.0, 1.0, 0.0, 0.0, 1.0, 0.1}, v[6] = {0.0};
    cl_integrator_opts io = {.rtol = 1e-6, .atol = 1e-8};
    const char *names[] = {"ida", "cvode-adams", "gsl-rk8pd", "gsl-msbdf"};
    for (size_t k = 0; k < 4; k++) {
        void *st = NULL;
        cl_error err = {0};
        cr_expect_eq(cl_integrator_find(names[k])->create(sys, &io, 0.0, x, v,
                                                          &st, &err),
                     CL_EUNSUPPORTED, "%s accepted projection", names[k]);
        cr_expect(strstr(err.msg, "response = project") &&
                      strstr(err.msg, names[k]),
                  "%s: %s", names[k], err.msg);
        cr_expect_null(st);
    }
    pr_free(&p);
    tmp_rm_rf(dir);
    /* CVODE BDF projects, but not with friction */
    particle(&p, dir, "shape = plane\nnormal = 0, 1, 0\nresponse = project\n"
                      "mu = 0.2");
    void *st = NULL;
    cl_error err = {0};
    cr_expect_eq(cl_integrator_find("cvode-bdf")->create(
                     cl_model_system(p.m), &io, 0.0, x, v, &st, &err),
                 CL_EUNSUPPORTED);
    cr_expect(strstr(err.msg, "friction"), "%s", err.msg);
    cr_expect_null(st);
    pr_free(&p);
    tmp_rm_rf(dir);
}

#define BARRIER_FLOOR "shape = plane\nnormal = 0, 1, 0\nresponse = barrier\n" \
                      "kappa = 1000\ndhat = 0.01\n"

/* Two particles 0.3 m above the barrier plane y = 0 moving to 0.1 m
 * below it reach it at 3/4 of the move: the filter allows 0.8 * 0.75. */
Test(contact, barrier_filter_is_the_safety_fraction_of_the_impact)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, BARRIER_FLOOR);
    const cl_system *sys = cl_model_system(p.m);
    cr_assert_not_null(sys->step_fraction);
    double x0[6] = {0.0, 0.3, 0.0, 0.1, 0.3, 0.0};
    double x1[6] = {0.2, -0.1, 0.1, 0.1, 0.2, 0.0};
    cr_expect_float_eq(sys->step_fraction(sys->data, 0.0, x0, 0.1, x1),
                       0.8 * 0.75, 1e-15);
    x1[1] = 0.05;
    cr_expect_eq(sys->step_fraction(sys->data, 0.0, x0, 0.1, x1), 1.0);
    double inside[6] = {0.0, -1e-3, 0.0, 0.1, 0.3, 0.0}, v[6] = {0}, f[6];
    cr_expect_eq(sys->force(sys->data, 0.0, inside, v, f), CL_EINFEASIBLE);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* Both particles of particle() with the obstacle `obstacle` + "ccd = ccd",
 * from x0 (the second 0.1 m along z) with velocity v0, by symplectic Euler
 * in `steps` steps of 0.01 s; the first particle's x and v at the end. */
static void fly(const char *obstacle, bool ccd, const double x0[3],
                const double v0[3], int steps, double x[3], double v[3])
{
    pr_problem p;
    char dir[512], body[512];
    snprintf(body, sizeof body, "%s\nccd = %s", obstacle,
             ccd ? "true" : "false");
    particle(&p, dir, body);
    cl_model_contact_start(p.m, 0.0, false);
    const cl_system *sys = cl_model_system(p.m);
    double xs[6], vs[6];
    for (int i = 0; i < 3; i++) {
        xs[i] = xs[3 + i] = x0[i];
        vs[i] = vs[3 + i] = v0[i];
    }
    xs[5] += 0.1;
    cl_integrator_opts io = {.dt = 0.01};
    const cl_integrator_type *type = cl_integrator_find("symplectic-euler");
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(type->create(sys, &io, 0.0, xs, vs, &st, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(type->advance(st, 0.01 * steps, xs, vs, &err), CL_OK, "%s",
                 err.msg);
    memcpy(x, xs, 3 * sizeof *x);
    memcpy(v, vs, 3 * sizeof *v);
    type->free(st);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* Dropped from 0.2 m at rest onto the barrier plane (m = 0.1 kg, 2 m/s
 * at the plane): the particle never reaches it, with kinsol-be and
 * kinsol-bdf2 (dt = 0.02: 4 cm a step, 4 dhat; the filtered Newton loop),
 * semi-be and semi-bdf2 (the filtered step), cvode-bdf (steps leaving
 * the feasible set retried smaller) and kinsol-midpoint (dt = 0.005; its
 * end point filtered too); with kinsol-be it comes to rest
 * where kappa (-b'(d)) = m g. */
Test(contact, barrier_keeps_a_dropped_particle_outside)
{
    const char *names[6] = {"kinsol-be", "kinsol-bdf2", "semi-be",
                            "semi-bdf2", "cvode-bdf", "kinsol-midpoint"};
    cl_integrator_opts io[6] = {{.dt = 0.02}, {.dt = 0.02}, {.dt = 0.02},
                                {.dt = 0.02}, {.rtol = 1e-6, .atol = 1e-9},
                                {.dt = 0.005}};
    for (int k = 0; k < 6; k++) {
        pr_problem p;
        char dir[512];
        particle(&p, dir, BARRIER_FLOOR);
        cl_model_contact_start(p.m, 0.0, false);
        double x0[3] = {0.0, 0.2, 0.0}, x[3], dmin, tmin;
        double low = run_particle(&p, names[k], &io[k], x0, 2.0, 100, up, x);
        cl_model_contact_closest(p.m, &dmin, &tmin);
        cr_log_info("%s: lowest %.6g m, min distance %.6g m at %.3g s, "
                    "final %.6g m", names[k], low, dmin, tmin, x[1]);
        cr_expect_gt(low, 0.0, "%s: reached the plane", names[k]);
        cr_expect_gt(dmin, 0.0, "%s", names[k]);
        cr_expect_leq(dmin, low, "%s: the hook saw every output", names[k]);
        if (k == 0) /* backward Euler damps the bounce away */
            cr_expect_float_eq(
                cl_barrier_lambda(
                    &cl_contact_obstacle(cl_model_contact(p.m), 0)->resp,
                    x[1]),
                0.1 * 9.81, 1e-3, "%s: at rest", names[k]);
        pr_free(&p);
        tmp_rm_rf(dir);
    }
}

/* The midpoint rule evaluates at the middle of its step; its end point,
 * twice as far from x_n, is filtered too.  At dt = 0.02 the bounce has no
 * feasible midpoint step (the end point of the step's exact solution lies
 * inside): the step fails as a solver failure instead of being accepted
 * with its end inside the plane (unfiltered, step 32 ended 4.1 mm inside;
 * the next step's first evaluation was infeasible). */
Test(contact, barrier_midpoint_never_accepts_an_end_inside)
{
    pr_problem p;
    char dir[512];
    particle(&p, dir, BARRIER_FLOOR);
    cl_model_contact_start(p.m, 0.0, false);
    const cl_system *sys = cl_model_system(p.m);
    const cl_integrator_type *type = cl_integrator_find("kinsol-midpoint");
    cl_integrator_opts io = {.dt = 0.02};
    double xs[6], v[6] = {0.0};
    void *st = NULL;
    cl_error err = {0};
    cl_model_initial_state(p.m, xs, v);
    xs[4] += 0.2 - xs[1];
    xs[1] = 0.2;
    cr_assert_eq(type->create(sys, &io, 0.0, xs, v, &st, &err), CL_OK, "%s",
                 err.msg);
    cl_status rc = CL_OK;
    long k = 1;
    for (; k <= 100 && rc == CL_OK; k++) {
        rc = type->advance(st, 0.02 * (double)k, xs, v, &err);
        if (rc == CL_OK)
            cr_expect_gt(xs[1], 0.0, "step %ld ended inside: %.6g m", k,
                         xs[1]);
    }
    cr_log_info("kinsol-midpoint, dt = 0.02: %ld steps, then %s", k - 1,
                rc == CL_OK ? "done" : err.msg);
    cr_expect(rc == CL_OK || rc == CL_ESOLVER, "%s", err.msg);
    type->free(st);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* A start 1e-4 m inside the barrier plane is refused before the first
 * step by every family (it was reported as a blow-up at t = 0 or as a
 * failed force evaluation, depending on the method), and so is a start on
 * the surface (d = 0); 1e-4 m outside is taken. */
Test(contact, barrier_start_inside_is_refused)
{
    const char *names[] = {"symplectic-euler", "rk4", "semi-be", "cvode-bdf",
                           "ida", "kinsol-galpha"};
    const double heights[3] = {-1e-4, 0.0, 1e-4};
    pr_problem p;
    char dir[512];
    particle(&p, dir, BARRIER_FLOOR);
    const cl_system *sys = cl_model_system(p.m);
    for (size_t k = 0; k < sizeof names / sizeof *names; k++)
        for (int h = 0; h < 3; h++) {
            const cl_integrator_type *type = cl_integrator_find(names[k]);
            cl_integrator_opts io = {.dt = 1e-3, .rtol = 1e-6, .atol = 1e-9};
            double xs[6], v[6] = {0.0};
            void *st = NULL;
            cl_error err = {0};
            cl_model_initial_state(p.m, xs, v);
            xs[1] = xs[4] = heights[h];
            cl_status rc = cl_integrator_create(type, sys, &io, 0.0, xs, v,
                                                &st, &err);
            if (h < 2) {
                cr_expect_eq(rc, CL_EINVAL, "%s at %g: %s", names[k],
                             heights[h], err.msg);
                cr_expect_not_null(strstr(err.msg, "barrier obstacle"),
                                   "%s", err.msg);
            } else {
                cr_expect_eq(rc, CL_OK, "%s: %s", names[k], err.msg);
            }
            if (st)
                type->free(st);
        }
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* A cloth falling onto a barrier sphere, cvode-bdf tight: the barrier
 * energy is the contact column of the balance and the lagged friction's
 * power its dissipation.  The friction's normal force is lagged at every
 * output (adaptive methods restart there), so its power jumps at the
 * samples and the trapezoidal W converges at first order in the sample
 * spacing: measured max |B| / S = 6.3e-2 and 9.1e-3 with 1000 and 6000
 * samples; without friction 3.1e-7 with 600. */
Test(contact, energy_balance_closes_with_barrier)
{
    sphere_drop_balance("response = barrier\nkappa = 1000\ndhat = 0.02\n",
                        600, 1e-6, 0.0);
}

Test(contact, energy_balance_closes_with_barrier_and_friction)
{
    sphere_drop_balance("response = barrier\nkappa = 1000\ndhat = 0.02\n"
                        "mu = 0.3\neps_v = 0.05\n",
                        6000, 2e-2, -0.1);
}

/* 100 m/s toward a box 1 mm thick, 0.45 m ahead: one step of 0.01 s
 * carries the particle 0.55 m past it.  With detection it stops on the
 * near face, x = 0.5 - 0.0005, its normal velocity removed; without, the
 * discrete check finds it outside at the end of every step. */
Test(contact, continuous_detection_stops_a_fast_particle_at_a_thin_box)
{
    const char *box = "shape = box\ncenter = 0.5, 1, 0\nsize = 0.001, 1, 1\n"
                      "response = project";
    const double x0[3] = {0.05, 1, 0}, v0[3] = {100, 0, 0};
    double x[3], v[3];
    fly(box, true, x0, v0, 3, x, v);
    cr_assert_float_eq(x[0], 0.4995, 1e-12, "stopped at x = %.17g", x[0]);
    cr_assert_eq(v[0], 0.0, "vx = %g", v[0]);
    fly(box, false, x0, v0, 3, x, v);
    cr_assert_float_eq(x[0], 3.05, 1e-12, "passed through to %.17g", x[0]);
    cr_assert_eq(v[0], 100.0);
}

/* A sphere of radius 1 cm at 50 m/s along x (its path), 0.25 m from a
 * particle at rest at t = 0.01 s and 0.25 m past it at 0.02 s: with
 * detection the relative path hits the sphere's front at s = 0.48 and the
 * particle is carried along in front of it (x = 0.5 + 0.01 at 0.02 s,
 * moving with it); without, it stays where it was (x; it falls). */
Test(contact, continuous_detection_catches_a_small_fast_sphere)
{
    const char *ball = "shape = sphere\ncenter = 0, 1, 0\nradius = 0.01\n"
                       "path = 0: -0.5, 0, 0; 1: 49.5, 0, 0\n"
                       "response = project";
    const double x0[3] = {0.25, 1, 0}, v0[3] = {0, 0, 0};
    double x[3], v[3];
    fly(ball, true, x0, v0, 2, x, v);
    cr_assert_float_eq(x[0], 0.51, 2e-3, "carried to x = %.17g", x[0]);
    /* the normal at the hit leans 0.2 rad down (the particle has fallen
     * 2 mm by then): vx = 50 cos^2 of it */
    cr_assert(v[0] > 47.0 && v[0] <= 50.0, "vx = %g", v[0]);
    fly(ball, false, x0, v0, 2, x, v);
    cr_assert_float_eq(x[0], 0.25, 1e-15, "x = %.17g", x[0]);
    cr_assert_eq(v[0], 0.0);
}

/* A run's start forgets every particle's memo of its distances: a memo
 * left at |x| ~ 1e78 (where a run that blew up ends) screened the sphere
 * out of the next run's forces.  The force at a state inside the sphere
 * after such an evaluation and a restart is a fresh model's. */
Test(contact, restart_forgets_the_memos)
{
    char dir[512];
    pr_problem p;
    tmp_mkdtemp(dir, sizeof dir, "contact");
    particle(&p, dir, "shape = sphere\ncenter = 0, 0, 0\nradius = 0.5\n"
                      "response = penalty\nk = 1000\n");
    const cl_system *sys = cl_model_system(p.m);
    double inside[6] = {0.0, 0.45, 0.0, 0.1, 0.43, 0.0};
    double far[6] = {1e78, 1e78, 0.0, -1e78, 1e78, 0.0};
    double v[6] = {0.0}, fresh[6], f[6];
    cl_model_contact_start(p.m, 0.0, false);
    cr_assert_eq(sys->force(sys->data, 0.0, inside, v, fresh), CL_OK);
    cr_assert_gt(fresh[1], 0.0, "pushed out: %g", fresh[1]);
    (void)sys->force(sys->data, 0.0, far, v, f);
    cl_model_contact_start(p.m, 0.0, false);
    cr_assert_eq(sys->force(sys->data, 0.0, inside, v, f), CL_OK);
    for (int i = 0; i < 6; i++)
        cr_assert_eq(f[i], fresh[i], "entry %d: %g against %g", i, f[i],
                     fresh[i]);
    pr_free(&p);
    tmp_rm_rf(dir);
}

/* A run that starts at t0 != 0 (a program of one's own may start its
 * integrator anywhere) tells the contact layer its start
 * (cl_model_contact_start): the first projection's continuous detection
 * sweeps that step only.  A particle at x = 1 flying away from a ccd
 * sphere (centre x = 0.5, radius 0.1) at 1 m/s flies on from t0 = 1 as
 * from 0 (before, the first sweep reached back to t = 0, through the
 * sphere, and stopped the particle on it at x = 0.4). */
Test(contact, a_run_from_t0_sweeps_its_own_first_step)
{
    pr_problem p;
    char dir[512];
    pr_load_text(&p, dir, "ccd",
                 "[cloth]\nnu = 2\nnv = 1\nsize = 1.0\n"
                 "particle_mass = 0.1\n[pins]\nat = 0,0\n[init]\n"
                 "velocity = 1, 0, 0\n[type1]\nenabled = false\n[type2]\n"
                 "enabled = false\n[damping]\nkd = 0\n[gravity]\n"
                 "g = 0, 0, 0\n[obstacle.ball]\nshape = sphere\n"
                 "center = 0.5, 0, 0\nradius = 0.1\nresponse = project\n"
                 "ccd = true\n");
    const cl_system *sys = cl_model_system(p.m);
    const cl_integrator_type *it = cl_integrator_find("symplectic-euler");
    cl_integrator_opts o = {.dt = 1e-3};
    cr_assert_eq(sys->n, 3);
    for (double t0 = 0.0; t0 <= 1.0; t0 += 1.0) {
        double x[3], v[3];
        void *st = NULL;
        cl_error err = {0};
        cl_model_initial_state(p.m, x, v);
        cr_assert_float_eq(x[0], 1.0, 1e-15);
        cl_model_contact_start(p.m, t0, false);
        cr_assert_eq(it->create(sys, &o, t0, x, v, &st, &err), CL_OK, "%s",
                     err.msg);
        cr_assert_eq(it->advance(st, t0 + 0.01, x, v, &err), CL_OK, "%s",
                     err.msg);
        it->free(st);
        cr_assert_float_eq(x[0], 1.01, 1e-12, "from t0 = %g: x = %.9g", t0,
                           x[0]);
        cr_assert_float_eq(v[0], 1.0, 1e-12, "from t0 = %g: v = %.9g", t0,
                           v[0]);
    }
    pr_free(&p);
}
