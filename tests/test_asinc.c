/* Tests for forces/asinc: the inverse sinc behind the Choi-Ko curvature
 * kappa = (2/L) asinc(|x_ij|/L) (Jiao, eq. 8), the sinc pieces of the
 * buckling force and its derivative (eq. 9, 12), and Jiao's
 * fifth-order polynomial fit of the inverse sinc (section 4.6). */
#include <criterion/criterion.h>

#include <float.h>
#include <math.h>

#include "forces/asinc.h"

#define PI 3.14159265358979323846

/* ---- long-double references ---------------------------------------------- */

/* 1 - sin(t)/t = sum_{k>=1} (-1)^(k+1) t^(2k)/(2k+1)!, summed in long
 * double until the terms vanish (|t| <= pi: terms below 2). */
static long double ref_one_minus_sinc(double t)
{
    long double s = (long double)t * t, term = s / 6.0L, sum = 0.0L;
    for (int k = 1; k < 60 && term != 0.0L; k++) {
        sum += term;
        term *= -s / ((2.0L * k + 2.0L) * (2.0L * k + 3.0L));
    }
    return sum;
}

/* d/dt (1 - sin t/t) = sum_{k>=1} (-1)^(k+1) 2k t^(2k-1)/(2k+1)!. */
static long double ref_one_minus_sinc_deriv(double t)
{
    long double s = (long double)t * t, sum = 0.0L;
    long double c = 1.0L / 6.0L; /* 1/(2k+1)! */
    long double pw = t;          /* t^(2k-1) */
    for (int k = 1; k < 60; k++) {
        long double term = (k % 2 ? 1.0L : -1.0L) * 2.0L * k * pw * c;
        sum += term;
        if (term == 0.0L)
            break;
        pw *= s;
        c /= (2.0L * k + 2.0L) * (2.0L * k + 3.0L);
    }
    return sum;
}

static double relerr(double a, long double ref)
{
    if (ref == 0.0L)
        return fabs(a);
    return (double)fabsl(((long double)a - ref) / ref);
}

/* ---- sinc and 1 - sinc --------------------------------------------------- */

Test(asinc, sinc_values)
{
    cr_assert_eq(cl_sinc(0.0), 1.0);
    cr_assert_eq(cl_one_minus_sinc(0.0), 0.0);
    cr_assert_eq(cl_one_minus_sinc_deriv(0.0), 0.0);
    double worst = 0.0;
    for (int i = 1; i <= 20000; i++) {
        double t = PI * i / 20000.0;
        long double ref = sinl((long double)t) / t;
        worst = fmax(worst, relerr(cl_sinc(t), ref));
        worst = fmax(worst, relerr(cl_sinc(-t), ref));
    }
    for (double t = 1e-12; t < 1e-2; t *= 1.7) {
        long double ref = 1.0L - ref_one_minus_sinc(t);
        worst = fmax(worst, relerr(cl_sinc(t), ref));
    }
    cr_assert_lt(worst, 4e-16, "sinc relative error %g", worst);
    cr_assert_float_eq(cl_sinc_normalised(0.5), 2.0 / PI, 1e-16);
    cr_assert_eq(cl_sinc_normalised(0.0), 1.0);
    cr_assert_lt(fabs(cl_sinc_normalised(1.0)), 1e-16);
}

Test(asinc, one_minus_sinc_matches_series)
{
    double worst = 0.0, worst_d = 0.0;
    /* Log grid through the series range, uniform grid over [0, pi]. */
    for (double t = 1e-150; t < 1.0; t *= 1.05) {
        worst = fmax(worst, relerr(cl_one_minus_sinc(t),
                                   ref_one_minus_sinc(t)));
        worst_d = fmax(worst_d, relerr(cl_one_minus_sinc_deriv(t),
                                       ref_one_minus_sinc_deriv(t)));
    }
    for (int i = 1; i <= 20000; i++) {
        double t = PI * i / 20000.0;
        worst = fmax(worst, relerr(cl_one_minus_sinc(t),
                                   ref_one_minus_sinc(t)));
        worst = fmax(worst, relerr(cl_one_minus_sinc(-t),
                                   ref_one_minus_sinc(t)));
        worst_d = fmax(worst_d, relerr(cl_one_minus_sinc_deriv(t),
                                       ref_one_minus_sinc_deriv(t)));
        worst_d = fmax(worst_d, relerr(-cl_one_minus_sinc_deriv(-t),
                                       ref_one_minus_sinc_deriv(t)));
    }
    /* Across the switch at |t| = 1 the two forms agree. */
    double below = nextafter(1.0, 0.0);
    worst = fmax(worst, relerr(cl_one_minus_sinc(below),
                               ref_one_minus_sinc(below)));
    cr_assert_lt(worst, 2e-15, "1 - sinc relative error %g", worst);
    cr_assert_lt(worst_d, 2e-15, "(1 - sinc)' relative error %g", worst_d);
    cr_assert_float_eq(cl_one_minus_sinc(1e-10), 1e-20 / 6.0, 1e-36);
    cr_assert_float_eq(cl_sinc_deriv(0.7), -cl_one_minus_sinc_deriv(0.7),
                       0.0);
}

Test(asinc, sinc_derivatives_vs_finite_differences)
{
    for (int i = 1; i < 60; i++) {
        double t = 3.1 * i / 60.0, h = 1e-5;
        double fd = (cl_one_minus_sinc(t + h) - cl_one_minus_sinc(t - h)) /
                    (2 * h);
        double an = cl_one_minus_sinc_deriv(t);
        cr_assert_lt(fabs(fd - an), 1e-9 * fmax(1.0, fabs(an)),
                     "t=%g fd=%.15g an=%.15g", t, fd, an);
        double x = 0.98 * i / 60.0;
        fd = (cl_sinc_normalised(x + h) - cl_sinc_normalised(x - h)) /
             (2 * h);
        an = cl_sinc_normalised_deriv(x);
        cr_assert_lt(fabs(fd - an), 1e-9 * fmax(1.0, fabs(an)),
                     "x=%g fd=%.15g an=%.15g", x, fd, an);
        fd = (cl_sinc(t + h) - cl_sinc(t - h)) / (2 * h);
        cr_assert_lt(fabs(fd - cl_sinc_deriv(t)), 1e-9);
    }
}

/* ---- exact inverse ------------------------------------------------------- */

Test(asinc, endpoints)
{
    cr_assert_eq(cl_asinc(1.0), 0.0);
    cr_assert_eq(cl_asinc(0.0), PI);
    cr_assert_eq(cl_asinc_1m(0.0), 0.0);
    cr_assert_eq(cl_asinc_1m(1.0), PI);
    /* Tiny e: t = sqrt(6e) to the last bit, subnormals included. */
    cr_assert_float_eq(cl_asinc_1m(1e-300), sqrt(6e-300), 1e-15 * 2.5e-150);
    double sub = DBL_TRUE_MIN * 1024;
    cr_assert_float_eq(cl_asinc_1m(sub), sqrt(6.0 * sub),
                       1e-15 * sqrt(6.0 * sub));
    /* Largest e below 1: t just below pi, sinc(t) ~ (pi - t)/pi. */
    double e = nextafter(1.0, 0.0);
    double t = cl_asinc_1m(e);
    cr_assert(t < PI && t > PI - 1e-14, "t = %.17g", t);
}

Test(asinc, y_form_roundtrip)
{
    /* asinc(sinc(t)) = t to 1e-12 absolute on [1e-3, pi - 1e-9].  The y
     * form is limited by sinc's rounding (delta ~ 2e-16) amplified by
     * dt/dy ~ 3/t: ~7e-13 at t = 1e-3. */
    const int n = 400000;
    const double a = 1e-3, b = PI - 1e-9;
    double worst = 0.0;
    for (int i = 0; i <= n; i++) {
        double t = a + (b - a) * i / n;
        worst = fmax(worst, fabs(cl_asinc(cl_sinc(t)) - t));
    }
    cr_assert_lt(worst, 1e-12, "worst absolute error %g", worst);
}

Test(asinc, e_form_roundtrip)
{
    /* asinc_1m(1 - sinc(t)) = t to 1e-13 relative for t in [1e-8, pi]: a
     * log grid over the small-t decades and a fine uniform grid. */
    double worst = 0.0;
    for (double t = 1e-8; t < 0.1; t *= 1.001)
        worst = fmax(worst, fabs(cl_asinc_1m(cl_one_minus_sinc(t)) / t - 1));
    const int n = 400000;
    for (int i = 0; i <= n; i++) {
        double t = 1e-8 + (PI - 1e-8) * i / n;
        worst = fmax(worst, fabs(cl_asinc_1m(cl_one_minus_sinc(t)) / t - 1));
    }
    cr_assert_lt(worst, 1e-13, "worst relative error %g", worst);

    /* Residual check on an e grid: g(t(e)) = e to a few ulp of e, also
     * on both sides of the series/Newton switch at e = 2e-3. */
    double worst_res = 0.0;
    for (int i = 1; i < 100000; i++) {
        double e = i / 100000.0;
        double r = (double)((ref_one_minus_sinc(cl_asinc_1m(e)) - e) / e);
        worst_res = fmax(worst_res, fabs(r));
    }
    for (double e = 1.9e-3; e < 2.1e-3; e += 1e-6) {
        double r = (double)((ref_one_minus_sinc(cl_asinc_1m(e)) - e) / e);
        worst_res = fmax(worst_res, fabs(r));
    }
    cr_assert_lt(worst_res, 1e-15, "worst relative residual %g", worst_res);
}

Test(asinc, newton_iterations)
{
    /* The piecewise initial guess is within 1.5e-9: one Newton step. */
    long hist[8] = {0};
    int worst = 0;
    for (int i = 1; i < 200000; i++) {
        int it = -1;
        cl_asinc_1m_ex(i / 200000.0, NULL, &it);
        cr_assert_geq(it, 0);
        worst = it > worst ? it : worst;
        hist[it < 7 ? it : 7]++;
    }
    cr_assert_leq(worst, 2, "max iterations %d", worst);
    cr_assert_gt(hist[1], 190000, "one-step solves %ld", hist[1]);
}

Test(asinc, derivative_vs_finite_differences)
{
    for (int i = 1; i < 400; i++) {
        double e = i / 400.0;
        double dt_de = 0.0;
        double t = cl_asinc_1m_ex(e, &dt_de, NULL);
        cr_assert_float_eq(dt_de, cl_asinc_1m_deriv(t), 0.0);
        double h = 1e-4 * fmin(e, 1.0 - e);
        double fd = (cl_asinc_1m(e + h) - cl_asinc_1m(e - h)) / (2 * h);
        cr_assert_lt(fabs(fd / dt_de - 1), 1e-7, "e=%g fd=%.15g an=%.15g",
                     e, fd, dt_de);
    }
    /* Small-e limit dt/de ~ 3/t and the end value dt/de(pi) = pi. */
    double t = cl_asinc_1m(1e-12);
    cr_assert_lt(fabs(cl_asinc_1m_deriv(t) * t / 3.0 - 1), 1e-10);
    cr_assert_lt(fabs(cl_asinc_1m_deriv(PI) / PI - 1), 1e-15);
    double d;
    cl_asinc_1m_ex(0.0, &d, NULL);
    cr_assert(isinf(d) && d > 0);
}

Test(asinc, invalid_inputs_give_nan)
{
    /* Documented choice: no clamping, NaN outside [0, 1]. */
    const double bad[] = {NAN, -1e-300, -0.5, nextafter(1.0, 2.0), 2.0,
                          INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double d = 0.0;
        int it = -1;
        cr_assert(isnan(cl_asinc_1m(bad[i])), "e = %g", bad[i]);
        cr_assert(isnan(cl_asinc_1m_ex(bad[i], &d, &it)));
        cr_assert(isnan(d));
        cr_assert_eq(it, 0);
        cr_assert(isnan(cl_asinc(bad[i])), "y = %g", bad[i]);
    }
}

/* ---- least squares and Jiao's polynomial --------------------------------- */

Test(asinc, polyfit_recovers_polynomials)
{
    double x[50], y[50], p[4];
    for (int i = 0; i < 50; i++) {
        x[i] = -1.0 + 2.0 * i / 49.0;
        y[i] = ((0.5 * x[i] - 2.0) * x[i] + 3.0) * x[i] - 7.0;
    }
    cr_assert_eq(cl_polyfit(x, y, 50, 3, p, NULL), CL_OK);
    const double want[4] = {0.5, -2.0, 3.0, -7.0};
    for (int k = 0; k < 4; k++)
        cr_assert_float_eq(p[k], want[k], 1e-14);

    /* A line through noisy-free but overdetermined data with a residual:
     * least squares of (0,0), (1,1), (2,1), (3,2) is y = 0.6 x + 0.1. */
    const double xs[4] = {0, 1, 2, 3}, ys[4] = {0, 1, 1, 2};
    double q[2];
    cr_assert_eq(cl_polyfit(xs, ys, 4, 1, q, NULL), CL_OK);
    cr_assert_float_eq(q[0], 0.6, 1e-15);
    cr_assert_float_eq(q[1], 0.1, 1e-15);

    cl_error err;
    cr_assert_eq(cl_polyfit(xs, ys, 2, 3, q, &err), CL_EINVAL);
    const double xnan[4] = {0, NAN, 2, 3};
    cr_assert_eq(cl_polyfit(xnan, ys, 4, 1, q, &err), CL_EINVAL);
    const double zero[4] = {0, 0, 0, 0};
    cr_assert_eq(cl_polyfit(zero, ys, 4, 1, q, &err), CL_EINVAL);
}

/* Reference coefficients.  They are the exact least-squares optima of the
 * double-precision data of Jiao's own pipeline: x_i = i (1/999) (x_999 = 1),
 * y_i = sin(pi x_i)/(pi x_i) evaluated in double, first fit solved from the
 * normal equations in 60-digit arithmetic (Python mpmath), rounded to
 * double; f = polyval(p1, x) by Horner in double and scale_range in double;
 * second fit solved the same way.  numpy itself was not available when
 * they were produced: numpy.polyfit (LAPACK gelsd, backward stable, scaled
 * condition number ~3.5e3) is expected to agree to ~1e-11 relative. */
static const double ref_p1[6] = {
    -6.012104803024493, 13.374920987586565, -10.934487816796421,
    3.978137913188176,  -1.3726298749254404, 1.0101686802485597};
static const double ref_p[6] = {
    -6.222657157169932, 13.843329505520066, -11.317428937523873,
    4.1174578901645615, -1.4207013009908216, 1.0};
static const double ref_fmin = 0.04400508627694566;
static const double ref_fmax = 0.966163593971614;

Test(asinc, seed_poly_reference_coefficients)
{
    cl_seed_fit fit;
    cl_error err;
    cr_assert_eq(cl_seed_poly_fit(&fit, &err), CL_OK, "%s", err.msg);
    for (int k = 0; k < 6; k++) {
        cr_assert_lt(fabs(fit.p1[k] / ref_p1[k] - 1), 1e-12, "p1[%d] %.17g",
                     k, fit.p1[k]);
        cr_assert_lt(fabs(fit.p[k] / ref_p[k] - 1), 1e-12, "p[%d] %.17g", k,
                     fit.p[k]);
    }
    cr_assert_lt(fabs(fit.fmin / ref_fmin - 1), 1e-12);
    cr_assert_lt(fabs(fit.fmax / ref_fmax - 1), 1e-12);
    double p[6];
    cr_assert_eq(cl_seed_poly_coeffs(p, &err), CL_OK);
    for (int k = 0; k < 6; k++)
        cr_assert_eq(p[k], fit.p[k]);
}

Test(asinc, seed_poly_is_least_squares_optimum)
{
    /* First fit: the residual r = x - p1(y) is orthogonal to every column
     * y^k of the Vandermonde matrix (zero gradient of |r|^2), measured as
     * a cosine in long double.  The optimum rounded to double gives 7e-14;
     * a backward-stable solve without refinement gives ~1.5e-12 here. */
    cl_seed_fit fit;
    cr_assert_eq(cl_seed_poly_fit(&fit, NULL), CL_OK);
    enum { N = CL_SEED_POLY_NPTS };
    static double x[N], y[N];
    for (int i = 0; i < N; i++)
        x[i] = i * (1.0 / (N - 1));
    x[N - 1] = 1.0;
    for (int i = 0; i < N; i++) {
        double a = PI * (x[i] == 0.0 ? 1e-20 : x[i]);
        y[i] = sin(a) / a;
        if (x[i] > 0.0)
            cr_assert_eq(y[i], cl_sinc_normalised(x[i]));
    }
    long double rr = 0.0L, dot[6] = {0}, cc[6] = {0};
    for (int i = 0; i < N; i++) {
        long double v = 0.0L;
        for (int k = 0; k < 6; k++)
            v = v * y[i] + fit.p1[k];
        long double r = x[i] - v, pw = 1.0L;
        rr += r * r;
        for (int k = 0; k < 6; k++) {
            dot[k] += pw * r;
            cc[k] += pw * pw;
            pw *= y[i];
        }
    }
    cr_assert_gt(sqrtl(rr), 0.2L); /* the fit is poor near y = 1 */
    for (int k = 0; k < 6; k++) {
        double cosine = (double)(fabsl(dot[k]) / sqrtl(cc[k] * rr));
        cr_assert_lt(cosine, 5e-13, "column y^%d: cosine %g", k, cosine);
    }
    /* Second fit: the scaled data are exactly the polynomial
     * (p1 - fmin)/fmax, so the refit reproduces it. */
    for (int k = 0; k < 6; k++) {
        double want = (k < 5 ? fit.p1[k] : fit.p1[k] - fit.fmin) / fit.fmax;
        cr_assert_lt(fabs(fit.p[k] - want), 1e-14 * fabs(want) + 1e-15,
                     "p[%d] %.17g vs %.17g", k, fit.p[k], want);
    }
}

Test(asinc, seed_poly_shape)
{
    double p[6];
    cr_assert_eq(cl_seed_poly_coeffs(p, NULL), CL_OK);
    cr_assert_lt(fabs(cl_seed_poly_eval(p, 0.0, NULL) - 1.0), 1e-12);
    cr_assert_lt(fabs(cl_seed_poly_eval(p, 1.0, NULL)), 1e-12);
    /* Approximates asinc(y)/pi (the normalised inverse), worst near y = 1
     * where asinc has its square-root branch: max deviation 0.057 at
     * y ~ 0.974.  Decreasing on [0, 1]. */
    double worst = 0.0;
    for (int i = 0; i <= 10000; i++) {
        double r = i / 10000.0, dp;
        double v = cl_seed_poly_eval(p, r, &dp);
        worst = fmax(worst, fabs(v - cl_asinc(r) / PI));
        cr_assert_lt(dp, 0.0, "p'(%g) = %g", r, dp);
    }
    cr_assert_lt(worst, 0.06, "max |p - asinc/pi| = %g", worst);
    cr_assert_gt(worst, 0.05); /* it is an approximation, not asinc */
    /* p' by Horner against central differences. */
    for (int i = 1; i < 20; i++) {
        double r = i / 20.0, h = 1e-6, dp;
        cl_seed_poly_eval(p, r, &dp);
        double fd = (cl_seed_poly_eval(p, r + h, NULL) -
                     cl_seed_poly_eval(p, r - h, NULL)) / (2 * h);
        cr_assert_lt(fabs(fd - dp), 1e-8, "r=%g fd=%.15g dp=%.15g", r, fd,
                     dp);
    }
}
