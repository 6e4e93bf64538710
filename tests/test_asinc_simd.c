/* The vectorised inverse sinc (forces/asinc.h: cl_asinc_1m_simd) against
 * the scalar cl_asinc_1m and the buckling denominator formed from the
 * scalar functions, over the whole range of e = (L - d)/L. */
#include <criterion/criterion.h>

#include <math.h>

#include "forces/asinc.h"

#define NE 4001

Test(asinc_simd, matches_scalar_inverse_and_denominator)
{
    static double e[NE], t[NE], D[NE];
    static unsigned char ok[NE];
    for (int i = 0; i < NE; i++) /* 1e-9 .. 1 - 1e-9, log-spaced near 0 */
        e[i] = i < 1000 ? pow(10.0, -9.0 + 6.3 * i / 1000.0)
                        : 2e-3 + (1.0 - 2e-3 - 1e-9) * (i - 1000) / 3000.0;
    cl_asinc_1m_simd(NE, e, t, D, ok);
    int good = 0;
    for (int i = 0; i < NE; i++) {
        if (!ok[i])
            continue;
        good++;
        double ts = cl_asinc_1m(e[i]), h = sin(0.5 * ts);
        double Ds = cl_one_minus_sinc(ts) - 2.0 * h * h;
        cr_assert_leq(fabs(t[i] - ts), 1e-15 * ts, "e = %.17g: t %.17g, "
                      "scalar %.17g", e[i], t[i], ts);
        cr_assert_leq(fabs(D[i] - Ds), 1e-14 * fabs(Ds), "e = %.17g: D "
                      "%.17g, scalar %.17g", e[i], D[i], Ds);
    }
    /* Declined only where the scalar method leaves one Newton step. */
    cr_assert_geq(good, NE - 10, "%d of %d", good, NE);
}

Test(asinc_simd, declines_outside_the_open_range)
{
    double e[4] = {0.0, 1.0, -0.25, NAN}, t[4], D[4];
    unsigned char ok[4];
    cl_asinc_1m_simd(4, e, t, D, ok);
    for (int i = 0; i < 4; i++)
        cr_assert_eq(ok[i], 0, "e = %g", e[i]);
}
