/* Shape diagnostics: stretch, out-of-plane amplitude, wrinkle count. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/diagnostics.h"

static cl_cloth strip(int nu, int nv)
{
    cl_cloth c;
    cl_error err;
    cr_assert_eq(cl_cloth_grid(nu, nv, 1.0, 0.2, 1.0, &c, &err), CL_OK);
    return c;
}

/* y = amp sin(k pi x / Su) along every row: k half-waves. */
static double *wave(const cl_cloth *c, int k, double amp)
{
    double *x = malloc(3 * c->np * sizeof *x);
    memcpy(x, c->X0, 3 * c->np * sizeof *x);
    for (size_t p = 0; p < c->np; p++)
        x[3 * p + 1] = amp * sin(k * M_PI * x[3 * p]);
    return x;
}

Test(diagnostics, wrinkles_count_sign_changes)
{
    cl_cloth c = strip(81, 5);
    for (int k = 1; k <= 6; k++) {
        double *x = wave(&c, k, 0.01);
        cr_assert_eq(cl_wrinkles(&c, x), k - 1, "%d half-waves", k);
        cr_assert_float_eq(cl_max_offplane(&c, x), 0.01, 1e-4);
        free(x);
    }
    cr_assert_eq(cl_wrinkles(&c, c.X0), 0, "flat");
    cl_cloth_free(&c);
}

Test(diagnostics, small_noise_is_ignored)
{
    cl_cloth c = strip(81, 5);
    double *x = wave(&c, 1, 0.01);
    /* Alternating noise at 1% of the amplitude near the (pinned-like)
     * ends must not count as wrinkles. */
    for (size_t p = 0; p < c.np; p++)
        if (fabs(x[3 * p + 1]) < 1e-4)
            x[3 * p + 1] = (p % 2 ? 1 : -1) * 1e-4;
    cr_assert_eq(cl_wrinkles(&c, x), 0);
    free(x);
    cl_cloth_free(&c);
}

Test(diagnostics, stretch_ratio)
{
    cl_cloth c = strip(5, 5);
    cl_pairset s;
    cl_error err;
    cr_assert_eq(cl_pairs_type1(&c, &s, &err), CL_OK);
    cr_assert_float_eq(cl_max_stretch(&s, c.X0), 1.0, 1e-15);
    double *x = malloc(3 * c.np * sizeof *x);
    for (size_t k = 0; k < 3 * c.np; k++)
        x[k] = 1.5 * c.X0[k];
    cr_assert_float_eq(cl_max_stretch(&s, x), 1.5, 1e-14);
    x[0] = NAN;
    cr_assert(isnan(cl_max_stretch(&s, x)), "a NaN propagates");
    free(x);
    cl_pairs_free(&s);
    cl_cloth_free(&c);
}
