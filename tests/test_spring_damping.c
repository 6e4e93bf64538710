/* Verification of the spring-damping term and the shared pair damping
 * (forces/pairdamp.h; the Verlet-and-PBD report's "spring and friction",
 * Jiao, eq. 14; docs/model.md 3.2; docs/architecture.md, "Checks every
 * force term passes") on the spring pairs of forces/springs.h:
 *   axial   f_a = kd (u . (v_b - v_a)) u,  df/dv = +-kd u u^T blocks,
 *           df/dx = +-G, G = (kd/d) [u (P w)^T + (u . w) P] (nonsymmetric);
 *   linear  f_a = -kd (v_a - v_b),  df/dv = +-kd I, df/dx = 0.
 * Damping is isolated with springs.enabled = false: the dashpots sit on the
 * pairs [springs] defines whether or not the springs term runs.  Checks:
 * forces and power against formulas computed here from the pair list, power
 * = sum f.v <= 0 = v^T (df/dv) v, Jacobians against central differences
 * (the axial df/dx with its asymmetry, translation row sums), Newton's
 * third law (and no torque for the central axial force), rigid-motion
 * invariance, a rigid rotation not damped by the axial model, and the
 * Choi-Ko damping's model = axial through the same helper. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"
#include "springcheck.h"

static const char *const models[] = {"spring-damping.model=linear",
                                     "spring-damping.model=axial"};

/* Damping-only case: model linear (ax = 0) or axial, up to three more
 * settings (NULL ends them early), in a jittered state with random
 * velocities. */
static sc_case damp_case(int ax, uint64_t seed, const char *a, const char *b,
                         const char *c3)
{
    sc_case c = sc_open(FD_SETS(models[ax], a, b, c3), seed);
    sc_state(&c, 1.03, 0.96, 0.05, 0.1, 1.0);
    return c;
}

/* Expected force (into f) and power on the spring pairs of `sets`. */
static double expected(const sc_case *c, const char *const *sets, double kd,
                       bool axial, double *f)
{
    cl_springnet net = sc_network(cl_model_cloth(c->m), sets);
    const double *x = c->x, *v = c->v;
    double power = 0.0;
    memset(f, 0, c->n * sizeof *f);
    for (size_t k = 0; k < net.set.n; k++) {
        const cl_pair *p = &net.set.pair[k];
        double d = cl_dist(x + 3 * p->a, x + 3 * p->b), uw = 0.0, fa;
        for (int i = 0; i < 3; i++)
            uw += (x[3 * p->b + i] - x[3 * p->a + i]) / d *
                  (v[3 * p->b + i] - v[3 * p->a + i]);
        for (int i = 0; i < 3; i++) {
            fa = axial ? kd * uw * (x[3 * p->b + i] - x[3 * p->a + i]) / d
                       : -kd * (v[3 * p->a + i] - v[3 * p->b + i]);
            f[3 * p->a + i] += fa;
            f[3 * p->b + i] -= fa;
            power += fa * (v[3 * p->a + i] - v[3 * p->b + i]);
        }
    }
    cl_springnet_free(&net);
    return power;
}

static double dot(const double *a, const double *b, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

Test(spring_damping, force_and_power_match_formula)
{
    for (int ax = 0; ax < 2; ax++) {
        sc_case c = damp_case(ax, 200 + ax, "cloth.nu=5", "cloth.nv=6",
                              "spring-damping.kd=0.37");
        cr_assert(fd_has_term(c.m, "spring-damping"));
        cr_assert(!fd_has_term(c.m, "springs"));
        cl_energy e = fd_eval(c.m, c.x, c.v, c.f);
        double power = expected(&c, NULL, 0.37, ax, c.g);
        double err = fd_relerr(c.f, c.g, c.n);
        cr_assert_lt(err, 1e-14, "force vs formula %g", err);
        cr_assert(fabs(e.power_diss - power) <= 1e-13 * fabs(power),
                  "power %.17g vs %.17g", e.power_diss, power);
        /* The reported power is sum_p f_p . v_p of the force itself. */
        double fv = dot(c.f, c.v, c.n);
        cr_assert(fabs(e.power_diss - fv) <= 1e-13 * fabs(fv));
        cr_assert_lt(e.power_diss, 0.0);
        for (size_t t = 0; t < e.nterm; t++)
            cr_assert_str_neq(e.name[t], "spring-damping");
        cr_assert_eq(e.potential, 0.0);
        sc_close(&c);
    }
}

/* The dashpots follow the spring network: levels, and a set left out. */
Test(spring_damping, pairs_follow_the_springs)
{
    const char *const nets[] = {"springs.levels=3", "springs.k_shear=0"};
    for (size_t k = 0; k < 2; k++) {
        sc_case c = damp_case(1, 210 + k, "cloth.n=6", nets[k],
                              "spring-damping.kd=2");
        fd_eval(c.m, c.x, c.v, c.f);
        expected(&c, FD_SETS(nets[k]), 2.0, true, c.g);
        cr_assert_lt(fd_relerr(c.f, c.g, c.n), 1e-14);
        sc_close(&c);
    }
}

/* Largest |J - J^T| relative to max |J|. */
static double asymmetry(const double *J, size_t n)
{
    double a = 0.0;
    for (size_t r = 0; r < n; r++)
        for (size_t c = 0; c < r; c++)
            a = fmax(a, fabs(J[r * n + c] - J[c * n + r]));
    return a / fd_maxabs(J, n * n);
}

/* Largest block-row sum (translation invariance) relative to max |J|. */
static double row_sums(const double *J, size_t n)
{
    double dev = 0.0;
    for (size_t row = 0; row < n; row++) {
        double s[3] = {0, 0, 0};
        for (size_t c = 0; c < n; c++)
            s[c % 3] += J[row * n + c];
        dev = fmax(dev, fmax(fabs(s[0]), fmax(fabs(s[1]), fabs(s[2]))));
    }
    return dev / fd_maxabs(J, n * n);
}

Test(spring_damping, jacobian_fd)
{
    const char *what[] = {"spring-damping linear", "spring-damping axial"};
    double worst[2][2] = {{0, 0}, {0, 0}};
    for (int ax = 0; ax < 2; ax++) {
        sc_case c = damp_case(ax, 220 + ax, "cloth.n=5", "spring-damping.kd=0.02",
                              NULL);
        double *Jx = fd_vec(c.n * c.n), *Jv = fd_vec(c.n * c.n);
        for (int trial = 0; trial < 3; trial++) {
            double ex, ev;
            fd_check_jacobian(c.m, c.x, c.v, 1e-6 * c.h, 1e-3, false,
                              what[ax], &ex, &ev);
            cr_assert_lt(ev, 1e-9, "df/dv vs FD: rel err %g", ev);
            if (ax)
                cr_assert_lt(ex, 1e-8, "axial df/dx vs FD: rel err %g", ex);
            else
                cr_assert_eq(ex, 0.0, "linear df/dx should vanish: %g", ex);
            worst[ax][0] = fmax(worst[ax][0], ex);
            worst[ax][1] = fmax(worst[ax][1], ev);
            fd_jacobian(c.m, c.x, c.v, Jx, Jv);
            /* df/dv is symmetric; the axial df/dx is not. */
            cr_assert_lt(asymmetry(Jv, c.n), 1e-15);
            cr_assert_lt(row_sums(Jv, c.n), 1e-14);
            if (ax) {
                cr_assert_gt(asymmetry(Jx, c.n), 1e-2,
                             "axial df/dx looks symmetric");
                cr_assert_lt(row_sums(Jx, c.n), 1e-14);
            }
            sc_state(&c, 0.98, 1.02, 0.1, 0.1, 2.0);
        }
        free(Jx);
        free(Jv);
        sc_close(&c);
    }
    fd_report("spring-damping linear worst df/dv", worst[0][1]);
    fd_report("spring-damping axial worst df/dx", worst[1][0]);
    fd_report("spring-damping axial worst df/dv", worst[1][1]);
}

/* power = sum f.v = v^T (df/dv) v <= 0 for any v (force linear in v). */
Test(spring_damping, dissipative)
{
    for (int ax = 0; ax < 2; ax++) {
        sc_case c = damp_case(ax, 240 + ax, "cloth.n=4", "spring-damping.kd=2",
                              NULL);
        double *Jx = fd_vec(c.n * c.n), *Jv = fd_vec(c.n * c.n);
        fd_jacobian(c.m, c.x, c.v, Jx, Jv);
        for (int trial = 0; trial < 20; trial++) {
            fd_random_vec(&c.r, 1.0, c.v, c.n);
            cl_energy e = fd_eval(c.m, c.x, c.v, c.f);
            for (size_t i = 0; i < c.n; i++)
                c.g[i] = dot(Jv + i * c.n, c.v, c.n);
            double q = dot(c.v, c.g, c.n);
            cr_assert_leq(e.power_diss, 0.0);
            cr_assert(fabs(q - e.power_diss) <= 1e-12 * fabs(q), "%g vs %g",
                      q, e.power_diss);
            cr_assert(fabs(dot(c.f, c.v, c.n) - e.power_diss) <=
                      1e-12 * fabs(q));
        }
        free(Jx);
        free(Jv);
        sc_close(&c);
    }
}

/* Newton's third law (and no torque for the central axial force), rigid
 * motions: f(R x + t, R v + w) = R f(x, v), Jacobians rotated alike. */
Test(spring_damping, balance_and_rigid_motion)
{
    for (int ax = 0; ax < 2; ax++) {
        sc_case c = damp_case(ax, 250 + ax, "cloth.n=5", "springs.levels=2",
                              "spring-damping.kd=1.5");
        fd_eval(c.m, c.x, c.v, c.f);
        double torque, net = fd_net_force(c.x, c.f, c.n / 3, &torque);
        cr_assert_lt(net, 1e-14, "net damping force %g", net);
        if (ax)
            cr_assert_lt(torque, 1e-14, "net axial torque %g", torque);
        for (int trial = 0; trial < 3; trial++) {
            double R[9], t[3], w[3];
            fd_rotation(&c.r, R);
            fd_random_vec(&c.r, 2.0, t, 3);
            fd_random_vec(&c.r, 2.0, w, 3);
            double e = fd_check_rigid(c.m, c.x, c.v, R, t, w,
                                      "spring-damping");
            cr_assert_lt(e, 1e-12, "rigid-motion deviation %g", e);
            sc_state(&c, 1.0, 1.0, 0.05, 0.05, 1.0);
        }
        sc_close(&c);
    }
}

/* v = omega x x: the axial model sees no stretching rate (force and power
 * zero to rounding), the linear one damps the rotation. */
Test(spring_damping, rigid_rotation_not_damped_axially)
{
    const double om[3] = {0.3, -1.1, 0.7};
    for (int ax = 0; ax < 2; ax++) {
        sc_case c = damp_case(ax, 270 + ax, "cloth.n=5", "spring-damping.kd=0.8",
                              NULL);
        for (size_t p = 0; p < c.n / 3; p++) {
            const double *xp = c.x + 3 * p;
            c.v[3 * p] = om[1] * xp[2] - om[2] * xp[1];
            c.v[3 * p + 1] = om[2] * xp[0] - om[0] * xp[2];
            c.v[3 * p + 2] = om[0] * xp[1] - om[1] * xp[0];
        }
        cl_energy e = fd_eval(c.m, c.x, c.v, c.f);
        double fscale = 0.8 * fd_maxabs(c.v, c.n);
        if (ax) {
            cr_assert_lt(fd_maxabs(c.f, c.n), 1e-14 * fscale);
            cr_assert_lt(fabs(e.power_diss), 1e-14 * fscale * fscale);
        } else {
            cr_assert_gt(fd_maxabs(c.f, c.n), 0.1 * fscale);
        }
        sc_close(&c);
    }
}

/* Two particles along x: f_0 = kd (v_1x - v_0x) (1, 0, 0) whatever the
 * transverse velocities; the default model is axial. */
Test(spring_damping, axial_on_one_spring)
{
    cl_model *m = sc_model(SC_BASE, FD_SETS("cloth.nu=2", "cloth.nv=1",
                                            "cloth.su=0.5",
                                            "spring-damping.kd=3"));
    double x[6] = {0, 0, 0, 0.7, 0, 0}, v[6] = {0.2, 5, -1, -0.3, 2, 4},
           f[6];
    cl_energy e = fd_eval(m, x, v, f);
    double want = 3 * (-0.3 - 0.2);
    cr_assert(fabs(f[0] - want) <= 1e-15 && f[1] == 0 && f[2] == 0);
    cr_assert(fabs(f[3] + want) <= 1e-15 && f[4] == 0 && f[5] == 0);
    cr_assert(fabs(e.power_diss + 3 * 0.5 * 0.5) <= 1e-14);
    cl_model_free(m);
}

Test(spring_damping, switches_and_errors)
{
    cl_model *m = sc_model(SC_BASE, FD_SETS("cloth.n=3"));
    cr_assert(!fd_has_term(m, "spring-damping"));
    cl_model_free(m);
    cl_error err = {0};
    cr_assert_neq(fd_model_try(FD_SETS("spring-damping.kd=1",
                                       "spring-damping.model=radial"),
                               &m, &err),
                  CL_OK);
    cr_assert_neq(fd_model_try(FD_SETS("spring-damping.kd=-1"), &m, &err),
                  CL_OK);
    cr_assert_neq(fd_model_try(FD_SETS("spring-damping.kd=1",
                                       "springs.levels=2",
                                       "springs.k_bend=1"),
                               &m, &err),
                  CL_OK);
}

/* Choi-Ko damping (Type1 pairs) with model = axial runs the same helper:
 * the same forces as spring-damping on levels = 1 (the same pairs), and a
 * Jacobian that matches central differences. */
Test(spring_damping, choiko_damping_axial_option)
{
    sc_case c = damp_case(1, 280, "cloth.n=5", "damping.kd=0.6",
                          "damping.model=axial");
    cl_model *sd = sc_model(SC_BASE, FD_SETS("cloth.n=5", "springs.levels=1",
                                             "spring-damping.kd=0.6"));
    cl_energy e1 = fd_eval(c.m, c.x, c.v, c.f), e2 = fd_eval(sd, c.x, c.v,
                                                             c.g);
    cr_assert_lt(fd_relerr(c.f, c.g, c.n), 1e-14);
    cr_assert(fabs(e1.power_diss - e2.power_diss) <=
              1e-13 * fabs(e2.power_diss));
    double ex, ev;
    fd_check_jacobian(c.m, c.x, c.v, 1e-6 * c.h, 1e-3, false,
                      "damping model=axial", &ex, &ev);
    cr_assert_lt(ex, 1e-8);
    cr_assert_lt(ev, 1e-9);
    cl_model_free(sd);
    sc_close(&c);
}

/* Springs, dashpots, gravity and pins together (ms-hang's terms on a
 * small grid): the assembled Jacobian of the sum against differences. */
Test(spring_damping, with_springs_gravity_pins)
{
    cl_model *m = FD_MODEL("cloth.n=5", "type1.enabled=false",
                           "type2.enabled=false", "damping.kd=0",
                           "springs.enabled=true", "spring-damping.kd=0.05");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), A[9];
    fd_rng r = {290};
    fd_scale(1.02, 0.97, A);
    fd_deform(m, A, 0.05, 0.1, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    double ex, ev;
    fd_check_jacobian(m, x, v, 1e-6 * 0.25, 1e-3, false,
                      "springs + spring-damping", &ex, &ev);
    cr_assert_lt(ex, 1e-8, "df/dx %g", ex);
    cr_assert_lt(ev, 1e-9, "df/dv %g", ev);
    free(x);
    free(v);
    cl_model_free(m);
}
