/* The amplification of one step on the undamped oscillator x'' = -w^2 x
 * (region.h, cl_region.amplification; docs/integrators.md 4.3), with
 * W = w h:
 *
 *  - backward Euler: R(z) = 1/(1 - z), |R(i W)| = 1/sqrt(1 + W^2);
 *  - the implicit midpoint rule: R(z) = (1 + z/2)/(1 - z/2), |R(i W)| = 1;
 *  - BDF2: the roots of (3/2 - z) q^2 - 2 q + 1/2 = 0, q = (2 +- sqrt(1 +
 *    2 z))/(3 - 2 z), the larger modulus at z = i W (Hairer and Wanner,
 *    "Solving Ordinary Differential Equations II", V.1);
 *  - generalized-alpha (Chung and Hulbert 1993, eq. 18): the spectral
 *    radius of the map (x, h v, h^2 a)_n -> (x, h v, h^2 a)_{n+1} of
 *    the method on a = -w^2 x, from the step of docs/integrators.md
 *    (4.2): with A = h^2 a,
 *      D A1 = -W^2 x0 - W^2 (1 - af) h v0 - (W^2 (1 - af)(1/2 - beta)
 *             + am) A0,   D = 1 - am + W^2 (1 - af) beta,
 *      x1 = x0 + h v0 + (1/2 - beta) A0 + beta A1,
 *      h v1 = h v0 + (1 - gamma) A0 + gamma A1;
 *    its eigenvalues by GSL (gsl_eigen_nonsymm).  It tends to rho_inf as
 *    W -> infinity (eq. 25) and is 1 at W = 0.  Where the three roots
 *    nearly coincide (rho_inf near 1 or 0 at large W) the eigenvalues are
 *    computed to about the cube root of round-off (1e-5 at rho_inf = 1,
 *    W = 1e6, where the exact radius is 1). */
#include "integrators/region.h"

#include <complex.h>
#include <math.h>

#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>

cl_galpha cl_galpha_params(double rho)
{
    double am = (2.0 * rho - 1.0) / (rho + 1.0), af = rho / (rho + 1.0);
    double g = 1.0 - am + af;
    return (cl_galpha){.am = am, .af = af, .gamma = 0.5 - am + af,
                       .beta = 0.25 * g * g};
}

static double amp_be(double wh, double param)
{
    (void)param;
    return 1.0 / sqrt(1.0 + wh * wh);
}

static double amp_midpoint(double wh, double param)
{
    (void)wh, (void)param;
    return 1.0;
}

static double amp_bdf2(double wh, double param)
{
    (void)param;
    double complex z = I * wh, s = csqrt(1.0 + 2.0 * z), d = 3.0 - 2.0 * z;
    return fmax(cabs((2.0 + s) / d), cabs((2.0 - s) / d));
}

/* One generalized-alpha step of the oscillator on y = (x, h v, h^2 a). */
static void galpha_map(const cl_galpha *p, double W, const double y[3],
                       double out[3])
{
    double w2 = W * W, d = 1.0 - p->am + w2 * (1.0 - p->af) * p->beta;
    double a1 = (-w2 * y[0] - w2 * (1.0 - p->af) * y[1] -
                 (w2 * (1.0 - p->af) * (0.5 - p->beta) + p->am) * y[2]) / d;
    out[0] = y[0] + y[1] + (0.5 - p->beta) * y[2] + p->beta * a1;
    out[1] = y[1] + (1.0 - p->gamma) * y[2] + p->gamma * a1;
    out[2] = a1;
}

static double amp_galpha(double wh, double rho)
{
    cl_galpha p = cl_galpha_params(rho);
    double a[9], col[3];
    for (int j = 0; j < 3; j++) {
        double e[3] = {j == 0, j == 1, j == 2};
        galpha_map(&p, wh, e, col);
        for (int i = 0; i < 3; i++)
            a[3 * i + j] = col[i];
    }
    gsl_matrix_view m = gsl_matrix_view_array(a, 3, 3);
    gsl_vector_complex *ev = gsl_vector_complex_alloc(3);
    gsl_eigen_nonsymm_workspace *w = gsl_eigen_nonsymm_alloc(3);
    double r = NAN;
    if (ev && w && gsl_eigen_nonsymm(&m.matrix, ev, w) == 0) {
        r = 0.0;
        for (size_t i = 0; i < 3; i++)
            r = fmax(r, gsl_complex_abs(gsl_vector_complex_get(ev, i)));
    }
    if (w)
        gsl_eigen_nonsymm_free(w);
    if (ev)
        gsl_vector_complex_free(ev);
    return r;
}

const cl_region cl_region_be = {.kind = CL_REGION_SECTOR, .alpha = 90.0,
                                .amplification = amp_be};
const cl_region cl_region_bdf2 = {.kind = CL_REGION_SECTOR, .alpha = 90.0,
                                  .amplification = amp_bdf2};
const cl_region cl_region_midpoint = {.kind = CL_REGION_SECTOR,
                                      .alpha = 90.0,
                                      .amplification = amp_midpoint};
const cl_region cl_region_galpha = {.kind = CL_REGION_SECTOR, .alpha = 90.0,
                                    .amplification = amp_galpha};
