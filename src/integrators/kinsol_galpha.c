/* kinsol-galpha: the generalized-alpha method (Chung and Hulbert, "A time
 * integration algorithm for structural dynamics with improved numerical
 * dissipation: the generalized-alpha method", 1993) on M a = f(t, x, v),
 * fixed step h = opts->dt, each step's nonlinear system solved by KINSOL
 * Newton in the new velocity (kinsol_common.h; docs/integrators.md 4.2).
 * With the parameters of rho_inf = opts->rho_inf in [0, 1]
 * (cl_galpha_params: am, af, gamma, beta) and the carried acceleration
 * a0 (M^-1 f at the initial state, then the method's own a1):
 *
 *   x1 = x0 + h v0 + h^2 ((1/2 - beta) a0 + beta a1),
 *   v1 = v0 + h ((1 - gamma) a0 + gamma a1),
 *   M ((1 - am) a1 + am a0) = f(t0 + (1 - af) h, (1 - af) x1 + af x0,
 *                                (1 - af) v1 + af v0).
 *
 * Eliminating a1 = (v1 - v0 - h (1 - gamma) a0) / (h gamma) and
 * multiplying the balance by h gamma / (1 - am) (am <= 1/2):
 *
 *   R(v1) = M (v1 - vb) - (gamma/(1 - am)) h f(te, xe, ve) = 0,
 *   vb = v0 + h ((1 - gamma) - gamma am/(1 - am)) a0,
 *   x1 = x1b + (beta/gamma) h v1,
 *   x1b = x0 + h (1 - beta/gamma) v0 + h^2 (1/2 - beta/gamma) a0,
 *   xe = x0 + (1 - af)(x1 - x0) = x0 + (1 - af)(beta/gamma) h (v1 - p),
 *   p = -(gamma/beta - 1) v0 - h (gamma/(2 beta) - 1) a0,
 *   ve = af v0 + (1 - af) v1,  te = 1 - af.
 *
 * In the common form: c = gamma/(1 - am), alpha = (1 - af) beta/gamma,
 * beta (common) = 1 - af, alpha1 = beta/gamma, te = 1 - af; the Newton
 * matrix is M - c (1 - af) h df/dv - c alpha h^2 df/dx.  At rho_inf = 1
 * (am = af = gamma = 1/2, beta = 1/4: Newmark's average acceleration with
 * the forces at the midpoint) vb = v0, x1b = x0 + (h/2) v0, p = -v0 and
 * every scalar is kinsol-midpoint's: the two take the same steps.  At
 * rho_inf = 0 (am = -1, af = 0, gamma = 3/2, beta = 1) the forces are
 * taken at the new state and the amplification tends to 0 as w h grows.
 * Second order for every rho_inf (gamma = 1/2 - am + af), A-stable, its
 * high-frequency damping set by rho_inf alone (region_amplification.c).
 * The predictor leaves the evaluation point at x0, as for the other
 * KINSOL methods. */
#include <math.h>

#include "integrators/kinsol_common.h"

enum { GA_AM, GA_AF, GA_GAMMA, GA_BETA };

static cl_status galpha_configure(const cl_integrator_opts *o,
                                  cl_kin_scheme *own, cl_error *err)
{
    double rho = o->rho_inf;
    if (!(rho >= 0.0 && rho <= 1.0))
        return cl_error_set(err, CL_EINVAL, "%s: rho_inf = %g outside "
                            "[0, 1] ([run] rho_inf, --rho-inf)", own->name,
                            rho);
    cl_galpha p = cl_galpha_params(rho);
    own->par[GA_AM] = p.am;
    own->par[GA_AF] = p.af;
    own->par[GA_GAMMA] = p.gamma;
    own->par[GA_BETA] = p.beta;
    own->c = p.gamma / (1.0 - p.am);
    own->alpha = (1.0 - p.af) * p.beta / p.gamma;
    own->beta = 1.0 - p.af;
    own->alpha1 = p.beta / p.gamma;
    own->te = 1.0 - p.af;
    return CL_OK;
}

static void galpha_prepare(cl_kin_step *st)
{
    const double *par = st->sc->par, h = st->h;
    double am = par[GA_AM], af = par[GA_AF], g = par[GA_GAMMA];
    double bg = par[GA_BETA] / g;
    double kvb = (1.0 - g) - g * am / (1.0 - am);
    double kpv = 1.0 / bg - 1.0, kpa = 0.5 / bg - 1.0;
    for (size_t i = 0; i < st->n; i++) {
        double x = st->x[i], v = st->v[i], a = st->acc[i];
        st->vb[i] = v + h * kvb * a;
        st->ve0[i] = af * v;
        st->x1b[i] = x + h * (1.0 - bg) * v + h * h * (0.5 - bg) * a;
        st->pred[i] = -kpv * v - h * kpa * a;
    }
}

/* a1 = (v1 - v0 - h (1 - gamma) a0) / (h gamma). */
static void galpha_finish(cl_kin_step *st, const double *v1)
{
    double g = st->sc->par[GA_GAMMA], h = st->h;
    for (size_t i = 0; i < st->n; i++)
        st->acc[i] = (v1[i] - st->v[i] - h * (1.0 - g) * st->acc[i]) /
                     (h * g);
}

static const cl_kin_scheme kin_galpha = {
    .name = "kinsol-galpha",
    .prepare = galpha_prepare,
    .configure = galpha_configure,
    .finish = galpha_finish,
};

CL_KIN_INTEGRATOR(cl_integrator_kinsol_galpha, kin_galpha, "kinsol-galpha",
                  &cl_region_galpha,
                  "generalized-alpha (Chung-Hulbert), numerical damping "
                  "rho_inf, KINSOL Newton + linsol (default klu), fixed "
                  "step dt", true);
