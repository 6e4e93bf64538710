/* The penalty response (contact/penalty.h): its force against the law, its
 * exact Jacobians and its energy against central finite differences, on
 * every shape and region (sphere, plane, box face/edge/corner, a cube
 * mesh's face/edge/vertex), on moving and rotating obstacles, with damping
 * and friction; no pull on a particle leaving faster than the damping
 * allows; the force without Jacobians against the full one. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/penalty.h"
#include "obstaclecase.h"

#define NSET 16

static bool force_at(const cl_obstacle *o, double t, const double x[3],
                     const double v[3], bool jac, cl_penalty_out *out)
{
    cl_contact_point q;
    cl_pose P;
    cl_obstacle_pose(o, t, &P);
    cl_obstacle_near(o, &P, x, INFINITY, NULL, &q);
    return cl_penalty_eval(&o->resp, &q, v, jac, out);
}

/* Largest difference of the analytic Jacobians from central differences of
 * the force, relative to the largest entry. */
static void check_jacobians(const cl_obstacle *o, double t, const double x[3],
                            const double v[3], const char *what)
{
    cl_penalty_out a, p, m;
    cr_assert(force_at(o, t, x, v, true, &a), "%s: not in the band", what);
    double h = 1e-7, ex = 0.0, ev = 0.0, sx = 0.0, sv = 0.0;
    for (int j = 0; j < 3; j++) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
        double vp[3] = {v[0], v[1], v[2]}, vm[3] = {v[0], v[1], v[2]};
        xp[j] += h;
        xm[j] -= h;
        cr_assert(force_at(o, t, xp, v, false, &p) &&
                  force_at(o, t, xm, v, false, &m));
        for (int i = 0; i < 3; i++) {
            double fd = (p.f[i] - m.f[i]) / (2 * h);
            ex = fmax(ex, fabs(fd - a.dfdx[3 * i + j]));
            sx = fmax(sx, fabs(a.dfdx[3 * i + j]));
        }
        vp[j] += h;
        vm[j] -= h;
        cr_assert(force_at(o, t, x, vp, false, &p) &&
                  force_at(o, t, x, vm, false, &m));
        for (int i = 0; i < 3; i++) {
            double fd = (p.f[i] - m.f[i]) / (2 * h);
            ev = fmax(ev, fabs(fd - a.dfdv[3 * i + j]));
            sv = fmax(sv, fabs(a.dfdv[3 * i + j]));
        }
    }
    cr_expect_lt(ex, 1e-8 * sx, "%s: df/dx off by %g (scale %g)", what, ex,
                 sx);
    cr_expect_lt(ev, 1e-8 * sv, "%s: df/dv off by %g (scale %g)", what, ev,
                 sv);
}

/* A moving, rotating obstacle with damping and friction: every term of
 * the Jacobians is exercised. */
#define MOVING "obstacle.o.path = 0: 0, 0, 0; 2: 0.4, -0.2, 0.3", \
               "obstacle.o.omega = 0.3, -0.7, 0.5",                  \
               "obstacle.o.response = penalty", "obstacle.o.k = 1000", \
               "obstacle.o.eps = 0.05", "obstacle.o.damping = 3",       \
               "obstacle.o.mu = 0.4", "obstacle.o.v_smooth = 0.05"

static const double vel[3] = {0.31, -0.52, 0.17};

/* The Jacobians at x with the velocity vel. */
static void check_at(const cl_obstacle *o, double t, const double x[3],
                     const char *what)
{
    check_jacobians(o, t, x, vel, what);
}

/* The Jacobians at the shape-frame points X[k] of the obstacle made from
 * `sets`, at time t. */
static void check_points(const char *const *sets, double t,
                         const double (*X)[3], const char *const *what,
                         int n)
{
    oc_check_points(sets, t, X, what, n, check_at);
}

Test(penalty, sphere_jacobians)
{
    const char *sets[NSET] = {"obstacle.o.shape = sphere",
                              "obstacle.o.center = 1, 2, 3",
                              "obstacle.o.radius = 0.5", MOVING, NULL};
    /* 0.02 m inside and 0.01 m outside, in the band, along a skew
     * direction */
    const double X[2][3] = {{0.2304, 0.288, 0.3072}, {0.2448, 0.306, 0.3264}};
    const char *what[2] = {"sphere, inside", "sphere, in the band"};
    check_points(sets, 0.7, X, what, 2);
}

Test(penalty, plane_jacobians)
{
    const char *sets[NSET] = {"obstacle.o.shape = plane",
                              "obstacle.o.point = 0, -1, 0",
                              "obstacle.o.normal = 0.2, 1, 0.1", MOVING, NULL};
    const double X[1][3] = {{0.1, -0.02, 0.1}};
    const char *what[1] = {"plane"};
    check_points(sets, 1.3, X, what, 1);
}

Test(penalty, box_jacobians)
{
    const char *sets[NSET] = {"obstacle.o.shape = box",
                              "obstacle.o.center = 0, 0, 0",
                              "obstacle.o.size = 2, 1, 1", MOVING, NULL};
    /* face (inside, outside), edge, corner */
    const double X[4][3] = {{0.3, 0.49, 0.1}, {0.3, 0.53, 0.1},
                            {1.02, 0.52, 0.0}, {1.02, 0.52, 0.53}};
    const char *what[4] = {"box face, inside", "box face, outside",
                           "box edge", "box corner"};
    check_points(sets, 0.4, X, what, 4);
}

Test(penalty, mesh_jacobians)
{
    char dir[512], file[800];
    oc_cube(dir, sizeof dir, file, sizeof file);
    const char *sets[NSET] = {"obstacle.o.shape = mesh", file, OC_CUBE_SCALE,
                              MOVING, NULL};
    const double X[3][3] = {{0.2, 0.3, 1.03}, {1.02, 0.3, 1.03},
                            {1.02, 1.03, 1.03}};
    const char *what[3] = {"mesh face", "mesh edge", "mesh vertex"};
    check_points(sets, 0.9, X, what, 3);
    tmp_rm_rf(dir);
}

/* The repulsion is minus the gradient of its energy, and the law's
 * magnitudes: k (eps - d) along n, mu k (eps - d) against the sliding when
 * it is fast. */
Test(penalty, energy_and_law)
{
    cl_obstacle o;
    const char *sets[NSET] = {"obstacle.o.shape = sphere",
                              "obstacle.o.radius = 1",
                              "obstacle.o.response = penalty",
                              "obstacle.o.k = 500", "obstacle.o.eps = 0.1",
                              "obstacle.o.mu = 0.5",
                              "obstacle.o.v_smooth = 1e-6", NULL};
    oc_make(&o, sets);
    double x[3] = {0.0, 1.04, 0.0}, v[3] = {2.0, 0.0, 0.0};
    cl_penalty_out a, p, m;
    cr_assert(force_at(&o, 0.0, x, v, false, &a));
    cr_expect_float_eq(a.f[1], 500 * (0.1 - 0.04), 1e-12);
    cr_expect_float_eq(a.f[0], -0.5 * 500 * (0.1 - 0.04), 1e-9);
    cr_expect_float_eq(a.energy, 0.5 * 500 * 0.06 * 0.06, 1e-12);
    cr_expect_float_eq(a.friction_power, a.f[0] * v[0], 1e-9);
    double h = 1e-6, xp[3] = {0.0, 1.04 + h, 0.0}, xm[3] = {0.0, 1.04 - h,
                                                            0.0};
    double zero[3] = {0.0, 0.0, 0.0};
    force_at(&o, 0.0, xp, zero, false, &p);
    force_at(&o, 0.0, xm, zero, false, &m);
    cr_expect_float_eq(-(p.energy - m.energy) / (2 * h), a.f[1], 1e-6);
    double out[3] = {0.0, 1.2, 0.0};
    cr_expect_not(force_at(&o, 0.0, out, v, true, &a), "outside the band");
    cl_obstacle_free(&o);
}

/* Hunt and Crossley's factor 1 - a w_n is held at 0: a particle leaving
 * the plane faster than 1/a (a = 2 s/m, 0.8 m/s against 0.5) feels no
 * normal force (it was pulled back by fe (1 - 1.6) = -0.6 fe), only the
 * friction mu fe, and the power of the normal force beyond the spring's
 * is -fe w_n; the Jacobians stay exact on both sides of the switch. */
Test(penalty, leaving_fast_is_not_pulled_back)
{
    cl_obstacle o;
    const char *sets[NSET] = {"obstacle.o.shape = plane",
                              "obstacle.o.normal = 0, 1, 0",
                              "obstacle.o.response = penalty",
                              "obstacle.o.k = 1000", "obstacle.o.eps = 0.01",
                              "obstacle.o.damping = 2", "obstacle.o.mu = 0.4",
                              "obstacle.o.v_smooth = 0.05", NULL};
    oc_make(&o, sets);
    double x[3] = {0.0, 0.004, 0.0}, fast[3] = {0.3, 0.8, 0.0},
           slow[3] = {0.3, 0.2, 0.0};
    double fe = 1000 * (0.01 - 0.004);
    cl_penalty_out a;
    cr_assert(force_at(&o, 0.0, x, fast, true, &a));
    cr_expect_eq(a.f[1], 0.0, "f_n = %g", a.f[1]);
    cr_expect_float_eq(a.f[0], -0.4 * fe * 0.3 / sqrt(0.09 + 0.0025), 1e-12,
                       "friction %g", a.f[0]);
    cr_expect_float_eq(a.power - a.friction_power, -fe * 0.8, 1e-12,
                       "power %g", a.power - a.friction_power);
    cr_assert(force_at(&o, 0.0, x, slow, true, &a));
    cr_expect_float_eq(a.f[1], fe * (1 - 2 * 0.2), 1e-12, "f_n %g", a.f[1]);
    cr_expect_float_eq(a.power - a.friction_power, -2 * fe * 0.2 * 0.2,
                       1e-12, "power %g", a.power - a.friction_power);
    check_jacobians(&o, 0.0, x, fast, "leaving fast");
    check_jacobians(&o, 0.0, x, slow, "leaving slowly");
    cl_obstacle_free(&o);
}

/* cl_penalty_forces gives cl_penalty_eval's forces, energies and powers
 * bit for bit, with and without friction and damping, in the band and out
 * of it, summed in order; points out of the band add nothing. */
Test(penalty, forces_without_jacobians_are_eval_s)
{
    static const double mu[] = {0.0, 0.5}, damping[] = {0.0, 1.0};
    enum { N = 5 };
    static const double d[N] = {-0.003, 0.004, 0.012, 0.0099, -1e-5};
    static const size_t near[N] = {4, 0, 2, 1, 3};
    cl_response_params r = {.kind = CL_RESPONSE_PENALTY, .k = 20,
                            .eps = 0.01, .v_smooth = 0.05};
    double v[3 * N];
    for (int i = 0; i < 3 * N; i++)
        v[i] = 0.1 * sin(1.0 + i);
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            cl_contact_slim s[N];
            double f[3 * N] = {0}, want[3 * N] = {0}, e = 0.5, p = -0.25;
            double we = 0.5, wp = -0.25;
            r.mu = mu[a];
            r.damping = damping[b];
            for (int i = 0; i < N; i++) {
                cl_contact_point q = {.d = d[i], .n = {0.6, 0.0, 0.8},
                                      .u = {0.01 * i, 0.0, -0.02}};
                cl_penalty_out o;
                s[i] = (cl_contact_slim){.d = q.d, .n = {0.6, 0.0, 0.8},
                                         .u = {0.01 * i, 0.0, -0.02}};
                if (!cl_penalty_eval(&r, &q, v + 3 * near[i], false, &o))
                    continue;
                for (int k = 0; k < 3; k++)
                    want[3 * near[i] + k] += o.f[k];
                we += o.energy;
                wp += o.power;
            }
            cl_penalty_forces(&r, s, near, N, v, f, &e, &p);
            cr_assert(!memcmp(f, want, sizeof f) && e == we && p == wp,
                      "mu %g, damping %g", r.mu, r.damping);
            cr_assert_eq(f[3 * near[2]], 0.0); /* out of the band */
            cr_assert(e > 0.5 && (b == 0 && a == 0 ? p == -0.25 : p < -0.25));
        }
}
