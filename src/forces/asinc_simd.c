/* The exact inverse sinc and the buckling denominator over many pairs at
 * once (forces/asinc.h: cl_asinc_1m_simd): the scalar method's arithmetic
 * (cl_asinc_1m, one Newton step from its initial guess) with both sides
 * of every branch computed and one selected, so that GCC vectorises the
 * loop; sin and cos come from glibc's libmvec. */
#include "forces/asinc.h"

#include <stdbool.h>

#include "forces/pairkern.h"

/* glibc's vector variant of sin (libmvec: _ZGVdN4v_sin, ...); math.h
 * declares it only under -ffast-math. */
#pragma omp declare simd notinbranch
double sin(double x);

/* g(t) = 1 - sinc t and g'(t), as asinc.c's g_and_dg forms them, but for
 * cos t = 1 - 2 sin^2(t/2): sin and cos of one argument would become
 * sincos, which has no vector variant.  g' only scales the Newton step,
 * whose rounding it does not reach (quadratic convergence). */
static inline void g_and_dg_both(double t, double *g, double *dg)
{
    double s = t * t;
    double gs = s * cl_asinc_horner(cl_asinc_g_ser, CL_ASINC_NSER, s);
    double dgs = t * cl_asinc_horner(cl_asinc_dg_ser, CL_ASINC_NSER, s);
    double sn = sin(t), hh = sin(0.5 * t), cs = 1.0 - 2.0 * hh * hh;
    double gt = 1.0 - sn / t, dgt = (sn - t * cs) / (t * t);
    bool series = t < CL_ASINC_SERIES_T;
    *g = series ? gs : gt;
    *dg = series ? dgs : dgt;
}

/* cos t - sinc t = (1 - sinc t) - 2 sin^2(t/2) for t >= 0, as
 * forces/type2.c's denominator forms it. */
static inline double denominator_both(double t)
{
    double s = t * t;
    double gs = s * cl_asinc_horner(cl_asinc_g_ser, CL_ASINC_NSER, s);
    double gt = 1.0 - sin(t) / t, h = sin(0.5 * t);
    return (t < CL_ASINC_SERIES_T ? gs : gt) - 2.0 * h * h;
}

CL_PAIR_KERNEL
void cl_asinc_1m_simd(size_t n, const double *e, double *t, double *D,
                      unsigned char *ok)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++) {
        double ee = e[i];
        double ts = sqrt(6.0 * ee) *
                    cl_asinc_horner(cl_asinc_rev_ser, 7, ee);
        double guess = cl_asinc_guess(ee), g, dg;
        double t0 = guess < M_PI ? guess : M_PI;
        g_and_dg_both(t0, &g, &dg);
        double r = g - ee, tn = t0 - r / dg;
        /* the bracket after the first evaluation: (t0, pi) or (0, t0) */
        bool inside = ((r < 0.0) & (tn > t0) & (tn < M_PI)) |
                      ((r >= 0.0) & (tn > 0.0) & (tn < t0));
        bool stops = fabs(tn - t0) <= CL_ASINC_NEWTON_STOP * tn;
        bool series = ee < CL_ASINC_SERIES_E;
        double tt = series ? ts : r == 0.0 ? t0 : tn;
        t[i] = tt;
        D[i] = denominator_both(tt);
        /* & and |, not && and ||: no branches in the loop */
        ok[i] = (ee > 0.0) & (ee < 1.0) & (tt >= 1e-8) &
                (series | (r == 0.0) | (inside & stops));
    }
}
