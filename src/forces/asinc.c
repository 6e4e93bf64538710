/* Inverse sinc for the Choi-Ko Type2 interaction: Jiao, eq. 8
 * (kappa = (2/L) asinc(|x_ij|/L)), eq. 9 and 12 (f_b and d|x_ij|/dkappa,
 * which need sinc, 1 - sinc and their derivatives), and section 4.6 (Jiao's
 * fifth-order polynomial fit of the inverse sinc, reproduced as Jiao's
 * numpy code computes it).  The mathematics is in asinc.h. */
#include "forces/asinc.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_vector.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- sinc and 1 - sinc --------------------------------------------------- */

/* Below this |t| the Taylor series (NSER terms) is used for 1 - sinc and
 * its derivative.  At |t| = 1 the direct forms lose at most a few ulp to
 * cancellation (sinc(1)/(1 - sinc(1)) ~ 5), and the series needs 9 terms. */
#define SERIES_T 1.0
#define NSER 9

/* g(t)/t^2 = sum_k (-1)^k s^k / (2k+3)!, s = t^2, highest power first. */
static const double g_ser[NSER] = {
    1.0 / 121645100408832000.0, /* 19! */
    -1.0 / 355687428096000.0,   /* 17! */
    1.0 / 1307674368000.0,      /* 15! */
    -1.0 / 6227020800.0,        /* 13! */
    1.0 / 39916800.0,           /* 11! */
    -1.0 / 362880.0,            /* 9! */
    1.0 / 5040.0,               /* 7! */
    -1.0 / 120.0,               /* 5! */
    1.0 / 6.0,                  /* 3! */
};

/* g'(t)/t = sum_k (-1)^k (2k+2) s^k / (2k+3)!, highest power first. */
static const double dg_ser[NSER] = {
    18.0 / 121645100408832000.0, -16.0 / 355687428096000.0,
    14.0 / 1307674368000.0,      -12.0 / 6227020800.0,
    10.0 / 39916800.0,           -8.0 / 362880.0,
    6.0 / 5040.0,                -4.0 / 120.0,
    2.0 / 6.0,
};

/* Horner's rule for c[0] s^(n-1) + ... + c[n-1]. */
static inline double horner(const double *c, int n, double s)
{
    double v = c[0];
#pragma GCC unroll 16
    for (int k = 1; k < n; k++)
        v = v * s + c[k];
    return v;
}

double cl_sinc(double t)
{
    if (fabs(t) < 1e-4) {
        double s = t * t;
        return 1.0 - s * (1.0 / 6.0 - s * (1.0 / 120.0));
    }
    return sin(t) / t;
}

double cl_one_minus_sinc(double t)
{
    if (fabs(t) < SERIES_T) {
        double s = t * t;
        return s * horner(g_ser, NSER, s);
    }
    return 1.0 - sin(t) / t;
}

double cl_one_minus_sinc_deriv(double t)
{
    if (fabs(t) < SERIES_T)
        return t * horner(dg_ser, NSER, t * t);
    return (sin(t) - t * cos(t)) / (t * t);
}

double cl_sinc_deriv(double t) { return -cl_one_minus_sinc_deriv(t); }

double cl_sinc_normalised(double x) { return cl_sinc(M_PI * x); }

double cl_sinc_normalised_deriv(double x)
{
    return -M_PI * cl_one_minus_sinc_deriv(M_PI * x);
}

/* g and g' together (one sin/cos pair at most). */
static void g_and_dg(double t, double *g, double *dg)
{
    if (t < SERIES_T) {
        double s = t * t;
        *g = s * horner(g_ser, NSER, s);
        *dg = t * horner(dg_ser, NSER, s);
        return;
    }
    double sn = sin(t), cs = cos(t);
    *g = 1.0 - sn / t;
    *dg = (sn - t * cs) / (t * t);
}

/* ---- exact inverse ------------------------------------------------------- */

/* Below this e the reverted series is exact to double precision: its first
 * omitted term is ~0.0063 e^7 relative (< 1e-21 here). */
#define SERIES_E 2e-3

/* t/sqrt(6e) = 1 + sum c_k e^k (series reversion of g), highest first. */
static const double rev_ser[7] = {
    317184685563.0 / 50226176000000.0,
    1766784699.0 / 179379200000.0,
    445617.0 / 27596800.0,
    3197.0 / 112000.0,
    321.0 / 5600.0,
    3.0 / 20.0,
    1.0,
};

/* Initial guess: t/sqrt(6e) = phi(e) on four pieces, each a degree-7
 * polynomial in u = (2e - (a + b))/(b - a) (coefficients of u^0..u^7) from
 * Chebyshev interpolation of the exact phi at 40 digits.  Max relative
 * error per piece: 1.7e-11, 2.2e-10, 1.5e-9, 1.2e-9.  Only the iteration
 * count depends on these numbers, never the result. */
static const double guess_edge[5] = {0.0, 0.3, 0.6, 0.85, 1.0};
static const double guess_poly[4][8] = {
    {1.0238950727880618, 0.02540540544496327, 0.0016365276070614606,
     0.00013825437366359546, 1.3304710866156467e-05, 1.3830451524162432e-06,
     1.5538793532169572e-07, 1.7644514900179991e-08},
    {1.0826277627666439, 0.034186601920070073, 0.0029490984368945095,
     0.00033939117321974446, 4.4811694904779778e-05, 6.420402526712971e-06,
     1.0223085910555779e-06, 1.6086526621287006e-07},
    {1.1579984513084567, 0.041726994027458011, 0.0044372311775374082,
     0.00064557169917034429, 0.00010877804474838345, 2.0020942031967574e-05,
     4.2627589213491644e-06, 8.6797996938353489e-07},
    {1.2397875653800166, 0.038234562092319076, 0.0038624238666095782,
     0.00055151373890255275, 9.2377341795518605e-05, 1.7004333628144597e-05,
     3.6370780646540199e-06, 7.4476324984255854e-07},
};

/* The initial guess sqrt(6e) phi(e) for e in [SERIES_E, 1]. */
static inline double guess(double e)
{
    /* The piece by selects rather than an index (branch-free). */
    const double *edge = guess_edge;
    bool p1 = e >= edge[1], p2 = e >= edge[2], p3 = e >= edge[3];
#define PIECE(v0, v1, v2, v3) (p3 ? (v3) : p2 ? (v2) : p1 ? (v1) : (v0))
    double a = PIECE(edge[0], edge[1], edge[2], edge[3]);
    double b = PIECE(edge[1], edge[2], edge[3], edge[4]);
    double u = (2.0 * e - (a + b)) / (b - a);
    const double(*c)[8] = guess_poly;
    double phi = PIECE(c[0][7], c[1][7], c[2][7], c[3][7]);
#pragma GCC unroll 8
    for (int j = 6; j >= 0; j--)
        phi = phi * u + PIECE(c[0][j], c[1][j], c[2][j], c[3][j]);
#undef PIECE
    return sqrt(6.0 * e) * phi;
}

/* Stop after a Newton step |dt| <= NEWTON_STOP t: the next error
 * is at most max(|g''| t/(2 g')) (NEWTON_STOP t)^2 / t
 * <= 1e-17 t. */
#define NEWTON_STOP 3e-9
#define MAX_ITERS 100

double cl_asinc_1m_ex(double e, double *dt_de, int *iters)
{
    int n = 0;
    double t;
    if (!(e >= 0.0 && e <= 1.0)) { /* NaN or out of range */
        t = NAN;
    } else if (e == 0.0) {
        t = 0.0;
    } else if (e == 1.0) {
        t = M_PI;
    } else if (e < SERIES_E) {
        t = sqrt(6.0 * e) * horner(rev_ser, 7, e);
    } else {
        /* Root lies in (0, M_PI): g(M_PI) rounds to 1 > e. */
        double lo = 0.0, hi = M_PI;
        t = fmin(guess(e), hi);
        while (n < MAX_ITERS) {
            double g, dg;
            g_and_dg(t, &g, &dg);
            n++;
            double r = g - e;
            if (r == 0.0)
                break;
            if (r < 0.0)
                lo = t;
            else
                hi = t;
            double tn = t - r / dg;
            if (tn == t) /* step below the resolution of t */
                break;
            int newton = tn > lo && tn < hi;
            if (!newton)
                tn = 0.5 * (lo + hi);
            double step = tn - t;
            t = tn;
            if (newton && fabs(step) <= NEWTON_STOP * t)
                break;
            if (hi - lo <= 2.0 * DBL_EPSILON * hi)
                break;
        }
    }
    if (iters)
        *iters = n;
    if (dt_de)
        *dt_de = cl_asinc_1m_deriv(t);
    return t;
}

double cl_asinc_1m(double e) { return cl_asinc_1m_ex(e, NULL, NULL); }

double cl_asinc_1m_deriv(double t)
{
    if (t == 0.0)
        return INFINITY;
    return 1.0 / cl_one_minus_sinc_deriv(t);
}

double cl_asinc(double y)
{
    if (!(y >= 0.0 && y <= 1.0))
        return NAN;
    return cl_asinc_1m(1.0 - y);
}

/* ---- least squares polynomial fit (numpy.polyfit) ------------------------ */

#define MAX_DEG 15

cl_status cl_polyfit(const double *x, const double *y, int n, int deg,
                     double *p, cl_error *err)
{
    if (!x || !y || !p || deg < 0 || deg > MAX_DEG || n <= deg)
        return cl_error_set(err, CL_EINVAL,
                            "polyfit: need 0 <= deg <= %d and more points "
                            "than the degree (n = %d, deg = %d)",
                            MAX_DEG, n, deg);
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return cl_error_set(err, CL_EINVAL,
                                "polyfit: non-finite data at point %d", i);
    const int m = deg + 1;
    double *a = malloc((size_t)n * (size_t)m * sizeof *a);
    if (!a)
        return cl_error_set(err, CL_ENOMEM,
                            "polyfit: cannot allocate %d x %d matrix", n, m);

    /* Vandermonde, highest power first; powers by repeated products as
     * numpy.vander does. */
    for (int i = 0; i < n; i++) {
        double pw = 1.0;
        a[(size_t)i * m + deg] = 1.0;
        for (int k = 1; k <= deg; k++) {
            pw = k == 1 ? x[i] : pw * x[i];
            a[(size_t)i * m + deg - k] = pw;
        }
    }
    double scale[MAX_DEG + 1];
    for (int j = 0; j < m; j++) {
        double s = 0.0;
        for (int i = 0; i < n; i++)
            s += a[(size_t)i * m + j] * a[(size_t)i * m + j];
        scale[j] = sqrt(s);
        if (!(scale[j] > 0.0) || !isfinite(scale[j])) {
            free(a);
            return cl_error_set(err, CL_EINVAL,
                                "polyfit: degenerate abscissae (column %d "
                                "of the Vandermonde matrix has norm %g)",
                                j, scale[j]);
        }
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < m; j++)
            a[(size_t)i * m + j] /= scale[j];

    /* A = U S V^T by one-sided Jacobi (A is overwritten by U). */
    double qbuf[(MAX_DEG + 1) * (MAX_DEG + 1)], sbuf[MAX_DEG + 1];
    gsl_matrix_view av = gsl_matrix_view_array(a, (size_t)n, (size_t)m);
    gsl_matrix_view qv = gsl_matrix_view_array(qbuf, (size_t)m, (size_t)m);
    gsl_vector_view sv = gsl_vector_view_array(sbuf, (size_t)m);
    int gs = gsl_linalg_SV_decomp_jacobi(&av.matrix, &qv.matrix, &sv.vector);
    if (gs != GSL_SUCCESS) {
        free(a);
        return cl_error_set(err, CL_ESOLVER, "polyfit: SVD failed: %s",
                            gsl_strerror(gs));
    }

    /* Minimum-norm solution, dropping s_j <= rcond s_max (numpy's rcond =
     * n * eps), then two steps of iterative refinement with the residual
     * evaluated in long double.  A backward-stable solve alone is off by
     * ~sqrt(n) eps cond ~ 1e-11 relative here; refinement brings it to the
     * least-squares optimum of the given data to ~1e-15 (where long double
     * is wider than double). */
    double smax = 0.0;
    for (int j = 0; j < m; j++)
        smax = fmax(smax, sbuf[j]);
    const double cut = (double)n * DBL_EPSILON * smax;
    double c[MAX_DEG + 1] = {0};
    long double *r = malloc((size_t)n * sizeof *r);
    if (!r) {
        free(a);
        return cl_error_set(err, CL_ENOMEM,
                            "polyfit: cannot allocate %d residuals", n);
    }
    for (int i = 0; i < n; i++)
        r[i] = y[i];
    for (int pass = 0; pass < 3; pass++) {
        if (pass > 0) { /* r = y - A c, A unscaled, in long double */
            for (int i = 0; i < n; i++) {
                long double v = 0.0L;
                for (int k = 0; k < m; k++)
                    v = v * (long double)x[i] + (long double)c[k] / scale[k];
                r[i] = (long double)y[i] - v;
            }
        }
        double dc[MAX_DEG + 1] = {0};
        for (int j = 0; j < m; j++) {
            if (!(sbuf[j] > cut))
                continue;
            long double ub = 0.0L;
            for (int i = 0; i < n; i++)
                ub += (long double)a[(size_t)i * m + j] * r[i];
            double w = (double)(ub / sbuf[j]);
            for (int k = 0; k < m; k++)
                dc[k] += qbuf[k * m + j] * w;
        }
        for (int k = 0; k < m; k++)
            c[k] += dc[k];
    }
    free(r);
    free(a);
    for (int k = 0; k < m; k++)
        p[k] = c[k] / scale[k];
    return CL_OK;
}

/* ---- Jiao's polynomial --------------------------------------------------- */

/* numpy.sinc, as numpy writes it. */
static double numpy_sinc(double x)
{
    double a = M_PI * (x == 0.0 ? 1.0e-20 : x);
    return sin(a) / a;
}

double cl_seed_poly_eval(const double p[CL_SEED_POLY_NCOEF], double r,
                         double *dp)
{
    double v = 0.0, dv = 0.0; /* numpy.polyval starts from 0 */
    for (int k = 0; k < CL_SEED_POLY_NCOEF; k++) {
        dv = dv * r + v;
        v = v * r + p[k];
    }
    if (dp)
        *dp = dv;
    return v;
}

cl_status cl_seed_poly_fit(cl_seed_fit *out, cl_error *err)
{
    enum { N = CL_SEED_POLY_NPTS, D = CL_SEED_POLY_DEGREE };
    if (!out)
        return cl_error_set(err, CL_EINVAL, "Jiao's polynomial: no output");
    double *buf = malloc(3 * (size_t)N * sizeof *buf);
    if (!buf)
        return cl_error_set(err, CL_ENOMEM,
                            "Jiao's polynomial: cannot allocate work arrays");
    double *x = buf, *y = buf + N, *f = buf + 2 * N;

    /* x = np.linspace(0, 1, 1000): i * (1/999), last point set to 1. */
    const double step = 1.0 / (double)(N - 1);
    for (int i = 0; i < N; i++)
        x[i] = (double)i * step;
    x[N - 1] = 1.0;
    for (int i = 0; i < N; i++)
        y[i] = numpy_sinc(x[i]);

    cl_status rc = cl_polyfit(y, x, N, D, out->p1, err);
    if (rc) {
        free(buf);
        return rc;
    }
    for (int i = 0; i < N; i++)
        f[i] = cl_seed_poly_eval(out->p1, x[i], NULL);

    /* scale_range(f, 0, 1): f += -min(f); f /= max(f) / (1 - 0); f += 0. */
    double mn = f[0];
    for (int i = 1; i < N; i++)
        mn = fmin(mn, f[i]);
    for (int i = 0; i < N; i++)
        f[i] += -mn;
    double mx = f[0];
    for (int i = 1; i < N; i++)
        mx = fmax(mx, f[i]);
    const double div = mx / (1.0 - 0.0);
    for (int i = 0; i < N; i++) {
        f[i] /= div;
        f[i] += 0.0;
    }
    out->fmin = mn;
    out->fmax = mx;

    rc = cl_polyfit(x, f, N, D, out->p, err);
    free(buf);
    return rc;
}

cl_status cl_seed_poly_coeffs(double p[CL_SEED_POLY_NCOEF], cl_error *err)
{
    cl_seed_fit fit;
    cl_status rc = cl_seed_poly_fit(&fit, err);
    if (rc)
        return rc;
    for (int k = 0; k < CL_SEED_POLY_NCOEF; k++)
        p[k] = fit.p[k];
    return CL_OK;
}
