/* The inverse sinc of the Type2 buckling force against Jiao's polynomial
 * (`clothode asinc`, README "Using it"; the asinc figure of README
 * "Reports"), on the chord ratios y = k/n, k = 0..n:
 *   t      = asinc(y), sinc(t) = y, t in [0, pi], solved from e = 1 - y
 *            (exact: e = (n - k)/n) by cl_asinc_1m,
 *   t/pi   = the normalised inverse Jiao's polynomial fits,
 *   p(y)   = Jiao's fifth-order polynomial (section 4.6), which Jiao
 *            uses in place of t (kappa = (2/L) p(d/L)),
 *   resid  = |1 - sinc(t) - e|, the solver's residual. */
#ifndef CL_ASINC_ERROR_H
#define CL_ASINC_ERROR_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "forces/asinc.h"

CL_BEGIN_DECLS

typedef struct {
    double y, t, t_over_pi, seed, resid;
} cl_asinc_row;

typedef struct {
    double p[CL_SEED_POLY_NCOEF];  /* Jiao's coefficients */
    double max_err_normalised;     /* max |p(y) - t/pi| ... */
    double y_err_normalised;       /* ... and where */
    double max_err_true;           /* max |p(y) - t| */
    double max_resid;
} cl_asinc_summary;

/* rows[0..n] (n + 1 of them), n >= 1; CL_EINVAL for n < 1. */
cl_status cl_asinc_error(size_t n, cl_asinc_row *rows, cl_asinc_summary *s,
                         cl_error *err);

CL_END_DECLS

#endif
