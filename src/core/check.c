/* Value checks shared by every layer (see check.h). */
#include "core/check.h"

#include <math.h>

/* a * 0 is +-0 for finite a and NaN for an infinity or NaN, and a sum of
 * zeros is zero in any order: a reduction without an early exit, which
 * GCC vectorises (it runs on every force evaluation). */
bool cl_all_finite(const double *a, size_t n)
{
    double acc = 0.0;
#pragma omp simd reduction(+ : acc)
    for (size_t i = 0; i < n; i++)
        acc += a[i] * 0.0;
    return acc == 0.0;
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
