/* Value checks shared by every layer (see check.h). */
#include "core/check.h"

#include <math.h>

bool cl_all_finite(const double *a, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(a[i]))
            return false;
    }
    return true;
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
