/* Verification of the Baraff-Witkin bend term and its damping (docs/model.md
 * 3.3; docs/architecture.md, "Checks every force term passes";
 * forces/bw_bend.c): C = theta - theta0 on every interior edge, theta the
 * signed angle between the normals of the edge's two triangles.
 *
 * The hinge itself (cl_bw_hinge): angle value and sign on hand-built pairs
 * of triangles at 0, 30, 90, 150 degrees (both signs) and near +-180, the
 * gradient against an independent form (unit normals and heights, Bridson
 * et al. 2003) and against central differences of theta, the Hessian
 * against central differences of the gradient, its symmetry and its
 * translation and rotation invariance, degenerate hinges.  The term: folded
 * 2 x 2 grids with known energy, Jacobians against central differences,
 * f = -dE/dx, Newton's third law, rotation invariance, force and energy
 * against the reference, and the damping with its documented
 * approximation of dd/dx. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwcheck.h"

#define DEG (M_PI / 180.0)

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void sub(const double *a, const double *b, double *c)
{
    for (int i = 0; i < 3; i++)
        c[i] = a[i] - b[i];
}

/* Independent hinge: unit normals n0 of (x0, x1, x2) and n1 of
 * (x1, x0, x3), theta = atan2((n0 x n1) . e^, n0 . n1); gradient in the
 * form of Bridson et al. with heights h0 = A0/l, h1 = A1/l:
 *   g2 = -n0/h0, g3 = -n1/h1,
 *   g1 = ((x2-x0).e^/l) n0/h0 + ((x3-x0).e^/l) n1/h1,
 *   g0 = ((x1-x2).e^/l) n0/h0 + ((x1-x3).e^/l) n1/h1. */
static double ref_theta(const double *x, double *g)
{
    const double *x0 = x, *x1 = x + 3, *x2 = x + 6, *x3 = x + 9;
    double e[3], a[3], b[3], n0[3], n1[3], m[3];
    sub(x1, x0, e);
    sub(x2, x0, a);
    sub(x3, x0, b);
    cross(e, a, n0);
    cross(b, e, n1);
    double l = sqrt(dot(e, e)), A0 = sqrt(dot(n0, n0)),
           A1 = sqrt(dot(n1, n1));
    for (int i = 0; i < 3; i++) {
        n0[i] /= A0;
        n1[i] /= A1;
        e[i] /= l;
    }
    cross(n0, n1, m);
    double theta = atan2(dot(m, e), dot(n0, n1));
    double h0 = A0 / l, h1 = A1 / l, d[3];
    double w[4][2];
    sub(x2, x0, d), w[1][0] = dot(d, e) / l;
    sub(x3, x0, d), w[1][1] = dot(d, e) / l;
    sub(x1, x2, d), w[0][0] = dot(d, e) / l;
    sub(x1, x3, d), w[0][1] = dot(d, e) / l;
    w[2][0] = -1.0, w[2][1] = 0.0;
    w[3][0] = 0.0, w[3][1] = -1.0;
    for (int v = 0; v < 4; v++)
        for (int i = 0; i < 3; i++)
            g[3 * v + i] = w[v][0] * n0[i] / h0 + w[v][1] * n1[i] / h1;
    return theta;
}

static void ref_bend(const bw_ref *r, const int *v, const double *xe,
                     double *C, double (*g)[CL_BW_NX])
{
    double X[12], g0[12];
    for (int m = 0; m < 4; m++)
        memcpy(X + 3 * m, r->cloth->X0 + 3 * v[m], 3 * sizeof *X);
    double c = ref_theta(xe, g[0]) - ref_theta(X, g0);
    C[0] = c > M_PI ? c - 2 * M_PI : c < -M_PI ? c + 2 * M_PI : c;
}

static bw_ref bend_ref(const cl_model *m, cl_diagonal diag)
{
    bw_ref r = bw_ref_elements(m, 4, 1, diag);
    r.cond = ref_bend;
    return r;
}

/* x0 = 0, x1 = (1,0,0), x2 = (0.3,1,0): N0 along +z.  x3 = (0.6, -cos p,
 * s sin p): the second triangle turned by p about the edge, to the side of
 * +N0 (s = +1) or -N0 (s = -1). */
static void hand_hinge(double p, double s, double *x)
{
    const double y[12] = {0, 0, 0, 1, 0, 0, 0.3, 1, 0,
                          0.6, -cos(p), s * sin(p)};
    memcpy(x, y, sizeof y);
}

/* ---- the hinge ----------------------------------------------------------- */

Test(bw_bend, angle_value_and_sign)
{
    const double angles[] = {0.0, 30.0, 90.0, 150.0, 179.0};
    for (size_t k = 0; k < sizeof angles / sizeof *angles; k++)
        for (int s = -1; s <= 1; s += 2) {
            double x[12], g[12], theta, N0z = 1.0;
            hand_hinge(angles[k] * DEG, s, x);
            cr_assert(cl_bw_hinge(x, &theta, g, NULL));
            /* theta = -s p: sign(theta) = -sign((x3 - x0) . N0). */
            double want = -s * angles[k] * DEG;
            cr_assert(fabs(theta - want) <= 1e-14,
                      "%g deg, side %d: theta %.17g, want %.17g", angles[k],
                      s, theta, want);
            if (angles[k] > 0)
                cr_assert_eq(theta > 0, x[11] * N0z < 0);
        }
}

/* The edge direction sets the sign: swapping the roles of the triangles
 * (edge reversed, x2 <-> x3) gives the same angle; reversing the edge in
 * place (x0 <-> x1) flips it. */
Test(bw_bend, angle_sign_follows_the_edge)
{
    double x[12], y[12], g[12], t1, t2;
    hand_hinge(40 * DEG, 1, x);
    cr_assert(cl_bw_hinge(x, &t1, g, NULL));
    memcpy(y, x + 3, 3 * sizeof *y);
    memcpy(y + 3, x, 3 * sizeof *y);
    memcpy(y + 6, x + 9, 3 * sizeof *y);
    memcpy(y + 9, x + 6, 3 * sizeof *y);
    cr_assert(cl_bw_hinge(y, &t2, g, NULL));
    cr_assert(fabs(t1 - t2) <= 1e-15, "%g vs %g", t1, t2);
    memcpy(y + 6, x + 6, 6 * sizeof *y);
    cr_assert(cl_bw_hinge(y, &t2, g, NULL));
    cr_assert(fabs(t1 + t2) <= 1e-15, "%g vs %g", t1, -t2);
}

Test(bw_bend, degenerate_hinges_carry_no_force)
{
    double x[12], g[12], H[144], theta;
    hand_hinge(30 * DEG, 1, x);
    x[6] = 0.5, x[7] = 0.0, x[8] = 0.0; /* x2 on the edge */
    cr_assert(!cl_bw_hinge(x, &theta, g, H));
    cr_assert_eq(theta, 0.0);
    cr_assert_eq(fd_maxabs(g, 12), 0.0);
    cr_assert_eq(fd_maxabs(H, 144), 0.0);
    hand_hinge(30 * DEG, 1, x);
    memcpy(x + 3, x, 3 * sizeof *x); /* zero-length edge */
    cr_assert(!cl_bw_hinge(x, &theta, g, H));
}

/* Random hinges: gradient = the independent form = central differences
 * of theta; Hessian = central differences of the gradient, symmetric;
 * sum of gradient blocks and of Hessian block rows zero (translation),
 * sum x_m x g_m zero (rotation). */
Test(bw_bend, hinge_derivatives)
{
    fd_rng r = {201};
    double worst_g = 0.0, worst_h = 0.0;
    for (int trial = 0; trial < 200; trial++) {
        double x[12], g[12], gr[12], H[144], Hf[144], theta;
        hand_hinge((10 + 160 * (0.5 + 0.5 * fd_rand(&r))) * DEG,
                   fd_rand(&r) < 0 ? -1 : 1, x);
        for (int i = 0; i < 12; i++)
            x[i] += 0.2 * fd_rand(&r);
        cr_assert(cl_bw_hinge(x, &theta, g, H));
        double tr = ref_theta(x, gr);
        cr_assert(fabs(theta - tr) <= 1e-13, "theta %g vs %g", theta, tr);
        cr_assert_lt(fd_relerr(g, gr, 12), 1e-12);
        double gf[12];
        for (int c = 0; c < 12; c++) {
            double y[12], tp, tm, gp[12], gm[12], h = 1e-6;
            memcpy(y, x, sizeof y);
            y[c] = x[c] + h;
            cl_bw_hinge(y, &tp, gp, NULL);
            y[c] = x[c] - h;
            cl_bw_hinge(y, &tm, gm, NULL);
            gf[c] = (tp - tm) / (2 * h);
            for (int i = 0; i < 12; i++)
                Hf[i * 12 + c] = (gp[i] - gm[i]) / (2 * h);
        }
        worst_g = fmax(worst_g, fd_relerr(gf, g, 12));
        worst_h = fmax(worst_h, fd_relerr(Hf, H, 144));
        double asym = 0.0, rows = 0.0, sum[3] = {0}, torque[3] = {0};
        for (int a = 0; a < 12; a++) {
            double rs[3] = {0};
            for (int b = 0; b < 12; b++) {
                asym = fmax(asym, fabs(H[a * 12 + b] - H[b * 12 + a]));
                rs[b % 3] += H[a * 12 + b];
            }
            rows = fmax(rows, fmax(fabs(rs[0]), fmax(fabs(rs[1]),
                                                     fabs(rs[2]))));
        }
        for (int v = 0; v < 4; v++) {
            double t[3];
            cross(x + 3 * v, g + 3 * v, t);
            for (int i = 0; i < 3; i++) {
                sum[i] += g[3 * v + i];
                torque[i] += t[i];
            }
        }
        double s = fd_maxabs(H, 144), sg = fd_maxabs(g, 12);
        cr_assert_lt(asym / s, 1e-12, "Hessian asymmetry %g", asym / s);
        cr_assert_lt(rows / s, 1e-12, "Hessian row sums %g", rows / s);
        cr_assert_lt(fd_maxabs(sum, 3) / sg, 1e-13);
        cr_assert_lt(fd_maxabs(torque, 3) / sg, 1e-12);
    }
    fd_report("bw-bend hinge gradient vs FD of theta", worst_g);
    fd_report("bw-bend hinge Hessian vs FD of gradient", worst_h);
    cr_assert_lt(worst_g, 1e-8, "gradient vs FD %g", worst_g);
    cr_assert_lt(worst_h, 1e-7, "Hessian vs FD %g", worst_h);
}

/* ---- the term ------------------------------------------------------------ */

/* 2 x 2 grid: one interior edge, the diagonal (0,0)-(1,1), i.e. particles
 * 0 and 3; particle 1 = (0,1) is turned about it by p: E = k p^2 / 2. */
Test(bw_bend, folded_square_energy)
{
    const double angles[] = {0.0, 30.0, 90.0, 150.0};
    cl_model *m = BW_ONLY("cloth.n=2", "bw-bend.enabled=true",
                          "bw-bend.k=0.25");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    for (size_t k = 0; k < sizeof angles / sizeof *angles; k++)
        for (int s = -1; s <= 1; s += 2) {
            double p = angles[k] * DEG;
            memcpy(x, cl_model_cloth(m)->X0, n * sizeof *x);
            /* rotate X1 = (0,0,1) about the axis (1,0,1)/sqrt 2 by s p */
            double c = cos(p), sn = s * sin(p), a = 1 / sqrt(2.0);
            double par = a, perp[3] = {-0.5, 0.0, 0.5}, ax[3] = {a, 0, a};
            double w[3];
            cross(ax, perp, w);
            for (int i = 0; i < 3; i++)
                x[3 + i] = par * ax[i] + c * perp[i] + sn * w[i];
            cl_energy e = fd_eval(m, x, v, f);
            double want = 0.5 * 0.25 * p * p;
            cr_assert(fabs(fd_term_energy(&e, "bw-bend") - want) <=
                          1e-14 + 1e-13 * want,
                      "%g deg: E = %.17g, want %.17g", angles[k],
                      fd_term_energy(&e, "bw-bend"), want);
        }
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

static void state(const cl_model *m, fd_rng *r, double *x, double *v)
{
    double A[9];
    fd_scale(1.02 + 0.02 * fd_rand(r), 0.98 + 0.02 * fd_rand(r), A);
    bw_state(m, A, 0.1, 0.4, 1.0, r, x, v);
}

Test(bw_bend, jacobian_fixed_diagonal)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-bend.enabled=true",
                          "bw-bend.k=3e-3");
    bw_potential_case(m, bend_ref(m, CL_DIAGONAL_FIXED),
                      (double[2]){3e-3, 0.0}, "bw-bend", state, 202,
                      "bw-bend fixed");
}

Test(bw_bend, jacobian_alternate_diagonal)
{
    cl_model *m = BW_ONLY("cloth.nu=5", "cloth.nv=4", "cloth.su=1.2",
                          "cloth.sv=0.7", "cloth.diagonal=alternate",
                          "bw-bend.enabled=true", "bw-bend.k=7e-4");
    bw_potential_case(m, bend_ref(m, CL_DIAGONAL_ALTERNATE),
                      (double[2]){7e-4, 0.0}, "bw-bend", state, 203,
                      "bw-bend alternate");
}

/* Flat rest state: theta = theta0 on every hinge, no force, no energy. */
Test(bw_bend, rest_is_free_of_force)
{
    cl_model *m = BW_ONLY("cloth.nu=6", "cloth.nv=5", "bw-bend.enabled=true");
    size_t n = fd_n(m);
    double *v = fd_vec(n), *f = fd_vec(n);
    cl_energy e = fd_eval(m, cl_model_cloth(m)->X0, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0);
    cr_assert_eq(fd_term_energy(&e, "bw-bend"), 0.0);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(bw_bend, rotation_invariance)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-bend.enabled=true",
                          "bw-bend.k=1e-3");
    bw_rigid_trials(m, state, 204, 3, 1e-10, "bw-bend");
    cl_model_free(m);
}

Test(bw_bend, damping)
{
    cl_model *m = BW_ONLY("cloth.nu=4", "cloth.nv=3", "cloth.su=0.9",
                          "cloth.sv=0.6", "bw-bend.enabled=true",
                          "bw-bend.k=0", "bw-bend.kd=2e-3");
    bw_ref ref = bend_ref(m, CL_DIAGONAL_FIXED);
    double kd[2] = {2e-3, 0.0};
    bw_damping_trials(m, "bw-bend", &ref, kd, state, 205, 2,
                      "bw-bend-damping");
    bw_ref_free(&ref);
    cl_model_free(m);
}
