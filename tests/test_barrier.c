/* The barrier response (contact/barrier.h): the law b(d) and its
 * derivatives, the force against the finite-difference gradient of the
 * energy, the unprojected Hessian against central differences of the
 * force on every shape and region (sphere, plane, box face/edge/corner, a
 * cube mesh's face/edge/vertex) of a moving, rotating obstacle, the lagged
 * friction's Jacobians against central differences, and the PSD
 * projection (positive semi-definite; equal to H where H already is). */
#include <criterion/criterion.h>

#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/barrier.h"
#include "obstaclecase.h"

#define NSET 16

static bool barrier_at(const cl_obstacle *o, double t, const double x[3],
                       bool jac, cl_barrier_out *out)
{
    cl_contact_point q;
    cl_pose P;
    cl_obstacle_pose(o, t, &P);
    cl_obstacle_near(o, &P, x, INFINITY, NULL, &q);
    return cl_barrier_eval(&o->resp, &q, jac, out);
}

/* The lagged friction at x, v with the lagged normal n and force lambda. */
static void friction_at(const cl_obstacle *o, double t, const double n[3],
                        double lambda, const double x[3], const double v[3],
                        bool jac, cl_barrier_out *out)
{
    cl_pose P;
    double u[3];
    cl_obstacle_pose(o, t, &P);
    cl_obstacle_velocity(o, &P, x, u);
    cl_barrier_friction(&o->resp, n, lambda, u, P.W, v, jac, out);
}

/* The largest difference of a 3x3 block from central differences of
 * g(z + h e_j), relative to the block's largest entry. */
typedef void (*vec_fn)(const void *ctx, const double z[3], double g[3]);

static double fd_error(vec_fn g, const void *ctx, const double z[3],
                       const double J[9], double h)
{
    double err = 0.0, scale = 0.0;
    for (int j = 0; j < 3; j++) {
        double zp[3] = {z[0], z[1], z[2]}, zm[3] = {z[0], z[1], z[2]};
        double gp[3], gm[3];
        zp[j] += h;
        zm[j] -= h;
        g(ctx, zp, gp);
        g(ctx, zm, gm);
        for (int i = 0; i < 3; i++) {
            err = fmax(err, fabs((gp[i] - gm[i]) / (2 * h) - J[3 * i + j]));
            scale = fmax(scale, fabs(J[3 * i + j]));
        }
    }
    return err / scale;
}

typedef struct {
    const cl_obstacle *o;
    double t, lambda;
    const double *n, *x, *v;
} probe;

static void barrier_force_fn(const void *ctx, const double z[3], double g[3])
{
    const probe *p = ctx;
    cl_barrier_out out;
    cr_assert(barrier_at(p->o, p->t, z, false, &out));
    for (int i = 0; i < 3; i++)
        g[i] = out.f[i];
}

/* minus the gradient of the energy, by central differences */
static void energy_gradient(const probe *p, const double x[3], double g[3])
{
    double h = 1e-7;
    for (int j = 0; j < 3; j++) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
        cl_barrier_out a, b;
        xp[j] += h;
        xm[j] -= h;
        cr_assert(barrier_at(p->o, p->t, xp, false, &a) &&
                  barrier_at(p->o, p->t, xm, false, &b));
        g[j] = -(a.energy - b.energy) / (2 * h);
    }
}

static void friction_x_fn(const void *ctx, const double z[3], double g[3])
{
    const probe *p = ctx;
    cl_barrier_out out;
    friction_at(p->o, p->t, p->n, p->lambda, z, p->v, false, &out);
    for (int i = 0; i < 3; i++)
        g[i] = out.f[i];
}

static void friction_v_fn(const void *ctx, const double z[3], double g[3])
{
    const probe *p = ctx;
    cl_barrier_out out;
    friction_at(p->o, p->t, p->n, p->lambda, p->x, z, false, &out);
    for (int i = 0; i < 3; i++)
        g[i] = out.f[i];
}

/* Force = -grad E, df/dx (unprojected) and the friction's df/dx, df/dv
 * against central differences at x, with the velocity v sliding (fast:
 * y > eps_v) or creeping (y < eps_v). */
static void check_point(const cl_obstacle *o, double t, const double x[3],
                        const char *what)
{
    cl_barrier_out a;
    probe p = {.o = o, .t = t, .x = x};
    cr_assert(barrier_at(o, t, x, true, &a), "%s: not within dhat", what);
    double g[3];
    energy_gradient(&p, x, g);
    for (int i = 0; i < 3; i++)
        cr_expect_lt(fabs(g[i] - a.f[i]), 1e-6 * fabs(a.f[0]) +
                     1e-6 * fabs(a.f[1]) + 1e-6 * fabs(a.f[2]),
                     "%s: f[%d] = %g, -dE/dx = %g", what, i, a.f[i], g[i]);
    double e = fd_error(barrier_force_fn, &p, x, a.dfdx, 1e-8);
    cr_expect_lt(e, 1e-6, "%s: df/dx off by %g relative", what, e);
    cl_contact_point q;
    cl_pose P;
    cl_obstacle_pose(o, t, &P);
    cl_obstacle_near(o, &P, x, INFINITY, NULL, &q);
    p.n = q.n;
    p.lambda = cl_barrier_lambda(&o->resp, q.d);
    const double vs[2][3] = {{0.31, -0.52, 0.17}, {0.004, 0.002, -0.003}};
    for (int k = 0; k < 2; k++) {
        cl_barrier_out fr;
        p.v = vs[k];
        friction_at(o, t, q.n, p.lambda, x, vs[k], true, &fr);
        double ex = fd_error(friction_x_fn, &p, x, fr.dfdx, 1e-7);
        double ev = fd_error(friction_v_fn, &p, vs[k], fr.dfdv, 1e-8);
        cr_expect_lt(ex, 1e-6, "%s: friction df/dx off by %g (v %d)", what,
                     ex, k);
        cr_expect_lt(ev, 1e-6, "%s: friction df/dv off by %g (v %d)", what,
                     ev, k);
        cr_expect_leq(fr.power, 0.0, "%s: friction dissipates", what);
    }
}

/* A moving, rotating obstacle with friction, the Hessian unprojected. */
#define MOVING "obstacle.o.path = 0: 0, 0, 0; 2: 0.4, -0.2, 0.3", \
               "obstacle.o.omega = 0.3, -0.7, 0.5",                  \
               "obstacle.o.response = barrier", "obstacle.o.kappa = 100", \
               "obstacle.o.dhat = 0.05", "obstacle.o.psd = false",      \
               "obstacle.o.mu = 0.4", "obstacle.o.eps_v = 0.01"

/* Sphere (0.012 and 0.03 m out, along a skew direction), plane (0.0095
 * m out), box face, edge and corner (0.02, 0.036, 0.03 m out), as shape-frame points relative to the pivot. */
Test(barrier, analytic_shape_derivatives)
{
    static const struct {
        const char *sets[NSET];
        double t, X[3][3];
        int n;
        const char *what[3];
    } c[] = {
        {{"obstacle.o.shape = sphere", "obstacle.o.center = -1, 0.5, 2",
          "obstacle.o.radius = 0.4", MOVING},
         0.6, {{0.2472, 0.0, 0.3296}, {0.258, 0.0, 0.344}}, 2,
         {"sphere, near", "sphere, far"}},
        {{"obstacle.o.shape = plane", "obstacle.o.point = 0, 0.5, 0",
          "obstacle.o.normal = -0.1, 1, 0.3", MOVING},
         1.1, {{0.2, 0.06, -0.1}}, 1, {"plane"}},
        {{"obstacle.o.shape = box", "obstacle.o.size = 1, 2, 1.5", MOVING},
         0.3, {{0.1, 1.02, 0.2}, {0.52, 1.03, 0.1}, {0.51, 1.02, 0.77}}, 3,
         {"box face", "box edge", "box corner"}},
    };
    for (size_t k = 0; k < sizeof c / sizeof c[0]; k++)
        oc_check_points(c[k].sets, c[k].t, (const double (*)[3])c[k].X,
                        c[k].what, c[k].n, check_point);
}

Test(barrier, mesh_derivatives)
{
    char dir[512], file[800];
    oc_cube(dir, sizeof dir, file, sizeof file);
    const char *sets[NSET] = {"obstacle.o.shape = mesh", file, OC_CUBE_SCALE,
                              MOVING, NULL};
    /* 0.02 m from the face z = 1, 0.032 m from the edge x = -1, z = 1,
     * 0.041 m from the vertex (-1, -1, 1) */
    const double X[3][3] = {{-0.3, 0.4, 1.02}, {-1.03, 0.2, 1.01},
                            {-1.02, -1.03, 1.02}};
    const char *what[3] = {"mesh face", "mesh edge", "mesh vertex"};
    oc_check_points(sets, 1.1, X, what, 3, check_point);
    tmp_rm_rf(dir);
}

/* b(d) = -(d - dhat)^2 ln(d / dhat) and its derivatives at d = dhat / 2
 * (hand-computed: with e = -dhat/2, l = -ln 2: b = ln2 dhat^2 / 4,
 * b' = -dhat ln 2 - dhat / 2, b'' = 2 ln 2 + 4 + 1); 0 from dhat on; the
 * force -kappa b' n points out. */
Test(barrier, law)
{
    double b, db, d2b, h = 0.02, l2 = log(2.0);
    cl_barrier_law(0.5 * h, h, &b, &db, &d2b);
    cr_expect_float_eq(b, l2 * h * h / 4, 1e-15);
    cr_expect_float_eq(db, -h * l2 - h / 2, 1e-15);
    cr_expect_float_eq(d2b, 2 * l2 + 5, 1e-14);
    cl_barrier_law(h, h, &b, &db, &d2b);
    cr_expect(b == 0.0 && db == 0.0 && d2b == 0.0);
    cl_response_params r = {.kind = CL_RESPONSE_BARRIER, .kappa = 3,
                            .dhat = h};
    cr_expect_float_eq(cl_barrier_lambda(&r, 0.5 * h), 3 * (h * l2 + h / 2),
                       1e-15);
    cr_expect_eq(cl_barrier_lambda(&r, 1.5 * h), 0.0);
    cr_expect_eq(cl_barrier_lambda(&r, -1e-3), 0.0);
}

/* The smallest eigenvalue of a symmetric 3x3 block, by LAPACK's dsyev
 * (backward stable: to round-off of the largest).  The trigonometric
 * roots of the characteristic polynomial (Smith, CACM 1961) lose half the
 * digits at a double eigenvalue, as here: -5.0e-7 against 124 for a rank-1
 * block on one machine's libm, beyond a 1e-9 relative tolerance. */
static double min_eigenvalue(const double A[9])
{
    double a[9], w[3];
    memcpy(a, A, sizeof a);
    cr_assert_eq(LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', 3, a, 3, w), 0);
    return w[0];
}

/* Near a sphere H = kappa (b'' n n^T + b' G) has the negative eigenvalue
 * kappa b' / rho twice (b' < 0, G = (I - n n^T) / rho): the projection
 * keeps kappa b'' n n^T.  Near a plane (G = 0) H is PSD already and the
 * projection leaves it as it is. */
Test(barrier, psd_projection)
{
    const char *sphere[] = {"obstacle.o.shape = sphere",
                            "obstacle.o.radius = 0.5",
                            "obstacle.o.response = barrier",
                            "obstacle.o.kappa = 100", "obstacle.o.dhat = 0.05",
                            NULL};
    cl_obstacle o;
    cl_barrier_out a;
    oc_make(&o, sphere);
    double x[3] = {0.3, 0.4, 0.12 * sqrt(3.0)}; /* |x| = 0.52: d = 0.02 */
    cr_assert(barrier_at(&o, 0.0, x, true, &a));
    double H[9], b, db, d2b, n[3], rho = sqrt(0.25 + 0.0432);
    cl_barrier_law(rho - 0.5, 0.05, &b, &db, &d2b);
    for (int i = 0; i < 3; i++)
        n[i] = x[i] / rho;
    for (int k = 0; k < 9; k++) {
        H[k] = -a.dfdx[k];
        cr_expect_float_eq(H[k], 100 * d2b * n[k / 3] * n[k % 3], 1e-9,
                           "H[%d]", k);
    }
    cr_expect_geq(min_eigenvalue(H), -1e-12 * 100 * d2b, "%g against %g",
                  min_eigenvalue(H), 100 * d2b);
    cl_obstacle_free(&o);
    const char *plane[] = {"obstacle.o.shape = plane",
                           "obstacle.o.normal = 0.2, 1, 0.1",
                           "obstacle.o.response = barrier",
                           "obstacle.o.kappa = 100", "obstacle.o.dhat = 0.05",
                           NULL};
    cl_barrier_out u;
    oc_make(&o, plane);
    double y[3] = {0.1, 0.02, -0.3};
    cr_assert(barrier_at(&o, 0.0, y, true, &a));
    o.resp.psd = false;
    cr_assert(barrier_at(&o, 0.0, y, true, &u));
    for (int k = 0; k < 9; k++)
        cr_expect_float_eq(a.dfdx[k], u.dfdx[k], 1e-12 * fabs(u.dfdx[0]) +
                           1e-300, "plane: block %d", k);
    cl_obstacle_free(&o);
}

/* A random symmetric block: the projection is PSD and keeps the PSD part
 * (projecting twice changes nothing). */
Test(barrier, psd_projection_of_indefinite_block)
{
    double H[9] = {2.0, 1.5, -0.3, 1.5, -1.0, 0.7, -0.3, 0.7, 0.5};
    cl_barrier_project_psd(H);
    cr_expect_geq(min_eigenvalue(H), -1e-12);
    double K[9];
    for (int k = 0; k < 9; k++)
        K[k] = H[k];
    cl_barrier_project_psd(K);
    for (int k = 0; k < 9; k++)
        cr_expect_float_eq(K[k], H[k], 1e-12);
}
