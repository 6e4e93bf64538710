/* Value checks shared by every layer (see check.h). */
#include "core/check.h"

#include <math.h>

/* a * 0 is +-0 for finite a and NaN for an infinity or NaN, and a sum of
 * zeros is zero in any order: a reduction without an early exit, which
 * GCC vectorises (it runs on every force evaluation and explicit step;
 * an AVX2 clone where the CPU has it).  Four partial sums, so that the
 * additions do not wait for each other. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
bool cl_all_finite(const double *a, size_t n)
{
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        s0 += a[i] * 0.0;
        s1 += a[i + 1] * 0.0;
        s2 += a[i + 2] * 0.0;
        s3 += a[i + 3] * 0.0;
    }
    for (; i < n; i++)
        s0 += a[i] * 0.0;
    return s0 + s1 + s2 + s3 == 0.0;
}

bool cl_all_finite_threads(const double *a, size_t n, int threads)
{
    if (threads <= 1)
        return cl_all_finite(a, n);
    bool all = true;
    size_t nt = (size_t)threads;
#pragma omp parallel for num_threads(threads) schedule(static) \
    reduction(&& : all)
    for (size_t t = 0; t < nt; t++)
        all = cl_all_finite(a + n * t / nt, n * (t + 1) / nt - n * t / nt) &&
              all;
    return all;
}

cl_status cl_check_masses(const double *mass, size_t n, const char *who,
                          cl_error *err)
{
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(mass[i]) || !(mass[i] > 0.0))
            return cl_error_set(err, CL_EINVAL,
                                "%s: mass[%zu] = %g, must be finite and > 0",
                                who, i, mass[i]);
    }
    return CL_OK;
}
