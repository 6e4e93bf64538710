/* The exact inverse sinc against Jiao's polynomial (see
 * asinc_error.h). */
#include "analysis/asinc_error.h"

#include <math.h>
#include <string.h>

cl_status cl_asinc_error(size_t n, cl_asinc_row *rows, cl_asinc_summary *s,
                         cl_error *err)
{
    memset(s, 0, sizeof *s);
    if (n < 1)
        return cl_error_set(err, CL_EINVAL, "points = %zu: expected >= 1",
                            n);
    cl_status rc = cl_seed_poly_coeffs(s->p, err);
    for (size_t k = 0; !rc && k <= n; k++) {
        cl_asinc_row *r = &rows[k];
        double e = (double)(n - k) / (double)n;
        r->y = (double)k / (double)n;
        r->t = cl_asinc_1m(e);
        r->t_over_pi = r->t / M_PI;
        r->seed = cl_seed_poly_eval(s->p, r->y, NULL);
        r->resid = fabs(cl_one_minus_sinc(r->t) - e);
        double en = fabs(r->seed - r->t_over_pi);
        if (en > s->max_err_normalised) {
            s->max_err_normalised = en;
            s->y_err_normalised = r->y;
        }
        s->max_err_true = fmax(s->max_err_true, fabs(r->seed - r->t));
        s->max_resid = fmax(s->max_resid, r->resid);
    }
    return rc;
}
