/* Inverse sinc for the Choi-Ko Type2 (buckling) interaction.
 *
 * Jiao, section 4.5: a compressed Type2 pair of rest length L and chord
 * d = |x_ij| < L is taken to lie on a circular arc of length L, whose
 * curvature is (eq. 8)
 *
 *     kappa = (2/L) asinc(d/L),
 *
 * where sinc(t) = sin(t)/t is the UNnormalised sinc and asinc is its inverse
 * on [0, pi] (asinc(1) = 0, asinc(0) = pi).  With t = kappa L/2 the buckling
 * force is (eq. 9) f_b = kb kappa^2 / (cos t - sinc t), obtained from
 * E = kb L kappa^2/2 and (eq. 12) d|x_ij|/dkappa = (L/kappa)(cos t - sinc t).
 *
 * Exact branch.  Near d = L, y = d/L is close to 1 and t ~ sqrt(6 (1 - y)):
 * forming 1 - y from y throws away the digits that determine t.  The solver
 * therefore takes e = 1 - y = (L - d)/L directly (callers form (L - d)/L,
 * which is exact to rounding) and solves
 *
 *     g(t) = 1 - sinc(t) = e,   g(t) = t^2/6 - t^4/120 + ...,   t in [0, pi].
 *
 * g is increasing on [0, pi] with g'(t) = (sin t - t cos t)/t^2 > 0 for t > 0
 * (g' ~ t/3 at 0, g'(pi) = 1/pi).  Conditioning: the relative condition
 * number of t with respect to e, e g'(t)^-1 / t, lies between 1/2 (t -> 0)
 * and 1 (t = pi), so t is as accurate as e; in the y form an absolute error
 * delta in y moves t by delta/g'(t) ~ 3 delta/t, i.e. the y form loses
 * accuracy as t -> 0 (y within 1e-16 of 1 cannot resolve t below ~2.6e-8).
 *
 * Polynomial branch (Jiao, section 4.6).  Jiao's own code builds a
 * fifth-order polynomial from numpy's NORMALISED sinc, sinc_n(x) =
 * sin(pi x)/(pi x):
 *
 *     x = linspace(0, 1, 1000); y = sinc_n(x)
 *     p1 = polyfit(y, x, 5)                 (x as a function of y)
 *     f = polyval(p1, x)                    (the x nodes used as sinc values)
 *     f = (f - min f) / max(f - min f)      (scale_range(f, 0, 1))
 *     p = polyfit(x, f, 5)                  (the final coefficients)
 *
 * and uses kappa = (2/L) p(d/L).  The polynomial approximates the normalised
 * inverse asinc_n(y) = asinc(y)/pi (to within ~0.05 on [0, 1]; p(0) = 1,
 * p(1) ~ 0, but it cannot follow the square-root behaviour at y -> 1), so
 * the kappa of Jiao's code is about 1/pi of the true arc curvature.  This
 * module reproduces the coefficients as numpy computes them; it does not
 * fix them.  (The "seed" in the names cl_seed_poly_* and in the option
 * value type2.asinc = seed-poly stands for Jiao's code.)
 *
 * All functions are pure, allocation-free and thread-safe, except
 * cl_seed_poly_coeffs / cl_seed_poly_fit, which allocate a small work array
 * (call them once, e.g. when a term is created). */
#ifndef CL_ASINC_H
#define CL_ASINC_H

#include <math.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* ---- sinc and 1 - sinc --------------------------------------------------- */

/* sinc(t) = sin(t)/t, sinc(0) = 1 (series 1 - t^2/6 + t^4/120 for tiny |t|). */
double cl_sinc(double t);

/* d sinc/dt = (t cos t - sin t)/t^2 = -cl_one_minus_sinc_deriv(t). */
double cl_sinc_deriv(double t);

/* g(t) = 1 - sin(t)/t without cancellation: the Taylor series
 * sum_{k>=1} (-1)^(k+1) t^(2k)/(2k+1)! for |t| < 1 (to full double
 * accuracy), 1 - sin(t)/t otherwise.  Relative error a few ulp for all t
 * in [-pi, pi]. */
double cl_one_minus_sinc(double t);

/* g'(t) = (sin t - t cos t)/t^2 (series t/3 - t^3/30 + ... for |t| < 1). */
double cl_one_minus_sinc_deriv(double t);

/* numpy's normalised sinc, sinc_n(x) = sin(pi x)/(pi x) = sinc(pi x), and
 * its derivative d sinc_n/dx = pi sinc'(pi x). */
double cl_sinc_normalised(double x);
double cl_sinc_normalised_deriv(double x);

/* ---- exact inverse ------------------------------------------------------- */

/* t in [0, pi] with 1 - sinc(t) = e, for e in [0, 1].
 * Returns 0 for e = 0, M_PI for e = 1, and NaN for NaN or e outside [0, 1]
 * (not clamped: callers only pass e = (L - d)/L with 0 <= d < L, so anything
 * else is a bug that should show).  e < 2e-3: the reverted series
 * t = sqrt(6e) (1 + 3e/20 + 321e^2/5600 + ...) to full accuracy, no
 * iteration.  Otherwise: t = sqrt(6e) phi(e) with phi a piecewise
 * degree-7 polynomial (relative error <= 1.5e-9), then safeguarded Newton on
 * g(t) - e in the bracket [0, pi] with bisection fallback, stopped once a
 * Newton step is below 3e-9 t (quadratic convergence, with
 * |g''| t / (2 g') <= 1 on [0, pi], makes the error after that step below
 * 1e-17 t).  Typically one Newton step; relative accuracy ~1e-16 in t. */
double cl_asinc_1m(double e);

/* As cl_asinc_1m; also returns dt/de = 1/g'(t) in *dt_de (+inf at e = 0)
 * and the number of g evaluations (Newton or bisection steps) in *iters.
 * Either pointer may be NULL. */
double cl_asinc_1m_ex(double e, double *dt_de, int *iters);

/* dt/de = 1/g'(t) at a solution t = cl_asinc_1m(e) (+inf at t = 0).  For
 * kappa = (2/L) t(e) with e = (L - d)/L: dkappa/dd = -(2/L^2) dt/de. */
double cl_asinc_1m_deriv(double t);

/* asinc(y) = cl_asinc_1m(1 - y) for y in [0, 1] (NaN outside): sinc(t) = y.
 * Prefer cl_asinc_1m near y = 1 (see the conditioning note above). */
double cl_asinc(double y);

/* ---- Jiao's polynomial (Jiao, section 4.6) ------------------------------- */

#define CL_SEED_POLY_DEGREE 5
#define CL_SEED_POLY_NCOEF (CL_SEED_POLY_DEGREE + 1)
#define CL_SEED_POLY_NPTS 1000

/* numpy.polyfit(x, y, deg) for n points: Vandermonde matrix (highest power
 * first), columns scaled to unit 2-norm, least squares by SVD (one-sided
 * Jacobi, GSL) with singular values below n * DBL_EPSILON * s_max dropped
 * as numpy's lstsq does (rcond), coefficients unscaled.  p[0..deg],
 * highest degree first.  Requires n > deg >= 0, deg <= 15.
 * CL_EINVAL for bad sizes or non-finite data, CL_ENOMEM, CL_ESOLVER. */
cl_status cl_polyfit(const double *x, const double *y, int n, int deg,
                     double *p, cl_error *err);

/* Every stage of the construction in Jiao's code, for reports. */
typedef struct {
    double p1[CL_SEED_POLY_NCOEF]; /* polyfit(sinc_n(x), x, 5) */
    double fmin, fmax;             /* min of polyval(p1, x) and max after the
                                      shift (the scale_range divisor) */
    double p[CL_SEED_POLY_NCOEF];  /* final: polyfit(x, scaled f, 5) */
} cl_seed_fit;

cl_status cl_seed_poly_fit(cl_seed_fit *out, cl_error *err);

/* The final coefficients p[0..5] of Jiao's code, highest degree first. */
cl_status cl_seed_poly_coeffs(double p[CL_SEED_POLY_NCOEF], cl_error *err);

/* p(r) by Horner in numpy.polyval's order (so values are bit-identical),
 * and p'(r) in *dp if dp is not NULL.  Jiao uses kappa = (2/L) p(d/L),
 * i.e. p approximates asinc(y)/pi, not asinc(y). */
double cl_seed_poly_eval(const double p[CL_SEED_POLY_NCOEF], double r,
                         double *dp);

CL_END_DECLS

#endif
