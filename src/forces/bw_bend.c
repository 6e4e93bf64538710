/* Baraff-Witkin bend (BW98 section 4, bend; docs/model.md 3.3) on every
 * interior edge of the grid mesh or mesh cloth (model/mesh.h):
 * C = theta - theta0, the signed angle between the normals of the edge's
 * two triangles, theta0 its value on the rest mesh (0 for the flat grid),
 * wrapped to [-pi, pi].
 *
 * Hinge (x0, x1, x2, x3): edge e = x1 - x0 as it runs in the first triangle
 * (x0, x1, x2); x3 is the far vertex of the second, (x1, x0, x3).  With
 * f0 = x2 - x0, f1 = x3 - x0 and the (unnormalised) normals
 *     N0 = e x f0,   N1 = f1 x e,   A0 = |N0|, A1 = |N1| (twice the areas),
 *     theta = atan2((N0 x N1) . e/|e|, N0 . N1)
 * (BW98: sin theta = (n0 x n1) . e^, cos theta = n0 . n1).  theta = 0 for a
 * flat hinge; theta > 0 when x3 lies on the side of triangle 0 away from N0,
 * i.e. sign(theta) = -sign((x3 - x0) . N0).
 *
 * Gradient (the discrete-shells hinge gradient: Grinspun et al. 2003,
 * "Discrete shells"; Bridson et al. 2003; Tamstorf & Grinspun 2013,
 * "Discrete bending forces and their Jacobians"), with l = |e|,
 * q0 = N0/A0^2, q1 = N1/A1^2 and the positions of the far vertices along
 * the edge alpha0 = f0.e/l^2, alpha1 = f1.e/l^2:
 *     g2 = -l q0,   g3 = -l q1,
 *     g1 = -alpha0 g2 - alpha1 g3,   g0 = -(g1 + g2 + g3)
 * (translation and rotation invariant: sum g = 0, sum x x g = 0).
 * Hessian: the exact derivative of those expressions, by the chain rule:
 *     dl = -e^ dx0 + e^ dx1,
 *     dN0 = ([f0]x - [e]x) dx0 - [f0]x dx1 + [e]x dx2,
 *     dN1 = ([e]x - [f1]x) dx0 + [f1]x dx1 - [e]x dx3,
 *     dq = (I - 2 N N^T/A^2)/A^2 dN,
 *     dalpha0 = (e.df0 + (f0 - 2 alpha0 e).de)/l^2   (likewise alpha1),
 *     dg2 = -(q0 dl^T + l dq0),   dg3 = -(q1 dl^T + l dq1),
 *     dg1 = -(g2 dalpha0^T + alpha0 dg2 + g3 dalpha1^T + alpha1 dg3),
 *     dg0 = -(dg1 + dg2 + dg3).
 * Nothing is dropped: the potential Jacobian -k (g g^T + C H) is exact
 * (verified against finite differences in tests/test_bw_bend.c).  The
 * damping term (bw-bend-damping) keeps -kd C' H of dd/dx and drops
 * -kd g (H v)^T (BW98 section 4, damping).  A hinge with a zero-length edge
 * or a zero-area triangle exerts no force.
 *
 * Units: C in rad, so k in J (N m) per rad^2 (about the bending stiffness
 * of the sheet, N m, on a regular grid) and kd in N m s.
 *
 * INI section [bw-bend]: enabled (false), k (N m, default 5e-5), kd (N m s,
 * default 0; the damping term runs when enabled and kd > 0). */
#include <math.h>
#include <string.h>

#include "forces/bw.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct {
    double e[3], f0[3], f1[3], N0[3], N1[3];
    double l, l2, A0s, A1s, alpha0, alpha1, q0[3], q1[3];
} hinge;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* [a]x, row-major: [a]x b = a x b. */
static void skew3(const double a[3], double S[9])
{
    S[0] = 0.0, S[1] = -a[2], S[2] = a[1];
    S[3] = a[2], S[4] = 0.0, S[5] = -a[0];
    S[6] = -a[1], S[7] = a[0], S[8] = 0.0;
}

static void mul3(const double A[9], const double B[9], double C[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] +
                           A[3 * i + 2] * B[6 + j];
}

/* dq/dN for q = N/|N|^2: (I - 2 N N^T/A^2)/A^2 with A^2 = As. */
static void inv_sq_jacobian(const double N[3], double As, double P[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            P[3 * i + j] = ((i == j) - 2.0 * N[i] * N[j] / As) / As;
}

/* Geometry of the hinge; false if degenerate. */
static bool hinge_setup(const double *x, hinge *h)
{
    for (int i = 0; i < 3; i++) {
        h->e[i] = x[3 + i] - x[i];
        h->f0[i] = x[6 + i] - x[i];
        h->f1[i] = x[9 + i] - x[i];
    }
    cross3(h->e, h->f0, h->N0);
    cross3(h->f1, h->e, h->N1);
    h->l2 = dot3(h->e, h->e);
    h->A0s = dot3(h->N0, h->N0);
    h->A1s = dot3(h->N1, h->N1);
    if (!(h->l2 > 0 && h->A0s > 0 && h->A1s > 0) || !isfinite(h->l2) ||
        !isfinite(h->A0s) || !isfinite(h->A1s))
        return false;
    h->l = sqrt(h->l2);
    h->alpha0 = dot3(h->f0, h->e) / h->l2;
    h->alpha1 = dot3(h->f1, h->e) / h->l2;
    for (int i = 0; i < 3; i++) {
        h->q0[i] = h->N0[i] / h->A0s;
        h->q1[i] = h->N1[i] / h->A1s;
    }
    return true;
}

/* Derivatives w.r.t. vertex v of l (dl), alpha0, alpha1 (da0, da1) and N0,
 * N1 (dN0, dN1, 3x3). */
static void hinge_parts(const hinge *h, double dl[4][3], double da0[4][3],
                        double da1[4][3], double dN0[4][9], double dN1[4][9])
{
    double Se[9], Sf0[9], Sf1[9];
    skew3(h->e, Se);
    skew3(h->f0, Sf0);
    skew3(h->f1, Sf1);
    memset(dN0, 0, 4 * sizeof *dN0);
    memset(dN1, 0, 4 * sizeof *dN1);
    for (int k = 0; k < 9; k++) {
        dN0[0][k] = Sf0[k] - Se[k];
        dN0[1][k] = -Sf0[k];
        dN0[2][k] = Se[k];
        dN1[0][k] = Se[k] - Sf1[k];
        dN1[1][k] = Sf1[k];
        dN1[3][k] = -Se[k];
    }
    memset(dl, 0, 4 * sizeof *dl);
    memset(da0, 0, 4 * sizeof *da0);
    memset(da1, 0, 4 * sizeof *da1);
    for (int i = 0; i < 3; i++) {
        double e = h->e[i], r0 = h->f0[i] - 2.0 * h->alpha0 * e,
               r1 = h->f1[i] - 2.0 * h->alpha1 * e;
        dl[0][i] = -e / h->l;
        dl[1][i] = e / h->l;
        da0[0][i] = -(e + r0) / h->l2;
        da0[1][i] = r0 / h->l2;
        da0[2][i] = e / h->l2;
        da1[0][i] = -(e + r1) / h->l2;
        da1[1][i] = r1 / h->l2;
        da1[3][i] = e / h->l2;
    }
}

/* H[(3r + i) 12 + 3v + j] = d g_{r,i} / d x_{v,j}. */
static void hinge_hessian(const hinge *h, const double *g, double *H)
{
    double dl[4][3], da0[4][3], da1[4][3], dN0[4][9], dN1[4][9], P0[9],
        P1[9];
    const double *g2 = g + 6, *g3 = g + 9;
    hinge_parts(h, dl, da0, da1, dN0, dN1);
    inv_sq_jacobian(h->N0, h->A0s, P0);
    inv_sq_jacobian(h->N1, h->A1s, P1);
    for (int v = 0; v < 4; v++) {
        double dq0[9], dq1[9], D[4][9];
        mul3(P0, dN0[v], dq0);
        mul3(P1, dN1[v], dq1);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                int k = 3 * i + j;
                D[2][k] = -(h->q0[i] * dl[v][j] + h->l * dq0[k]);
                D[3][k] = -(h->q1[i] * dl[v][j] + h->l * dq1[k]);
                D[1][k] = -(g2[i] * da0[v][j] + h->alpha0 * D[2][k] +
                            g3[i] * da1[v][j] + h->alpha1 * D[3][k]);
                D[0][k] = -(D[1][k] + D[2][k] + D[3][k]);
            }
        for (int r = 0; r < 4; r++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    H[(3 * r + i) * 12 + 3 * v + j] = D[r][3 * i + j];
    }
}

bool cl_bw_hinge(const double *x, double *theta, double *g, double *H)
{
    hinge h;
    if (!hinge_setup(x, &h)) {
        *theta = 0.0;
        memset(g, 0, 12 * sizeof *g);
        if (H)
            memset(H, 0, 144 * sizeof *H);
        return false;
    }
    double M[3];
    cross3(h.N0, h.N1, M);
    *theta = atan2(dot3(M, h.e) / h.l, dot3(h.N0, h.N1));
    for (int i = 0; i < 3; i++) {
        g[6 + i] = -h.l * h.q0[i];
        g[9 + i] = -h.l * h.q1[i];
        g[3 + i] = -h.alpha0 * g[6 + i] - h.alpha1 * g[9 + i];
        g[i] = -(g[3 + i] + g[6 + i] + g[9 + i]);
    }
    if (H)
        hinge_hessian(&h, g, H);
    return true;
}

static bool bend_rest(const double *x, double *rest)
{
    double g[12];
    return cl_bw_hinge(x, &rest[0], g, NULL);
}

static void bend_cond(const double *rest, const double b[2], const double *x,
                      bool want_hess, cl_bw_cond *out)
{
    (void)b;
    double theta;
    bool ok = cl_bw_hinge(x, &theta, out->g[0], want_hess ? out->H[0] : NULL);
    double C = theta - rest[0];
    if (C > M_PI)
        C -= 2.0 * M_PI;
    else if (C < -M_PI)
        C += 2.0 * M_PI;
    out->C[0] = ok ? C : 0.0;
}

static const cl_bw_spec bend_spec = {
    .section = "bw-bend",
    .nv = 4,
    .nc = 1,
    .nrest = 1,
    .cond = bend_cond,
    .k_default = 5e-5,
    .kd_default = 0.0,
    .hinge_rest = bend_rest,
};

CL_BW_TERM_TYPES(bw_bend, "bw-bend", bend_spec,
                 "Baraff-Witkin bend C = theta - theta0 on the interior "
                 "edges (exact Jacobian)",
                 "Baraff-Witkin bend damping -kd (dC/dx) C' ([bw-bend] kd)");
