/* gsl-rk8pd: GSL's explicit embedded Runge-Kutta Prince-Dormand (8, 9)
 * (gsl_odeiv2_step_rk8pd, 13 stages) on the first-order form
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),
 *
 * adaptive step through gsl_odeiv2_driver with error control on y
 * (|local error_i| <= atol + rtol |y_i|, opts->rtol / opts->atol), exact
 * stop at every output time.  A non-stiff, high-accuracy reference for the
 * other integrators; on stiff cloth its step is bounded by stability (about
 * 1/omega_max) whatever the tolerance.  Options, failures and statistics
 * (jac_evals = 0): integrators/gslode.h. */
#include "integrators/gslode.h"

CL_GSLODE_INTEGRATOR(cl_integrator_gsl_rk8pd, "gsl-rk8pd",
                     &cl_region_adaptive,
                     "GSL odeiv2 rk8pd, explicit adaptive Runge-Kutta (8,9), "
                     "rtol/atol",
                     &gsl_odeiv2_step_rk8pd, NULL, 0, NULL);
