/* gsl-msbdf: GSL's variable-order (1..5) variable-step BDF in Nordsieck
 * form with modified Newton iteration (gsl_odeiv2_step_msbdf) on
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * adaptive through gsl_odeiv2_driver (error control on y, opts->rtol /
 * opts->atol; options, failures, statistics: integrators/gslode.h).  GSL
 * factorises the Newton matrix densely (LU of 2n x 2n), so the method is a
 * small-problem reference: systems with n > 1728 unknowns (3 * 24 * 24, a
 * 24 x 24 grid of free particles; 2n = 3456, a 95 MB dense matrix) are
 * refused with CL_EUNSUPPORTED.
 *
 * The Jacobian is dense, row-major, filled from the system's 3x3 block
 * Jacobians (sys->jacobian, blocks in sys->pattern, block CSR):
 *
 *   dfdy = [ 0              I            ]      rows 0..n-1: x' = v
 *          [ M^-1 df/dx     M^-1 df/dv   ]      rows n..2n-1
 *
 * dfdt = (0, M^-1 df/dt).  For fixed pins f does not depend on t and
 * df/dt = 0; a problem with moving pins ([pins] velocity) has df/dt != 0
 * (the pin positions move with t).  The integrator cannot tell the two
 * apart from the system interface, so df/dt is always taken by the
 * forward difference (f(t + d, x, v) - f(t, x, v)) / d, d = sqrt(eps)
 * max(1, |t|): exactly 0 for fixed pins, first-order accurate for moving
 * ones, one extra force evaluation per Jacobian evaluation (counted in
 * rhs_evals).  (GSL 2.7's msbdf does not read dfdt; it is filled for the
 * gsl_odeiv2_system contract.)  jac_evals counts the Jacobian calls;
 * GSL re-evaluates the Jacobian only every 50 steps or after a Newton
 * failure. */
#include "integrators/gslode.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include <gsl/gsl_errno.h>

#include "core/check.h"
#include "linalg/firstorder.h"

#define CL_MSBDF_MAX_N (3 * 24 * 24)

/* dfdt = (0, M^-1 (f(t + d) - f(t)) / d), f(t) already in s->f. */
static int msbdf_dfdt(cl_gslode *s, double t, const double *y, double *dfdt)
{
    size_t n = s->n;
    double d = sqrt(DBL_EPSILON) * fmax(1.0, fabs(t));
    d = (t + d) - t;
    cl_status st = s->sys->force(s->sys->data, t + d, y, y + n, s->ft);
    s->nrhs++;
    if (st != CL_OK)
        return cl_gslode_failed(s, st, t + d);
    for (size_t i = 0; i < n; i++) {
        dfdt[i] = 0.0;
        dfdt[n + i] = s->inv_mass[i] * (s->ft[i] - s->f[i]) / d;
    }
    if (!cl_all_finite(dfdt + n, n))
        return cl_gslode_failed(s, CL_EBLOWUP, t + d);
    return GSL_SUCCESS;
}

static int msbdf_jacobian(double t, const double y[], double *dfdy,
                          double dfdt[], void *params)
{
    cl_gslode *s = params;
    size_t n = s->n, nval = 9 * s->sys->pattern->nnzb;
    cl_status st = s->sys->jacobian(s->sys->data, t, y, y + n, s->f,
                                    s->dfdx, s->dfdv);
    s->njac++;
    if (st != CL_OK)
        return cl_gslode_failed(s, st, t);
    if (!cl_all_finite(s->dfdx, nval) || !cl_all_finite(s->dfdv, nval)
        || !cl_all_finite(s->f, n))
        return cl_gslode_failed(s, CL_EBLOWUP, t);
    cl_firstorder_dense(s->sys->pattern, s->inv_mass, s->dfdx, s->dfdv, dfdy);
    return msbdf_dfdt(s, t, y, dfdt);
}

CL_GSLODE_INTEGRATOR(cl_integrator_gsl_msbdf, "gsl-msbdf",
                     &cl_region_bdf5,
                     "GSL odeiv2 msbdf, BDF orders 1-5 with dense Jacobian "
                     "(n <= 1728), rtol/atol",
                     &gsl_odeiv2_step_msbdf, msbdf_jacobian, CL_MSBDF_MAX_N,
                     "24 x 24 free particles: GSL's msbdf factorises a "
                     "dense 2n x 2n Newton matrix; use cvode-bdf for larger "
                     "cloths");
