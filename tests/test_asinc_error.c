/* The asinc error table (analysis/asinc_error.c): the ends of the exact
 * inverse (asinc(0) = pi, asinc(1) = 0), sinc(asinc(y)) = y between, and
 * Jiao's polynomial's largest distance from asinc/pi, 0.057 near
 * y = 0.974 (paper/findings.md), with its curvature about 1/pi of the
 * arc's (largest distance from asinc 2.14, at y = 0). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>

#include "analysis/asinc_error.h"

Test(asinc_error, table_and_summary)
{
    enum { N = 100000 };
    cl_asinc_row *r = malloc((N + 1) * sizeof *r);
    cl_asinc_summary s;
    cl_error err = {0};
    cr_assert_not_null(r);
    cr_assert_eq(cl_asinc_error(N, r, &s, &err), CL_OK, "%s", err.msg);
    cr_assert_float_eq(r[0].t, M_PI, 1e-15);
    cr_assert_eq(r[N].t, 0.0);
    for (size_t k = 1; k < N; k += 997)
        cr_assert_float_eq(sin(r[k].t) / r[k].t, r[k].y, 1e-13, "y = %g",
                           r[k].y);
    cr_assert_lt(s.max_resid, 1e-15);
    cr_assert(s.max_err_normalised > 0.055 && s.max_err_normalised < 0.058,
              "%g", s.max_err_normalised);
    cr_assert(s.y_err_normalised > 0.97 && s.y_err_normalised < 0.98, "%g",
              s.y_err_normalised);
    cr_assert_float_eq(s.max_err_true, M_PI - 1.0, 1e-12);
    cr_assert_eq(s.p[CL_SEED_POLY_NCOEF - 1], 1.0);
    free(r);
}

Test(asinc_error, no_points_refused)
{
    cl_asinc_row r[1];
    cl_asinc_summary s;
    cl_error err = {0};
    cr_assert_eq(cl_asinc_error(0, r, &s, &err), CL_EINVAL);
}
